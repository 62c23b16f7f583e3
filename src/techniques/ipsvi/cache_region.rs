//! Which cache texels a line block can change: the light rays that cross the
//! block's sweep plane inside the volume, i.e. the projection of the plane's
//! cross-section of the box onto the cache. A block updates that region and the
//! previous block's: with ping-pong images, each image then holds every texel
//! as of its own block (a texel outside both regions did not change since the
//! image was last written two blocks ago), so nothing stale is ever read.

use crate::render::light_space::{LightProjection, LightSpacePlane};
use glam::Vec3;

/// Texels [x0, x0 + w) x [y0, y0 + h) of the cache.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct TexelRect {
    pub x0: u32,
    pub y0: u32,
    pub w: u32,
    pub h: u32,
}

impl TexelRect {
    pub fn full(size: u32) -> TexelRect {
        TexelRect { x0: 0, y0: 0, w: size, h: size }
    }

    pub fn count(&self) -> u32 {
        self.w * self.h
    }

    pub fn union(&self, other: &TexelRect) -> TexelRect {
        if self.count() == 0 {
            return *other;
        }
        if other.count() == 0 {
            return *self;
        }
        let x0 = self.x0.min(other.x0);
        let y0 = self.y0.min(other.y0);
        let x1 = (self.x0 + self.w).max(other.x0 + other.w);
        let y1 = (self.y0 + self.h).max(other.y0 + other.h);
        TexelRect { x0, y0, w: x1 - x0, h: y1 - y0 }
    }
}

const EDGES: [(usize, usize); 12] =
    [(0, 1), (2, 3), (4, 5), (6, 7), (0, 2), (1, 3), (4, 6), (5, 7), (0, 4), (1, 5), (2, 6), (3, 7)];

/// Texels whose rays cross plane (n, d) inside the box of `corners`, one texel of margin.
pub fn plane_region(geometry: &LightSpacePlane, corners: &[Vec3; 8], plane: [f32; 4]) -> TexelRect {
    let size = geometry.size;
    if geometry.projection == LightProjection::Octahedral {
        // The octahedral map does not keep polygons convex: update it all.
        return TexelRect::full(size);
    }
    let n = Vec3::new(plane[0], plane[1], plane[2]);
    let side: Vec<f32> = corners.iter().map(|c| n.dot(*c) + plane[3]).collect();
    let mut lo = (f32::INFINITY, f32::INFINITY);
    let mut hi = (f32::NEG_INFINITY, f32::NEG_INFINITY);
    let mut any = false;
    for (a, b) in EDGES {
        let (sa, sb) = (side[a], side[b]);
        if (sa <= 0.0) != (sb <= 0.0) || sa == 0.0 || sb == 0.0 {
            let t = if sa == sb { 0.0 } else { sa / (sa - sb) };
            let p = corners[a] + (corners[b] - corners[a]) * t.clamp(0.0, 1.0);
            let (x, y, _) = geometry.coord(p);
            lo = (lo.0.min(x), lo.1.min(y));
            hi = (hi.0.max(x), hi.1.max(y));
            any = true;
        }
    }
    if !any {
        return TexelRect::default();
    }
    let clamp = |v: f32| v.clamp(0.0, size as f32) as u32;
    let (x0, y0) = (clamp(lo.0.floor() - 1.0), clamp(lo.1.floor() - 1.0));
    let (x1, y1) = (clamp(hi.0.ceil() + 1.0), clamp(hi.1.ceil() + 1.0));
    TexelRect { x0, y0, w: x1.saturating_sub(x0), h: y1.saturating_sub(y0) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::LightKind;
    use glam::UVec3;

    #[test]
    fn plane_across_the_light_is_a_thin_band_and_outside_the_box_is_empty() {
        let bx = crate::scene::VolumeBox::new(UVec3::splat(32), Vec3::ONE);
        // Light from +x; a plane x = 0.1 contains no light ray direction, every ray crosses it.
        let g = LightSpacePlane::fit(&LightKind::Directional { direction: Vec3::NEG_X }, &bx, 64);
        let across = plane_region(&g, &bx.corners(), [1.0, 0.0, 0.0, -0.1]);
        assert!(across.count() > 60 * 60, "{across:?}");
        // A plane containing the light direction (y = 0.1) is crossed by one band of rays.
        let along = plane_region(&g, &bx.corners(), [0.0, 1.0, 0.0, -0.1]);
        assert!(along.w.min(along.h) <= 4, "{along:?}");
        assert_eq!(plane_region(&g, &bx.corners(), [0.0, 1.0, 0.0, -3.0]).count(), 0);
    }

    #[test]
    fn union_covers_both() {
        let a = TexelRect { x0: 2, y0: 3, w: 4, h: 1 };
        let b = TexelRect { x0: 5, y0: 1, w: 1, h: 1 };
        assert_eq!(a.union(&b), TexelRect { x0: 2, y0: 1, w: 4, h: 3 });
        assert_eq!(TexelRect::default().union(&b), b);
    }
}
