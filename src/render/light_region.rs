//! Which texels of a light-space image a pass can change: the light rays that
//! cross a plane (or a slab between two parallel planes) inside the volume's
//! box, i.e. the projection of its cross-section of the box. IPSVI's line
//! blocks update that region of the cache, half-angle's slices that region of
//! the light buffer, each together with the previous pass's region: with
//! ping-pong images, each image then holds every texel as of its own pass (a
//! texel outside both regions did not change since the image was last written
//! two passes ago), so nothing stale is ever read.

use crate::render::light_space::{LightProjection, LightSpacePlane};
use glam::Vec3;

/// Texels [x0, x0 + w) x [y0, y0 + h) of a light-space image.
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
    covering(lo, hi, size)
}

/// The texels of a `size`-texel image covering texel coordinates [lo, hi],
/// with one texel of margin.
fn covering(lo: (f32, f32), hi: (f32, f32), size: u32) -> TexelRect {
    let clamp = |v: f32| v.clamp(0.0, size as f32) as u32;
    let (x0, y0) = (clamp(lo.0.floor() - 1.0), clamp(lo.1.floor() - 1.0));
    let (x1, y1) = (clamp(hi.0.ceil() + 1.0), clamp(hi.1.ceil() + 1.0));
    TexelRect { x0, y0, w: x1.saturating_sub(x0), h: y1.saturating_sub(y0) }
}

/// Texels whose rays cross the slab `lo <= dot(x, normal) <= hi` inside the
/// box of `corners`, one texel of margin: the projection of the box's part
/// between the two planes (its vertices are the crossings of the box's edges
/// with both planes and the corners between them).
pub fn slab_region(geometry: &LightSpacePlane, corners: &[Vec3; 8], normal: Vec3, lo: f32, hi: f32) -> TexelRect {
    if geometry.projection == LightProjection::Octahedral {
        return TexelRect::full(geometry.size);
    }
    let plane = |d: f32| [normal.x, normal.y, normal.z, -d];
    let planes = plane_region(geometry, corners, plane(lo)).union(&plane_region(geometry, corners, plane(hi)));
    corners.iter().filter(|c| (lo..=hi).contains(&normal.dot(**c))).fold(planes, |region, c| {
        let (x, y, _) = geometry.coord(*c);
        region.union(&covering((x, y), (x, y), geometry.size))
    })
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
    fn a_slab_covers_both_planes_and_the_corners_between_them() {
        let bx = crate::scene::VolumeBox::new(UVec3::splat(32), Vec3::ONE);
        let g = LightSpacePlane::fit(&LightKind::Directional { direction: Vec3::NEG_X }, &bx, 64);
        let (n, corners) = (Vec3::new(0.0, 1.0, 0.0), bx.corners());
        // A thin slab is the band of its planes; one holding the whole box is the whole projection.
        let thin = slab_region(&g, &corners, n, 0.05, 0.1);
        assert_eq!(
            thin,
            plane_region(&g, &corners, [0.0, 1.0, 0.0, -0.05]).union(&plane_region(
                &g,
                &corners,
                [0.0, 1.0, 0.0, -0.1]
            ))
        );
        let whole = slab_region(&g, &corners, n, -10.0, 10.0);
        assert!(whole.count() > 60 * 60, "{whole:?}");
        assert_eq!(slab_region(&g, &corners, n, 3.0, 4.0).count(), 0);
    }

    #[test]
    fn union_covers_both() {
        let a = TexelRect { x0: 2, y0: 3, w: 4, h: 1 };
        let b = TexelRect { x0: 5, y0: 1, w: 1, h: 1 };
        assert_eq!(a.union(&b), TexelRect { x0: 2, y0: 1, w: 4, h: 3 });
        assert_eq!(TexelRect::default().union(&b), b);
    }
}
