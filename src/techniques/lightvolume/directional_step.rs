//! A directional light's step from slice to slice of a propagation group,
//! computed once on the host: its direction, path length per slice and the
//! lateral shift of its previous-slice lookup are the same at every voxel, so
//! the slice shader (glsl/lightvolume_slice.comp, `step_from_host`, with
//! the shared medium) reads
//! them from the light's pass entry instead of computing them per voxel
//! (llvmpipe runs that arithmetic on every voxel of every slice).

use super::groups::{GroupMember, PropagationGroup};
use super::propagation::MIN_AXIS_COSINE;
use crate::render::frame_params::GpuLight;
use glam::{DVec3, UVec3};

/// The `radiance_path` and `lateral_step` of a directional light's entry.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionalStep {
    /// rgb: factor * radiance (times cos^2 for a per-voxel weighted member);
    /// w: path length per unit of axis length (1 / cos), 0 when not carried.
    pub radiance_path: [f32; 4],
    /// xy: shift of the previous-slice lookup over one slice, in texels of
    /// the slice's u and v axes; zw: their reciprocals (infinite for zero).
    pub lateral_step: [f32; 4],
}

impl DirectionalStep {
    /// Nothing carried (also what non-directional entries hold: unused).
    pub const NONE: DirectionalStep = DirectionalStep { radiance_path: [0.0; 4], lateral_step: [0.0; 4] };

    /// The step of `member` (a directional light) in `group`, for a box of
    /// half extent `box_half` split into `grid` illumination voxels. Computed
    /// in f64 and rounded once: deterministic for a light state, so adding and
    /// later subtracting the same light gives bit-equal contributions.
    pub fn of(member: &GroupMember, group: &PropagationGroup, box_half: [f32; 3], grid: UVec3) -> DirectionalStep {
        let a = group.axis;
        let (u, v) = ((a + 1) % 3, (a + 2) % 3);
        let state: &GpuLight = &member.state;
        let travel_direction = DVec3::new(state.pos_type[0] as f64, state.pos_type[1] as f64, state.pos_type[2] as f64);
        let travel_direction = travel_direction.normalize_or_zero();
        // Cosine between the light's travel and the group's direction.
        let c = travel_direction[a] * group.travel as f64;
        if c.is_nan() || c <= f64::from(MIN_AXIS_COSINE) {
            return DirectionalStep::NONE;
        }
        // Toward the light, over one slice (the axis step dstep): w * dstep / c.
        let toward = -travel_direction;
        let dstep = 2.0 * box_half[a] as f64 / grid[a] as f64;
        let along = dstep / c;
        let texels = |axis: usize| toward[axis] * along * grid[axis] as f64 / (2.0 * box_half[axis] as f64);
        // No lateral move is +0 with a +infinite reciprocal: the shader's
        // distance to the face ahead, (face - texel) / shift, is then +infinite
        // (a -0 from negating the direction would make it -infinite).
        let shift = |axis: usize| match texels(axis) as f32 {
            0.0 => (0.0, f32::INFINITY),
            s => (s, 1.0 / s),
        };
        let ((su, inverse_u), (sv, inverse_v)) = (shift(u), shift(v));
        let weight = member.factor * if member.per_voxel { (c * c) as f32 } else { 1.0 };
        let rgb = [0, 1, 2].map(|i| weight * state.radiance[i]);
        DirectionalStep {
            radiance_path: [rgb[0], rgb[1], rgb[2], (1.0 / c) as f32],
            lateral_step: [su, sv, inverse_u, inverse_v],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn member(direction: [f32; 3], factor: f32) -> GroupMember {
        let state = GpuLight {
            pos_type: [direction[0], direction[1], direction[2], 0.0],
            radiance: [1.0, 0.5, 0.25, 0.0],
            ..GpuLight::default()
        };
        GroupMember { light: 0, factor, state, per_voxel: false }
    }

    /// -y group on a box of half extents (1, 0.5, 2) split into 32 x 16 x 64
    /// voxels: every voxel is 1/16 wide along x, 1/16 along y, 1/16 along z.
    fn down() -> (PropagationGroup, [f32; 3], UVec3) {
        (PropagationGroup { axis: 1, travel: -1, members: Vec::new() }, [1.0, 0.5, 2.0], UVec3::new(32, 16, 64))
    }

    #[test]
    fn light_straight_along_the_axis_looks_up_the_texel_behind_with_a_unit_path() {
        let (group, half, grid) = down();
        let step = DirectionalStep::of(&member([0.0, -3.0, 0.0], 0.5), &group, half, grid);
        assert_eq!(step.radiance_path, [0.5, 0.25, 0.125, 1.0]);
        // +0 and +infinity, not the -0 and -infinity that negating 0 gives:
        // the shader's distance to the lateral face must come out +infinite.
        assert_eq!(step.lateral_step.map(f32::to_bits), [0.0, 0.0, f32::INFINITY, f32::INFINITY].map(f32::to_bits));
    }

    #[test]
    fn an_oblique_light_shifts_the_lookup_toward_the_light_by_its_lateral_travel_per_slice() {
        let (group, half, grid) = down();
        // The y axis's slices have u = z, v = x. Travelling down and toward +z
        // at 45 degrees: one slice down (1/16) is 1/16 along z, one texel; the
        // lookup lies toward the light, at -z. v (x) is not moved.
        let step = DirectionalStep::of(&member([0.0, -1.0, 1.0], 1.0), &group, half, grid);
        let [_, _, _, path] = step.radiance_path;
        assert!((path - 2f32.sqrt()).abs() < 1e-6, "{path}");
        assert!((step.lateral_step[0] + 1.0).abs() < 1e-6, "{:?}", step.lateral_step);
        assert!((step.lateral_step[2] + 1.0).abs() < 1e-6, "{:?}", step.lateral_step);
        assert_eq!(step.lateral_step[1], 0.0);
        // Toward +x (v) at 30 degrees off the axis: tan 30 * 1/16 world = tan 30 texels.
        let tilt = 30f32.to_radians();
        let step = DirectionalStep::of(&member([tilt.sin(), -tilt.cos(), 0.0], 1.0), &group, half, grid);
        assert!((step.lateral_step[1] + tilt.tan()).abs() < 1e-6, "{:?}", step.lateral_step);
        assert!((step.radiance_path[3] - 1.0 / tilt.cos()).abs() < 1e-6);
    }

    #[test]
    fn light_against_the_group_or_along_its_slices_is_not_carried() {
        let (group, half, grid) = down();
        assert_eq!(DirectionalStep::of(&member([0.0, 1.0, 0.2], 1.0), &group, half, grid), DirectionalStep::NONE);
        assert_eq!(DirectionalStep::of(&member([1.0, -1e-5, 0.0], 1.0), &group, half, grid), DirectionalStep::NONE);
    }

    #[test]
    fn a_member_weighted_per_voxel_takes_the_squared_cosine_and_a_negative_factor_subtracts() {
        let (group, half, grid) = down();
        let mut m = member([0.0, -1.0, 1.0], -2.0);
        m.per_voxel = true;
        let step = DirectionalStep::of(&m, &group, half, grid);
        // cos^2 = 1/2: -2 * 1/2 * radiance.
        for (got, want) in step.radiance_path[..3].iter().zip([-1.0, -0.5, -0.25]) {
            assert!((got - want).abs() < 1e-6, "{:?}", step.radiance_path);
        }
    }
}
