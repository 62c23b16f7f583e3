//! The segmented line kernel (`ipsvi.line_kernel = "segmented"`) against the
//! serial one: the same claims and the same early-termination stops whatever
//! the split (exact, by order-free digests), the same image up to the order
//! of compositing, on every light placement; its combines on fabricated
//! segments; the shape report's figures; the line barrier still load-bearing.
use crate::common;

use common::cli::{sweeplab, temp_dir};
use common::*;
use glam::Vec3;
use sweeplab::metrics::compare;
use sweeplab::render::{ChainsByRole, FrameResult, GpuScene, LineShape, StopsPassShape, VolumeTexels};
use sweeplab::scene::synthetic::slab_under_sphere;
use sweeplab::scene::{Camera, Light, Projection, Scene};
use sweeplab::techniques::ipsvi::renderer::IpsviRenderer;
use sweeplab::techniques::ipsvi::{
    render_study, render_with, BreakdownStep, CacheUpdate, EarlyTermination, IpsviSettings, IpsviStudy, LineKernel,
    SyncStrategy, WritePass, WriteRule,
};
use sweeplab::techniques::{render, Technique};
use sweeplab::vk::subgroups::SubgroupSupport;
use sweeplab::vk::{Context, Profiler};

pub(crate) const SIZE: u32 = 48;

pub(crate) fn slab_scene(lights: Vec<Light>) -> Scene {
    ipsvi_slab_scene(lights, SIZE)
}

/// Lights outside the volume (a directional light, a point light in each of
/// the four zones), behind it (a directional light toward the camera, a point
/// light on the far side) and inside it, and a spot light with an
/// orthographic camera.
pub(crate) fn light_placements() -> Vec<(&'static str, Scene)> {
    let camera = scene_with(slab_under_sphere(8), vec![], SIZE, SIZE).camera;
    let basis = camera.basis(SIZE, SIZE);
    let (r, u, f) = (basis.right.normalize(), basis.up.normalize(), camera.forward());
    let mut spot = slab_scene(vec![spot_light(2.0)]);
    spot.camera.projection = Projection::Orthographic { height: 1.8 };
    vec![
        ("directional", slab_scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)])),
        ("directional from behind", slab_scene(vec![directional(-f + u * 0.4 + r * 0.2, 2.0)])),
        ("point, right zone", slab_scene(vec![point(r * 1.2 + u * 0.3)])),
        ("point, left zone", slab_scene(vec![point(-r * 1.2 + u * 0.2)])),
        ("point, up zone", slab_scene(vec![point(u * 1.2 + r * 0.2)])),
        ("point, down zone", slab_scene(vec![point(-u * 1.2 - r * 0.2)])),
        ("point behind the volume", slab_scene(vec![point(f * 1.3 + u * 0.3 + r * 0.1)])),
        ("point inside the volume", slab_scene(vec![point(Vec3::new(0.15, 0.35, 0.1))])),
        ("orthographic, spot", spot),
    ]
}

pub(crate) fn settings(line_kernel: LineKernel, segments: u32, segment_rounds: u32) -> IpsviSettings {
    IpsviSettings { cache_size: 64, line_kernel, segments, segment_rounds, ..IpsviSettings::default() }
}

const DIGESTS: IpsviStudy = IpsviStudy {
    single_dispatch_baseline: false,
    breakdown_step: BreakdownStep::Full,
    keep_redundant_claims: false,
    digests: true,
    omit_view_stops_barrier: false,
};

fn frame(ctx: &Context, gpu: &GpuScene, s: &IpsviSettings) -> FrameResult {
    let mut profiler = Profiler::new(ctx, 64).unwrap();
    render_study(gpu, s, &DIGESTS, SIZE, SIZE, &mut profiler, SyncStrategy::BarrierGlobal).unwrap()
}

fn shape(f: &FrameResult) -> &LineShape {
    f.shape.as_ref().expect("an IPSVI frame reports its shape")
}

/// The segmented kernel's image may differ from the serial one's only by the
/// order in which the over operator combines a ray's samples (every light
/// read and cache write is the same: the digests). In f32 that moves a
/// composite of n terms by at most about n * 2^-24 of its size; rays here
/// have up to ~150 samples: 150 * 6e-8 = 9e-6 of the peak, bounded at 1e-5.
/// Measured on lavapipe: at most 4.9e-7 of the peak (rounding errors of
/// opposite signs cancel); 1.2e-6 with texel lanes, where a texel's march
/// toward the light is summed in parts as well: that reordering stays within
/// the tolerance as measured, not by the bound above (a light ray's march may
/// be longer than a view ray).
const COMPOSITING_ORDER_TOLERANCE: f64 = 1e-5;

/// (segments, rounds) the tests split rays into: lavapipe's whole subgroup
/// in the default rounds, one round, and more rounds than a ray has segments
/// of samples (shading then composites one sample per segment and round).
/// Each split of each mode is a pipeline lavapipe compiles, most of these
/// tests' time.
const SPLITS: [(u32, u32); 3] = [(8, 4), (4, 1), (2, 64)];

/// Against the serial kernel on every light placement, under both write rules
/// and light rays: claims and stops exactly the serial kernel's for every
/// split, the image within the compositing-order tolerance, and no farther
/// from the ground truth.
fn matches_serial(modes: &[(&str, IpsviSettings)], scenes: &[(&str, Scene)]) {
    matches_serial_in(&SPLITS, modes, scenes);
}

pub(crate) fn matches_serial_in(splits: &[(u32, u32)], modes: &[(&str, IpsviSettings)], scenes: &[(&str, Scene)]) {
    let ctx = validated_context();
    let smallest_subgroup = SubgroupSupport::of(&ctx).min_size;
    for (what, scene) in scenes {
        let gpu = GpuScene::upload_with(&ctx, scene, VolumeTexels::Float32).unwrap();
        let mut profiler = Profiler::new(&ctx, 64).unwrap();
        let truth = render(&gpu, Technique::Reference, SIZE, SIZE, &mut profiler).unwrap().image;
        for (mode, base) in modes {
            let serial_settings = IpsviSettings { line_kernel: LineKernel::Serial, texel_segments: 0, ..base.clone() };
            let serial = frame(&ctx, &gpu, &serial_settings);
            assert_eq!(shape(&serial).kernel, "serial");
            let peak = serial.image.max_value() as f64;
            let serial_rmse = compare(&serial.image, &truth).unwrap().rmse;
            for &(segments, segment_rounds) in splits {
                let s = IpsviSettings { line_kernel: LineKernel::Segmented, segments, segment_rounds, ..base.clone() };
                let seg = frame(&ctx, &gpu, &s);
                let case = format!("{what}, {mode}, {segments} segments, {segment_rounds} rounds");
                let lanes = sweeplab::techniques::ipsvi::line_kernel::auto_texel_lanes(segments).min(smallest_subgroup);
                let texels = if base.texel_segments != 0 { base.texel_segments } else { lanes };
                let label = match texels {
                    1 => format!("segmented x{segments}"),
                    t => format!("segmented x{segments}, texels x{t}"),
                };
                assert_eq!(shape(&seg).kernel, label, "{case}");
                assert_eq!(shape(&seg).claim_digest, shape(&serial).claim_digest, "{case}: claims differ");
                assert_eq!(shape(&seg).stop_digest, shape(&serial).stop_digest, "{case}: stops differ");
                let d = compare(&seg.image, &serial.image).unwrap();
                let rmse = compare(&seg.image, &truth).unwrap().rmse;
                println!(
                    "{case}: max |segmented - serial| {:.2e} of peak; rmse vs truth {rmse:.6e} (serial {serial_rmse:.6e})",
                    d.max_abs / peak
                );
                assert!(d.max_abs <= COMPOSITING_ORDER_TOLERANCE * peak, "{case}: {d:?}");
                assert!(rmse <= serial_rmse * (1.0 + 1e-3), "{case}: farther from the truth than serial");
            }
        }
    }
    assert_validation_clean(&ctx);
}

/// Every light placement in one test: one context, so each kernel's pipeline
/// is compiled once (most of these tests' time on lavapipe).
#[test]
fn segmented_matches_serial_for_lights_outside_behind_and_inside_the_volume() {
    let modes = [("every-sample", settings(LineKernel::Auto, 0, 4))];
    matches_serial(&modes, &light_placements());
}

#[test]
fn segmented_matches_serial_in_the_other_modes() {
    let base = settings(LineKernel::Auto, 0, 4);
    let scenes = light_placements();
    let scene = |name: &str| scenes.iter().filter(|(w, _)| *w == name).cloned().collect::<Vec<_>>();
    let (directional, inside) = (scene("directional"), scene("point inside the volume"));
    let mode = |what, s| [(what, s)];
    matches_serial(&mode("non-empty", IpsviSettings { write_rule: WriteRule::NonEmpty, ..base.clone() }), &inside);
    matches_serial(
        &mode("light rays", IpsviSettings { cache_update: CacheUpdate::LightRays, ..base.clone() }),
        &directional,
    );
    let exit_points = IpsviSettings { early_termination: EarlyTermination::ExitPoints, ..base.clone() };
    matches_serial(&mode("exit points", exit_points), &inside);
    let never = IpsviSettings { early_termination: EarlyTermination::Off, ..base.clone() };
    matches_serial(&mode("no early termination", never), &directional);
    let merged = IpsviSettings { merge_sweeps: true, packed_store: true, line_width: 2, ..base };
    matches_serial(&mode("merged, packed, two lines", merged), &inside);
}

/// A near-opaque medium where most view rays stop: the stops (and the claims,
/// which end runs at the stop) are the serial kernel's for every split, with
/// plain and exit-point termination; and the stop digest sees them (it
/// differs from a frame that never stops).
#[test]
fn early_termination_stops_where_the_serial_kernel_stops() {
    stops_where_the_serial_kernel_stops(&[SPLITS[0], SPLITS[2]]);
}

fn stops_where_the_serial_kernel_stops(splits: &[(u32, u32)]) {
    let ctx = validated_context();
    let mut scene = slab_scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)]);
    for p in &mut scene.transfer.points {
        if p.rgba[3] > 0.0 {
            p.rgba[3] = 0.9;
        }
    }
    let gpu = GpuScene::upload_with(&ctx, &scene, VolumeTexels::Float32).unwrap();
    let off = IpsviSettings { early_termination: EarlyTermination::Off, ..settings(LineKernel::Serial, 0, 4) };
    let never = frame(&ctx, &gpu, &off);
    for early_termination in [EarlyTermination::Plain, EarlyTermination::ExitPoints] {
        for write_rule in WriteRule::ALL {
            let base = IpsviSettings { early_termination, write_rule, ..settings(LineKernel::Serial, 0, 4) };
            let serial = frame(&ctx, &gpu, &base);
            assert_ne!(shape(&serial).stop_digest, shape(&never).stop_digest, "{early_termination:?}: no ray stopped");
            let peak = serial.image.max_value() as f64;
            for &(segments, segment_rounds) in splits {
                let s = IpsviSettings { line_kernel: LineKernel::Segmented, segments, segment_rounds, ..base.clone() };
                let seg = frame(&ctx, &gpu, &s);
                let case =
                    format!("{early_termination:?}, {write_rule:?}, {segments} segments, {segment_rounds} rounds");
                assert_eq!(shape(&seg).stop_digest, shape(&serial).stop_digest, "{case}: stops differ");
                assert_eq!(shape(&seg).claim_digest, shape(&serial).claim_digest, "{case}: claims differ");
                // The segments share only the samples up to the stop.
                let d = compare(&seg.image, &serial.image).unwrap();
                assert!(d.max_abs <= COMPOSITING_ORDER_TOLERANCE * peak, "{case}: {d:?}");
            }
        }
    }
    assert_validation_clean(&ctx);
}

/// More segments than lavapipe's 8-lane subgroup: a pixel's segments span 2
/// to 16 subgroups of its workgroup, their parts combined through shared
/// memory (32 is a GPU's default count, in one subgroup there), and a
/// texel's marches split over 2 to 8 lanes (an eighth of the segments).
/// Claims, stops and image are the serial kernel's as in one subgroup.
#[test]
fn segmented_matches_serial_with_segments_across_subgroups() {
    let ctx = validated_context();
    assert_eq!(SubgroupSupport::of(&ctx).min_size, 8, "lavapipe's default subgroup");
    drop(ctx);
    let scenes = light_placements();
    let every_sample = [("every-sample", settings(LineKernel::Auto, 0, 4))];
    matches_serial_in(&[(32, 4), (16, 1)], &every_sample, &scenes);
    // 16 subgroups (the costliest pipelines here): outside, inside, a spot.
    let some = [scenes[0].clone(), scenes[7].clone(), scenes[8].clone()];
    matches_serial_in(&[(128, 1)], &every_sample, &some);
    let rays = IpsviSettings { cache_update: CacheUpdate::LightRays, ..settings(LineKernel::Auto, 0, 4) };
    matches_serial_in(&[(32, 4)], &[("light rays", rays)], &some[..2]);
    stops_where_the_serial_kernel_stops(&[(32, 4), (64, 2)]);
}

/// A texel's marches toward the light split over its lanes (texel-ray
/// writes, and light rays' advances), within lavapipe's subgroup: the same
/// claims and stops as the serial kernel, the image up to the order of
/// compositing, on every light placement.
#[test]
fn split_texel_marches_match_the_serial_kernel() {
    let texels = |s: IpsviSettings| IpsviSettings { texel_segments: 4, ..s };
    let rays = IpsviSettings { cache_update: CacheUpdate::LightRays, ..settings(LineKernel::Auto, 0, 4) };
    let modes = [
        ("every-sample, texels x4", texels(settings(LineKernel::Auto, 0, 4))),
        ("light rays, texels x4", texels(rays)),
    ];
    matches_serial_in(&[(8, 4), (4, 1)], &modes, &light_placements());
}

/// One segment per pixel in one round is the serial march in the segmented
/// kernel: the same samples, reads and compositing in the same order.
/// Measured on lavapipe: the same image bit for bit.
#[test]
fn one_segment_per_pixel_reproduces_the_serial_kernel() {
    let ctx = validated_context();
    for (what, scene) in light_placements().into_iter().take(2) {
        let gpu = GpuScene::upload_with(&ctx, &scene, VolumeTexels::Float32).unwrap();
        let serial = frame(&ctx, &gpu, &settings(LineKernel::Serial, 0, 4));
        let one = frame(&ctx, &gpu, &settings(LineKernel::Segmented, 1, 1));
        assert!(one.image == serial.image, "{what}: {:?}", compare(&one.image, &serial.image).unwrap());
    }
    assert_validation_clean(&ctx);
}

/// The line barrier between blocks stays load-bearing with the segmented
/// kernel: without it synchronization validation reports the hazard on the
/// cache, in both cache-update modes.
#[test]
fn the_line_barrier_is_still_load_bearing() {
    let ctx = validated_context();
    let scene = slab_scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)]);
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let mut profiler = Profiler::new(&ctx, 64).unwrap();
    for cache_update in CacheUpdate::ALL {
        let s = IpsviSettings { cache_size: 32, cache_update, ..settings(LineKernel::Segmented, 4, 4) };
        let what = format!("segmented, {}", cache_update.name());
        assert_ipsvi_line_barrier_load_bearing(&ctx, &gpu, &s, &IpsviStudy::default(), &mut profiler, 16, &what);
    }
}

/// The barrier after the first sweep's cache initialisation also hands the
/// view-stops pass's stops to the line dispatches: without it
/// synchronization validation reports the line kernel's read of the stops
/// the pass wrote. With it the same frame is clean.
#[test]
fn the_view_stops_barrier_is_load_bearing() {
    use sweeplab::techniques::ipsvi::{render_study, SyncStrategy};
    let ctx = validated_context();
    let scene = slab_scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)]);
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let mut profiler = Profiler::new(&ctx, 64).unwrap();
    let s = IpsviSettings { cache_size: 32, ..settings(LineKernel::Segmented, 4, 4) };
    for omit_view_stops_barrier in [false, true] {
        let study = IpsviStudy { omit_view_stops_barrier, ..IpsviStudy::default() };
        profiler.reset();
        render_study(&gpu, &s, &study, 16, 16, &mut profiler, SyncStrategy::BarrierGlobal).unwrap();
        let messages = ctx.take_validation_messages();
        let reported = messages.iter().any(|m| m.contains("SYNC-HAZARD") && m.contains("ipsvi view stops"));
        assert_eq!(reported, omit_view_stops_barrier, "barrier omitted: {omit_view_stops_barrier}: {messages:?}");
        if !omit_view_stops_barrier {
            assert!(messages.is_empty(), "{messages:?}");
        }
    }
}

/// lavapipe's subgroups are as wide as its vectors: 8 lanes at its default
/// 256 bits, 16 with `LP_NATIVE_VECTOR_WIDTH=512`, the widest it compiles (a
/// GPU's default is 32 segments). This suite binary again, in a child process
/// with that setting (it must be set before the driver loads), and with a
/// shader cache of its own: Mesa 22.3's does not key on the vector width, and
/// a shader compiled at 512 bits, loaded by a 256-bit process, runs silently
/// wrong (docs/testing.md, "Tests in a wider lavapipe").
fn in_wider_lavapipe(vector_bits: &str, test: &str) -> String {
    let cache = std::env::temp_dir().join(format!("sweeplab-mesa-shader-cache-lp{vector_bits}"));
    let out = std::process::Command::new(std::env::current_exe().unwrap())
        .args([test, "--exact", "--ignored", "--nocapture", "--test-threads=1"])
        .env("LP_NATIVE_VECTOR_WIDTH", vector_bits)
        .env("MESA_SHADER_CACHE_DIR", cache)
        .output()
        .expect("run the suite in a child process");
    let all = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success() && all.contains("1 passed"), "{test} at {vector_bits}-bit vectors:\n{all}");
    all
}

/// 16 segments per pixel in 16-lane subgroups: one more level of every scan
/// than lavapipe's default subgroup allows, on every light placement and in
/// a medium where most rays stop; and a texel's marches split over 16 lanes
/// (texel-ray writes and light rays' advances), more than the default
/// subgroup holds.
#[test]
fn segmented_matches_serial_at_16_segments_in_16_lane_subgroups() {
    in_wider_lavapipe("512", "ipsvi_segmented::at_16_segments");
}

#[test]
#[ignore = "run by segmented_matches_serial_at_16_segments_in_16_lane_subgroups with LP_NATIVE_VECTOR_WIDTH=512"]
fn at_16_segments() {
    let ctx = validated_context();
    assert_eq!(SubgroupSupport::of(&ctx).size, 16, "needs LP_NATIVE_VECTOR_WIDTH=512");
    drop(ctx);
    let texels = |s: IpsviSettings| IpsviSettings { texel_segments: 16, ..s };
    let rays = IpsviSettings { cache_update: CacheUpdate::LightRays, ..settings(LineKernel::Auto, 0, 4) };
    let modes = [
        ("every-sample", settings(LineKernel::Auto, 0, 4)),
        ("every-sample, texels x16", texels(settings(LineKernel::Auto, 0, 4))),
        ("light rays, texels x16", texels(rays)),
    ];
    matches_serial_in(&[(16, 4)], &modes, &light_placements());
    stops_where_the_serial_kernel_stops(&[(16, 4)]);
}

/// With `LP_NATIVE_VECTOR_WIDTH=1024` lavapipe reports 32-lane subgroups but
/// compiles 16-lane ones: the kernel finds its workgroups in subgroups it
/// cannot cluster 32 segments in, and the frame is refused by name instead
/// of composited from partial clusters.
#[test]
fn subgroups_narrower_than_reported_are_refused_by_name() {
    in_wider_lavapipe("1024", "ipsvi_segmented::at_32_segments_in_16_lane_subgroups");
}

#[test]
#[ignore = "run by subgroups_narrower_than_reported_are_refused_by_name with LP_NATIVE_VECTOR_WIDTH=1024"]
fn at_32_segments_in_16_lane_subgroups() {
    let ctx = validated_context();
    assert_eq!(SubgroupSupport::of(&ctx).size, 32, "needs LP_NATIVE_VECTOR_WIDTH=1024");
    let scene = slab_scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)]);
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let mut profiler = Profiler::new(&ctx, 64).unwrap();
    let s = settings(LineKernel::Segmented, 32, 4);
    let e = render_with(&gpu, &s, SIZE, SIZE, &mut profiler, SyncStrategy::BarrierGlobal).err().unwrap();
    assert!(e.to_string().contains("partial subgroups") && e.to_string().contains("ipsvi.line_kernel"), "{e}");
    assert_validation_clean(&ctx);
}

/// Modes the segmented kernel cannot run are refused with the setting named;
/// `auto` takes the serial kernel on lavapipe (a CPU device).
#[test]
fn what_cannot_be_segmented_is_refused_by_name_and_auto_is_serial_on_a_cpu() {
    let ctx = validated_context();
    let scene = slab_scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)]);
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let mut profiler = Profiler::new(&ctx, 64).unwrap();
    let segmented = settings(LineKernel::Segmented, 0, 4);
    let sample_pass = IpsviSettings { write_pass: WritePass::Sample, ..segmented.clone() };
    let e = render_with(&gpu, &sample_pass, 16, 16, &mut profiler, SyncStrategy::BarrierGlobal).err().unwrap();
    assert!(e.to_string().contains("write_pass = \"sample\""), "{e}");
    let too_many = IpsviSettings { segments: 512, ..segmented };
    let e = render_with(&gpu, &too_many, 16, 16, &mut profiler, SyncStrategy::BarrierGlobal).err().unwrap();
    assert!(e.to_string().contains("ipsvi.segments = 512"), "{e}");
    let auto = render_with(&gpu, &settings(LineKernel::Auto, 0, 4), 16, 16, &mut profiler, SyncStrategy::BarrierGlobal);
    assert_eq!(shape(&auto.unwrap()).kernel, "serial", "auto on lavapipe");
    assert_validation_clean(&ctx);
}

/// A uniform cube (16 voxels) seen head-on by an orthographic camera: every
/// ray that hits it has the same samples.
fn uniform_cube() -> Scene {
    let volume = seeded_volume("uniform", glam::UVec3::splat(16), Vec3::ONE, 1, |_, _| 200);
    let mut scene = scene_with(volume, vec![directional(Vec3::new(0.0, -1.0, 0.3), 1.0)], SIZE, SIZE);
    scene.camera = Camera::orbit(Vec3::ZERO, 3.0, 0.0, 0.0, Projection::Orthographic { height: 0.6 });
    scene
}

/// The chain of each role of a line's invocations, in the uniform cube with
/// view samples (whole frames: pixels, texels and claims all run): the claim
/// march never reads the light, so its chain is known exactly: a ray's n
/// samples serial, and segmented its first segment's, ceil(n / S) (the
/// claims are dealt in one round). A pixel marches the same samples plus its
/// reads' marches toward the light; a texel's chain is its own light march.
/// The line's chain is the longest role's.
#[test]
fn the_shape_report_names_the_role_of_each_chain() {
    let ctx = validated_context();
    let mut scene = uniform_cube();
    for p in &mut scene.transfer.points {
        p.rgba[3] = 1e-3;
    }
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let shape_of = |line_kernel, segments| {
        let s = IpsviSettings { cache_size: 32, line_kernel, segments, segment_rounds: 4, ..IpsviSettings::default() };
        let shape = frame(&ctx, &gpu, &s).shape.unwrap();
        println!("{}", shape.summary());
        shape
    };
    let serial = shape_of(LineKernel::Serial, 0);
    let roles = serial.chain_median_by_role;
    let n = roles.claims;
    assert!(n >= 32, "the cube's 16 voxels at step 0.5: {n} samples");
    assert!(roles.pixels > n && roles.texels > 0, "{roles:?}");
    let segmented = shape_of(LineKernel::Segmented, 8);
    let len = n.div_ceil(8);
    let seg_roles = segmented.chain_median_by_role;
    assert_eq!(seg_roles.claims, len, "{seg_roles:?}");
    assert!(seg_roles.pixels > len && seg_roles.pixels < roles.pixels, "{seg_roles:?}");
    for s in [&serial, &segmented] {
        let r = s.chain_median_by_role;
        assert!(s.chain_median >= r.pixels.max(r.texels).max(r.claims), "{}", s.summary());
        // Every line shades, so some role is the longest in each.
        let b = s.lines_bound_by;
        assert!(b.pixels.max(b.texels).max(b.claims) > 0, "{}", s.summary());
        assert!(b.pixels + b.texels + b.claims >= s.line_dispatches, "{}", s.summary());
    }
    // Serial: a pixel's march holds the whole ray, longer than any texel's.
    assert_eq!(serial.lines_bound_by.pixels, serial.line_dispatches, "{}", serial.summary());
    assert_validation_clean(&ctx);
}

/// A uniform, nearly transparent cube seen head-on by an orthographic camera:
/// every ray that hits it has the same samples, so the shape report's chain
/// is known exactly. Ray casting only (breakdown step `lines`: no cache reads
/// or writes), light rays, plain termination. A medium that never stops the
/// ray: the serial chain is a ray's n samples; the segmented one, the first
/// segment's stretch in every round, ceil(n / (S R)) samples (fewer in the
/// last round). A denser one that stops it after sample s: the serial chain
/// is s + 1; the segmented one the same sum over the s + 1 samples up to the
/// stop. The view-stops pass (segmented only): every segment's opacity,
/// ceil(n / S), and the segment holding the stop once more up to it; S
/// invocations per pixel of the image.
#[test]
fn the_shape_report_counts_invocations_and_the_longest_chain_exactly() {
    let ctx = validated_context();
    let scene = uniform_cube();
    let study = IpsviStudy { breakdown_step: BreakdownStep::Lines, ..IpsviStudy::default() };
    let shape_of = |opacity: f32, line_kernel, segments, segment_rounds| {
        let mut scene = scene.clone();
        for p in &mut scene.transfer.points {
            p.rgba[3] = opacity;
        }
        let gpu = GpuScene::upload(&ctx, &scene).unwrap();
        let s = IpsviSettings {
            cache_update: CacheUpdate::LightRays,
            cache_size: 32,
            line_kernel,
            segments,
            segment_rounds,
            ..IpsviSettings::default()
        };
        let mut renderer = IpsviRenderer::build(&gpu, &s, &study, SIZE, SIZE, None).unwrap();
        let mut profiler = Profiler::new(&ctx, 64).unwrap();
        let shape = renderer.frame(&mut profiler, SyncStrategy::BarrierGlobal).unwrap().shape.unwrap();
        println!("opacity {opacity}, {} ({segment_rounds} rounds): {}", shape.kernel, shape.summary());
        (shape, renderer.line_group())
    };
    // Opacities of the transfer function: one that never stops the ray, one
    // that stops it after sample 20 of 32 (checked below).
    const CLEAR: f32 = 1e-3;
    const STOPPING: f32 = 0.6;
    let (serial, group) = shape_of(CLEAR, LineKernel::Serial, 0, 4);
    let n = serial.chain_max;
    let only_pixels = ChainsByRole { pixels: n, texels: 0, claims: 0 };
    assert_eq!(serial.chain_median_by_role, only_pixels, "ray casting only: every chain a pixel's");
    let every_line = ChainsByRole { pixels: SIZE, texels: 0, claims: 0 };
    assert_eq!(serial.lines_bound_by, every_line, "the pixels are every line's longest");
    assert!(n >= 32, "the cube's 16 voxels at step 0.5: {n} samples");
    assert_eq!(serial.stops_pass, None, "the serial kernel stops as it marches");
    // The whole line's pixels in whole workgroups, one dispatch per line.
    assert_eq!(serial.invocations_max, SIZE.next_multiple_of(group));
    assert_eq!((serial.line_dispatches, serial.chain_median), (SIZE, n), "every ray hits the cube");
    let stop = shape_of(STOPPING, LineKernel::Serial, 0, 4).0.chain_max - 1;
    assert!(stop > n / 4 && stop < n - 1, "the denser cube stops the ray in its middle: after sample {stop} of {n}");
    // Segment 0's samples of a ray of m dealt in rounds.
    let dealt = |m: u32, segments: u32, rounds: u32| {
        let len = m.div_ceil(segments * rounds);
        (0..m).step_by((len * segments) as usize).map(|lo| len.min(m - lo)).sum::<u32>()
    };
    for (segments, rounds) in [(2, 1), (8, 1), (8, 4), (4, 64)] {
        let case = format!("{segments} segments, {rounds} rounds");
        let (shape, group) = shape_of(CLEAR, LineKernel::Segmented, segments, rounds);
        assert_eq!(shape.chain_max, dealt(n, segments, rounds), "{case}");
        assert_eq!(shape.invocations_max, (SIZE * segments).next_multiple_of(group), "{case}");
        let len = n.div_ceil(segments);
        let invocations = u64::from((SIZE * SIZE * segments).next_multiple_of(group));
        assert_eq!(shape.stops_pass, Some(StopsPassShape { invocations, chain: len }), "{case}, no stop");
        let stopping = shape_of(STOPPING, LineKernel::Segmented, segments, rounds).0;
        let case = format!("{case}, stop after sample {stop}");
        assert_eq!(stopping.chain_max, dealt(stop + 1, segments, rounds), "{case}");
        // The pass's segment holding the stop: its whole segment, then again up to the stop.
        let chain = len + (stop - stop / len * len + 1);
        assert_eq!(stopping.stops_pass, Some(StopsPassShape { invocations, chain }), "{case}");
    }
    assert_validation_clean(&ctx);
}

/// `render` prints the shape beside the settings, and `--profile-json` holds it.
#[test]
fn render_prints_the_shape_and_profile_json_holds_it() {
    let dir = temp_dir("ipsvi-shape");
    let json = dir.join("profile.json");
    let o = sweeplab(&[
        "render",
        "--scene",
        concat!(env!("CARGO_MANIFEST_DIR"), "/tests/scenes/slab-under-sphere.toml"),
        "--size",
        "24x24",
        "--technique",
        "ipsvi",
        "--set",
        "ipsvi.line_kernel=\"segmented\"",
        "--set",
        "ipsvi.cache_size=32",
        "--out",
        dir.join("out.png").to_str().unwrap(),
        "--profile-json",
        json.to_str().unwrap(),
    ]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{out}{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.contains("line_kernel: segmented") && out.contains("line shape (segmented x8)"), "{out}");
    let profile: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let shape = &profile["line_shape"];
    assert_eq!(shape["kernel"], "segmented x8");
    assert!(shape["chain_max"].as_u64().unwrap() > 0 && shape["invocations_median"].as_u64().unwrap() >= 24 * 8);
    std::fs::remove_dir_all(&dir).ok();
}

// ---- the combines on fabricated segments (glsl/ipsvi_segment_scan_probe.comp) ----

/// One fabricated segment as the probe reads it: composite (C rgb, T),
/// optical depth, runs (flags, lead texel, lead depth, trail texel, trail depth).
#[derive(Clone, Default)]
struct Segment {
    c: [f32; 3],
    t: f32,
    tau: u32,
    samples: Vec<(u32, f32)>,
}

/// A stretch's runs summarized straight from its samples (texel, depth): the
/// ground truth the scan's combine must reproduce for any prefix.
fn runs_of(samples: &[(u32, f32)], nearest: bool) -> [u32; 5] {
    let Some(&(first, d0)) = samples.first() else { return [0, u32::MAX, 0, u32::MAX, 0] };
    let depth = |a: f32, b: f32| if nearest { a.min(b) } else { b };
    let (mut lead_d, mut closed, mut trail) = (d0, false, (first, d0));
    for &(k, d) in &samples[1..] {
        if k == trail.0 {
            trail.1 = depth(trail.1, d);
            if !closed {
                lead_d = trail.1;
            }
        } else {
            closed = true;
            trail = (k, d);
        }
    }
    [1 | if closed { 2 } else { 0 }, first, lead_d.to_bits(), trail.0, trail.1.to_bits()]
}

/// Runs the probe on `rays` rays of `segments` segments each: per segment
/// (total composite rgb + T, tau before, tau total, next texel,
/// runs before [5], runs total [5]).
fn probe(ctx: &Context, segments: u32, nearest: bool, input: &[Segment]) -> Vec<[u32; 20]> {
    use ash::vk;
    use sweeplab::shaders::ipsvi_segment_scan_probe as probe;
    use sweeplab::vk::descriptors::Resource;
    use sweeplab::vk::{Buffer, ComputePipeline, ComputePipelineDesc};
    let words: Vec<[u32; 12]> = input
        .iter()
        .map(|s| {
            let r = runs_of(&s.samples, nearest);
            let [c0, c1, c2] = s.c.map(f32::to_bits);
            [c0, c1, c2, s.t.to_bits(), s.tau, r[0], r[1], r[2], r[3], r[4], 0, 0]
        })
        .collect();
    let usage = vk::BufferUsageFlags::STORAGE_BUFFER;
    let segments_buffer = Buffer::with_data(ctx, "probe segments", &words, usage).unwrap();
    let bytes = (input.len() * 80) as u64;
    let results = Buffer::new(ctx, "probe results", bytes, usage, gpu_allocator::MemoryLocation::GpuToCpu).unwrap();
    // More segments than a subgroup: one cluster per workgroup, as the kernel runs them.
    let cross = segments > sweeplab::vk::subgroups::SubgroupSupport::of(ctx).min_size;
    let group = if cross { segments } else { 64 };
    let specialization = [(0, segments), (1, nearest as u32), (2, group), (3, cross as u32)];
    let desc = ComputePipelineDesc {
        name: "ipsvi_segment_scan_probe",
        shader: &probe::INTERFACE,
        specialization: &specialization,
        max_sets: 1,
    };
    let mut pipeline = ComputePipeline::new(ctx, &desc).unwrap();
    let set = pipeline
        .create_set(&[
            (probe::SEGMENTS, Resource::StorageBuffer(&segments_buffer)),
            (probe::RESULTS, Resource::StorageBuffer(&results)),
        ])
        .unwrap();
    sweeplab::vk::commands::submit_and_wait(ctx, "probe", |rec| {
        rec.bind(&pipeline, set);
        rec.push(&pipeline, &(input.len() as u32));
        rec.dispatch((input.len() as u32).div_ceil(group), 1, 1);
        rec.barrier(&sweeplab::vk::Barrier::memory(
            "probe_write_to_host_read",
            sweeplab::vk::barriers::Access::COMPUTE_WRITE,
            sweeplab::vk::barriers::Access::HOST_READ,
        ));
        Ok(())
    })
    .unwrap();
    results.read::<[u32; 20]>(input.len()).unwrap()
}

/// A small seeded generator (the tests' own, no crate).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The over operator combined in depth order (C_a + T_a C_b, T_a T_b), in f64.
fn over_in_order(segments: &[Segment]) -> ([f64; 3], f64) {
    let (mut c, mut t) = ([0.0f64; 3], 1.0f64);
    for s in segments {
        for (sum, term) in c.iter_mut().zip(s.c) {
            *sum += t * term as f64;
        }
        t *= s.t as f64;
    }
    (c, t)
}

#[test]
fn the_scan_combines_fabricated_segments_exactly_and_in_depth_order() {
    let ctx = validated_context();
    let mut rng = Lcg(42);
    // 16 to 128 span lavapipe's 8-lane subgroups (2 to 16 of them).
    for segments in [1u32, 2, 4, 8, 16, 32, 128] {
        for nearest in [true, false] {
            let rays = 48usize;
            let mut input = Vec::new();
            for ray in 0..rays {
                for s in 0..segments {
                    // Ray 0: transmittance underflow (each segment 1e-30, some exactly 0 on ray 1).
                    let t = match ray {
                        0 => 1e-30,
                        1 if s == 1 => 0.0,
                        _ => rng.next() as f32,
                    };
                    let c = [rng.next() as f32, rng.next() as f32 * 4.0, rng.next() as f32 * 1e3];
                    // Optical depths up to 2^22 units each (the kernel's cap per sample is 2^22).
                    let tau = (rng.next() * (1u64 << 22) as f64 * 8.0) as u32;
                    // Runs over a three-texel alphabet so runs cross segments, some segments empty.
                    let n = (rng.next() * 5.0) as usize;
                    let samples = (0..n).map(|_| ((rng.next() * 3.0) as u32 * 0x10001, rng.next() as f32)).collect();
                    input.push(Segment { c, t, tau, samples });
                }
            }
            let out = probe(&ctx, segments, nearest, &input);
            for ray in 0..rays {
                let seg = &input[ray * segments as usize..(ray + 1) * segments as usize];
                let (c, t) = over_in_order(seg);
                let (rc, _) = over_in_order(&seg.iter().rev().cloned().collect::<Vec<_>>());
                let cap = 1u64 << 30;
                let mut before = 0u64;
                let total_tau = seg.iter().fold(0u64, |a, s| (a + s.tau as u64).min(cap));
                for (i, s) in seg.iter().enumerate() {
                    let r = out[ray * segments as usize + i];
                    let got_c = [0, 1, 2].map(|ch| f32::from_bits(r[ch]) as f64);
                    let got_t = f32::from_bits(r[3]) as f64;
                    let case = format!("{segments} segments, nearest {nearest}, ray {ray}, segment {i}");
                    for ch in 0..3 {
                        // f32 over S segments: a few ulp of the largest term.
                        assert!(
                            (got_c[ch] - c[ch]).abs() <= 1e-6 * c[ch].abs().max(1e-30) * 4.0,
                            "{case}: C {got_c:?} vs {c:?}"
                        );
                        assert!(got_c[ch].is_finite(), "{case}");
                    }
                    // (Ray 0's product underflows f32: zero or a denormal.)
                    assert!((got_t - t).abs() <= 1e-6 * t + 2e-38, "{case}: T {got_t} vs {t}");
                    if segments > 1 && ray > 1 && (rc[2] - c[2]).abs() > 1e-3 * c[2] {
                        // Not commutative: the combine is in depth order, not reversed.
                        assert!((got_c[2] - c[2]).abs() < (got_c[2] - rc[2]).abs(), "{case}: reversed order");
                    }
                    assert_eq!(r[4] as u64, before, "{case}: optical depth before");
                    assert_eq!(r[5] as u64, total_tau, "{case}: optical depth in all");
                    before = (before + s.tau as u64).min(cap);
                    // Runs: of the samples before this segment, and of all.
                    let earlier: Vec<(u32, f32)> = seg[..i].iter().flat_map(|s| s.samples.clone()).collect();
                    let all: Vec<(u32, f32)> = seg.iter().flat_map(|s| s.samples.clone()).collect();
                    assert_eq!(r[7..12], runs_of(&earlier, nearest), "{case}: runs before");
                    assert_eq!(r[12..17], runs_of(&all, nearest), "{case}: runs in all");
                    let next = seg[i + 1..].iter().find_map(|s| s.samples.first().map(|x| x.0)).unwrap_or(u32::MAX);
                    assert_eq!(r[6], next, "{case}: next texel");
                }
                if ray == 0 {
                    let got_t = f32::from_bits(out[0][3]);
                    assert!((0.0..1e-29).contains(&got_t), "underflow to zero or a denormal: {got_t}");
                }
            }
        }
    }
    assert_validation_clean(&ctx);
}
