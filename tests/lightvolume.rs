//! The light volume technique: its illumination volume against the analytic
//! transmittance of a homogeneous slab, its propagation groups and their
//! secondary command buffers, its image against the ground truth of model (i),
//! validation, and extreme intensities.
use crate::common;

use common::*;
use glam::{UVec3, Vec3};
use std::path::Path;
use sweeplab::linear_image::LinearImage;
use sweeplab::metrics::compare;
use sweeplab::reference::CpuRenderKind;
use sweeplab::render::{GpuScene, VolumeTexels};
use sweeplab::scene::synthetic::slab_under_sphere;
use sweeplab::scene::{
    presets, Camera, ControlPoint, Falloff, Light, LightKind, OpticalModel, Projection, Scene, TransferFunction,
    TransferLut, Volume, VolumeFilter, VoxelData,
};
use sweeplab::techniques::lightvolume::{render_frame, LightVolumeFrame, LightVolumeSettings};
use sweeplab::techniques::parse_scene_str;
use sweeplab::techniques::{render, Technique};
use sweeplab::vk::{Context, Profiler};

const SIZE: u32 = 48;

/// `lightvolume.shared_medium`: the medium sampled along the axis and shared by
/// the lights of a pass (exact for a homogeneous medium, like per light).
fn set_shared_medium(scene: &mut Scene, shared: bool) {
    scene.settings.get_mut::<LightVolumeSettings>().shared_medium = shared;
}

/// The light volume at `scale`, propagating model (i) (one transmittance, not
/// chromatic) with the medium integrated along each light's own direction:
/// the tests below state their tolerances against model (i) for that
/// propagation unless they set otherwise.
fn with_scale(mut scene: Scene, scale: u32) -> Scene {
    // Model (i) and the per-light propagation these tests were written for.
    scene.settings.set(LightVolumeSettings {
        scale,
        chromatic: false,
        shared_medium: false,
        ..LightVolumeSettings::default()
    });
    scene
}

fn frame(ctx: &Context, scene: &Scene, size: u32, read_illumination: bool) -> (LightVolumeFrame, Profiler) {
    let gpu = GpuScene::upload_with(ctx, scene, VolumeTexels::Float32).unwrap();
    let mut profiler = Profiler::new(ctx, 64).unwrap();
    profiler.reset();
    let out = render_frame(&gpu, size, size, &mut profiler, read_illumination).unwrap();
    (out, profiler)
}

/// An n^3 volume of one value: a homogeneous slab filling the whole box.
fn homogeneous_scene(n: u32, direction: Vec3, scale: u32) -> (Scene, f64) {
    let mut scene = with_scale(scene_with(homogeneous(n), vec![directional(direction, 1.5)], 16, 16), scale);
    scene.lights[0].color = Vec3::new(1.0, 0.5, 0.25);
    scene.transfer = TransferFunction {
        points: vec![
            ControlPoint { value: 0.0, rgba: [1.0, 1.0, 1.0, 0.0] },
            ControlPoint { value: 1.0, rgba: [1.0, 1.0, 1.0, 0.15] },
        ],
    };
    let sigma = scene.transfer.bake(TransferLut::DEFAULT_SIZE).sample(1.0)[3];
    (scene, sigma)
}

/// Errors of the illumination volume against `radiance * exp(-sigma * path(p))`,
/// `path` in data voxels from the voxel centre p to the box exit toward the
/// light: (largest relative error, largest absolute error over the radiance,
/// mean relative error).
fn errors_against_analytic(out: &LightVolumeFrame, sigma: f64, path: impl Fn(Vec3) -> f64) -> (f64, f64, f64) {
    let grid = out.grid;
    let volume = &out.illumination.as_ref().unwrap().high;
    let (mut worst, mut worst_abs, mut sum, mut count) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for z in 0..grid.z {
        for y in 0..grid.y {
            for x in 0..grid.x {
                let v = volume[(x + grid.x * (y + grid.y * z)) as usize];
                // Centre in [0, 1]^3 box coordinates.
                let uvw = (Vec3::new(x as f32, y as f32, z as f32) + 0.5) / grid.as_vec3();
                let expected = (-sigma * path(uvw)).exp() * 1.5;
                for (c, colour) in [1.0, 0.5, 0.25].into_iter().enumerate() {
                    let e = expected * colour;
                    let abs = (v[c] as f64 - e).abs();
                    worst = worst.max(abs / e);
                    worst_abs = worst_abs.max(abs / (1.5 * colour));
                    sum += abs / e;
                    count += 1.0;
                }
            }
        }
    }
    (worst, worst_abs, sum / count)
}

fn homogeneous(n: u32) -> Volume {
    Volume {
        name: "homogeneous".into(),
        dims: UVec3::splat(n),
        spacing: Vec3::ONE,
        data: VoxelData::U8(vec![255; (n * n * n) as usize]),
        value_range: (0.0, 255.0),
        non_finite_voxels: 0,
        interpolation: Default::default(),
    }
}

/// Stated tolerance of the slab test: the propagation integrates a homogeneous
/// medium exactly (opacity-corrected sub-steps), so what is left is f32
/// rounding of a few dozen products: relative error below 1e-4. The same with
/// 8-bit filter weights: a homogeneous medium has no neighbour differences, so
/// the error model (docs/filtering.md) adds nothing.
const SLAB_TOLERANCE: f64 = 1e-4;

#[test]
fn directional_light_straight_down_through_a_homogeneous_slab_gives_the_analytic_transmittance() {
    let ctx = validated_context();
    let n = 16;
    let cases = [(1, false), (2, false), (4, false), (1, true), (4, true)];
    for (filter, (scale, shared)) in VolumeFilter::ALL.into_iter().flat_map(|f| cases.map(|c| (f, c))) {
        let (mut scene, sigma) = homogeneous_scene(n, Vec3::NEG_Y, scale);
        scene.render.filter = filter;
        set_shared_medium(&mut scene, shared);
        let (out, _) = frame(&ctx, &scene, 16, true);
        assert_eq!(out.groups().len(), 1, "one group for a light straight down");
        assert_eq!(out.groups()[0].direction_name(), "-y");
        assert_eq!(out.grid, UVec3::splat(n / scale));
        // Depth below the top face in data voxels.
        let (worst, _, _) = errors_against_analytic(&out, sigma, |uvw| (1.0 - uvw.y as f64) * n as f64);
        println!(
            "{filter:?} scale {scale}, shared medium {shared}: grid {}, worst relative error {worst:.2e}",
            out.grid
        );
        assert!(worst <= SLAB_TOLERANCE, "{filter:?} scale {scale}, shared {shared}: worst relative error {worst:.2e}");
        assert!(out.image.as_ref().unwrap().all_finite());
    }
    assert_validation_clean(&ctx);
}

/// Stated tolerances of the oblique test, measured on lavapipe: bilinear
/// resampling from slice to slice overestimates the convex exp(-path), most
/// along the ridge where the face the light enters through changes, and the
/// error compounds with depth: mean relative error MEAN and largest absolute
/// error (transmittance units) ABS, measured 0.0513 and 0.1053 for this 16^3
/// volume at scale 1; the largest relative error, 0.81 in the deepest and
/// darkest voxels, is printed, not bounded.
const OBLIQUE_MEAN_TOLERANCE: f64 = 0.06;
const OBLIQUE_ABS_TOLERANCE: f64 = 0.12;

#[test]
fn oblique_directional_light_splits_into_two_groups_that_agree_with_the_analytic_transmittance() {
    let ctx = validated_context();
    let n = 16;
    let direction = Vec3::new(0.5, -1.0, 0.25);
    for shared in [false, true] {
        let (mut scene, sigma) = homogeneous_scene(n, direction, 1);
        set_shared_medium(&mut scene, shared);
        let (out, _) = frame(&ctx, &scene, 16, true);
        let names: Vec<String> = out.groups().iter().map(|g| g.direction_name()).collect();
        assert_eq!(names, ["+x", "-y"], "light travelling mostly down and toward +x");
        let sum: f32 = out.groups().iter().map(|g| g.members[0].factor).sum();
        assert!((sum - 1.0).abs() < 1e-5);
        let w = -direction.normalize();
        // Distance (data voxels) to the box exit along w from uvw in the unit cube.
        let path = |uvw: Vec3| {
            let t = (0..3)
                .map(|a| {
                    if w[a] > 0.0 {
                        (1.0 - uvw[a]) / w[a]
                    } else if w[a] < 0.0 {
                        -uvw[a] / w[a]
                    } else {
                        f32::MAX
                    }
                })
                .fold(f32::MAX, f32::min);
            t as f64 * n as f64
        };
        let (worst, worst_abs, mean) = errors_against_analytic(&out, sigma, path);
        println!("oblique, shared medium {shared}: mean relative error {mean:.4}, largest absolute {worst_abs:.4}, largest relative {worst:.4}");
        assert!(mean <= OBLIQUE_MEAN_TOLERANCE, "shared {shared}: mean relative error {mean:.4}");
        assert!(worst_abs <= OBLIQUE_ABS_TOLERANCE, "shared {shared}: largest absolute error {worst_abs:.4}");
    }
    assert_validation_clean(&ctx);
}

#[test]
fn lights_in_exactly_two_groups_record_exactly_two_group_passes() {
    let ctx = validated_context();
    let lights =
        vec![directional(Vec3::NEG_Y, 1.0), directional(Vec3::new(0.0, -1.0, 0.0), 0.5), directional(Vec3::X, 0.7)];
    let scene = with_scale(scene_with(slab_under_sphere(16), lights, 16, 16), 2);
    let (out, mut profiler) = frame(&ctx, &scene, 16, false);
    let profile = profiler.resolve(ctx.memory.device_local_peak()).unwrap();
    let groups: Vec<&str> =
        profile.scopes.iter().map(|s| s.name.as_str()).filter(|n| n.starts_with("lightvolume_group_")).collect();
    assert_eq!(groups, ["lightvolume_group_+x_1lights", "lightvolume_group_-y_2lights"]);
    // One dispatch per slice of each group (8 slices each) and the ray cast.
    assert_eq!(out.dispatches, 8 + 8 + 1);
    assert!(out.image.as_ref().unwrap().all_finite());
    assert_validation_clean(&ctx);
}

fn slab_sphere_scene(lights: Vec<Light>, scale: u32) -> Scene {
    let mut scene = with_scale(scene_with(slab_under_sphere(32), lights, SIZE, SIZE), scale);
    scene.transfer = presets::preset("slab-sphere").unwrap();
    scene.reference.model = OpticalModel::SingleScattering;
    // The same view march as the technique, and fine shadow rays: the error
    // left is the light volume's own.
    scene.reference.step_voxels = scene.render.step_voxels;
    scene.reference.shadow_step_voxels = 0.125;
    scene.render.emission = 0.2;
    scene
}

fn relative_rmse(test: &LinearImage, reference: &LinearImage) -> f64 {
    compare(test, reference).unwrap().rmse / reference.max_value() as f64
}

/// Stated tolerance against model (i) on the sphere-over-slab scene, 32^3 data,
/// 48x48, relative RMSE against the brightest reference value, measured on
/// lavapipe: scale 1 0.0496, unshaded DVR 0.1398. The light volume is an
/// approximation: light is known at illumination voxel centres only, and these
/// test volumes have surfaces one data voxel sharp (opacity 0.95 per voxel,
/// optical depth 3), so the view samples on a surface see light interpolated
/// between a voxel in air and one already deep in shadow (log-space
/// interpolation in the ray cast limits this), and the sphere's shadow is
/// resampled bilinearly from slice to slice. Coarser scales on these surfaces
/// are held by `coarser_illumination_volumes_converge_at_first_order` instead.
const RMSE_TOLERANCE: f64 = 0.055;
/// With the medium shared by the lights of a pass (sampled along the axis, not
/// along the light), scale 1: measured 0.0575 (0.0496 per light).
const SHARED_MEDIUM_TOLERANCE: f64 = 0.065;

/// (light volume, unshaded DVR) relative RMSE against the reference, and the
/// reference's peak.
fn light_volume_and_dvr_error(ctx: &Context, scene: &Scene) -> (f64, f64, f64) {
    let gpu = GpuScene::upload_with(ctx, scene, VolumeTexels::Float32).unwrap();
    let mut profiler = Profiler::new(ctx, 64).unwrap();
    let out = render(&gpu, Technique::LightVolume, SIZE, SIZE, &mut profiler).unwrap();
    assert!(out.image.all_finite());
    let reference = common::reference_image(&gpu, SIZE, SIZE);
    let unshaded = render(&gpu, Technique::Dvr, SIZE, SIZE, &mut profiler).unwrap().image;
    (relative_rmse(&out.image, &reference), relative_rmse(&unshaded, &reference), reference.max_value() as f64)
}

/// In both volume filters: with 8-bit weights the stated tolerance grows by
/// twice the error model's RMS bound (docs/filtering.md), relative to the peak.
#[test]
fn sphere_over_slab_matches_model_i_within_the_stated_tolerance() {
    let ctx = validated_context();
    for filter in VolumeFilter::ALL {
        for (shared, tolerance) in [(false, RMSE_TOLERANCE), (true, SHARED_MEDIUM_TOLERANCE)] {
            let mut scene = slab_sphere_scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)], 1);
            scene.render.filter = filter;
            set_shared_medium(&mut scene, shared);
            let (rmse, dvr, peak) = light_volume_and_dvr_error(&ctx, &scene);
            let kind = CpuRenderKind::Reference(OpticalModel::SingleScattering);
            let tolerance = tolerance + 2.0 * filter_bound_rms(&scene, kind, SIZE) / peak;
            println!(
                "{filter:?}, scale 1, shared medium {shared}: relative rmse {rmse:.4} (unshaded DVR {dvr:.4}), allowed {tolerance:.4}"
            );
            assert!(rmse <= tolerance, "{filter:?} shared {shared}: relative rmse {rmse:.4} above {tolerance}");
            assert!(rmse < 0.5 * dvr, "rmse {rmse:.4} not clearly below unshaded DVR's {dvr:.4}");
        }
    }
    assert_validation_clean(&ctx);
}

/// The error of scales 2 and 4 is the illumination grid's: it grows with the
/// illumination voxel, at first order (about twice per doubling), so a medium
/// that the coarse grid resolves is lit well at every scale. Measured on the
/// sphere over the slab with opacity 0.3 per data voxel (optical depth 0.36, 1.4
/// per scale-4 voxel): scale 1 0.0143, 2 0.0273, 4 0.0442 against unshaded DVR
/// 0.1107. On the one-voxel-sharp surfaces above (optical depth 3 per data
/// voxel, so 6 inside one scale-2 voxel) the same order gives scale 2 0.1155:
/// no better than unshaded DVR there, which is what the coarse scale trades
/// (docs/lightvolume.md); a scene needs scale 1 for surfaces that sharp.
#[test]
fn coarser_illumination_volumes_converge_at_first_order() {
    let ctx = validated_context();
    let mut errors = Vec::new();
    for scale in [1, 2, 4] {
        let mut scene = slab_sphere_scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)], scale);
        for p in &mut scene.transfer.points {
            p.rgba[3] = p.rgba[3].min(0.3);
        }
        let (rmse, dvr, _) = light_volume_and_dvr_error(&ctx, &scene);
        println!("opacity 0.3, scale {scale}: relative rmse {rmse:.4} (unshaded DVR {dvr:.4})");
        // Every scale lights this medium far better than no lighting at all.
        assert!(rmse < 0.5 * dvr, "scale {scale}: rmse {rmse:.4} against unshaded DVR's {dvr:.4}");
        errors.push(rmse);
    }
    for pair in errors.windows(2) {
        let order = (pair[1] / pair[0]).log2();
        println!("observed order of convergence in the illumination voxel: {order:.2}");
        assert!((0.5..=1.5).contains(&order), "errors {errors:?}: order {order:.2} is not first order");
    }
    assert!(errors[0] <= 0.02, "scale 1 on a resolved medium: {errors:?}");
    assert_validation_clean(&ctx);
}

fn every_light_kind(intensity: f32) -> Vec<Light> {
    vec![
        Light {
            kind: LightKind::Directional { direction: Vec3::new(-0.4, -1.0, 0.3) },
            color: Vec3::new(1.0, 0.9, 0.8),
            intensity,
            falloff: Falloff::None,
        },
        Light {
            kind: LightKind::Point { position: Vec3::new(0.9, 0.4, -0.3) },
            color: Vec3::new(0.6, 0.8, 1.0),
            intensity,
            falloff: Falloff::InverseSquare,
        },
        spot_light(intensity),
        // Inside the volume: its second group carries light against its direction.
        Light {
            kind: LightKind::Point { position: Vec3::new(0.1, 0.2, 0.05) },
            color: Vec3::ONE,
            intensity,
            falloff: Falloff::None,
        },
    ]
}

#[test]
fn every_light_kind_renders_validation_clean() {
    let ctx = validated_context();
    for scale in [1, 2, 4] {
        let scene = slab_sphere_scene(every_light_kind(1.0), scale);
        let (out, _) = frame(&ctx, &scene, 24, true);
        assert!(out.image.as_ref().unwrap().all_finite(), "scale {scale}");
        let volume = out.illumination.unwrap().high;
        assert!(volume.iter().all(|v| v.iter().all(|c| c.is_finite() && *c >= 0.0)), "scale {scale}");
        assert!(volume.iter().any(|v| v[0] > 0.0), "scale {scale}: no light at all");
    }
    assert_validation_clean(&ctx);
}

#[test]
fn extreme_intensities_give_finite_output() {
    let ctx = validated_context();
    for intensity in [1e-6, 1e6] {
        let scene = slab_sphere_scene(every_light_kind(intensity), 2);
        let (out, _) = frame(&ctx, &scene, 16, true);
        assert!(out.image.as_ref().unwrap().all_finite(), "intensity {intensity}");
        assert!(
            out.illumination.unwrap().high.iter().all(|v| v.iter().all(|c| c.is_finite())),
            "intensity {intensity}"
        );
    }
    assert_validation_clean(&ctx);
}

#[test]
fn no_lights_renders_the_emission_term_and_bad_settings_are_errors() {
    let ctx = validated_context();
    let scene = slab_sphere_scene(vec![], 2);
    let (out, _) = frame(&ctx, &scene, 16, false);
    assert!(out.groups().is_empty());
    assert_eq!(out.dispatches, 1, "the ray cast alone");
    assert!(out.image.as_ref().unwrap().all_finite());
    // Set in code: refused when rendered.
    let mut bad = slab_sphere_scene(vec![directional(Vec3::NEG_Y, 1.0)], 2);
    bad.settings.get_mut::<LightVolumeSettings>().scale = 3;
    let gpu = GpuScene::upload(&ctx, &bad).unwrap();
    let mut profiler = Profiler::new(&ctx, 64).unwrap();
    assert!(render(&gpu, Technique::LightVolume, 8, 8, &mut profiler).is_err(), "scale = 3");
    // Written in a scene file: refused when the file is read.
    for table in ["[lightvolume]\nscale = 3\n", "[lightvolume]\nscale = 2\nalbedo = 1\n", "lightvolume = 2\n"] {
        let text = format!("[volume]\nsynthetic = \"slab-under-sphere\"\nsize = 8\n{table}");
        assert!(parse_scene_str(&text, Path::new(""), "bad.toml", &[]).is_err(), "{table}");
    }
    assert_validation_clean(&ctx);
}

/// Point and spot lights against model (i) at scale 1 on the sphere-over-slab
/// scene (48x48), relative RMSE measured on lavapipe: point light outside the
/// volume 0.0486, spot light 0.0283, point light inside the volume 0.0467
/// (0.0559 when its second group could not carry the light travelling
/// against it); unshaded DVR 0.137, 0.122, 0.197.
#[test]
fn point_and_spot_lights_match_model_i_at_full_resolution() {
    let ctx = validated_context();
    let cases = [
        ("point outside", LightKind::Point { position: Vec3::new(0.3, 1.2, 0.2) }, Falloff::None, 2.0, 0.055),
        (
            "spot",
            LightKind::Spot {
                position: Vec3::new(0.2, 1.2, 0.3),
                direction: Vec3::new(-0.1, -1.0, -0.2),
                inner_cone_deg: 15.0,
                outer_cone_deg: 30.0,
            },
            Falloff::InverseSquare,
            2.0,
            0.035,
        ),
        ("point inside", LightKind::Point { position: Vec3::new(0.15, 0.35, 0.1) }, Falloff::None, 1.5, 0.065),
    ];
    for (what, kind, falloff, intensity, tolerance) in cases {
        let light = Light { kind, color: Vec3::ONE, intensity, falloff };
        let scene = slab_sphere_scene(vec![light], 1);
        let gpu = GpuScene::upload_with(&ctx, &scene, VolumeTexels::Float32).unwrap();
        let mut profiler = Profiler::new(&ctx, 64).unwrap();
        let out = render(&gpu, Technique::LightVolume, SIZE, SIZE, &mut profiler).unwrap().image;
        let reference = common::reference_image(&gpu, SIZE, SIZE);
        let unshaded = render(&gpu, Technique::Dvr, SIZE, SIZE, &mut profiler).unwrap().image;
        let rmse = relative_rmse(&out, &reference);
        let dvr = relative_rmse(&unshaded, &reference);
        println!("{what}: relative rmse {rmse:.4} (unshaded DVR {dvr:.4})");
        assert!(out.all_finite(), "{what}");
        assert!(rmse <= tolerance, "{what}: relative rmse {rmse:.4} above {tolerance}");
        assert!(rmse < 0.5 * dvr, "{what}: rmse {rmse:.4} not clearly below unshaded DVR's {dvr:.4}");
    }
    assert_validation_clean(&ctx);
}

fn peak_of(volume: &[[f32; 4]]) -> f32 {
    volume.iter().flat_map(|v| v[..3].iter().copied()).fold(0.0f32, f32::max)
}

fn largest_difference(a: &[[f32; 4]], b: &[[f32; 4]]) -> f32 {
    a.iter().zip(b).flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).abs())).fold(0.0f32, f32::max)
}

/// Coherence-based propagation shares group passes between lights; sequential
/// propagation (the paper's baseline) gives every light and face its own pass.
/// Both must build the same illumination volume.
#[test]
fn coherent_and_sequential_propagation_give_the_same_volume() {
    let ctx = validated_context();
    let lights = vec![
        directional(Vec3::new(0.2, -1.0, 0.1), 1.0),
        directional(Vec3::new(-0.3, -1.0, 0.2), 0.5),
        directional(Vec3::new(1.0, -0.4, 0.0), 0.7),
    ];
    let mut volumes = Vec::new();
    let mut passes = Vec::new();
    for (coherent, shared) in [(true, false), (false, false), (true, true), (false, true)] {
        let mut scene = scene_with(slab_under_sphere(16), lights.clone(), 16, 16);
        scene.settings.set(LightVolumeSettings {
            scale: 2,
            coherent,
            shared_medium: shared,
            ..LightVolumeSettings::default()
        });
        let (out, _) = frame(&ctx, &scene, 16, true);
        passes.push(out.groups().len());
        volumes.push(out.illumination.unwrap().high);
    }
    assert!(passes[1] > passes[0], "sequential must take more passes: {passes:?}");
    for pair in [0, 2] {
        let (peak, worst) = (peak_of(&volumes[pair]), largest_difference(&volumes[pair], &volumes[pair + 1]));
        assert!(peak > 0.1);
        let shared = pair == 2;
        assert!(worst <= 1e-5 * peak, "coherent and sequential differ by {worst} (peak {peak}, shared {shared})");
    }
    // Sharing the medium changes the volume (it is an approximation), not wildly.
    let peak = peak_of(&volumes[0]);
    let shared_change = largest_difference(&volumes[0], &volumes[2]);
    println!("shared medium changes the volume by up to {:.4} of its peak", shared_change / peak);
    assert!(shared_change > 0.0 && shared_change < 0.5 * peak);
    assert_validation_clean(&ctx);
}

/// The homogeneous cube of `homogeneous_scene` seen side-on (orthographic,
/// horizontal view rays, so an image row is a depth below the top face), with
/// no emission and a black background: every pixel is the lit part alone. The
/// reference's view march is the technique's; its shadow rays are exact in a
/// homogeneous medium.
fn side_view_of_the_lit_cube(scale: u32, chromatic: bool) -> Scene {
    let (mut scene, _) = homogeneous_scene(16, Vec3::NEG_Y, scale);
    scene.settings.set(LightVolumeSettings { scale, chromatic, ..LightVolumeSettings::default() });
    if chromatic {
        for p in &mut scene.transfer.points {
            p.rgba[..3].copy_from_slice(&[0.8, 0.5, 0.2]);
        }
    }
    scene.camera = Camera::orbit(Vec3::ZERO, 3.0, 0.0, 0.0, Projection::Orthographic { height: 1.25 });
    scene.render.emission = 0.0;
    scene.render.background = Vec3::ZERO;
    scene.reference.model = OpticalModel::SingleScattering;
    scene.reference.chromatic = chromatic;
    scene.reference.step_voxels = scene.render.step_voxels;
    scene
}

/// Stated tolerance of the face test: the light volume holds the exact
/// transmittance at voxel centres (slab test) and log(light) is linear in the
/// depth, so its log-space interpolation, extrapolated over the half voxel
/// between the outermost centres and the faces, is exact up to f32 rounding:
/// largest relative error per pixel below 2e-4 (measured about 1e-5). Clamping
/// at the outermost centres instead was off by the transmittance of half an
/// illumination voxel in the first and last lit rows (measured: -4.0 % and
/// +4.1 % at scale 1 here).
const FACE_TOLERANCE: f64 = 2e-4;

#[test]
fn a_homogeneous_cube_lit_straight_down_is_exact_at_every_depth_including_the_faces() {
    let ctx = validated_context();
    let size = 40;
    for chromatic in [false, true] {
        for scale in [1, 2, 4] {
            let scene = side_view_of_the_lit_cube(scale, chromatic);
            let gpu = GpuScene::upload_with(&ctx, &scene, VolumeTexels::Float32).unwrap();
            let mut profiler = Profiler::new(&ctx, 64).unwrap();
            let out = render(&gpu, Technique::LightVolume, size, size, &mut profiler).unwrap().image;
            let reference = common::reference_image(&gpu, size, size);
            let floor = 1e-3 * reference.max_value();
            // Largest relative error of each row that sees the cube.
            let rows: Vec<(u32, f64)> = (0..size)
                .filter_map(|y| {
                    let worst = (0..size)
                        .flat_map(|x| {
                            let i = (y * size + x) as usize;
                            let (a, b) = (out.pixels[i], reference.pixels[i]);
                            (0..3).filter(move |&c| b[c] > floor).map(move |c| ((a[c] - b[c]) / b[c]).abs() as f64)
                        })
                        .reduce(f64::max)?;
                    Some((y, worst))
                })
                .collect();
            let (first, last) = (rows[0], rows[rows.len() - 1]);
            let worst = rows.iter().map(|r| r.1).fold(0.0, f64::max);
            println!(
                "chromatic {chromatic}, scale {scale}: {} lit rows, first row {} error {:.2e}, last row {} error {:.2e}, \
                 worst {worst:.2e}",
                rows.len(),
                first.0,
                first.1,
                last.0,
                last.1
            );
            // The cube spans 32 rows: the half-voxel layers at the faces are in the image.
            assert!(rows.len() >= 30, "{rows:?}");
            assert!(worst <= FACE_TOLERANCE, "chromatic {chromatic}, scale {scale}: rows {rows:?}");
        }
    }
    assert_validation_clean(&ctx);
}

/// The illumination volume of `scene` against `expected(voxel centre)` over the
/// voxels where `expected` is some: (largest error over the largest expected
/// value, mean relative error), and the smallest value per octant of the box.
fn volume_against(out: &LightVolumeFrame, expected: impl Fn(Vec3) -> Option<f64>) -> (f64, f64, [f64; 8]) {
    let grid = out.grid;
    let volume = out.illumination.as_ref().unwrap();
    let (mut worst, mut peak, mut sum, mut count) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let mut octant_least = [f64::INFINITY; 8];
    for z in 0..grid.z {
        for y in 0..grid.y {
            for x in 0..grid.x {
                let i = (x + grid.x * (y + grid.y * z)) as usize;
                let uvw = (Vec3::new(x as f32, y as f32, z as f32) + 0.5) / grid.as_vec3();
                let p = uvw - 0.5;
                let Some(e) = expected(p) else { continue };
                let v = volume.value(i, 0);
                worst = worst.max((v - e).abs());
                peak = peak.max(e);
                sum += (v - e).abs() / e;
                count += 1.0;
                let octant = (p.x > 0.0) as usize + 2 * (p.y > 0.0) as usize + 4 * (p.z > 0.0) as usize;
                octant_least[octant] = octant_least[octant].min(v / e);
            }
        }
    }
    (worst / peak, sum / count, octant_least)
}

/// Stated tolerances for a point light at the centre of the homogeneous cube
/// (16^3, scale 1, model (i)), against the analytic `exp(-sigma * distance)`,
/// measured on lavapipe: largest error 0.0057 of the peak and mean relative
/// error 0.0063, with the medium along the light or shared alike; every voxel
/// gets at least 0.983 of its light (the old two groups left half the cube
/// dark). The image against the model (i) ground truth: relative RMSE 0.0046
/// (unshaded DVR 0.47).
const CENTRE_WORST: f64 = 0.01;
const CENTRE_MEAN: f64 = 0.01;
const LEAST_SHARE: f64 = 0.97;
const CENTRE_RMSE: f64 = 0.008;

#[test]
fn a_point_light_at_the_centre_of_a_homogeneous_cube_lights_all_octants() {
    let ctx = validated_context();
    let n = 16;
    for shared in [false, true] {
        let (mut scene, sigma) = homogeneous_scene(n, Vec3::NEG_Y, 1);
        set_shared_medium(&mut scene, shared);
        scene.lights[0].kind = LightKind::Point { position: Vec3::ZERO };
        scene.lights[0].color = Vec3::ONE;
        scene.reference.step_voxels = scene.render.step_voxels;
        scene.reference.shadow_step_voxels = 0.25;
        let (out, _) = frame(&ctx, &scene, 16, true);
        let mut names: Vec<String> = out.groups().iter().map(|g| g.direction_name()).collect();
        names.sort();
        assert_eq!(names, ["+x", "+y", "+z", "-x", "-y", "-z"], "all six groups");
        let expected = |p: Vec3| Some(1.5 * (-sigma * (p.length() * n as f32) as f64).exp());
        let (worst, mean, least) = volume_against(&out, expected);
        println!("point light at the centre, shared medium {shared}: largest error {worst:.4} of the peak, mean relative {mean:.4}, least share per octant {least:.3?}");
        assert!(worst <= CENTRE_WORST && mean <= CENTRE_MEAN, "shared {shared}: {worst:.4} {mean:.4}");
        assert!(least.iter().all(|&l| l >= LEAST_SHARE), "an octant is left dark: {least:?}");
        let gpu = GpuScene::upload_with(&ctx, &scene, VolumeTexels::Float32).unwrap();
        let mut profiler = Profiler::new(&ctx, 64).unwrap();
        let image = render(&gpu, Technique::LightVolume, SIZE, SIZE, &mut profiler).unwrap().image;
        let reference = common::reference_image(&gpu, SIZE, SIZE);
        let unshaded = render(&gpu, Technique::Dvr, SIZE, SIZE, &mut profiler).unwrap().image;
        let (rmse, dvr) = (relative_rmse(&image, &reference), relative_rmse(&unshaded, &reference));
        println!("  image: relative rmse {rmse:.4} (unshaded DVR {dvr:.4})");
        assert!(rmse <= CENTRE_RMSE, "shared {shared}: relative rmse {rmse:.4}");
    }
    assert_validation_clean(&ctx);
}

/// Stated tolerance for a spot light inside the cube pointing away from the
/// centre (hard cone, model (i)): inside the cone (5 degrees clear of its edge)
/// the largest error is below 0.01 of the peak (measured 0.0059 along +x,
/// one pass; see the printed figure for the cone between +x and -y, two
/// passes); outside it (5 degrees clear) the light is below 1e-6 of the peak.
const SPOT_INSIDE_WORST: f64 = 0.01;

#[test]
fn a_spot_light_inside_pointing_away_from_the_centre_lights_what_its_cone_covers() {
    let ctx = validated_context();
    let n = 16;
    let position = Vec3::new(0.1, 0.0, 0.0);
    // A cone along an axis fits one pass; one between two axes, inside both
    // half-spaces, fits the two passes of a directional light along it.
    for (direction, outer, passes) in
        [(Vec3::X, 30.0f32, vec!["+x"]), (Vec3::new(1.0, -0.6, 0.0), 20.0, vec!["+x", "-y"])]
    {
        let (mut scene, sigma) = homogeneous_scene(n, Vec3::NEG_Y, 1);
        scene.lights[0].kind = LightKind::Spot { position, direction, inner_cone_deg: outer, outer_cone_deg: outer };
        scene.lights[0].color = Vec3::ONE;
        let (out, _) = frame(&ctx, &scene, 16, true);
        let names: Vec<String> = out.groups().iter().map(|g| g.direction_name()).collect();
        assert_eq!(names, passes, "spot along {direction}, cone {outer}");
        let angle = |p: Vec3| (p - position).angle_between(direction).to_degrees();
        let lit = |p: Vec3| {
            (angle(p) < outer - 5.0).then(|| 1.5 * (-sigma * ((p - position).length() * n as f32) as f64).exp())
        };
        let (worst, mean, _) = volume_against(&out, lit);
        println!("spot inside along {direction}: largest error {worst:.4} of the peak inside the cone, mean relative {mean:.4}");
        assert!(worst <= SPOT_INSIDE_WORST, "inside the cone: {worst:.4}");
        let volume = out.illumination.as_ref().unwrap();
        let grid = out.grid;
        let peak = (0..volume.high.len()).map(|i| volume.value(i, 0)).fold(0.0, f64::max);
        for i in 0..volume.high.len() {
            let (x, y, z) = (i as u32 % grid.x, i as u32 / grid.x % grid.y, i as u32 / (grid.x * grid.y));
            let p = (Vec3::new(x as f32, y as f32, z as f32) + 0.5) / grid.as_vec3() - 0.5;
            if angle(p) > outer + 5.0 {
                assert!(volume.value(i, 0).abs() <= 1e-6 * peak, "light outside the cone at {p}");
            }
        }
    }
    assert_validation_clean(&ctx);
}
