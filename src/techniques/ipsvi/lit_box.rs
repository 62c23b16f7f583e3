//! `ipsvi.fit_to_visible`: the box the cache is fitted to and the light rays
//! are clipped to, made of the volume's cells where the medium can be anything
//! but empty. Outside it the medium's extinction is exactly 0, so light crosses
//! it unchanged, and a tighter box gives smaller cache texels and shorter
//! marches to a light ray's box entry. Conservative by construction: a cell is
//! the region a trilinear fetch blends the same eight voxels in (clamped to the
//! edge, as the sampler is), its values lie between their least and greatest
//! (with exact or 8-bit weights alike), and a value range is visible where any
//! LUT entry the interpolation of [`TransferLut::sample`] can touch has sigma > 0.

use crate::scene::framing::WorldBox;
use crate::scene::{TransferLut, Volume, VolumeBox};
use glam::{UVec3, Vec3};

/// Whether any value in [lo, hi] can get extinction from the LUT, one entry of
/// slack on each side for the rounding of `s * n - 0.5`.
struct VisibleRanges {
    /// prefix[i]: entries below i with sigma > 0.
    prefix: Vec<u32>,
}

impl VisibleRanges {
    fn new(lut: &TransferLut) -> VisibleRanges {
        let mut prefix = Vec::with_capacity(lut.texels.len() + 1);
        let mut count = 0;
        prefix.push(0);
        for t in &lut.texels {
            count += (t[3] > 0.0) as u32;
            prefix.push(count);
        }
        VisibleRanges { prefix }
    }

    fn any(&self, lo: f32, hi: f32) -> bool {
        let n = self.prefix.len() - 1;
        let entry = |s: f32| ((s * n as f32 - 0.5).clamp(0.0, (n - 1) as f32)).floor() as usize;
        let first = entry(lo).saturating_sub(1);
        let last = (entry(hi) + 2).min(n - 1);
        self.prefix[last + 1] > self.prefix[first]
    }
}

/// Least and greatest value of each cell column (x, y) of voxel slice z: the
/// 2x2 voxels (clamped) cell (cx, cy) blends, cx in 0..=dx, cy in 0..=dy.
fn slice_ranges(volume: &Volume, z: i32) -> (Vec<f32>, Vec<f32>) {
    let d = volume.dims.as_ivec3();
    let (w, h) = ((d.x + 1) as usize, (d.y + 1) as usize);
    let z = z.clamp(0, d.z - 1);
    let at = |x: i32, y: i32| {
        let (x, y) = (x.clamp(0, d.x - 1), y.clamp(0, d.y - 1));
        volume.data.normalized((x + d.x * (y + d.y * z)) as usize)
    };
    // Along x first (cell cx blends voxels cx - 1 and cx), then along y.
    let mut row_min = vec![0.0f32; w * d.y as usize];
    let mut row_max = vec![0.0f32; w * d.y as usize];
    for y in 0..d.y {
        let mut previous = at(-1, y);
        for cx in 0..w as i32 {
            let v = at(cx, y);
            let i = y as usize * w + cx as usize;
            row_min[i] = previous.min(v);
            row_max[i] = previous.max(v);
            previous = v;
        }
    }
    let mut min = vec![0.0f32; w * h];
    let mut max = vec![0.0f32; w * h];
    for cy in 0..h as i32 {
        let (y0, y1) = ((cy - 1).clamp(0, d.y - 1) as usize, cy.clamp(0, d.y - 1) as usize);
        for cx in 0..w {
            min[cy as usize * w + cx] = row_min[y0 * w + cx].min(row_min[y1 * w + cx]);
            max[cy as usize * w + cx] = row_max[y0 * w + cx].max(row_max[y1 * w + cx]);
        }
    }
    (min, max)
}

/// The world box of every cell whose values can be visible, or the volume's box
/// when none can (nothing then changes the light, and the box stays as it was).
pub fn lit_box(volume: &Volume, lut: &TransferLut, volume_box: &VolumeBox) -> WorldBox {
    let ranges = VisibleRanges::new(lut);
    let d = volume.dims.as_ivec3();
    let w = (d.x + 1) as usize;
    // Cell c (per axis 0..=d) blends voxels c - 1 and c, clamped to the edge.
    let (mut lo, mut hi) = (UVec3::MAX, UVec3::ZERO);
    let mut below = slice_ranges(volume, -1);
    for cz in 0..=d.z {
        let above = slice_ranges(volume, cz);
        for (i, ((mn0, mx0), (mn1, mx1))) in below.0.iter().zip(&below.1).zip(above.0.iter().zip(&above.1)).enumerate()
        {
            if ranges.any(mn0.min(*mn1), mx0.max(*mx1)) {
                let c = UVec3::new((i % w) as u32, (i / w) as u32, cz as u32);
                lo = lo.min(c);
                hi = hi.max(c);
            }
        }
        below = above;
    }
    if lo.cmpgt(hi).any() {
        return WorldBox::of_volume(volume_box);
    }
    // Cell c spans uvw [(c - 0.5) / d, (c + 0.5) / d], clipped to the volume;
    // a voxel's width of slack against rounding.
    let dims = volume.dims.as_vec3();
    let uvw_lo = ((lo.as_vec3() - 0.5 - 1.0) / dims).max(Vec3::ZERO);
    let uvw_hi = ((hi.as_vec3() + 0.5 + 1.0) / dims).min(Vec3::ONE);
    let world = |u: Vec3| u * 2.0 * volume_box.half_extent - volume_box.half_extent;
    WorldBox { min: world(uvw_lo), max: world(uvw_hi) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{ControlPoint, TransferFunction, VoxelData};

    fn volume(dims: UVec3, data: Vec<f32>) -> Volume {
        Volume {
            name: "test".into(),
            dims,
            spacing: Vec3::ONE,
            data: VoxelData::F32(data),
            value_range: (0.0, 1.0),
            non_finite_voxels: 0,
            interpolation: Default::default(),
        }
    }

    /// Opacity 0 outside [from, to], 0.5 inside (steep linear edges).
    fn band(from: f32, to: f32) -> TransferLut {
        let point = |value: f32, a: f32| ControlPoint { value, rgba: [1.0, 1.0, 1.0, a] };
        let points =
            vec![point(0.0, 0.0), point(from, 0.0), point(from + 1e-3, 0.5), point(to, 0.5), point(to + 1e-3, 0.0)];
        TransferFunction::new(points).unwrap().bake(TransferLut::DEFAULT_SIZE)
    }

    #[test]
    fn the_box_holds_every_point_where_a_fetch_can_see_the_medium() {
        // 16^3 zeros with one voxel of 1 at (10, 4, 7); opacity only above 0.5.
        let dims = UVec3::splat(16);
        let mut data = vec![0.0; 16 * 16 * 16];
        data[10 + 16 * (4 + 16 * 7)] = 1.0;
        let vol = volume(dims, data);
        let lut = band(0.5, 0.998);
        let bx = VolumeBox::new(dims, Vec3::ONE);
        let lit = lit_box(&vol, &lut, &bx);
        // The voxel's value reaches the trilinear fetch within one voxel of its
        // centre: centre 10.5 voxels, so [9.5, 11.5] must be inside.
        let voxel = |i: f32| i / 16.0 * 2.0 * bx.half_extent.x - bx.half_extent.x;
        for (axis, c) in [(0, 10.5), (1, 4.5), (2, 7.5)] {
            assert!(lit.min[axis] <= voxel(c - 1.0) && lit.max[axis] >= voxel(c + 1.0), "{axis}: {lit:?}");
            assert!(lit.max[axis] - lit.min[axis] < 0.5 * 2.0 * bx.half_extent[axis], "{axis}: not tight: {lit:?}");
        }
        // A value range that only passes through the visible band between two
        // voxels (0 next to 1, opacity only in [0.4, 0.6]) is visible too.
        let middle = band(0.4, 0.6);
        assert!(VisibleRanges::new(&middle).any(0.0, 1.0) && !VisibleRanges::new(&middle).any(0.0, 0.3));
        let between = lit_box(&vol, &middle, &bx);
        assert!(between.min.x <= voxel(9.5) && between.max.x >= voxel(11.5), "{between:?}");
        // Nothing visible: the volume's box.
        let none = lit_box(&volume(dims, vec![0.0; 16 * 16 * 16]), &lut, &bx);
        assert_eq!(none, WorldBox::of_volume(&bx));
    }
}
