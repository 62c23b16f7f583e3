//! Coherence-based propagation groups (selective light updates, section 4):
//! six groups, one per propagation direction (+-x, +-y, +-z). Each light joins
//! the group of the volume face closest to it with factor alpha_c (equation 5a)
//! and the group of the second closest face with alpha_sc = 1 - alpha_c (5b).
//! A light's share of one group is a [`Contribution`]; passes are built from
//! contributions, each with a sign (+1 adds it to the volume, -1 subtracts it).

use crate::render::frame_params::{gpu_light, GpuLight};
use crate::scene::{Light, LightKind};
use glam::Vec3;
use std::f32::consts::PI;

/// Below this a light's share of a group is dropped: it would add nothing but
/// the cost of a whole group pass.
const MIN_FACTOR: f32 = 1e-6;

/// One light's membership in a group pass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GroupMember {
    /// Index into the scene's lights (the light's id).
    pub light: usize,
    /// Contribution factor alpha (equations 5a/5b), negative where the pass
    /// subtracts the light's earlier state.
    pub factor: f32,
    /// The light as propagated (for a subtraction: its old state).
    pub state: GpuLight,
}

/// What one light in one state adds to the volume through one group. Equal
/// contributions propagate to bit-equal values (same shader, same inputs,
/// whatever else shares the pass), which is what lets a subtraction cancel an
/// earlier addition.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contribution {
    pub light: usize,
    pub state: GpuLight,
    pub axis: usize,
    pub travel: i32,
    /// Positive alpha.
    pub factor: f32,
}

impl Contribution {
    /// Group index in pass order: +x, -x, +y, -y, +z, -z.
    pub fn group_slot(&self) -> usize {
        self.axis * 2 + if self.travel > 0 { 0 } else { 1 }
    }
}

/// The lights propagated along one axis direction.
#[derive(Clone, Debug, PartialEq)]
pub struct PropagationGroup {
    /// 0 = x, 1 = y, 2 = z.
    pub axis: usize,
    /// Direction the light travels along the axis: +1 or -1. Propagation starts
    /// at the slice nearest the light, on the face at -travel.
    pub travel: i32,
    pub members: Vec<GroupMember>,
}

impl PropagationGroup {
    /// "-y" for light travelling toward -y.
    pub fn direction_name(&self) -> String {
        format!("{}{}", if self.travel > 0 { '+' } else { '-' }, ['x', 'y', 'z'][self.axis])
    }

    /// Profiler scope of the group pass, e.g. `lightvolume_group_-y_2lights`;
    /// a pass that subtracts says how many it adds and subtracts, e.g.
    /// `lightvolume_group_-y_1add_1sub`.
    pub fn scope_name(&self) -> String {
        let subs = self.members.iter().filter(|m| m.factor < 0.0).count();
        if subs == 0 {
            format!("lightvolume_group_{}_{}lights", self.direction_name(), self.members.len())
        } else {
            format!("lightvolume_group_{}_{}add_{subs}sub", self.direction_name(), self.members.len() - subs)
        }
    }
}

/// Unit direction from the volume centre (the origin) toward the light. A
/// directional light lies at -direction; a light at the centre itself has no
/// direction and is taken as straight above (+y), like a zero light direction.
pub fn light_position_direction(light: &Light) -> Vec3 {
    match light.kind {
        LightKind::Directional { direction } => -direction.normalize_or(Vec3::NEG_Y),
        LightKind::Point { position } | LightKind::Spot { position, .. } => position.normalize_or(Vec3::Y),
    }
}

/// (axis, travel, factor) of the closest and the second closest face of a
/// light at unit direction `l_pos`. The face closest to the light has the
/// outward normal n with the largest `l_pos . n`; its group propagates along
/// n_F = -n (away from the light), so `l_pos . -n_F = cos(angle to the face
/// normal)` and a light straight above gets factor 1 in the -y group.
pub fn face_factors(l_pos: Vec3) -> [(usize, i32, f32); 2] {
    let c = l_pos.abs().to_array();
    let mut order = [0usize, 1, 2];
    order.sort_by(|&i, &j| c[j].total_cmp(&c[i]));
    let travel = |axis: usize| if l_pos[axis] >= 0.0 { -1 } else { 1 };
    let closest = order[0];
    let alpha_c = 1.0 - 2.0 * c[closest].clamp(-1.0, 1.0).acos() / PI;
    let second = order[1];
    [(closest, travel(closest), alpha_c), (second, travel(second), 1.0 - alpha_c)]
}

/// Every contribution of the lights that are on (`None` is a light switched
/// off), in light order.
pub fn contributions(lights: &[Option<Light>]) -> Vec<Contribution> {
    let mut out = Vec::new();
    for (index, light) in lights.iter().enumerate() {
        let Some(light) = light else { continue };
        let state = gpu_light(light);
        for (axis, travel, factor) in face_factors(light_position_direction(light)) {
            if factor > MIN_FACTOR {
                out.push(Contribution { light: index, state, axis, travel, factor });
            }
        }
    }
    out
}

/// Passes for `items` (a contribution and the sign it enters with), in group
/// order (+x, -x, +y, -y, +z, -z, so each axis runs consecutively and its slice
/// buffers are reused). Coherent: one pass per non-empty group, split after
/// `pass_lights` members; sequential: one pass per item.
pub fn group_passes(items: &[(Contribution, f32)], coherent: bool, pass_lights: usize) -> Vec<PropagationGroup> {
    let mut by_group: Vec<Vec<GroupMember>> = vec![Vec::new(); 6];
    for (c, sign) in items {
        by_group[c.group_slot()].push(GroupMember { light: c.light, factor: sign * c.factor, state: c.state });
    }
    let per_pass = if coherent { pass_lights.max(1) } else { 1 };
    let mut passes = Vec::new();
    for (slot, members) in by_group.into_iter().enumerate() {
        for chunk in members.chunks(per_pass) {
            passes.push(PropagationGroup {
                axis: slot / 2,
                travel: if slot % 2 == 0 { 1 } else { -1 },
                members: chunk.to_vec(),
            });
        }
    }
    passes
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Falloff;

    /// The passes of an entire coherent update of `lights`, all on.
    fn propagation_groups(lights: &[Light]) -> Vec<PropagationGroup> {
        let on: Vec<Option<Light>> = lights.iter().copied().map(Some).collect();
        let items: Vec<_> = contributions(&on).into_iter().map(|c| (c, 1.0)).collect();
        group_passes(&items, true, usize::MAX)
    }

    fn directional(direction: Vec3) -> Light {
        Light { kind: LightKind::Directional { direction }, color: Vec3::ONE, intensity: 1.0, falloff: Falloff::None }
    }

    #[test]
    fn a_light_straight_above_propagates_downward_alone() {
        let groups = propagation_groups(&[directional(Vec3::NEG_Y)]);
        assert_eq!(groups.len(), 1);
        assert_eq!(groups[0].direction_name(), "-y");
        assert!((groups[0].members[0].factor - 1.0).abs() < 1e-6);
        assert_eq!(groups[0].scope_name(), "lightvolume_group_-y_1lights");
    }

    #[test]
    fn a_diagonal_light_splits_evenly_and_factors_sum_to_one() {
        let groups = propagation_groups(&[directional(Vec3::new(1.0, -1.0, 0.0))]);
        let names: Vec<String> = groups.iter().map(|g| g.direction_name()).collect();
        assert_eq!(names, ["+x", "-y"]);
        for g in &groups {
            assert!((g.members[0].factor - 0.5).abs() < 1e-5, "{g:?}");
        }
        let l = Light {
            kind: LightKind::Point { position: Vec3::new(0.2, 0.3, -2.0) },
            color: Vec3::ONE,
            intensity: 1.0,
            falloff: Falloff::None,
        };
        let groups = propagation_groups(&[l]);
        let names: Vec<String> = groups.iter().map(|g| g.direction_name()).collect();
        // Closest face -z (light travels +z), second the +y face (travels -y).
        assert_eq!(names, ["-y", "+z"]);
        let sum: f32 = groups.iter().map(|g| g.members[0].factor).sum();
        assert!((sum - 1.0).abs() < 1e-6);
    }
}
