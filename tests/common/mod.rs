//! Helpers shared by the GPU tests: a validated context and small scenes built
//! directly from the scene types.
#![allow(dead_code)]

pub mod cli;

use glam::{UVec3, Vec3};
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};
use sweeplab::linear_image::LinearImage;
use sweeplab::render::GpuScene;
use sweeplab::scene::*;
use sweeplab::techniques::{self, Technique};
use sweeplab::vk::{Context, ContextOptions, Profiler};

/// A context with validation and synchronization validation on.
pub fn validated_context() -> Context {
    context(true)
}

/// A context without validation, for what validation would disturb (racy
/// configurations by design, CPU-time measurements).
pub fn unvalidated_context() -> Context {
    context(false)
}

fn context(validate: bool) -> Context {
    let options = ContextOptions { device: std::env::var("SWEEPLAB_DEVICE").ok(), validate, ..Default::default() };
    Context::new(&options).expect("Vulkan context")
}

/// Fails the test with every message the validation layer reported.
pub fn assert_validation_clean(ctx: &Context) {
    let messages = ctx.take_validation_messages();
    assert!(messages.is_empty(), "validation reported {} message(s):\n{}", messages.len(), messages.join("\n"));
}

/// User + system CPU seconds from a Linux `stat` file: `/proc/self/stat` for
/// the process (all threads, lavapipe's included), `/proc/thread-self/stat`
/// for the calling thread. Unlike wall time it does not grow when other
/// processes share the cores (clock ticks of 10 ms).
pub fn cpu_seconds(stat_file: &str) -> f64 {
    let stat = std::fs::read_to_string(stat_file).unwrap_or_else(|e| panic!("{stat_file} (Linux): {e}"));
    // Fields after the command name (which ends at the last ')'): utime is the
    // 14th overall, stime the 15th.
    let fields: Vec<&str> = stat.rsplit(')').next().unwrap_or_default().split_whitespace().collect();
    let ticks = |i: usize| fields[i].parse::<f64>().expect("a clock-tick count");
    (ticks(11) + ticks(12)) / 100.0
}

/// A `dims` U8 volume whose voxel (x, y, z) is `value(position, random)`,
/// `random` a seeded 64-bit LCG state drawn anew for every voxel (x fastest).
pub fn seeded_volume(
    name: &str,
    dims: UVec3,
    spacing: Vec3,
    seed: u64,
    mut value: impl FnMut(UVec3, u64) -> u8,
) -> Volume {
    let mut state = seed;
    let mut data = Vec::with_capacity((dims.x * dims.y * dims.z) as usize);
    for z in 0..dims.z {
        for y in 0..dims.y {
            for x in 0..dims.x {
                state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                data.push(value(UVec3::new(x, y, z), state));
            }
        }
    }
    Volume {
        name: name.into(),
        dims,
        spacing,
        data: VoxelData::U8(data),
        value_range: (0.0, 255.0),
        non_finite_voxels: 0,
        interpolation: Default::default(),
    }
}

/// A sphere of radius `r` (in voxels) in an n^3 U8 volume, with a soft edge.
pub fn sphere_volume(n: u32, r: f32) -> Volume {
    let c = (n as f32 - 1.0) * 0.5;
    let mut data = Vec::with_capacity((n * n * n) as usize);
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                let d = Vec3::new(x as f32 - c, y as f32 - c, z as f32 - c).length();
                data.push(((r - d + 0.5).clamp(0.0, 1.0) * 255.0) as u8);
            }
        }
    }
    Volume {
        name: "sphere".into(),
        dims: UVec3::splat(n),
        spacing: Vec3::ONE,
        data: VoxelData::U8(data),
        value_range: (0.0, 255.0),
        non_finite_voxels: 0,
        interpolation: Default::default(),
    }
}

pub fn scene_with(volume: Volume, lights: Vec<Light>, width: u32, height: u32) -> Scene {
    Scene {
        volume,
        transfer: TransferFunction {
            points: vec![
                ControlPoint { value: 0.0, rgba: [0.0, 0.0, 0.0, 0.0] },
                ControlPoint { value: 0.2, rgba: [0.9, 0.6, 0.3, 0.0] },
                ControlPoint { value: 1.0, rgba: [0.9, 0.8, 0.7, 0.3] },
            ],
        },
        camera: Camera::orbit(Vec3::ZERO, 2.5, 30.0, 20.0, Projection::Perspective { fov_y_deg: 30.0 }),
        lights,
        render: RenderSettings {
            width,
            height,
            step_voxels: 0.5,
            background: Vec3::new(0.05, 0.05, 0.08),
            emission: 0.1,
            // Off: the tolerances of these tests were measured with midpoint
            // samples, and some compare sample positions across techniques;
            // tests that want jitter turn it on.
            jitter: false,
            filter: VolumeFilter::Exact,
        },
        reference: ReferenceSettings {
            model: OpticalModel::SingleScattering,
            step_voxels: 0.5,
            shadow_step_voxels: 0.5,
            min_transmittance: 1e-4,
            chromatic: false,
        },
        phong: PhongSettings { ambient: 0.2, diffuse: 0.8, specular: 0.3, shininess: 32.0 },
        settings: TechniqueSettings::default(),
        technique_tables: Vec::new(),
    }
}

pub fn directional(direction: Vec3, intensity: f32) -> Light {
    Light { kind: LightKind::Directional { direction }, color: Vec3::ONE, intensity, falloff: Falloff::None }
}

/// The spot light of the IPSVI and light-volume tests: above the volume,
/// pointing down and a little sideways, inverse-square falloff.
pub fn spot_light(intensity: f32) -> Light {
    Light {
        kind: LightKind::Spot {
            position: Vec3::new(0.2, 1.2, 0.3),
            direction: Vec3::new(-0.1, -1.0, -0.2),
            inner_cone_deg: 15.0,
            outer_cone_deg: 30.0,
        },
        color: Vec3::ONE,
        intensity,
        falloff: Falloff::InverseSquare,
    }
}

/// tests/scenes/cornell-box.toml at `n`^3, rendered at `size`^2, with the
/// `[ao]` table `ao` (its keys, one per line).
pub fn cornell_box_scene(n: u32, size: u32, ao: &str) -> Scene {
    let text = format!(
        "[volume]\nsynthetic = \"cornell-box\"\nsize = {n}\n[transfer]\npreset = \"cornell\"\n\
         [camera]\nazimuth = 0.0\nelevation = 0.0\nfov_y = 40.0\n\
         [[lights]]\ntype = \"spot\"\nposition = [0.0, 0.4, 0.0]\ndirection = [0.0, -1.0, 0.0]\n\
         inner_cone = 50.0\nouter_cone = 70.0\nfalloff = \"inverse-square\"\nintensity = 0.3\n\
         [render]\nwidth = {size}\nheight = {size}\n[ao]\n{ao}\n"
    );
    techniques::scene_from_toml_str(&text, std::path::Path::new(""), "cornell", &[]).unwrap()
}

/// IPSVI's line barrier, load-bearing: `s` renders validation-clean with the
/// barrier between line blocks, and without it (`racy`) synchronization
/// validation reports a hazard on the cache, at `size` x `size` (llvmpipe
/// compiles a shader per power-of-two-ness of its images: a caller picks the
/// size its module renders at, docs/testing.md). `what` names the case in the
/// failure message.
pub fn assert_ipsvi_line_barrier_load_bearing(
    ctx: &Context,
    gpu: &sweeplab::render::GpuScene,
    s: &sweeplab::techniques::ipsvi::IpsviSettings,
    study: &sweeplab::techniques::ipsvi::IpsviStudy,
    profiler: &mut sweeplab::vk::Profiler,
    size: u32,
    what: &str,
) {
    use sweeplab::techniques::ipsvi::{render_study, SyncStrategy};
    profiler.reset();
    render_study(gpu, s, study, size, size, profiler, SyncStrategy::BarrierGlobal).unwrap();
    assert_validation_clean(ctx);
    profiler.reset();
    render_study(gpu, s, study, size, size, profiler, SyncStrategy::Racy).unwrap();
    let messages = ctx.take_validation_messages();
    assert!(
        messages.iter().any(|m| m.contains("SYNC-HAZARD") && m.contains("ipsvi cache")),
        "{what}: missing line barrier not reported: {messages:?}"
    );
}

/// The RMS over pixels and channels of the 8-bit filter error model's per-pixel
/// bound (docs/filtering.md) for `scene` rendered as `kind` at `size`^2 with its
/// own `render.filter`: zero with exact filtering. A technique compared with
/// the reference on the GPU, both filtered so, may move by this twice (each
/// image by at most its bound; the technique's sensitivity to the medium is
/// taken as the reference's, the same optical model on the same medium).
pub fn filter_bound_rms(scene: &Scene, kind: sweeplab::reference::CpuRenderKind, size: u32) -> f64 {
    let bound = sweeplab::reference::filter_bound_image(scene, kind, scene.render.filter, size, size).unwrap();
    let squares: f64 = bound.pixels.iter().map(|p| (p[0] as f64).powi(2)).sum();
    (squares / bound.pixels.len() as f64).sqrt()
}

/// The reference of the IPSVI tests' scenes: model (ii), light step 0.125,
/// the slab-and-sphere transfer function, emission 0.2.
pub fn reference_settings(scene: &mut Scene) {
    scene.transfer = presets::preset("slab-sphere").unwrap();
    scene.reference.model = OpticalModel::EmissiveScattering;
    scene.reference.step_voxels = scene.render.step_voxels;
    scene.reference.shadow_step_voxels = 0.125;
    scene.reference.min_transmittance = 1e-4;
    scene.render.emission = 0.2;
}

/// The IPSVI tests' known-shadow scene: a sphere over a slab
/// (synthetic::slab_under_sphere, 32^3) at `size`^2 with its reference.
pub fn ipsvi_slab_scene(lights: Vec<Light>, size: u32) -> Scene {
    let mut scene = scene_with(sweeplab::scene::synthetic::slab_under_sphere(32), lights, size, size);
    reference_settings(&mut scene);
    scene
}

/// The point light of the IPSVI tests.
pub fn point(position: Vec3) -> Light {
    Light {
        kind: LightKind::Point { position },
        color: Vec3::new(1.0, 0.9, 0.8),
        intensity: 1.5,
        falloff: Falloff::None,
    }
}

/// The ground truth of `gpu`'s scene at `width` x `height`, rendered once per
/// run of the suite: a test asking for a scene, volume format and size that
/// another test (or an earlier step of its own) asked for gets the image that
/// one rendered, with validation, instead of marching the brute-force shadow
/// rays again. The key is everything the reference reads (as
/// `sweeplab::techniques::ground_truth_cache` keys it); a test asking while
/// another renders the same key waits for that image.
pub fn reference_image(gpu: &GpuScene, width: u32, height: u32) -> LinearImage {
    static IMAGES: OnceLock<Mutex<HashMap<String, Arc<OnceLock<LinearImage>>>>> = OnceLock::new();
    let s = gpu.scene;
    let key = format!(
        "{:032x} {:?} {:?} | {:?} | {:?} | {:?} | {:?} | {:?} | {:?} {:?} | {width}x{height}",
        sweeplab::techniques::ao::cache::volume_content_hash(&s.volume),
        s.volume.dims,
        s.volume.spacing,
        s.transfer,
        s.camera,
        s.lights,
        s.render,
        s.reference,
        gpu.volume_format,
        gpu.filter,
    );
    let slot =
        IMAGES.get_or_init(Default::default).lock().unwrap_or_else(|p| p.into_inner()).entry(key).or_default().clone();
    slot.get_or_init(|| {
        let mut profiler = Profiler::new(gpu.ctx, 64).unwrap();
        techniques::render(gpu, Technique::Reference, width, height, &mut profiler).unwrap().image
    })
    .clone()
}
