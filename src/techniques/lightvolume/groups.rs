//! Coherence-based propagation groups (selective light updates, section 4):
//! six groups, one per propagation direction (+-x, +-y, +-z). Each light joins
//! the group of the volume face closest to it with factor alpha_c (equation 5a)
//! and the group of the second closest face with alpha_sc = 1 - alpha_c (5b).
//! A light's share of one group is a [`Contribution`]; passes are built from
//! contributions, each with a sign (+1 adds it to the volume, -1 subtracts it).
//!
//! Point and spot lights near the volume send light both ways along an axis:
//! one *beside* the volume (outside it, but within its extent along one of its
//! two group axes) also joins the opposite group of that axis with the same
//! factor, and each group carries the light only where it travels the group's
//! way; one *inside* the volume joins all six groups (section 7.3), each voxel
//! weighted by the squared cosine between the light's travel and the group's
//! axis (the weights of the three axes sum to one), and a spot light only the
//! groups its cone reaches. Nothing travelling against a group is dropped.

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
    /// The factor is weighted per voxel by cos^2 (a light inside the volume).
    pub per_voxel: bool,
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
    /// Weighted per voxel by cos^2 between travel and axis (a light inside).
    pub per_voxel: bool,
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

/// The direction a spot light points (unit).
fn light_spot_direction(light: &Light) -> Vec3 {
    match light.kind {
        LightKind::Spot { direction, .. } => direction.normalize_or(Vec3::NEG_Y),
        _ => Vec3::NEG_Y,
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

/// Whether a spot light's cone (outer half-angle) reaches a direction that
/// travels `travel` along `axis`; other lights reach every direction.
fn cone_reaches(light: &Light, axis: usize, travel: i32) -> bool {
    let LightKind::Spot { direction, outer_cone_deg, .. } = light.kind else { return true };
    let spot = direction.normalize_or(Vec3::NEG_Y);
    let angle = (spot[axis] * travel as f32).clamp(-1.0, 1.0).acos();
    angle - outer_cone_deg.to_radians() < 0.5 * PI
}

/// Whether every direction of a spot light's cone travels along `travel` on
/// `axis` (so that group alone can carry all its light, with a constant factor).
fn cone_within(light: &Light, axis: usize, travel: i32) -> bool {
    let LightKind::Spot { direction, outer_cone_deg, .. } = light.kind else { return false };
    let spot = direction.normalize_or(Vec3::NEG_Y);
    let angle = (spot[axis] * travel as f32).clamp(-1.0, 1.0).acos();
    // A margin of a degree: the shader drops directions within 1e-4 of the plane.
    angle + outer_cone_deg.to_radians() < 0.5 * PI - 1f32.to_radians()
}

/// Every contribution of the lights that are on (`None` is a light switched
/// off), in light order, for a volume box of half extent `box_half` (world
/// units, centred at the origin).
pub fn contributions(lights: &[Option<Light>], box_half: Vec3) -> Vec<Contribution> {
    let mut out = Vec::new();
    for (index, light) in lights.iter().enumerate() {
        let Some(light) = light else { continue };
        // A far light propagates as its directional limit (Scene::rendered_lights).
        let light = &light.far_limit(box_half.length());
        let state = gpu_light(light);
        let position = match light.kind {
            LightKind::Directional { .. } => None,
            LightKind::Point { position } | LightKind::Spot { position, .. } => Some(position),
        };
        // Within the box's extent along `axis`: light leaves it both ways.
        let within = |axis: usize| position.is_some_and(|p| p[axis].abs() < box_half[axis]);
        let mut push = |axis: usize, travel: i32, factor: f32, per_voxel: bool| {
            if factor > MIN_FACTOR {
                out.push(Contribution { light: index, state, axis, travel, factor, per_voxel });
            }
        };
        if (0..3).all(within) {
            // A spot light whose cone fits the two groups a directional light
            // along its axis would take gets those two, with their factors
            // (section 7.3: a cone that fits two passes costs two).
            let along_axis = matches!(light.kind, LightKind::Spot { direction, .. } if direction != Vec3::ZERO)
                .then(|| face_factors(-light_spot_direction(light)));
            if let Some(groups) =
                along_axis.filter(|g| g.iter().all(|&(a, t, f)| f <= MIN_FACTOR || cone_within(light, a, t)))
            {
                for (axis, travel, factor) in groups {
                    push(axis, travel, factor, false);
                }
                continue;
            }
            for axis in 0..3 {
                for travel in [1, -1] {
                    if cone_reaches(light, axis, travel) {
                        push(axis, travel, 1.0, true);
                    }
                }
            }
            continue;
        }
        for (axis, travel, factor) in face_factors(light_position_direction(light)) {
            push(axis, travel, factor, false);
            if within(axis) && cone_reaches(light, axis, -travel) {
                push(axis, -travel, factor, false);
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
        by_group[c.group_slot()].push(GroupMember {
            light: c.light,
            factor: sign * c.factor,
            state: c.state,
            per_voxel: c.per_voxel,
        });
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
        // A box small enough that the point lights below are outside it and
        // beside none of its faces.
        let items: Vec<_> = contributions(&on, Vec3::splat(0.25)).into_iter().map(|c| (c, 1.0)).collect();
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

    fn point(position: Vec3) -> Option<Light> {
        Some(Light { kind: LightKind::Point { position }, color: Vec3::ONE, intensity: 1.0, falloff: Falloff::None })
    }

    fn slots(cs: &[Contribution]) -> Vec<String> {
        let names = ["+x", "-x", "+y", "-y", "+z", "-z"];
        cs.iter().map(|c| names[c.group_slot()].to_string()).collect()
    }

    #[test]
    fn a_point_light_inside_joins_all_six_groups_weighted_per_voxel() {
        let cs = contributions(&[point(Vec3::new(0.1, -0.2, 0.05))], Vec3::splat(0.5));
        assert_eq!(slots(&cs), ["+x", "-x", "+y", "-y", "+z", "-z"]);
        assert!(cs.iter().all(|c| c.per_voxel && c.factor == 1.0));
    }

    #[test]
    fn a_point_light_beside_the_volume_carries_both_ways_along_the_axis_it_is_within() {
        // Above the box (closest face +y: travels -y), within its x extent: the
        // second group's axis is x, so both x directions carry its share.
        let cs = contributions(&[point(Vec3::new(0.3, 0.8, 0.0))], Vec3::splat(0.5));
        let mut names = slots(&cs);
        names.sort();
        assert_eq!(names, ["+x", "-x", "-y"]);
        let x: Vec<f32> = cs.iter().filter(|c| c.axis == 0).map(|c| c.factor).collect();
        assert_eq!(x[0], x[1]);
        let y = cs.iter().find(|c| c.axis == 1).unwrap().factor;
        assert!((x[0] + y - 1.0).abs() < 1e-6);
        assert!(cs.iter().all(|c| !c.per_voxel));
        // Far from every face's extent: the paper's two groups.
        assert_eq!(contributions(&[point(Vec3::new(2.0, 3.0, 1.0))], Vec3::splat(0.5)).len(), 2);
    }

    #[test]
    fn a_spot_light_inside_joins_the_groups_its_cone_reaches() {
        let spot = |direction: Vec3, outer: f32| {
            Some(Light {
                kind: LightKind::Spot { position: Vec3::ZERO, direction, inner_cone_deg: outer, outer_cone_deg: outer },
                color: Vec3::ONE,
                intensity: 1.0,
                falloff: Falloff::None,
            })
        };
        // Along an axis: that group alone carries the whole cone.
        let narrow = contributions(&[spot(Vec3::X, 30.0)], Vec3::splat(0.5));
        assert_eq!(slots(&narrow), ["+x"]);
        assert!(!narrow[0].per_voxel && narrow[0].factor == 1.0);
        // Between two axes, inside both half-spaces: the two groups of a
        // directional light along the spot, their factors summing to one.
        let between = contributions(&[spot(Vec3::new(1.0, -0.6, 0.0), 20.0)], Vec3::splat(0.5));
        assert_eq!(slots(&between), ["+x", "-y"]);
        assert!((between.iter().map(|c| c.factor).sum::<f32>() - 1.0).abs() < 1e-6);
        // A cone that crosses a group's plane: per voxel, the groups it reaches.
        let crossing = contributions(&[spot(Vec3::new(1.0, -0.6, 0.0), 50.0)], Vec3::splat(0.5));
        assert!(crossing.iter().all(|c| c.per_voxel), "{:?}", slots(&crossing));
        assert_eq!(slots(&crossing), ["+x", "+y", "-y", "+z", "-z"], "never back toward -x");
        let wide = contributions(&[spot(Vec3::X, 100.0)], Vec3::splat(0.5));
        assert_eq!(wide.len(), 6);
    }
}
