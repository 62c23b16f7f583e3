//! Selective light updates (section 5 of the paper) on the persistent light
//! volume: a selective update gives the volume an entire update gives, toggling
//! is one signed propagation, recorded passes are replayed while their lights
//! are unchanged, incremental mode converges, and long random add / move /
//! remove sequences with lights from 1e-3 to 1e3 do not drift.
use crate::common;

use common::*;
use glam::Vec3;
use sweeplab::render::{GpuScene, VolumeTexels};
use sweeplab::scene::synthetic::slab_under_sphere;
use sweeplab::scene::{presets, Falloff, Light, LightKind, Scene};
use sweeplab::techniques::lightvolume::plan::PeakGeometry;
use sweeplab::techniques::lightvolume::{
    CostEstimate, IlluminationReadback, LightVolumeFrame, LightVolumeRenderer, LightVolumeSettings, UpdateKind,
};
use sweeplab::vk::{Context, Profiler};

/// The slab under the sphere at light volume scale 2, then `settings`.
fn scene(settings: impl FnOnce(&mut LightVolumeSettings)) -> Scene {
    let mut scene = scene_with(slab_under_sphere(16), vec![], 16, 16);
    scene.transfer = presets::preset("slab-sphere").unwrap();
    scene.settings.get_mut::<LightVolumeSettings>().scale = 2;
    settings(scene.settings.get_mut::<LightVolumeSettings>());
    scene
}

fn defaults(_: &mut LightVolumeSettings) {}

fn coloured(kind: LightKind, color: Vec3, intensity: f32) -> Light {
    Light { kind, color, intensity, falloff: Falloff::None }
}

fn dir(x: f32, y: f32, z: f32) -> LightKind {
    LightKind::Directional { direction: Vec3::new(x, y, z) }
}

/// Four lights, two of them sharing the -y group.
fn four_lights() -> Vec<Option<Light>> {
    vec![
        Some(coloured(dir(0.1, -1.0, 0.2), Vec3::new(1.0, 0.9, 0.8), 1.0)),
        Some(coloured(dir(-0.2, -1.0, 0.1), Vec3::new(0.6, 0.7, 1.0), 0.7)),
        Some(coloured(dir(1.0, -0.3, 0.2), Vec3::new(1.0, 0.5, 0.2), 1.5)),
        Some(Light {
            kind: LightKind::Point { position: Vec3::new(0.3, 0.2, -1.6) },
            color: Vec3::ONE,
            intensity: 2.0,
            falloff: Falloff::InverseSquare,
        }),
    ]
}

struct Run<'a> {
    ctx: &'a Context,
    profiler: Profiler,
}

impl<'a> Run<'a> {
    fn new(ctx: &'a Context) -> Self {
        Run { ctx, profiler: Profiler::new(ctx, 256).unwrap() }
    }

    fn update(&mut self, r: &mut LightVolumeRenderer, lights: &[Option<Light>]) -> (LightVolumeFrame, Vec<String>) {
        self.profiler.reset();
        let out = r.update(lights, &mut self.profiler).unwrap();
        let report = self.profiler.resolve(self.ctx.memory.device_local_peak()).unwrap();
        (out, report.scopes.iter().map(|s| s.name.clone()).collect())
    }
}

/// A validated context, `scene` uploaded with exact (f32) trilinear filtering
/// and a light volume renderer on it: what most tests here start from. Any
/// validation message fails the test.
fn on_renderer<R>(scene: Scene, test: impl FnOnce(&Context, &GpuScene, &mut LightVolumeRenderer, &mut Run) -> R) -> R {
    let ctx = validated_context();
    let gpu = GpuScene::upload_with(&ctx, &scene, VolumeTexels::Float32).unwrap();
    let mut r = LightVolumeRenderer::new(&gpu).unwrap();
    let mut run = Run::new(&ctx);
    let out = test(&ctx, &gpu, &mut r, &mut run);
    assert_validation_clean(&ctx);
    out
}

/// Largest |a - b| over the rgb of every voxel, with the two-float sums read exactly.
fn largest_difference(a: &IlluminationReadback, b: &IlluminationReadback) -> f64 {
    (0..a.high.len()).flat_map(|i| (0..3).map(move |c| (a.value(i, c) - b.value(i, c)).abs())).fold(0.0, f64::max)
}

fn largest_value(a: &IlluminationReadback) -> f64 {
    (0..a.high.len()).flat_map(|i| (0..3).map(move |c| a.value(i, c))).fold(0.0, f64::max)
}

fn smallest_value(a: &IlluminationReadback) -> f64 {
    (0..a.high.len()).flat_map(|i| (0..3).map(move |c| a.value(i, c))).fold(f64::INFINITY, f64::min)
}

/// The volume a fresh renderer builds for `lights` with an entire update.
fn entire(ctx: &Context, gpu: &GpuScene, lights: &[Option<Light>]) -> IlluminationReadback {
    let mut r = LightVolumeRenderer::new(gpu).unwrap();
    let mut run = Run::new(ctx);
    let (out, _) = run.update(&mut r, lights);
    assert_eq!(out.update.plan.kind, UpdateKind::Entire);
    r.read_illumination().unwrap()
}

/// Stated tolerance of selective against entire updates with compensated sums:
/// both hold the same f32 contributions summed exactly up to the rounding of
/// the low words (about u^2 = 3.6e-15 of the running sum per addition), so
/// they agree to 1e-12 of the brightest voxel.
const SELECTIVE_TOLERANCE: f64 = 1e-12;

#[test]
fn a_selective_state_change_and_a_toggle_give_the_volume_of_an_entire_update() {
    on_renderer(scene(defaults), |ctx, gpu, r, run| {
        let mut lights = four_lights();
        let (first, scopes) = run.update(r, &lights);
        assert_eq!(first.update.plan.kind, UpdateKind::Entire);
        assert!(scopes.contains(&"lightvolume_entire_update".to_string()), "{scopes:?}");

        // Move light 1 a little: one pass subtracts its old state and adds the new.
        lights[1] = Some(coloured(dir(-0.25, -1.0, 0.15), Vec3::new(0.6, 0.7, 1.0), 0.7));
        let (moved, scopes) = run.update(r, &lights);
        let plan = &moved.update.plan;
        assert_eq!(plan.kind, UpdateKind::Selective, "{}", plan.reason);
        assert_eq!(plan.changed_lights, 1);
        assert!(
            scopes.contains(&"lightvolume_selective_update".to_string()),
            "decision not in the profile: {scopes:?}"
        );
        assert!(scopes.contains(&"lightvolume_group_-y_1add_1sub".to_string()), "{scopes:?}");
        assert!(plan.selective.passes < plan.entire.passes, "{}", plan.reason);
        let selective = r.read_illumination().unwrap();
        let fresh = entire(ctx, gpu, &lights);
        let peak = largest_value(&fresh);
        let diff = largest_difference(&selective, &fresh);
        println!("state change: largest difference {diff:.3e} of peak {peak:.3}");
        assert!(peak > 0.1);
        assert!(diff <= SELECTIVE_TOLERANCE * peak, "selective differs from entire by {diff:.3e} (peak {peak})");

        // Switch light 2 off: only its subtraction runs, one propagation per face.
        lights[2] = None;
        let (off, scopes) = run.update(r, &lights);
        assert_eq!(off.update.plan.kind, UpdateKind::Selective, "{}", off.update.plan.reason);
        let members: Vec<_> = off.groups().iter().flat_map(|g| &g.members).collect();
        assert!(!members.is_empty() && members.iter().all(|m| m.light == 2 && m.factor < 0.0), "{members:?}");
        assert_eq!(off.update.plan.selective.propagations, members.len());
        assert!(scopes.iter().any(|s| s.ends_with("_0add_1sub")), "{scopes:?}");
        let toggled = r.read_illumination().unwrap();
        let fresh = entire(ctx, gpu, &lights);
        let diff = largest_difference(&toggled, &fresh);
        println!("toggle: largest difference {diff:.3e}");
        assert!(diff <= SELECTIVE_TOLERANCE * peak);
        // And on again: the sum returns to where it was.
        lights[2] = four_lights()[2];
        let (on, _) = run.update(r, &lights);
        assert!(on.groups().iter().flat_map(|g| &g.members).all(|m| m.light == 2 && m.factor > 0.0));
        assert!(largest_difference(&r.read_illumination().unwrap(), &selective) <= SELECTIVE_TOLERANCE * peak);
    });
}

#[test]
fn recorded_passes_are_replayed_while_their_lights_are_unchanged() {
    on_renderer(scene(|lv| lv.cost_estimate = CostEstimate::Entire), |_, _, r, run| {
        // Two lights straight down (-y) and one along +x: two passes.
        let mut lights = vec![
            Some(coloured(dir(0.0, -1.0, 0.0), Vec3::ONE, 1.0)),
            Some(coloured(dir(0.0, -1.0, 0.0), Vec3::ONE, 0.5)),
            Some(coloured(dir(1.0, 0.0, 0.0), Vec3::ONE, 0.7)),
        ];
        let (first, _) = run.update(r, &lights);
        assert_eq!((first.update.recorded, first.update.reused), (2, 0));
        let before = r.read_illumination().unwrap();
        // Nothing changed: nothing propagates.
        let (same, _) = run.update(r, &lights);
        assert_eq!(same.update.plan.kind, UpdateKind::Unchanged);
        assert_eq!(same.dispatches, 0);
        // A forced rebuild replays both recorded passes and gives the same volume bit for bit.
        r.invalidate();
        let (again, _) = run.update(r, &lights);
        assert_eq!((again.update.recorded, again.update.reused), (0, 2));
        let after = r.read_illumination().unwrap();
        assert_eq!(before.high, after.high);
        // Changing the +x light re-records its pass only.
        lights[2] = Some(coloured(dir(1.0, 0.0, 0.0), Vec3::ONE, 0.9));
        let (changed, _) = run.update(r, &lights);
        assert_eq!(changed.update.plan.kind, UpdateKind::Entire);
        assert_eq!((changed.update.recorded, changed.update.reused), (1, 1));
    });
}

#[test]
fn incremental_mode_runs_at_most_n_passes_a_frame_and_converges_to_the_entire_update() {
    let ctx = validated_context();
    let lights = four_lights();
    let full = {
        let scene = scene(defaults);
        let gpu = GpuScene::upload_with(&ctx, &scene, VolumeTexels::Float32).unwrap();
        entire(&ctx, &gpu, &lights)
    };
    let scene = scene(|lv| lv.max_passes_per_frame = 1);
    let gpu = GpuScene::upload_with(&ctx, &scene, VolumeTexels::Float32).unwrap();
    let mut r = LightVolumeRenderer::new(&gpu).unwrap();
    let mut profiler = Profiler::new(&ctx, 256).unwrap();
    let mut images = Vec::new();
    let mut deferred = Vec::new();
    for _ in 0..8 {
        let out = r.render(&lights, 16, 16, &mut profiler, false).unwrap();
        assert!(out.groups().len() <= 1, "{} passes in one frame", out.groups().len());
        deferred.push(out.update.plan.deferred);
        images.push(out.image.unwrap());
        if out.update.plan.kind == UpdateKind::Unchanged {
            break;
        }
    }
    println!("passes left after each frame: {deferred:?}");
    let total = deferred[0] + 1;
    assert!(total >= 3, "the scene needs several passes: {deferred:?}");
    assert_eq!(deferred[..total], (0..total).rev().collect::<Vec<_>>()[..], "one pass a frame");
    assert_ne!(images[0].pixels, images[total - 1].pixels, "the image changes while the update proceeds");
    let done = r.read_illumination().unwrap();
    let peak = largest_value(&full);
    assert!(largest_difference(&done, &full) <= SELECTIVE_TOLERANCE * peak);
    assert_validation_clean(&ctx);
}

/// xorshift64*: reproducible random updates without a dependency.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f32 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 40) as f32 / (1u64 << 24) as f32
    }

    fn signed(&mut self) -> f32 {
        2.0 * self.next() - 1.0
    }

    fn vec3(&mut self, scale: f32) -> Vec3 {
        Vec3::new(self.signed(), self.signed(), self.signed()) * scale
    }
}

/// Powers of the light identities: 1e-3 to 1e3 in one scene.
const POWERS: [f32; 7] = [1e-3, 1e-2, 1e-1, 1.0, 1e1, 1e2, 1e3];

fn random_light(rng: &mut Rng, power: f32) -> Light {
    let color = Vec3::new(0.3, 0.3, 0.3) + rng.vec3(0.35).abs() * 2.0;
    let kind = match (rng.next() * 3.0) as u32 {
        0 => LightKind::Directional { direction: rng.vec3(1.0).normalize_or(Vec3::NEG_Y) },
        1 => LightKind::Point { position: rng.vec3(1.6) },
        _ => {
            let position = rng.vec3(1.6);
            LightKind::Spot {
                position,
                direction: (-position + rng.vec3(0.3)).normalize_or(Vec3::NEG_Y),
                inner_cone_deg: 20.0,
                outer_cone_deg: 35.0,
            }
        }
    };
    let falloff = if rng.next() < 0.5 { Falloff::None } else { Falloff::InverseSquare };
    Light { kind, color, intensity: power, falloff }
}

struct DriftOutcome {
    /// Largest difference to a fresh entire update, over the weakest light's peak value.
    relative_to_weakest: f64,
    smallest: f64,
    selective: usize,
    entire: usize,
    /// Entire updates forced by the drift bound.
    rebases: usize,
}

/// `updates` random changes (one light each: moved, switched off or on) to the
/// lights of POWERS, then the volume against a fresh entire update of the final
/// lights (the dimmest alone).
fn drift(settings: impl FnOnce(&mut LightVolumeSettings), updates: usize) -> DriftOutcome {
    let scene = scene(settings);
    let box_ = scene.volume_box();
    let geometry = PeakGeometry { box_half: box_.half_extent, voxel_length: box_.voxel_length };
    on_renderer(scene, |ctx, gpu, r, run| {
        let mut rng = Rng(0x5eed_1234_abcd_0001);
        let mut lights: Vec<Option<Light>> = POWERS.iter().map(|&p| Some(random_light(&mut rng, p))).collect();
        let (mut selective, mut entire_updates, mut rebases) = (0, 0, 0);
        // The last updates switch every light but the dimmest off, so that most of
        // the volume is left with little or no light: where subtraction would leave
        // negative light.
        let tail = POWERS.len() - 1;
        for step in 0..updates {
            let i = if step + tail >= updates {
                POWERS.len() - (updates - step)
            } else {
                (rng.next() * POWERS.len() as f32) as usize
            };
            lights[i] = if step + tail >= updates || (lights[i].is_some() && rng.next() < 0.25) {
                None
            } else {
                Some(random_light(&mut rng, POWERS[i]))
            };
            if step + tail == updates {
                lights[0] = lights[0].or_else(|| Some(random_light(&mut rng, POWERS[0])));
            }
            let (out, _) = run.update(r, &lights);
            match out.update.plan.kind {
                UpdateKind::Selective => selective += 1,
                UpdateKind::Entire => entire_updates += 1,
                UpdateKind::Unchanged => {}
            }
            rebases += out.update.plan.reason.starts_with("re-base") as usize;
        }
        let selective_volume = r.read_illumination().unwrap();
        let fresh = entire(ctx, gpu, &lights);
        let weakest = sweeplab::techniques::lightvolume::contributions(&lights, geometry.box_half)
            .iter()
            .map(|c| geometry.peak(&c.state, c.factor))
            .fold(f64::INFINITY, f64::min);
        let diff = largest_difference(&selective_volume, &fresh);
        DriftOutcome {
            relative_to_weakest: diff / weakest,
            smallest: smallest_value(&selective_volume) / weakest,
            selective,
            entire: entire_updates,
            rebases,
        }
    })
}

/// Stated bound of the drift test: after the random updates the volume differs
/// from a fresh entire update of the final lights by at most 1e-6 of the
/// weakest light's peak value (1e-3 * its inverse-square and cone shape), the
/// re-base tolerance; no voxel is negative beyond that.
const DRIFT_TOLERANCE: f64 = 1e-6;

fn assert_no_drift(outcome: &DriftOutcome, updates: usize) {
    println!(
        "{updates} updates: {} selective, {} entire ({} re-bases); difference {:.3e} and smallest value {:.3e} of the \
         weakest light's peak",
        outcome.selective, outcome.entire, outcome.rebases, outcome.relative_to_weakest, outcome.smallest
    );
    assert!(outcome.relative_to_weakest <= DRIFT_TOLERANCE, "drift {:.3e}", outcome.relative_to_weakest);
    assert!(outcome.smallest >= -DRIFT_TOLERANCE, "negative light {:.3e}", outcome.smallest);
    assert!(outcome.selective * 10 >= updates * 8, "too few selective updates to test drift");
}

#[test]
fn random_updates_with_lights_from_1e_minus_3_to_1e3_do_not_drift() {
    let updates = 1000;
    assert_no_drift(&drift(defaults, updates), updates);
}

/// The whole 10,000-update sequence of the issue, in CI like every other test
/// (measured 27 s alone on lavapipe with 2 cores, 2026-12-05).
#[test]
fn ten_thousand_random_updates_do_not_drift() {
    let updates = 10_000;
    assert_no_drift(&drift(defaults, updates), updates);
}

#[test]
fn plain_f32_sums_drift_past_the_bound_unless_re_based() {
    let updates = 300;
    // Without compensation and never re-based, subtracting the 1e3 light leaves
    // rounding far above the dimmest light: compensation is what holds the bound.
    let plain = drift(|lv| (lv.compensated, lv.rebase_tolerance) = (false, 1e30), updates);
    println!(
        "plain f32, never re-based: difference {:.3e}, smallest value {:.3e} of the weakest peak",
        plain.relative_to_weakest, plain.smallest
    );
    assert!(plain.relative_to_weakest > DRIFT_TOLERANCE, "plain sums did not drift: the test cannot tell");
    // With the re-base policy, plain sums stay within the bound by re-basing.
    let rebased = drift(|lv| lv.compensated = false, updates);
    println!("plain f32, re-based: {} entire updates, difference {:.3e}", rebased.entire, rebased.relative_to_weakest);
    assert!(rebased.relative_to_weakest <= DRIFT_TOLERANCE);
    assert!(rebased.entire > updates / 2, "plain sums must re-base often");
}

#[test]
fn the_slice_barrier_is_load_bearing_under_synchronization_validation() {
    let ctx = validated_context();
    let scene = scene(|lv| lv.racy = true);
    let gpu = GpuScene::upload_with(&ctx, &scene, VolumeTexels::Float32).unwrap();
    let mut r = LightVolumeRenderer::new(&gpu).unwrap();
    let mut run = Run::new(&ctx);
    run.update(&mut r, &four_lights());
    let messages = ctx.take_validation_messages();
    assert!(
        messages.iter().any(|m| m.contains("SYNC-HAZARD") && m.contains("lightvolume slice")),
        "a pass without its slice barriers went unreported: {messages:?}"
    );
}

#[test]
fn shortening_and_growing_the_light_list_subtracts_and_adds_the_lights_it_drops_and_gains() {
    on_renderer(scene(|lv| lv.cost_estimate = CostEstimate::Selective), |ctx, gpu, r, run| {
        let all = four_lights();
        run.update(r, &all);
        // Lights 2 and 3 dropped off the end, light 1 moved: their old states are
        // subtracted from the slots they were propagated from.
        let mut short = all[..2].to_vec();
        short[1] = Some(coloured(dir(-0.3, -1.0, 0.1), Vec3::ONE, 0.9));
        let (out, _) = run.update(r, &short);
        assert_eq!(out.update.plan.kind, UpdateKind::Selective);
        assert_eq!(out.update.plan.changed_lights, 3, "{}", out.update.plan.reason);
        let fresh = entire(ctx, gpu, &short);
        let peak = largest_value(&entire(ctx, gpu, &all));
        assert!(largest_difference(&r.read_illumination().unwrap(), &fresh) <= SELECTIVE_TOLERANCE * peak);
        // And back to all four plus a fifth.
        let mut long = all.clone();
        long.push(Some(coloured(dir(0.0, -1.0, -0.4), Vec3::new(0.2, 1.0, 0.4), 1.1)));
        run.update(r, &long);
        let fresh = entire(ctx, gpu, &long);
        assert!(largest_difference(&r.read_illumination().unwrap(), &fresh) <= SELECTIVE_TOLERANCE * peak);
    });
}

/// Near-opaque medium (alpha 0.999 per voxel in the dense parts), lights at
/// grazing angles to a face, one along the view direction, and a moved light
/// crossing the diagonal where its share passes from one group to the other:
/// everything stays finite and non-negative, and the selective update still
/// gives the entire update's volume.
#[test]
fn near_opaque_media_grazing_lights_and_group_crossings_stay_finite_and_exact() {
    // Model (i): one transmittance, so the white-red medium shadows every channel.
    let mut scene = scene(|lv| lv.chromatic = false);
    scene.transfer = sweeplab::scene::TransferFunction {
        points: vec![
            sweeplab::scene::ControlPoint { value: 0.0, rgba: [1.0, 1.0, 1.0, 0.0] },
            sweeplab::scene::ControlPoint { value: 0.3, rgba: [1.0, 0.8, 0.6, 0.999] },
            sweeplab::scene::ControlPoint { value: 1.0, rgba: [1.0, 0.8, 0.6, 0.999] },
        ],
    };
    let view = scene.camera.forward();
    on_renderer(scene, |ctx, gpu, r, run| {
        let mut lights = vec![
            Some(coloured(dir(1.0, -1e-4, 0.0), Vec3::ONE, 1.0)),
            Some(coloured(dir(1e-5, -1.0, 0.0), Vec3::ONE, 1.0)),
            Some(coloured(LightKind::Directional { direction: view }, Vec3::ONE, 1.0)),
            Some(coloured(dir(0.6, -0.4, 0.0), Vec3::new(1.0, 0.3, 0.1), 5.0)),
        ];
        run.update(r, &lights);
        // Light 3 swings across the x = y diagonal: its larger share moves from +x to -y.
        let mut kinds = Vec::new();
        for step in 1..=5 {
            let t = step as f32 / 5.0;
            lights[3] = Some(coloured(dir(0.6 - 0.2 * t, -0.4 - 0.2 * t, 0.05 * t), Vec3::new(1.0, 0.3, 0.1), 5.0));
            let (out, _) = run.update(r, &lights);
            kinds.push(out.update.plan.kind);
        }
        assert!(kinds.iter().all(|k| *k == UpdateKind::Selective), "{kinds:?}");
        let volume = r.read_illumination().unwrap();
        let fresh = entire(ctx, gpu, &lights);
        let peak = largest_value(&fresh);
        assert!((0..volume.high.len()).all(|i| (0..3).all(|c| volume.value(i, c).is_finite())));
        assert!(smallest_value(&volume) >= -SELECTIVE_TOLERANCE * peak, "negative light {}", smallest_value(&volume));
        let diff = largest_difference(&volume, &fresh);
        println!("near-opaque, grazing: peak {peak:.3}, difference {diff:.3e}");
        assert!(peak > 0.5 && diff <= SELECTIVE_TOLERANCE * peak, "difference {diff:.3e} of peak {peak}");
        // The opaque medium does shadow: the darkest voxel holds almost no light.
        let darkest = (0..fresh.high.len()).map(|i| fresh.value(i, 0)).fold(f64::INFINITY, f64::min);
        assert!(darkest < 1e-3 * peak, "darkest voxel {darkest:.3e}");
    });
}

#[test]
fn a_light_moved_back_and_forth_replays_its_recorded_selective_passes() {
    on_renderer(scene(defaults), |ctx, gpu, r, run| {
        let a = four_lights();
        let mut b = a.clone();
        b[0] = Some(coloured(dir(0.15, -1.0, 0.2), Vec3::new(1.0, 0.9, 0.8), 1.0));
        run.update(r, &a);
        let mut counts = Vec::new();
        for state in [&b, &a, &b, &a] {
            let (out, _) = run.update(r, state);
            assert_eq!(out.update.plan.kind, UpdateKind::Selective);
            counts.push((out.update.recorded, out.update.reused));
        }
        // The first move each way records its passes; from then on they are replayed.
        let passes = counts[0].0;
        assert!(passes > 0);
        assert_eq!(counts, [(passes, 0), (passes, 0), (0, passes), (0, passes)]);
        let fresh = entire(ctx, gpu, &a);
        let peak = largest_value(&fresh);
        assert!(largest_difference(&r.read_illumination().unwrap(), &fresh) <= SELECTIVE_TOLERANCE * peak);
    });
}

/// Forty lights of one direction fill two groups; at 16 lights a pass each
/// group is split into three passes of the same axis, run consecutively, and
/// the volume is the one of unsplit passes.
#[test]
fn groups_larger_than_a_pass_are_split_and_give_the_same_volume() {
    let ctx = validated_context();
    let lights: Vec<Option<Light>> = (0..40)
        .map(|i| {
            let a = i as f32 * 2.4;
            Some(coloured(dir(0.35 + 0.04 * a.cos(), -1.0, 0.25 + 0.04 * a.sin()), Vec3::ONE, 0.05))
        })
        .collect();
    let mut volumes = Vec::new();
    for pass_lights in [16usize, 64] {
        let scene = scene(|lv| lv.pass_lights = pass_lights as u32);
        let gpu = GpuScene::upload_with(&ctx, &scene, VolumeTexels::Float32).unwrap();
        let mut r = LightVolumeRenderer::new(&gpu).unwrap();
        let (out, scopes) = Run::new(&ctx).update(&mut r, &lights);
        let names: Vec<String> = out.groups().iter().map(|g| g.scope_name()).collect();
        println!("pass_lights {pass_lights}: {names:?}");
        assert!(out.groups().iter().all(|g| g.members.len() <= pass_lights));
        let expected = if pass_lights == 16 { 6 } else { 2 };
        assert_eq!(out.groups().len(), expected, "{names:?}");
        assert_eq!(scopes.iter().filter(|s| s.starts_with("lightvolume_group_")).count(), expected);
        volumes.push(r.read_illumination().unwrap());
    }
    let peak = largest_value(&volumes[1]);
    assert!(largest_difference(&volumes[0], &volumes[1]) <= SELECTIVE_TOLERANCE * peak);
    assert_validation_clean(&ctx);
}

/// A point light moved from outside the volume to near its centre (all six
/// groups, weighted per voxel) and back: each move subtracts the old groups and
/// adds the new ones in one selective update (the other lights use all six
/// groups, so the passes tie with an entire update's and the share of changed
/// lights decides), which gives the volume of an entire update.
#[test]
fn moving_a_point_light_inside_the_volume_and_back_is_a_selective_update() {
    on_renderer(scene(defaults), |ctx, gpu, r, run| {
        let mut lights = four_lights();
        lights.push(Some(coloured(dir(0.0, 1.0, -0.3), Vec3::new(0.8, 0.8, 1.0), 0.5)));
        let outside = lights[3];
        let (first, _) = run.update(r, &lights);
        assert_eq!(first.update.plan.kind, UpdateKind::Entire);
        let inside =
            Some(Light { kind: LightKind::Point { position: Vec3::new(0.05, -0.1, 0.02) }, ..outside.unwrap() });
        // Outside, the light is beside the volume (within its x extent): +z, and
        // its x share both ways.
        for (what, state, groups) in [("inside", inside, 6), ("outside", outside, 3)] {
            lights[3] = state;
            let (moved, scopes) = run.update(r, &lights);
            let plan = &moved.update.plan;
            assert_eq!(plan.kind, UpdateKind::Selective, "{what}: {}", plan.reason);
            assert_eq!(plan.changed_lights, 1);
            let added: Vec<_> = moved.groups().iter().flat_map(|g| &g.members).filter(|m| m.factor > 0.0).collect();
            assert_eq!(added.len(), groups, "{what}: {scopes:?}");
            assert!(added.iter().all(|m| m.light == 3 && m.per_voxel == (what == "inside")));
            let selective = r.read_illumination().unwrap();
            let fresh = entire(ctx, gpu, &lights);
            let (peak, diff) = (largest_value(&fresh), largest_difference(&selective, &fresh));
            println!("moved {what}: {} passes, largest difference {diff:.3e} of peak {peak:.3}", plan.passes.len());
            assert!(diff <= SELECTIVE_TOLERANCE * peak, "{what}: selective differs from entire by {diff:.3e}");
        }
    });
}

#[test]
fn an_update_with_more_contributions_than_the_entry_block_holds_is_an_error() {
    use sweeplab::techniques::lightvolume::propagation::MAX_ENTRIES;
    on_renderer(scene(defaults), |_, _, r, run| {
        // Point lights inside the box take all six groups: one more light than fits.
        let inside = |i: usize| {
            let x = -0.4 + 0.8 * (i as f32 / (MAX_ENTRIES / 6) as f32);
            Some(Light {
                kind: LightKind::Point { position: Vec3::new(x, 0.1, -0.05) },
                color: Vec3::ONE,
                intensity: 1.0,
                falloff: Falloff::None,
            })
        };
        let lights: Vec<Option<Light>> = (0..MAX_ENTRIES / 6 + 1).map(inside).collect();
        run.profiler.reset();
        let error = r.update(&lights, &mut run.profiler).err().expect("too many contributions");
        assert!(error.to_string().contains("light contributions"), "{error}");
        // Within the bound the same renderer still updates.
        let (out, _) = run.update(r, &lights[..4]);
        assert_eq!(out.update.plan.kind, UpdateKind::Entire);
    });
}
