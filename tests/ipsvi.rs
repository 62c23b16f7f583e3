//! IPSVI against the ground truth of model (ii), its per-line barrier under
//! synchronization validation, what it leaves out, and extreme cases.
use crate::common;

use common::*;
use glam::Vec3;
use sweeplab::linear_image::LinearImage;
use sweeplab::metrics::compare;
use sweeplab::render::{GpuScene, VolumeTexels};
use sweeplab::scene::synthetic::slab_under_sphere;
use sweeplab::scene::{Light, Projection, Scene};
use sweeplab::techniques::ipsvi::renderer::plans;
use sweeplab::techniques::ipsvi::{render_with, CacheUpdate, IpsviSettings, ReadFronts, SyncStrategy, WriteRule};
use sweeplab::techniques::{render, RenderOutput, Technique};
use sweeplab::vk::{Context, Profiler};

const SIZE: u32 = 48;

/// The known-shadow scene: a sphere over a slab (synthetic::slab_under_sphere).
fn slab_scene(lights: Vec<Light>) -> Scene {
    let mut scene = ipsvi_slab_scene(lights, SIZE);
    // What `render` (no explicit settings) uses: the settings of the tolerance.
    scene.settings.set(IpsviSettings { cache_size: 256, light_step_voxels: 0.125, ..IpsviSettings::default() });
    scene
}

fn ipsvi_and_reference(ctx: &Context, scene: &Scene, settings: &IpsviSettings) -> (RenderOutput, LinearImage) {
    let gpu = GpuScene::upload_with(ctx, scene, VolumeTexels::Float32).unwrap();
    let mut profiler = Profiler::new(ctx, 8192).unwrap();
    profiler.reset();
    let frame = render_with(&gpu, settings, SIZE, SIZE, &mut profiler, SyncStrategy::BarrierGlobal).unwrap();
    let profile = profiler.resolve(ctx.memory.device_local_peak()).unwrap();
    let ipsvi = RenderOutput {
        technique: Technique::Ipsvi,
        image: frame.image,
        profile,
        dispatches: frame.dispatches,
        barriers: frame.barriers,
        shape: frame.shape,
    };
    let reference = common::reference_image(&gpu, SIZE, SIZE);
    (ipsvi, reference)
}

/// The stated tolerance of IPSVI against model (ii) (line width 1, piecewise
/// integration, cache 256, light step 0.125 voxel like the reference's shadow
/// rays), relative to the brightest reference value: RMSE within 2%, and 99% of
/// the pixels within 8%. Single pixels may be off by more: on these hard-surfaced
/// test volumes the light terminator is one texel sharp, and the cache's bilinear
/// lookup puts such a sample partly in shadow. (With a 0.5-voxel light step the
/// discretization of the hard surfaces alone costs 3-6% RMSE: a speed knob.)
const RMSE_TOLERANCE: f64 = 0.02;
const P99_TOLERANCE: f64 = 0.08;

/// The 99th percentile of per-pixel max-channel errors.
fn p99_error(test: &LinearImage, reference: &LinearImage) -> f64 {
    let mut e: Vec<f32> = test
        .pixels
        .iter()
        .zip(&reference.pixels)
        .map(|(a, b)| (0..3).map(|c| (a[c] - b[c]).abs()).fold(0.0, f32::max))
        .collect();
    e.sort_by(f32::total_cmp);
    e[(e.len() * 99 / 100).min(e.len() - 1)] as f64
}

fn settings() -> IpsviSettings {
    IpsviSettings { cache_size: 256, light_step_voxels: 0.125, ..IpsviSettings::default() }
}

/// The tolerance scenes: a directional light, a point light in each zone and
/// inside the volume, an orthographic camera with a spot light.
fn tolerance_scenes() -> Vec<(&'static str, Scene)> {
    let camera = scene_with(slab_under_sphere(8), vec![], SIZE, SIZE).camera;
    let basis = camera.basis(SIZE, SIZE);
    let (r, u) = (basis.right.normalize(), basis.up.normalize());
    let mut spot = slab_scene(vec![spot_light(2.0)]);
    spot.camera.projection = Projection::Orthographic { height: 1.8 };
    vec![
        ("directional", slab_scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)])),
        ("right zone", slab_scene(vec![point(r * 1.2 + u * 0.3)])),
        ("left zone", slab_scene(vec![point(-r * 1.2 + u * 0.2)])),
        ("up zone", slab_scene(vec![point(u * 1.2 + r * 0.2)])),
        ("down zone", slab_scene(vec![point(-u * 1.2 - r * 0.2)])),
        ("inside the volume", slab_scene(vec![point(Vec3::new(0.15, 0.35, 0.1))])),
        ("orthographic, spot", spot),
    ]
}

/// The relative RMSE and p99 of `s` on `scene` against its reference.
fn relative_errors(ctx: &Context, scene: &Scene, s: &IpsviSettings) -> (f64, f64) {
    let (ipsvi, reference) = ipsvi_and_reference(ctx, scene, s);
    assert!(ipsvi.image.all_finite());
    let peak = reference.max_value() as f64;
    (compare(&ipsvi.image, &reference).unwrap().rmse / peak, p99_error(&ipsvi.image, &reference) / peak)
}

/// Both write rules on every tolerance scene, held to the stated tolerance,
/// and `write_rule = "every-sample"` (the default, the paper's) to bounds
/// four times tighter: relative RMSE within EVERY_RMSE and p99 within
/// EVERY_P99 on each. Measured on lavapipe: at most 0.17 % RMSE and 0.90 % p99 (summed RMSE 0.0073), so the bounds keep
/// about half as margin. Non-empty is the closer rule on this cache (summed
/// 0.0055; on a like scene 32-bit cache texels err the same, so it is not the
/// halves' rounding). Our reading: at about 0.16 px most texels a non-empty
/// sample reads were never written, so its march goes back to the box entry
/// along its own light ray, which is exact, where every-sample's reads blend
/// texels carried along their own rays, a fraction of a pixel to the side. On
/// texels near a pixel every-sample is the closer rule
/// (tests/ipsvi_view_samples.rs; docs/ipsvi.md).
const EVERY_RMSE: f64 = 0.005;
const EVERY_P99: f64 = 0.02;

#[test]
fn every_tolerance_scene_meets_the_stated_tolerance_and_every_sample_four_times_tighter() {
    let ctx = validated_context();
    let every = settings();
    assert_eq!(every.write_rule, WriteRule::EverySample, "the default rule");
    let non_empty = IpsviSettings { write_rule: WriteRule::NonEmpty, ..settings() };
    let (mut every_sum, mut non_empty_sum) = (0.0, 0.0);
    for (what, scene) in tolerance_scenes() {
        let (e_rmse, e_p99) = relative_errors(&ctx, &scene, &every);
        let (n_rmse, n_p99) = relative_errors(&ctx, &scene, &non_empty);
        println!("{what}: every-sample rmse {e_rmse:.4} p99 {e_p99:.4}; non-empty rmse {n_rmse:.4} p99 {n_p99:.4}");
        assert!(e_rmse <= EVERY_RMSE && e_p99 <= EVERY_P99, "{what}: every-sample rmse {e_rmse:.4}, p99 {e_p99:.4}");
        assert!(
            n_rmse <= RMSE_TOLERANCE && n_p99 <= P99_TOLERANCE,
            "{what}: non-empty rmse {n_rmse:.4}, p99 {n_p99:.4}"
        );
        every_sum += e_rmse;
        non_empty_sum += n_rmse;
    }
    println!("summed relative rmse: every-sample {every_sum:.4}, non-empty {non_empty_sum:.4}");
    assert_validation_clean(&ctx);
}

/// `read_fronts = "auto"` takes per-texel fronts on this cache (256 texels,
/// about 0.16 px), and they are what holds either rule to the tolerance
/// there: blended fronts mix texels written at this line with texels no
/// sample reached for many lines into one depth that fits neither. Bound:
/// per texel at most PER_TEXEL_OVER_BLENDED of blended's relative RMSE on the
/// point light inside the volume (measured every-sample 0.0007 against
/// 0.0144, p99 0.0040 against 0.0862, beyond the stated 8 %; non-empty 0.0004
/// against 0.0038).
const PER_TEXEL_OVER_BLENDED: f64 = 0.25;

#[test]
fn per_texel_fronts_hold_both_rules_on_texels_finer_than_pixels() {
    let ctx = validated_context();
    let scene = slab_scene(vec![point(Vec3::new(0.15, 0.35, 0.1))]);
    for write_rule in [WriteRule::EverySample, WriteRule::NonEmpty] {
        let auto = IpsviSettings { write_rule, ..settings() };
        assert_eq!(auto.read_fronts, ReadFronts::Auto);
        assert!(auto.per_texel_fronts(&scene, SIZE, SIZE), "auto should take per-texel fronts at cache 256");
        let per_texel = IpsviSettings { read_fronts: ReadFronts::PerTexel, ..auto.clone() };
        let blended = IpsviSettings { read_fronts: ReadFronts::Blended, ..auto.clone() };
        let (p_rmse, p_p99) = relative_errors(&ctx, &scene, &per_texel);
        let (b_rmse, b_p99) = relative_errors(&ctx, &scene, &blended);
        let (a_rmse, _) = relative_errors(&ctx, &scene, &auto);
        println!(
            "inside the volume, {}: per-texel rmse {p_rmse:.4} p99 {p_p99:.4}, blended rmse {b_rmse:.4} p99 {b_p99:.4}",
            write_rule.name()
        );
        assert_eq!(a_rmse, p_rmse, "auto is per-texel here");
        assert!(
            p_rmse <= PER_TEXEL_OVER_BLENDED * b_rmse,
            "{write_rule:?}: per-texel {p_rmse:.4} vs blended {b_rmse:.4}"
        );
    }
    assert_validation_clean(&ctx);
}

#[test]
fn piecewise_integration_lowers_the_error_of_wide_lines() {
    let scene = slab_scene(vec![directional(Vec3::new(0.6, -1.0, 0.1), 2.0)]);
    let ctx = validated_context();
    let mut errors = Vec::new();
    for piecewise in [false, true] {
        let s = IpsviSettings { line_width: 8, piecewise, ..settings() };
        let (ipsvi, reference) = ipsvi_and_reference(&ctx, &scene, &s);
        errors.push(compare(&ipsvi.image, &reference).unwrap().rmse);
    }
    println!("line width 8: rmse without PI {:.5}, with PI {:.5}", errors[0], errors[1]);
    assert!(errors[1] < errors[0] * 0.8, "piecewise integration should cut the error: {errors:?}");
    assert_validation_clean(&ctx);
}

/// The barrier between line blocks is load-bearing: without it synchronization
/// validation reports the hazard on the ping-pong cache.
#[test]
fn sweep_without_line_barriers_is_reported_by_synchronization_validation() {
    let scene = slab_scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)]);
    let ctx = validated_context();
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let mut profiler = Profiler::new(&ctx, 64).unwrap();
    let s = IpsviSettings { cache_size: 32, ..IpsviSettings::default() };
    assert_ipsvi_line_barrier_load_bearing(&ctx, &gpu, &s, &Default::default(), &mut profiler, 16, "default settings");
}

#[test]
fn one_dispatch_per_line_block_and_only_inside_the_projected_box() {
    let mut scene = slab_scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)]);
    // Zoomed out: the volume covers a small part of the image.
    scene.camera =
        sweeplab::scene::Camera::orbit(Vec3::ZERO, 6.0, 30.0, 20.0, Projection::Perspective { fov_y_deg: 30.0 });
    let ctx = validated_context();
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    // Light rays: no claim dispatch ahead of the first block (tests/ipsvi_view_samples.rs).
    let s = IpsviSettings {
        line_width: 4,
        cache_size: 32,
        cache_update: CacheUpdate::LightRays,
        ..IpsviSettings::default()
    };
    let plan = &plans(&gpu, &s, SIZE, SIZE)[0];
    let lines = plan.lines();
    assert!(lines > 4 && lines < SIZE / 2, "the box spans {lines} of {SIZE} lines");
    let mut profiler = Profiler::new(&ctx, 64).unwrap();
    profiler.reset();
    let frame = render_with(&gpu, &s, SIZE, SIZE, &mut profiler, SyncStrategy::BarrierGlobal).unwrap();
    // One cache init per sweep, one dispatch per block: first block 1 line, then 4.
    assert_eq!(frame.dispatches, 1 + plan.dispatches());
    assert_eq!(plan.dispatches(), 1 + (lines - 1).div_ceil(4));
}

#[test]
fn no_light_means_no_sweep_and_no_cache() {
    let ctx = validated_context();
    // The cache pair of light-rays mode (view samples add their pair and claim keys).
    let mut lit = slab_scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)]);
    lit.settings.get_mut::<IpsviSettings>().cache_update = CacheUpdate::LightRays;
    let dark = slab_scene(vec![]);
    let mut memory = Vec::new();
    for scene in [&dark, &lit] {
        let gpu = GpuScene::upload(&ctx, scene).unwrap();
        let mut profiler = Profiler::new(&ctx, 64).unwrap();
        let out = render(&gpu, Technique::Ipsvi, 16, 16, &mut profiler).unwrap();
        memory.push((out.dispatches, out.profile.gpu_memory_bytes));
        if scene.lights.is_empty() {
            assert_eq!(out.dispatches, 1, "emission-only ray casting, no sweep");
            assert!(out.profile.passes.iter().all(|p| !p.name.starts_with("ipsvi")));
        }
    }
    let cache_bytes = 256u64 * 256 * (8 + 2) * 2;
    // The lit frame holds the cache pair on top of what the dark frame holds (plus
    // small parameter buffers).
    let extra = memory[1].1 - memory[0].1;
    assert!(extra >= cache_bytes && extra < cache_bytes + 64 * 1024, "extra {extra} for a cache of {cache_bytes}");
    assert_validation_clean(&ctx);
}

/// What the lights add: the frame minus the same scene rendered without lights
/// (emission and background alone), so a test of "lit" cannot pass on the
/// background or the emission term.
fn lit_part(lit: &LinearImage, unlit: &LinearImage) -> LinearImage {
    let mut out = lit.clone();
    for (p, q) in out.pixels.iter_mut().zip(&unlit.pixels) {
        for c in 0..3 {
            p[c] -= q[c];
        }
    }
    out
}

#[test]
fn extreme_cases_stay_finite_and_lit() {
    let ctx = validated_context();
    let mut cases: Vec<(&str, Scene)> = Vec::new();
    for intensity in [1e-6f32, 1e6] {
        let mut s = slab_scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), intensity)]);
        s.render.emission = 0.0;
        cases.push((if intensity < 1.0 { "intensity 1e-6" } else { "intensity 1e6" }, s));
    }
    let mut opaque = slab_scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)]);
    for p in &mut opaque.transfer.points {
        if p.rgba[3] > 0.0 {
            p.rgba[3] = 0.999_999;
        }
    }
    cases.push(("near-opaque", opaque));
    cases.push(("grazing light", slab_scene(vec![directional(Vec3::new(1.0, -0.002, 0.0), 2.0)])));
    let mut parallel = slab_scene(vec![]);
    parallel.camera.projection = Projection::Orthographic { height: 1.8 };
    let view = parallel.camera.forward();
    parallel.lights = vec![directional(view, 2.0)];
    cases.push(("light parallel to the view", parallel));
    for (what, scene) in &cases {
        let mut unlit_scene = scene.clone();
        unlit_scene.lights.clear();
        let mut parts = Vec::new();
        for (technique, s) in [
            (Technique::Ipsvi, scene),
            (Technique::Ipsvi, &unlit_scene),
            (Technique::Reference, scene),
            (Technique::Reference, &unlit_scene),
        ] {
            let gpu = GpuScene::upload(&ctx, s).unwrap();
            let mut profiler = Profiler::new(&ctx, 64).unwrap();
            parts.push(render(&gpu, technique, 24, 24, &mut profiler).unwrap().image);
        }
        assert!(parts[0].all_finite(), "{what}: non-finite pixels");
        let (ipsvi, reference) = (lit_part(&parts[0], &parts[1]), lit_part(&parts[2], &parts[3]));
        // Lit against the unlit run: the light adds at least a tenth of what it
        // adds in the ground truth, wherever that is, whatever the background.
        let peak = reference.max_value() as f64;
        assert!(peak > 0.0, "{what}: the ground truth itself is unlit");
        assert!(
            ipsvi.max_value() as f64 > 0.1 * peak,
            "{what}: light adds {} (ground truth {peak})",
            ipsvi.max_value()
        );
        // And where it adds it: the lit part against the ground truth's lit part.
        // The stated tolerance, relative to the lit part's peak (measured on
        // lavapipe: 0.20% at 1e-6, 0.13% at 1e6, 0.02% grazing, 0.01% parallel).
        // Near-opaque surfaces are one sample thick, so the one-texel terminator
        // (see RMSE_TOLERANCE) covers more of the lit pixels: measured 0.25%,
        // bound 1% (an earlier build measured 3.0% here, against a bound of 4%).
        let tolerance = if *what == "near-opaque" { 0.01 } else { RMSE_TOLERANCE };
        let rmse = compare(&ipsvi, &reference).unwrap().rmse / peak;
        println!("{what}: lit part relative rmse {rmse:.4} of lit peak {peak:.3e}");
        assert!(rmse <= tolerance, "{what}: lit part relative rmse {rmse}");
    }
    assert_validation_clean(&ctx);
}

#[test]
fn exit_point_termination_gives_the_same_image_and_allocates_only_when_on() {
    use sweeplab::techniques::ipsvi::EarlyTermination;
    let scene = slab_scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)]);
    let ctx = validated_context();
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let mut profiler = Profiler::new(&ctx, 4096).unwrap();
    let mut results = Vec::new();
    for ert in [EarlyTermination::Off, EarlyTermination::Plain, EarlyTermination::ExitPoints] {
        // Light rays: view rays do not feed the cache, so stopping them is exact
        // (view samples lose features: tests/ipsvi_view_samples.rs, figure 5).
        let s = IpsviSettings {
            early_termination: ert,
            cache_size: 64,
            cache_update: CacheUpdate::LightRays,
            ..IpsviSettings::default()
        };
        profiler.reset();
        ctx.memory.reset_peak();
        let frame = render_with(&gpu, &s, SIZE, SIZE, &mut profiler, SyncStrategy::BarrierGlobal).unwrap();
        let profile = profiler.resolve(ctx.memory.device_local_peak()).unwrap();
        let prepass = profile.passes.iter().any(|p| p.name == "ipsvi_ert_prepass");
        assert_eq!(prepass, ert == EarlyTermination::ExitPoints, "{ert:?}: pre-pass recorded only in exit-points mode");
        results.push((frame.image, profile.gpu_memory_bytes));
    }
    // Stopping at transmittance 1e-4 changes a pixel by at most 1e-4 of what lies behind.
    let peak = results[0].0.max_value() as f64;
    for (i, name) in [(1, "plain"), (2, "exit-points")] {
        let stats = compare(&results[i].0, &results[0].0).unwrap();
        assert!(stats.max_abs <= 1e-3 * peak, "{name}: {stats:?}");
    }
    let low = (SIZE.div_ceil(4) * SIZE.div_ceil(4)) as u64;
    assert!(results[2].1 >= results[1].1 + low * (8 + 4 * 3) - 4, "pre-pass images not counted: {results:?}");
    assert_eq!(results[0].1, results[1].1, "off and plain allocate the same");
    assert_validation_clean(&ctx);
}

#[test]
fn forward_cone_scattering_blurs_light_and_stays_finite() {
    let scene = slab_scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)]);
    let ctx = validated_context();
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let mut profiler = Profiler::new(&ctx, 64).unwrap();
    let mut images = Vec::new();
    for albedo in [0.0, 0.6] {
        // Forward-cone scattering is a light-rays feature (view samples refuse albedo > 0).
        let s = IpsviSettings {
            albedo,
            cone_angle_deg: 30.0,
            cache_size: 64,
            cache_update: CacheUpdate::LightRays,
            ..IpsviSettings::default()
        };
        profiler.reset();
        images.push(render_with(&gpu, &s, SIZE, SIZE, &mut profiler, SyncStrategy::BarrierGlobal).unwrap().image);
    }
    assert!(images[1].all_finite());
    let change = compare(&images[1], &images[0]).unwrap();
    assert!(change.rmse > 1e-3, "albedo 0.6 must change the image: {change:?}");
    // Scattering only redistributes light inside the cone: the total stays close.
    let sum = |img: &LinearImage| img.pixels.iter().map(|p| (p[0] + p[1] + p[2]) as f64).sum::<f64>();
    let ratio = sum(&images[1]) / sum(&images[0]);
    assert!((0.7..1.3).contains(&ratio), "total light changed by {ratio}");
    assert_validation_clean(&ctx);
}
