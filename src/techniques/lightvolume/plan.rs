//! What one update of the illumination volume propagates (section 5): the
//! difference between the contributions the volume holds and those of the
//! current lights, as a selective update (subtract what went, add what came,
//! in shared passes) or an entire one (clear, then everything), chosen by the
//! cost estimate; in incremental mode at most N passes a frame, the rest
//! following in later frames.

use super::groups::{group_passes, Contribution, PropagationGroup};
use super::settings::{CostEstimate, LightVolumeSettings};
use crate::render::frame_params::GpuLight;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UpdateKind {
    /// The volume already holds the current lights: nothing is propagated.
    Unchanged,
    /// Clear, then propagate every light.
    Entire,
    /// Propagate only the changed lights: old states subtracted, new added.
    Selective,
}

impl UpdateKind {
    /// Profiler scope of the update.
    pub fn scope_name(self) -> &'static str {
        match self {
            UpdateKind::Unchanged => "lightvolume_unchanged",
            UpdateKind::Entire => "lightvolume_entire_update",
            UpdateKind::Selective => "lightvolume_selective_update",
        }
    }
}

/// Passes and light propagations of one way of updating.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct UpdateCost {
    pub passes: usize,
    /// Light propagations over all passes (a changed light counts twice).
    pub propagations: usize,
}

/// The decision and what it is based on.
#[derive(Clone, Debug, PartialEq)]
pub struct UpdatePlan {
    pub kind: UpdateKind,
    /// Why, in words (printed by the CLI, kept in bench records).
    pub reason: String,
    pub selective: UpdateCost,
    pub entire: UpdateCost,
    /// Lights whose contributions changed, and lights on before or after.
    pub changed_lights: usize,
    pub lights: usize,
    /// Passes to run now, in order.
    pub passes: Vec<PropagationGroup>,
    /// Passes of the chosen update left for later frames (incremental mode).
    pub deferred: usize,
}

/// A bound on the rounding error selective updates leave in the volume, in the
/// volume's units, kept since the last entire update (the last re-base).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DriftBound {
    pub bound: f64,
}

/// f32 unit roundoff.
const U: f64 = f32::EPSILON as f64 / 2.0;

impl DriftBound {
    /// Rounding error of one addition into a voxel whose running sum is at most
    /// `magnitude`: u * magnitude for plain f32 sums; for compensated sums only
    /// the rounding of the low word, 2 u^2 * magnitude (the high word's error is
    /// carried exactly).
    pub fn per_addition(magnitude: f64, compensated: bool) -> f64 {
        if compensated {
            2.0 * U * U * magnitude
        } else {
            U * magnitude
        }
    }
}

/// Box geometry the peaks are measured in.
#[derive(Clone, Copy, Debug)]
pub struct PeakGeometry {
    pub box_half: glam::Vec3,
    pub voxel_length: f32,
}

impl PeakGeometry {
    /// Largest light value a light in `state` with contribution `factor` can
    /// put into a voxel: its brightest channel times the factor, with
    /// inverse-square falloff at the closest distance the shader allows (one
    /// voxel, or the distance to the box).
    pub fn peak(&self, state: &GpuLight, factor: f32) -> f64 {
        let r = state.radiance;
        let brightest = r[0].max(r[1]).max(r[2]).max(0.0) as f64;
        let mut shape = 1.0;
        if state.pos_type[3] != 0.0 && state.params[0] > 0.5 {
            let p = glam::Vec3::from_slice(&state.pos_type[..3]);
            let outside = (p.abs() - self.box_half).max(glam::Vec3::ZERO).length();
            let d = outside.max(self.voxel_length) as f64;
            shape = 1.0 / (d * d);
        }
        brightest * shape * factor.abs() as f64
    }

    fn of(&self, c: &Contribution) -> f64 {
        self.peak(&c.state, c.factor)
    }
}

/// The rounding bound of adding (or subtracting) contributions of the given
/// peak values into a volume holding `present`: each rounds once per voxel
/// against a running sum no larger than everything present plus itself.
fn rounding(
    present: &[Contribution],
    peaks: impl Iterator<Item = f64>,
    compensated: bool,
    geometry: PeakGeometry,
) -> f64 {
    let present_peak: f64 = present.iter().map(|c| geometry.of(c)).sum();
    peaks.map(|p| DriftBound::per_addition(present_peak + p, compensated)).sum()
}

/// `present` minus `target` as a multiset (what must be subtracted), and
/// `target` minus `present` (what must be added).
fn difference(present: &[Contribution], target: &[Contribution]) -> (Vec<Contribution>, Vec<Contribution>) {
    let mut unmatched: Vec<Option<&Contribution>> = target.iter().map(Some).collect();
    let mut subtract = Vec::new();
    for p in present {
        match unmatched.iter_mut().find(|t| t.is_some_and(|t| t == p)) {
            Some(slot) => *slot = None,
            None => subtract.push(*p),
        }
    }
    let add = unmatched.into_iter().flatten().copied().collect();
    (subtract, add)
}

fn distinct_lights<'c>(cs: impl Iterator<Item = &'c Contribution>) -> Vec<usize> {
    let mut ids: Vec<usize> = cs.map(|c| c.light).collect();
    ids.sort_unstable();
    ids.dedup();
    ids
}

/// State kept between updates besides the contributions.
#[derive(Clone, Copy, Debug, Default)]
pub struct PlanState {
    /// The volume holds no valid sum (before the first update, or asked to
    /// rebuild): only an entire update will do.
    pub invalid: bool,
    /// The previous frame left passes for later (incremental mode).
    pub pending: bool,
    pub drift: DriftBound,
}

/// Chooses the update that brings the volume from `present` to `target`.
pub fn plan_update(
    present: &[Contribution],
    target: &[Contribution],
    settings: &LightVolumeSettings,
    state: &PlanState,
    geometry: PeakGeometry,
) -> UpdatePlan {
    let (subtract, add) = difference(present, target);
    let changed = distinct_lights(subtract.iter().chain(&add));
    let lights = distinct_lights(present.iter().chain(target)).len();
    let mut items: Vec<(Contribution, f32)> = subtract.iter().map(|c| (*c, -1.0)).collect();
    items.extend(add.iter().map(|c| (*c, 1.0)));
    // Subtractions and additions of one light side by side in their pass.
    items.sort_by_key(|(c, sign)| (c.group_slot(), c.light, *sign > 0.0));
    let pass_lights = settings.pass_lights as usize;
    let selective_passes = group_passes(&items, settings.coherent, pass_lights);
    let entire_items: Vec<(Contribution, f32)> = target.iter().map(|c| (*c, 1.0)).collect();
    let entire_passes = group_passes(&entire_items, settings.coherent, pass_lights);
    let selective = UpdateCost { passes: selective_passes.len(), propagations: items.len() };
    let entire = UpdateCost { passes: entire_passes.len(), propagations: entire_items.len() };
    let share_selective = 2 * changed.len() <= lights;

    // The rounding bound a selective update would leave.
    let drift_after = state.drift.bound
        + rounding(present, items.iter().map(|(c, _)| geometry.of(c)), settings.compensated, geometry);
    let weakest = target.iter().map(|c| geometry.of(c)).filter(|p| *p > 0.0).fold(f64::INFINITY, f64::min);
    let tolerance = settings.rebase_tolerance * weakest;

    let (kind, reason) = if state.invalid {
        (UpdateKind::Entire, "the volume holds no valid sum yet".to_string())
    } else if items.is_empty() {
        (UpdateKind::Unchanged, "no light changed".to_string())
    } else if target.is_empty() {
        (UpdateKind::Entire, "no light left: clearing is the whole update".to_string())
    } else if drift_after > tolerance {
        (
            UpdateKind::Entire,
            format!(
                "re-base: the rounding bound after a selective update, {drift_after:.2e}, exceeds {:.0e} of the \
                 weakest light's peak ({weakest:.2e})",
                settings.rebase_tolerance
            ),
        )
    } else if state.pending {
        (UpdateKind::Selective, "continuing an incremental update".to_string())
    } else {
        let share = format!("{} of {lights} lights changed", changed.len());
        let counts = format!(
            "selective {} passes / {} propagations, entire {} / {}",
            selective.passes, selective.propagations, entire.passes, entire.propagations
        );
        let pick_selective = match settings.cost_estimate {
            CostEstimate::Share => share_selective,
            CostEstimate::Passes if selective.passes != entire.passes => selective.passes < entire.passes,
            CostEstimate::Passes => share_selective,
            CostEstimate::Selective => true,
            CostEstimate::Entire => false,
        };
        let kind = if pick_selective { UpdateKind::Selective } else { UpdateKind::Entire };
        (kind, format!("cost estimate '{}': {share}; {counts}", settings.cost_estimate.name()))
    };
    let mut passes = match kind {
        UpdateKind::Unchanged => Vec::new(),
        UpdateKind::Entire => entire_passes,
        UpdateKind::Selective => selective_passes,
    };
    let limit = settings.max_passes_per_frame as usize;
    let deferred = if limit > 0 && passes.len() > limit { passes.len() - limit } else { 0 };
    passes.truncate(passes.len() - deferred);
    UpdatePlan { kind, reason, selective, entire, changed_lights: changed.len(), lights, passes, deferred }
}

/// The contributions the volume holds after running `passes` (from an empty
/// volume when `cleared`).
pub fn apply(present: &mut Vec<Contribution>, cleared: bool, passes: &[PropagationGroup]) {
    if cleared {
        present.clear();
    }
    for pass in passes {
        for m in &pass.members {
            let c = Contribution {
                light: m.light,
                state: m.state,
                axis: pass.axis,
                travel: pass.travel,
                factor: m.factor.abs(),
                per_voxel: m.per_voxel,
            };
            if m.factor < 0.0 {
                if let Some(i) = present.iter().position(|p| *p == c) {
                    present.swap_remove(i);
                }
            } else {
                present.push(c);
            }
        }
    }
}

/// The drift bound after running `plan` (reset by an entire update).
pub fn drift_after(
    state: &PlanState,
    present_before: &[Contribution],
    plan: &UpdatePlan,
    settings: &LightVolumeSettings,
    geometry: PeakGeometry,
) -> DriftBound {
    match plan.kind {
        UpdateKind::Unchanged => state.drift,
        UpdateKind::Entire => DriftBound::default(),
        UpdateKind::Selective => {
            let members = plan.passes.iter().flat_map(|p| &p.members);
            let peaks = members.map(|m| geometry.peak(&m.state, m.factor));
            let added = rounding(present_before, peaks, settings.compensated, geometry);
            DriftBound { bound: state.drift.bound + added }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Falloff, Light, LightKind};
    use crate::techniques::lightvolume::groups::contributions;
    use glam::Vec3;

    fn light(direction: Vec3, intensity: f32) -> Option<Light> {
        Some(Light { kind: LightKind::Directional { direction }, color: Vec3::ONE, intensity, falloff: Falloff::None })
    }

    const GEOMETRY: PeakGeometry = PeakGeometry { box_half: Vec3::ONE, voxel_length: 0.1 };

    fn plan(before: &[Option<Light>], after: &[Option<Light>], settings: &LightVolumeSettings) -> UpdatePlan {
        let c = |lights| contributions(lights, GEOMETRY.box_half);
        plan_update(&c(before), &c(after), settings, &PlanState::default(), GEOMETRY)
    }

    fn four_lights() -> Vec<Option<Light>> {
        vec![
            light(Vec3::NEG_Y, 1.0),
            light(Vec3::new(0.1, -1.0, 0.0), 1.0),
            light(Vec3::new(-0.1, -1.0, 0.05), 1.0),
            light(Vec3::new(0.0, -1.0, 0.1), 1.0),
        ]
    }

    #[test]
    fn one_moved_light_among_four_is_a_selective_pass_that_subtracts_and_adds() {
        let before = four_lights();
        let mut after = before.clone();
        after[1] = light(Vec3::new(0.15, -1.0, 0.0), 1.0);
        let p = plan(&before, &after, &LightVolumeSettings::default());
        assert_eq!(p.kind, UpdateKind::Selective, "{}", p.reason);
        assert_eq!(p.changed_lights, 1);
        let names: Vec<String> = p.passes.iter().map(|g| g.scope_name()).collect();
        assert!(names.contains(&"lightvolume_group_-y_1add_1sub".to_string()), "{names:?}");
        assert_eq!(p.selective.propagations, 4, "two faces, each subtracted and added");
    }

    #[test]
    fn toggling_a_light_is_one_signed_propagation_per_face() {
        let before = four_lights();
        let mut after = before.clone();
        after[2] = None;
        let p = plan(&before, &after, &LightVolumeSettings::default());
        assert_eq!(p.kind, UpdateKind::Selective);
        assert!(p.passes.iter().flat_map(|g| &g.members).all(|m| m.factor < 0.0 && m.light == 2));
        let back = plan(&after, &before, &LightVolumeSettings::default());
        assert!(back.passes.iter().flat_map(|g| &g.members).all(|m| m.factor > 0.0 && m.light == 2));
    }

    #[test]
    fn the_cost_estimates_prefer_entire_updates_when_most_lights_change() {
        let before = four_lights();
        let mut after = before.clone();
        for (i, l) in after.iter_mut().enumerate().take(3) {
            *l = light(Vec3::new(0.2 * i as f32, -1.0, 0.3), 2.0);
        }
        let share = LightVolumeSettings { cost_estimate: CostEstimate::Share, ..Default::default() };
        assert_eq!(plan(&before, &after, &share).kind, UpdateKind::Entire);
        // The moved lights also open a +x pass: more passes than an entire update.
        let passes = plan(&before, &after, &LightVolumeSettings::default());
        assert!(passes.selective.passes > passes.entire.passes, "{passes:?}");
        assert_eq!(passes.kind, UpdateKind::Entire);
        // Two lights straight down, one brighter: one pass either way, the share decides (1 of 2).
        let down = vec![light(Vec3::NEG_Y, 1.0), light(Vec3::NEG_Y, 0.5)];
        let brighter = vec![light(Vec3::NEG_Y, 1.0), light(Vec3::NEG_Y, 0.7)];
        let tie = plan(&down, &brighter, &LightVolumeSettings::default());
        assert_eq!((tie.selective.passes, tie.entire.passes), (1, 1));
        assert_eq!(tie.kind, UpdateKind::Selective, "{}", tie.reason);
        // Two lights, one changed: half changed, so selective (the paper's rule at exactly 50%).
        let two = &before[..2];
        let mut two_after = two.to_vec();
        two_after[0] = light(Vec3::new(0.05, -1.0, 0.0), 1.0);
        assert_eq!(plan(two, &two_after, &share).kind, UpdateKind::Selective);
        // Sequential propagation: the pass count follows the propagations.
        let seq = LightVolumeSettings { coherent: false, ..Default::default() };
        let p = plan(&before, &after, &seq);
        assert_eq!(p.selective.passes, p.selective.propagations);
        assert_eq!(p.kind, UpdateKind::Entire, "{}", p.reason);
    }

    #[test]
    fn unchanged_lights_need_nothing_and_an_invalid_volume_needs_everything() {
        let lights = four_lights();
        let s = LightVolumeSettings::default();
        assert_eq!(plan(&lights, &lights, &s).kind, UpdateKind::Unchanged);
        let state = PlanState { invalid: true, ..Default::default() };
        let c = contributions(&lights, GEOMETRY.box_half);
        let p = plan_update(&c, &c, &s, &state, GEOMETRY);
        assert_eq!(p.kind, UpdateKind::Entire);
        assert_eq!(p.passes.len(), p.entire.passes);
    }

    #[test]
    fn incremental_mode_defers_passes_and_apply_tracks_what_the_volume_holds() {
        let lights: Vec<_> =
            (0..6).map(|i| light(Vec3::new((i as f32 - 2.5) * 0.8, -0.5 + 0.3 * (i % 2) as f32, 0.7), 1.0)).collect();
        let s = LightVolumeSettings { max_passes_per_frame: 1, ..Default::default() };
        let target = contributions(&lights, GEOMETRY.box_half);
        let mut present = Vec::new();
        let mut state = PlanState { invalid: true, ..Default::default() };
        let mut frames = 0;
        loop {
            let p = plan_update(&present, &target, &s, &state, GEOMETRY);
            if p.kind == UpdateKind::Unchanged {
                break;
            }
            assert!(p.passes.len() <= 1);
            state.drift = drift_after(&state, &present, &p, &s, GEOMETRY);
            apply(&mut present, p.kind == UpdateKind::Entire, &p.passes);
            state.invalid = false;
            state.pending = p.deferred > 0;
            frames += 1;
            assert!(frames < 20, "incremental update does not converge");
        }
        let first = plan_update(&[], &target, &s, &PlanState { invalid: true, ..Default::default() }, GEOMETRY);
        assert_eq!(frames, first.entire.passes, "one pass a frame");
        assert!(first.entire.passes > 1);
        assert_eq!(difference(&present, &target), (vec![], vec![]));
    }

    #[test]
    fn plain_f32_sums_re_base_far_sooner_than_compensated_ones() {
        let before = vec![light(Vec3::NEG_Y, 1e3), light(Vec3::new(0.1, -1.0, 0.0), 1e-3)];
        let mut after = before.clone();
        after[0] = light(Vec3::new(0.05, -1.0, 0.0), 1e3);
        let plain = LightVolumeSettings { compensated: false, ..Default::default() };
        let p = plan(&before, &after, &plain);
        assert_eq!(p.kind, UpdateKind::Entire);
        assert!(p.reason.starts_with("re-base"), "{}", p.reason);
        let p = plan(&before, &after, &LightVolumeSettings::default());
        assert_eq!(p.kind, UpdateKind::Selective, "{}", p.reason);
    }
}
