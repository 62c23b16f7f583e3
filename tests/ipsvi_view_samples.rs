//! IPSVI with `cache_update = "view-samples"` (the paper's mechanism, section
//! 4.3): against the ground truth of model (ii), the figure 5 scene that plain
//! early ray termination gets wrong, the line barrier under synchronization
//! validation, and what each write resolution does with the race.
use crate::common;

use common::*;
use glam::{UVec3, Vec3};
use sweeplab::linear_image::LinearImage;
use sweeplab::metrics::compare;
use sweeplab::reference::CpuRenderKind;
use sweeplab::render::{GpuScene, VolumeTexels};
use sweeplab::scene::settings_table::SettingsTable;
use sweeplab::scene::synthetic::slab_under_sphere;
use sweeplab::scene::{
    Camera, ControlPoint, Light, OpticalModel, Projection, Scene, TransferFunction, Volume, VolumeFilter, VoxelData,
};
use sweeplab::techniques::ipsvi::{
    render_study, CacheUpdate, CacheWrite, EarlyTermination, IpsviSettings, IpsviStudy, ReadFronts, SyncStrategy,
    WritePass, WriteRule, WriteValue,
};

use sweeplab::vk::{Context, Profiler};

pub(crate) const SIZE: u32 = 48;

fn slab_scene(lights: Vec<Light>) -> Scene {
    ipsvi_slab_scene(lights, SIZE)
}

pub(crate) fn view_samples(cache_size: u32, cache_write: CacheWrite) -> IpsviSettings {
    IpsviSettings {
        cache_size,
        light_step_voxels: 0.125,
        cache_update: CacheUpdate::ViewSamples,
        cache_write,
        ..IpsviSettings::default()
    }
}

pub(crate) fn ipsvi(ctx: &Context, gpu: &GpuScene, s: &IpsviSettings, sync: SyncStrategy) -> LinearImage {
    render_at(ctx, gpu, s, &IpsviStudy::default(), sync, SIZE)
}

fn render_at(
    ctx: &Context,
    gpu: &GpuScene,
    s: &IpsviSettings,
    study: &IpsviStudy,
    sync: SyncStrategy,
    size: u32,
) -> LinearImage {
    let mut profiler = Profiler::new(ctx, 8192).unwrap();
    profiler.reset();
    render_study(gpu, s, study, size, size, &mut profiler, sync).unwrap().image
}

pub(crate) fn reference(_ctx: &Context, gpu: &GpuScene) -> LinearImage {
    common::reference_image(gpu, SIZE, SIZE)
}

/// RMSE relative to the brightest reference value.
pub(crate) fn relative_rmse(test: &LinearImage, reference: &LinearImage) -> f64 {
    compare(test, reference).unwrap().rmse / reference.max_value() as f64
}

/// Figure 5 of the paper in a 32^3 volume: an opaque wall A in front (toward
/// the camera) hides a block B behind it; light from above carries B's shadow
/// onto the floor C, which the camera sees under A.
fn figure5_scene(with_b: bool) -> Scene {
    let n = 32u32;
    let inside = |i: UVec3, lo: [u32; 3], hi: [u32; 3]| (0..3).all(|a| i[a] >= lo[a] && i[a] < hi[a]);
    let mut data = Vec::with_capacity((n * n * n) as usize);
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                let i = UVec3::new(x, y, z);
                let floor = inside(i, [2, 2, 2], [30, 6, 30]);
                let hidden = with_b && inside(i, [10, 18, 8], [22, 24, 14]);
                let wall = inside(i, [6, 14, 23], [26, 28, 27]);
                data.push(if floor || hidden || wall { 255u8 } else { 0 });
            }
        }
    }
    let volume = Volume {
        name: "figure-5".into(),
        dims: UVec3::splat(n),
        spacing: Vec3::ONE,
        data: VoxelData::U8(data),
        value_range: (0.0, 255.0),
        non_finite_voxels: 0,
        interpolation: Default::default(),
    };
    let mut scene = scene_with(volume, vec![directional(Vec3::new(0.1, -1.0, 0.05), 2.0)], SIZE, SIZE);
    reference_settings(&mut scene);
    // This volume is binary: an opaque band at 255 (what "slab-sphere" was
    // before it became ramps for smooth volumes, and what the figures below
    // were measured with) keeps wall A opaque on every sample.
    let (grey, orange, slab) = ([0.8, 0.8, 0.8], [1.0, 0.6, 0.3], 128.0 / 255.0);
    let at = |value: f32, [r, g, b]: [f32; 3], alpha: f32| ControlPoint { value, rgba: [r, g, b, alpha] };
    let points = vec![
        at(0.0, grey, 0.0),
        at(slab - 0.04, grey, 0.0),
        at(slab - 0.02, grey, 0.95),
        at(slab + 0.02, grey, 0.95),
        at(slab + 0.04, grey, 0.0),
        at(0.96, orange, 0.0),
        at(0.98, orange, 0.95),
        at(1.0, orange, 0.95),
        at(1.0, orange, 0.95),
    ];
    scene.transfer = TransferFunction { points };
    scene.camera = Camera::orbit(Vec3::ZERO, 2.5, 0.0, 12.0, Projection::Perspective { fov_y_deg: 30.0 });
    scene
}

/// RMSE (relative to the reference's peak) over the pixels `mask` selects.
fn masked_rmse(test: &LinearImage, reference: &LinearImage, mask: &[bool]) -> f64 {
    let (mut sum, mut count) = (0.0f64, 0usize);
    for ((a, b), _) in test.pixels.iter().zip(&reference.pixels).zip(mask).filter(|(_, m)| **m) {
        sum += (0..3).map(|c| ((a[c] - b[c]) as f64).powi(2)).sum::<f64>() / 3.0;
        count += 1;
    }
    (sum / count.max(1) as f64).sqrt() / reference.max_value() as f64
}

/// The pixels the hidden block B changes in the ground truth (its shadow on C:
/// B itself is hidden behind A), by more than 5% of the peak.
fn shadow_of_b(ctx: &Context) -> Vec<bool> {
    let (with_b, without_b) = (figure5_scene(true), figure5_scene(false));
    let a = reference(ctx, &GpuScene::upload_with(ctx, &with_b, VolumeTexels::Float32).unwrap());
    let b = reference(ctx, &GpuScene::upload_with(ctx, &without_b, VolumeTexels::Float32).unwrap());
    let peak = a.max_value();
    a.pixels.iter().zip(&b.pixels).map(|(p, q)| (0..3).any(|c| (p[c] - q[c]).abs() > 0.05 * peak)).collect()
}

/// Cache texels about as many as pixels (48 for 48x48): the samples of a line
/// then really feed the texels the next line reads. (With the 256 cache of
/// tests/ipsvi.rs most texels a sample reads were never written, and piecewise
/// integration marches back to the box entry: exact, and tested there at the
/// light-rays tolerance.)
pub(crate) const FED_CACHE: u32 = 48;

/// The stated tolerance of view-samples mode at FED_CACHE against model (ii),
/// relative RMSE: 1.5% for a directional light, 3.5% for point and spot lights
/// (measured on lavapipe 0.97%, and 0.38% to 2.36%, two lights 1.65%; light-rays
/// mode at the same cache 0.95%, and 0.36% to 1.96%), so the bounds keep about
/// half of the measured error as margin. Why worse than light rays: a texel holds the light at one
/// depth along its ray, written by one sample of the previous line; a reader
/// nearer the light than that depth cannot march back and is over-attenuated,
/// and bilinear reads mix texels written at different depths. Light-rays mode
/// keeps every texel's front on the sweep plane, so neither happens there.
/// (Texel-ray writes store at the texel ray's crossing of the writer's line
/// plane, the paper's cache plane; before, at the sample's own depth, the
/// errors were 1.05% and 0.41% to 2.64%: NON_EMPTY_OVER_LIGHT_RAYS.)
pub(crate) const DIRECTIONAL_TOLERANCE: f64 = 0.015;
pub(crate) const POINT_TOLERANCE: f64 = 0.035;
/// Summed over the eight scenes, non-empty's relative RMSE over light rays':
/// measured 1.13 (storing at the sample's own depth instead of the plane
/// crossing: 1.25, which this bound rejects).
const NON_EMPTY_OVER_LIGHT_RAYS: f64 = 1.2;
/// `write_rule = "every-sample"` (Listing 4.1: empty samples write too; the
/// default), same scenes and cache: 1.4% directional, 3% point and spot, each
/// tighter than non-empty's. Measured on lavapipe 0.95% directional and
/// 0.36-1.96% point and spot (non-empty 0.97% and 0.38-2.36%), so the bounds
/// keep about half of the measured error as margin.
/// Why it is tighter: every run end, empty ones included, moves its texel's
/// depth to the current line, so a reader marches back about one line, never
/// to a depth written many lines before, and a reader nearer the light than the
/// stored depth (over-attenuated, see above) is rare: the writes keep pace with
/// the sweep.
const EVERY_SAMPLE_DIRECTIONAL_TOLERANCE: f64 = 0.014;
const EVERY_SAMPLE_POINT_TOLERANCE: f64 = 0.03;

#[test]
fn view_samples_match_the_reference_on_the_ipsvi_scenes() {
    let ctx = validated_context();
    let camera = scene_with(slab_under_sphere(8), vec![], SIZE, SIZE).camera;
    let basis = camera.basis(SIZE, SIZE);
    let (r, u) = (basis.right.normalize(), basis.up.normalize());
    let mut spot = slab_scene(vec![spot_light(2.0)]);
    spot.camera.projection = Projection::Orthographic { height: 1.8 };
    let cases = vec![
        ("directional", slab_scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)]), DIRECTIONAL_TOLERANCE),
        ("right zone", slab_scene(vec![point(r * 1.2 + u * 0.3)]), POINT_TOLERANCE),
        ("left zone", slab_scene(vec![point(-r * 1.2 + u * 0.2)]), POINT_TOLERANCE),
        ("up zone", slab_scene(vec![point(u * 1.2 + r * 0.2)]), POINT_TOLERANCE),
        ("down zone", slab_scene(vec![point(-u * 1.2 - r * 0.2)]), POINT_TOLERANCE),
        ("inside the volume", slab_scene(vec![point(Vec3::new(0.15, 0.35, 0.1))]), POINT_TOLERANCE),
        ("orthographic, spot", spot, POINT_TOLERANCE),
        (
            "two lights",
            slab_scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), 1.0), point(-r * 1.2 + u * 0.2)]),
            POINT_TOLERANCE,
        ),
    ];
    // write_value = "texel-ray" (the default) against the paper's "sample".
    let (mut texel_ray_sum, mut sample_sum, mut every_sum, mut light_rays_sum) = (0.0, 0.0, 0.0, 0.0);
    for (what, scene, tolerance) in &cases {
        let gpu = GpuScene::upload_with(&ctx, scene, VolumeTexels::Float32).unwrap();
        let truth = reference(&ctx, &gpu);
        let light_rays =
            IpsviSettings { cache_update: CacheUpdate::LightRays, ..view_samples(FED_CACHE, CacheWrite::Racy) };
        let lr = relative_rmse(&ipsvi(&ctx, &gpu, &light_rays, SyncStrategy::BarrierGlobal), &truth);
        let vs_settings =
            IpsviSettings { write_rule: WriteRule::NonEmpty, ..view_samples(FED_CACHE, CacheWrite::Farthest) };
        assert_eq!(vs_settings.write_value, WriteValue::TexelRay);
        let vs_image = ipsvi(&ctx, &gpu, &vs_settings, SyncStrategy::BarrierGlobal);
        assert!(vs_image.all_finite(), "{what}: non-finite pixels");
        let vs = relative_rmse(&vs_image, &truth);
        let sample = IpsviSettings { write_value: WriteValue::Sample, ..vs_settings };
        let vs_sample = relative_rmse(&ipsvi(&ctx, &gpu, &sample, SyncStrategy::BarrierGlobal), &truth);
        let every = IpsviSettings { write_rule: WriteRule::EverySample, ..vs_settings.clone() };
        let every_image = ipsvi(&ctx, &gpu, &every, SyncStrategy::BarrierGlobal);
        assert!(every_image.all_finite(), "{what}: every-sample: non-finite pixels");
        let vs_every = relative_rmse(&every_image, &truth);
        println!(
            "{what}: relative rmse view-samples {vs:.4} (sample writes {vs_sample:.4}, every-sample {vs_every:.4}), light-rays {lr:.4}"
        );
        assert!(vs <= *tolerance, "{what}: view-samples relative rmse {vs:.4} > {tolerance}");
        let every_tolerance = if *tolerance == DIRECTIONAL_TOLERANCE {
            EVERY_SAMPLE_DIRECTIONAL_TOLERANCE
        } else {
            EVERY_SAMPLE_POINT_TOLERANCE
        };
        assert!(vs_every <= every_tolerance, "{what}: every-sample relative rmse {vs_every:.4} > {every_tolerance}");
        texel_ray_sum += vs;
        sample_sum += vs_sample;
        every_sum += vs_every;
        light_rays_sum += lr;
    }
    // Every-sample, the default, is no farther overall: measured 0.0668 against
    // 0.0683. (0.092 against 0.104 before the slab-sphere preset's slab band
    // was widened: the grey film the sphere wore, which every-sample caught
    // more of, was most of the difference; CHANGELOG.md.)
    println!("sum of relative rmse: every-sample {every_sum:.4}, non-empty {texel_ray_sum:.4}");
    assert!(every_sum <= texel_ray_sum, "every-sample {every_sum:.4} vs non-empty {texel_ray_sum:.4}");
    let over = texel_ray_sum / light_rays_sum;
    println!("non-empty over light rays, summed: {over:.3}");
    assert!(over <= NON_EMPTY_OVER_LIGHT_RAYS, "non-empty {texel_ray_sum:.4} vs light rays {light_rays_sum:.4}");
    // With 8-bit filter weights (docs/filtering.md): the stated tolerance plus
    // twice the error model's RMS bound, relative to the peak.
    for (what, scene, tolerance) in &cases {
        let mut scene = scene.clone();
        scene.render.filter = VolumeFilter::Gpu8Bit;
        let gpu = GpuScene::upload_with(&ctx, &scene, VolumeTexels::Float32).unwrap();
        let truth = reference(&ctx, &gpu);
        let vs = relative_rmse(
            &ipsvi(&ctx, &gpu, &view_samples(FED_CACHE, CacheWrite::Farthest), SyncStrategy::BarrierGlobal),
            &truth,
        );
        let kind = CpuRenderKind::Reference(OpticalModel::EmissiveScattering);
        let allowed = tolerance + 2.0 * filter_bound_rms(&scene, kind, SIZE) / truth.max_value() as f64;
        println!("{what}, 8-bit weights: relative rmse view-samples {vs:.4}, allowed {allowed:.4}");
        assert!(vs <= allowed, "{what}, 8-bit weights: view-samples relative rmse {vs:.4} > {allowed:.4}");
    }
    println!("sum of relative rmse: texel-ray writes {texel_ray_sum:.4}, sample writes {sample_sum:.4}");
    assert!(
        texel_ray_sum < 0.9 * sample_sum,
        "texel-ray writes should not blur the light at every line: {texel_ray_sum:.4} vs {sample_sum:.4}"
    );
    assert_validation_clean(&ctx);
}

/// Figure 5: plain early ray termination stops the view rays at A, so B never
/// reaches the cache and C is lit where B shadows it; exit points (section 5.1)
/// march those rays on far enough. Measured without piecewise integration,
/// where the cache is all a sample knows of the light. With it, a texel B never
/// wrote still has its front at the box entry, and the march from C back to it
/// passes through B: piecewise integration hides figure 5 here (printed).
#[test]
fn plain_early_termination_loses_the_hidden_feature_and_exit_points_recover_it() {
    let ctx = validated_context();
    let shadow = shadow_of_b(&ctx);
    assert!(shadow.iter().filter(|m| **m).count() >= 10, "B must shadow part of the image");
    let scene = figure5_scene(true);
    let gpu = GpuScene::upload_with(&ctx, &scene, VolumeTexels::Float32).unwrap();
    let truth = reference(&ctx, &gpu);
    for piecewise in [false, true] {
        let mut error = Vec::new();
        for ert in [EarlyTermination::Off, EarlyTermination::Plain, EarlyTermination::ExitPoints] {
            let s =
                IpsviSettings { piecewise, early_termination: ert, ..view_samples(FED_CACHE, CacheWrite::Farthest) };
            error.push(masked_rmse(&ipsvi(&ctx, &gpu, &s, SyncStrategy::BarrierGlobal), &truth, &shadow));
        }
        let light_rays = IpsviSettings {
            piecewise,
            cache_update: CacheUpdate::LightRays,
            ..view_samples(FED_CACHE, CacheWrite::Farthest)
        };
        let lr = masked_rmse(&ipsvi(&ctx, &gpu, &light_rays, SyncStrategy::BarrierGlobal), &truth, &shadow);
        println!(
            "piecewise {piecewise}: relative rmse in B's shadow: off {:.4}, plain {:.4}, exit-points {:.4} (light-rays plain {lr:.4})",
            error[0], error[1], error[2]
        );
        if !piecewise {
            // Measured 0.148 / 0.547 / 0.206.
            assert!(error[1] > 2.0 * error[2], "plain should lose B's shadow: {error:?}");
            assert!(error[2] < 1.5 * error[0], "exit points should recover it: {error:?}");
        }
    }
    assert_validation_clean(&ctx);
}

/// The barrier after each line block is load-bearing in both modes, with
/// every write resolution, both write rules, both write values and both store
/// layouts (`packed_store`): without it synchronization validation reports the
/// hazard on the cache. At the bit-identity tests' size, cache and volume
/// format (below), so that most of its variants are theirs: on a fresh
/// machine (16x16, a 32-texel cache and an 8-bit volume) they compiled apart.
#[test]
fn line_barrier_is_reported_missing_in_both_modes() {
    let ctx = validated_context();
    let scene = ipsvi_slab_scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)], IDENTITY_SIZE);
    let gpu = GpuScene::upload_with(&ctx, &scene, VolumeTexels::Float32).unwrap();
    let mut profiler = Profiler::new(&ctx, 64).unwrap();
    let modes = [
        (CacheUpdate::LightRays, CacheWrite::Racy),
        (CacheUpdate::ViewSamples, CacheWrite::Racy),
        (CacheUpdate::ViewSamples, CacheWrite::Farthest),
        (CacheUpdate::ViewSamples, CacheWrite::Nearest),
    ];
    for (cache_update, cache_write) in modes {
        for write_rule in WriteRule::ALL {
            if cache_update == CacheUpdate::LightRays && write_rule != WriteRule::NonEmpty {
                continue; // light rays do not use the rule
            }
            let writes = WriteValue::ALL.into_iter().flat_map(|v| [(v, false), (v, true)]);
            for ((write_value, packed_store), write_pass) in writes.flat_map(|w| WritePass::RUN.map(|p| (w, p))) {
                if cache_update == CacheUpdate::LightRays && write_value != WriteValue::TexelRay {
                    continue;
                }
                let s = IpsviSettings {
                    cache_size: IDENTITY_SIZE,
                    cache_update,
                    cache_write,
                    write_rule,
                    write_value,
                    packed_store,
                    write_pass,
                    ..IpsviSettings::default()
                };
                // The claim pass's barriers too, where line width 1 leaves it out.
                let study = IpsviStudy { keep_redundant_claims: true, ..IpsviStudy::default() };
                if (write_pass == WritePass::Texel && !s.texel_pass()) || s.validate().is_err() {
                    continue; // light rays have no write pass; the texel pass needs texel-ray claims
                }
                assert_ipsvi_line_barrier_load_bearing(
                    &ctx,
                    &gpu,
                    &s,
                    &study,
                    &mut profiler,
                    IDENTITY_SIZE,
                    &format!(
                        "{cache_update:?}/{cache_write:?}/{write_rule:?}/{write_value:?}/packed {packed_store}/{} pass",
                        write_pass.name()
                    ),
                );
            }
        }
    }
}

/// Image size of the bit-identity tests below, with a cache of as many
/// texels (as FED_CACHE at SIZE): two ways of recording the same frame give
/// the same image at any size. Not a power of two, like SIZE and FED_CACHE:
/// llvmpipe compiles a shader per power-of-two-ness of its images, so these
/// tests share the module's compiled variants (at 32 they compiled their own).
const IDENTITY_SIZE: u32 = 24;

/// A bit-identity test's frame: IDENTITY_SIZE, barriers.
fn identity_frame(ctx: &Context, gpu: &GpuScene, s: &IpsviSettings, study: &IpsviStudy) -> LinearImage {
    render_at(ctx, gpu, s, study, SyncStrategy::BarrierGlobal, IDENTITY_SIZE)
}

/// View samples with the bit-identity tests' fed cache.
fn identity_samples(cache_write: CacheWrite) -> IpsviSettings {
    view_samples(IDENTITY_SIZE, cache_write)
}

/// One light of each kind the bit-identity tests compare on, at
/// IDENTITY_SIZE: directional, a point in the right zone, a point inside the
/// volume, a spot.
fn four_light_setups() -> [(&'static str, Scene); 4] {
    let size = IDENTITY_SIZE;
    let camera = scene_with(slab_under_sphere(8), vec![], size, size).camera;
    let basis = camera.basis(size, size);
    let (r, u) = (basis.right.normalize(), basis.up.normalize());
    let scene = |lights| ipsvi_slab_scene(lights, size);
    [
        ("directional", scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)])),
        ("right zone", scene(vec![point(r * 1.2 + u * 0.3)])),
        ("inside the volume", scene(vec![point(Vec3::new(0.15, 0.35, 0.1))])),
        ("spot", scene(vec![spot_light(2.0)])),
    ]
}

/// At one line per block with texel-ray writes every writer of a texel stores
/// the same value, so the claim pass is left out (`records_claims`): the image
/// is that of the recorded claims bit for bit, on directional, point and spot
/// lights, under both resolutions and both write rules; at two lines per block
/// the pass stays.
#[test]
fn the_claim_pass_left_out_at_one_line_per_block_changes_nothing() {
    let ctx = validated_context();
    let scenes = four_light_setups();
    let plain = IpsviStudy::default();
    for (what, scene) in &scenes {
        let gpu = GpuScene::upload_with(&ctx, scene, VolumeTexels::Float32).unwrap();
        for write in [CacheWrite::Farthest, CacheWrite::Nearest] {
            for write_rule in WriteRule::ALL {
                // The sample pass: the texel pass needs the claims.
                let left_out = IpsviSettings { write_rule, write_pass: WritePass::Sample, ..identity_samples(write) };
                let kept = IpsviStudy { keep_redundant_claims: true, ..IpsviStudy::default() };
                assert!(!left_out.records_claims() && left_out.claims_recorded(kept.keep_redundant_claims));
                let (a, b) =
                    (identity_frame(&ctx, &gpu, &left_out, &plain), identity_frame(&ctx, &gpu, &left_out, &kept));
                assert!(a == b, "{what}, {}, {write_rule:?}: the image changed without the claim pass", write.name());
            }
        }
    }
    // Blocks of two lines lie in two planes: there the winner matters, and the
    // comparison above would see it (racy stores against the claimed ones).
    let two_lines =
        IpsviSettings { line_width: 2, write_pass: WritePass::Sample, ..identity_samples(CacheWrite::Farthest) };
    assert!(two_lines.records_claims());
    let gpu = GpuScene::upload_with(&ctx, &scenes[1].1, VolumeTexels::Float32).unwrap();
    let claimed = identity_frame(&ctx, &gpu, &two_lines, &plain);
    let racy = identity_frame(&ctx, &gpu, &IpsviSettings { cache_write: CacheWrite::Racy, ..two_lines }, &plain);
    assert!(claimed != racy, "at two lines per block the claims must change the image");
    assert_validation_clean(&ctx);
}

/// `packed_store` (value and code in one rgba32ui texel, one store instead of
/// two) gives the two-store image bit for bit: light rays, and view samples
/// under both claimed resolutions, both write rules and both write values, at
/// one and two lines per block, on directional, point and spot lights.
#[test]
fn the_packed_store_is_bit_identical_to_two_stores() {
    let ctx = validated_context();
    let mut modes = vec![IpsviSettings { cache_update: CacheUpdate::LightRays, ..identity_samples(CacheWrite::Racy) }];
    for write in [CacheWrite::Farthest, CacheWrite::Nearest] {
        for write_rule in WriteRule::ALL {
            for write_value in WriteValue::ALL {
                modes.push(IpsviSettings { write_rule, write_value, ..identity_samples(write) });
            }
        }
    }
    modes.push(IpsviSettings { line_width: 2, ..identity_samples(CacheWrite::Farthest) });
    let plain = IpsviStudy::default();
    for (what, scene) in &four_light_setups() {
        let gpu = GpuScene::upload_with(&ctx, scene, VolumeTexels::Float32).unwrap();
        for two in &modes {
            let packed = IpsviSettings { packed_store: true, ..two.clone() };
            let (a, b) = (identity_frame(&ctx, &gpu, two, &plain), identity_frame(&ctx, &gpu, &packed, &plain));
            let mode = format!(
                "{what}, {:?} {} {:?} {:?} lw {}",
                two.cache_update,
                two.cache_write.name(),
                two.write_rule,
                two.write_value,
                two.line_width
            );
            assert!(a.pixels.iter().any(|p| p[0] > 0.0), "{mode}: the image is black");
            assert!(a == b, "{mode}: the packed store changed the image");
        }
    }
    assert_validation_clean(&ctx);
}

/// `write_pass = "texel"` (the claim march names the texels a block's runs end
/// in; the block's texel invocations march and store them) gives the image of
/// the sample loop's stores bit for bit: both claimed resolutions, both write
/// rules, one and two lines per block (where the key's pixel picks the plane),
/// packed and two stores, on directional, point (outside and inside the
/// volume) and spot lights; and with merged sweeps, exit points and the
/// visible box. The claim pass is then recorded even at one line per block.
#[test]
fn the_texel_write_pass_is_bit_identical_to_the_sample_loop() {
    let ctx = validated_context();
    let plain = IpsviStudy::default();
    let mut modes = Vec::new();
    for write in [CacheWrite::Farthest, CacheWrite::Nearest] {
        for write_rule in WriteRule::ALL {
            for line_width in [1, 2] {
                modes.push(IpsviSettings { write_rule, line_width, ..identity_samples(write) });
            }
        }
    }
    let base = identity_samples(CacheWrite::Farthest);
    modes.push(IpsviSettings { packed_store: true, ..base.clone() });
    modes.push(IpsviSettings { packed_store: true, line_width: 2, ..base.clone() });
    modes.push(IpsviSettings { merge_sweeps: true, ..base.clone() });
    modes.push(IpsviSettings { early_termination: EarlyTermination::ExitPoints, ..base.clone() });
    modes.push(IpsviSettings { fit_to_visible: true, ..base.clone() });
    for (what, scene) in &four_light_setups() {
        let gpu = GpuScene::upload_with(&ctx, scene, VolumeTexels::Float32).unwrap();
        for mode in &modes {
            let sample = &IpsviSettings { write_pass: WritePass::Sample, ..mode.clone() };
            let texel = IpsviSettings { write_pass: WritePass::Texel, ..mode.clone() };
            assert!(texel.texel_pass() && texel.records_claims() && texel.validate().is_ok());
            assert!(!sample.texel_pass() && mode.texel_pass(), "auto takes the texel pass");
            let (a, b) = (identity_frame(&ctx, &gpu, sample, &plain), identity_frame(&ctx, &gpu, &texel, &plain));
            let mode = format!(
                "{what}, {} {:?} lw {} packed {} merged {} {:?} visible box {}",
                sample.cache_write.name(),
                sample.write_rule,
                sample.line_width,
                sample.packed_store,
                sample.merge_sweeps,
                sample.early_termination,
                sample.fit_to_visible
            );
            assert!(a.pixels.iter().any(|p| p[0] > 0.0), "{mode}: the image is black");
            if a != b {
                let d = compare(&b, &a).unwrap();
                panic!("{mode}: the texel pass changed the image (rmse {:e}, max {:e})", d.rmse, d.max_abs);
            }
        }
    }
    assert_validation_clean(&ctx);
}

/// Claimed writes (farthest, nearest) give the same image every frame; the
/// paper's racy store may not (printed: whether it differed on this device),
/// and what the resolution changes against the racy store.
#[test]
fn claimed_writes_are_deterministic_and_racy_writes_are_reported() {
    let ctx = validated_context();
    let camera = scene_with(slab_under_sphere(8), vec![], SIZE, SIZE).camera;
    let basis = camera.basis(SIZE, SIZE);
    let scene = slab_scene(vec![point(basis.right.normalize() * 1.2 + basis.up.normalize() * 0.3)]);
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let mut images = Vec::new();
    for write in CacheWrite::ALL {
        let s = IpsviSettings { line_width: 2, ..view_samples(FED_CACHE, write) };
        let first = ipsvi(&ctx, &gpu, &s, SyncStrategy::BarrierGlobal);
        let mut differing = 0;
        for _ in 0..4 {
            let again = ipsvi(&ctx, &gpu, &s, SyncStrategy::BarrierGlobal);
            differing += (again != first) as u32;
        }
        println!("{}: {differing} of 4 repeated frames differ from the first", write.name());
        if write.claims() {
            assert_eq!(differing, 0, "{}: claimed writes must repeat exactly", write.name());
        }
        images.push(first);
    }
    let peak = images[0].max_value() as f64;
    for i in 1..images.len() {
        let d = compare(&images[i], &images[0]).unwrap();
        println!(
            "{} vs racy: relative rmse {:.5}, max {:.5}",
            CacheWrite::ALL[i].name(),
            d.rmse / peak,
            d.max_abs / peak
        );
    }
    assert_validation_clean(&ctx);
}

/// The breakdown test's image size and cache, the command line's breakdown
/// test's (`--sizes 16`, `ipsvi.cache_size=16`, an 8-bit volume of a power of
/// two): the same shader variants.
const BREAKDOWN_SIZE: u32 = 16;

/// The breakdown's steps (bench ipsvi --breakdown) run validation-clean; the
/// last is the IPSVI frame bit for bit, and with view samples (farthest claims,
/// texel-ray writes: every part on) each earlier step leaves a part out and
/// renders another image; with light rays every step from the carry (their
/// texel advance) on is the frame. Both write rules. Per-texel fronts at
/// BREAKDOWN_SIZE, as the command line's breakdown test reads at its 16 px
/// (cli.rs): the same shader variants, which a fresh machine then compiles
/// once, not twice.
#[test]
fn breakdown_steps_end_in_the_ipsvi_frame() {
    use sweeplab::techniques::ipsvi::BreakdownStep;
    let ctx = validated_context();
    let scene = slab_scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)]);
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let carry = BreakdownStep::ALL.iter().position(|s| *s == BreakdownStep::Carry).unwrap();
    let cases = [
        (CacheUpdate::ViewSamples, WriteRule::NonEmpty, WritePass::Sample),
        (CacheUpdate::ViewSamples, WriteRule::EverySample, WritePass::Sample),
        (CacheUpdate::ViewSamples, WriteRule::NonEmpty, WritePass::Texel),
        (CacheUpdate::ViewSamples, WriteRule::EverySample, WritePass::Texel),
        (CacheUpdate::LightRays, WriteRule::NonEmpty, WritePass::Sample),
    ];
    for (cache_update, write_rule, write_pass) in cases {
        let s = IpsviSettings {
            cache_update,
            write_rule,
            write_pass,
            read_fronts: ReadFronts::PerTexel,
            ..view_samples(BREAKDOWN_SIZE, CacheWrite::Farthest)
        };
        let frame = render_at(&ctx, &gpu, &s, &IpsviStudy::default(), SyncStrategy::BarrierGlobal, BREAKDOWN_SIZE);
        let steps: Vec<LinearImage> = BreakdownStep::ALL
            .iter()
            .map(|&breakdown_step| {
                let study = IpsviStudy { breakdown_step, ..IpsviStudy::default() };
                render_at(&ctx, &gpu, &s, &study, SyncStrategy::BarrierGlobal, BREAKDOWN_SIZE)
            })
            .collect();
        let what = format!("{cache_update:?}/{write_rule:?}/{write_pass:?}");
        assert_eq!(steps.last(), Some(&frame), "{what}: the full step is the frame");
        for (i, step) in steps[..steps.len() - 1].iter().enumerate() {
            let rmse = compare(step, &frame).unwrap().rmse;
            if cache_update == CacheUpdate::LightRays && i >= carry {
                assert_eq!(step, &frame, "{what}: step {i}: light rays write everything in the carry step");
            } else {
                assert!(rmse > 1e-5, "{what}: step {i} should differ (rmse {rmse:e})");
            }
        }
        // Without the cache the light is unshadowed: brighter overall.
        let sum = |img: &LinearImage| img.pixels.iter().map(|p| (p[0] + p[1] + p[2]) as f64).sum::<f64>();
        assert!(sum(&steps[0]) > sum(&frame), "{what}: no cache, no shadow");
    }
    assert_validation_clean(&ctx);
}

/// `empty_runs_move_depth`: bit for bit a no-op under `write_rule =
/// "non-empty"` (no run is empty there), and under "every-sample" a bounded
/// change: an empty run's write skips the march along its texel's own ray
/// over about one line, so it drops what medium that short stretch crosses
/// (the view ray's samples in the texel were empty, the texel's ray need not be).
#[test]
fn empty_runs_move_depth_is_exact_without_empty_runs_and_bounded_with_them() {
    let ctx = validated_context();
    let camera = scene_with(slab_under_sphere(8), vec![], SIZE, SIZE).camera;
    let basis = camera.basis(SIZE, SIZE);
    let cases = [
        ("directional", slab_scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)])),
        ("right zone", slab_scene(vec![point(basis.right.normalize() * 1.2 + basis.up.normalize() * 0.3)])),
    ];
    for (what, scene) in &cases {
        let gpu = GpuScene::upload_with(&ctx, scene, VolumeTexels::Float32).unwrap();
        let truth = reference(&ctx, &gpu);
        let non_empty =
            IpsviSettings { write_rule: WriteRule::NonEmpty, ..view_samples(FED_CACHE, CacheWrite::Farthest) };
        let moved = IpsviSettings { empty_runs_move_depth: true, ..non_empty.clone() };
        assert_eq!(
            ipsvi(&ctx, &gpu, &non_empty, SyncStrategy::BarrierGlobal),
            ipsvi(&ctx, &gpu, &moved, SyncStrategy::BarrierGlobal),
            "{what}: non-empty has no empty runs"
        );
        let every = IpsviSettings { write_rule: WriteRule::EverySample, ..non_empty };
        let every_moved = IpsviSettings { empty_runs_move_depth: true, ..every.clone() };
        let (marched, moved) = (
            ipsvi(&ctx, &gpu, &every, SyncStrategy::BarrierGlobal),
            ipsvi(&ctx, &gpu, &every_moved, SyncStrategy::BarrierGlobal),
        );
        let change = relative_rmse(&moved, &marched);
        let (e_marched, e_moved) = (relative_rmse(&marched, &truth), relative_rmse(&moved, &truth));
        println!("{what}: every-sample rmse {e_marched:.4}, moving empty runs {e_moved:.4}; change {change:.5}");
        assert!(change > 0.0, "{what}: every-sample has empty runs, so the skip must show");
        assert!(change <= EMPTY_RUN_CHANGE_BOUND, "{what}: change {change:.5} > {EMPTY_RUN_CHANGE_BOUND}");
    }
    assert_validation_clean(&ctx);
}

/// Relative RMSE between every-sample with and without the empty-run march:
/// measured 0.034 (directional) and 0.005 (right zone), which is why the skip
/// is an option and off by default (the error against the ground truth grows
/// from 1.0% to 3.6% on the directional case: an empty run just above a
/// surface moves the depth across the surface's edge on the texel's ray).
const EMPTY_RUN_CHANGE_BOUND: f64 = 0.05;
