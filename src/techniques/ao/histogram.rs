//! Local histograms (section 3.1, equations 1-3): for every voxel x, two
//! histograms of the intensities around it, one per hemisphere.
//!
//! Our reading of the paper, which this brute-force reference implements (the
//! GPU space sweep must give the same numbers):
//! - S_r(x) holds the voxels whose centres lie within distance r * d_min of x's
//!   centre, where d_min is the smallest distance between two voxels (the
//!   smallest spacing); with anisotropic spacing the sphere is round in world
//!   space and holds fewer voxels along the coarse axes.
//! - The centre voxel is left out (equation 2's x-bar != x), so every distance
//!   is at least 1 in units of d_min and no weight exceeds 1.
//! - Weight f_dist(d) = 1 / d^2, d = |x - x-bar| / d_min.
//! - Intensity bin k of x-bar: the normalized intensity s in [0, 1] scaled to
//!   2^b bins, k = min(floor(s * 2^b), 2^b - 1), equation 3's g(f, k). For 8-bit
//!   data and b = 8 that is the raw byte.
//! - Voxels of the sphere outside the volume contribute nothing (nothing is
//!   there), and every histogram is divided by the same N_r, the number of
//!   lattice voxels in S_r without the centre ("normalized by the number of
//!   voxels lying in the sphere"), so a voxel near the border simply sees less
//!   surroundings, as it would next to empty space.
//! - Hemispheres: the plane through x perpendicular to the gradient g
//!   ([`central_gradient`]) splits S_r. The forward hemisphere H_f is the one the
//!   shading normal n = -g points into (dot(x-bar - x, g) < 0): for an object
//!   brighter than its surroundings that is the outside, where what occludes the
//!   surface lies (the paper's "occlusion, which is given by the forward facing
//!   hemisphere", figure 7). H_b is the other side (dot > 0). A voxel exactly on
//!   the plane (dot = 0) gives half its weight to each; so where the gradient is
//!   zero (homogeneous regions) both histograms are equal, each half of the
//!   whole sphere's, and forward + backward is always the full-sphere histogram.
//!   The dot product is taken in f32 as g.x*o.x + g.y*o.y + g.z*o.z, o the offset
//!   in units of d_min.

use std::ops::Range;

use glam::{IVec3, UVec3, Vec3};

use super::bin_runs::BinRuns;
use super::gradient::central_gradient;
use super::lane_rows::{LaneRows, LaneScratch, LANES};
use super::row_runs::StencilRows;
use crate::scene::Volume;

/// The voxels of S_r around a centre, as offsets with their weights.
#[derive(Clone, Debug)]
pub struct SphereStencil {
    /// Lattice offsets, centre excluded.
    pub offsets: Vec<IVec3>,
    /// The same offsets in world units divided by d_min (for the hemisphere test).
    pub directions: Vec<Vec3>,
    /// 1 / d^2, d in units of d_min.
    pub weights: Vec<f64>,
    /// Largest |offset| along each axis.
    pub extent: UVec3,
}

impl SphereStencil {
    pub fn new(radius: u32, spacing: Vec3) -> SphereStencil {
        let d_min = spacing.min_element() as f64;
        let scale = [spacing.x as f64 / d_min, spacing.y as f64 / d_min, spacing.z as f64 / d_min];
        let r = radius as f64;
        let extent = UVec3::from(scale.map(|s| (r / s + 1e-9).floor() as u32));
        let mut stencil = SphereStencil { offsets: vec![], directions: vec![], weights: vec![], extent };
        let e = extent.as_ivec3();
        for z in -e.z..=e.z {
            for y in -e.y..=e.y {
                for x in -e.x..=e.x {
                    let w = [x as f64 * scale[0], y as f64 * scale[1], z as f64 * scale[2]];
                    let d2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
                    if d2 == 0.0 || d2 > r * r + 1e-9 {
                        continue;
                    }
                    stencil.offsets.push(IVec3::new(x, y, z));
                    stencil.directions.push(Vec3::new(w[0] as f32, w[1] as f32, w[2] as f32));
                    stencil.weights.push(1.0 / d2);
                }
            }
        }
        stencil
    }

    /// N_r: the voxels of the sphere without its centre, the normalization.
    pub fn voxel_count(&self) -> usize {
        self.offsets.len()
    }

    /// What one normalized hemisphere histogram sums to when its whole
    /// hemisphere lies inside the volume: half the summed weights over N_r
    /// (the stencil is symmetric under o -> -o, and the plane is shared half
    /// and half, so both sides always get exactly half). Equations 4-5 divide by
    /// 2/3 pi r^3, which with 1/d^2 weights does not give a fully occluded
    /// hemisphere O_env = 1; dividing by this does.
    pub fn full_hemisphere_mass(&self) -> f64 {
        self.weights.iter().sum::<f64>() / (2.0 * self.voxel_count().max(1) as f64)
    }
}

/// Intensity bin of a normalized value: `min(floor(s * bins), bins - 1)`.
#[inline]
pub fn intensity_bin(s: f32, bins: usize) -> usize {
    ((s.clamp(0.0, 1.0) as f64 * bins as f64) as usize).min(bins - 1)
}

/// Forward and backward histograms of a run of voxels, `bins` values each, voxel
/// after voxel (x fastest, then y, then z).
#[derive(Clone, Debug, PartialEq)]
pub struct HistogramSlab {
    /// Linear indices of the voxels.
    pub voxels: Range<usize>,
    pub bins: usize,
    pub forward: Vec<f32>,
    pub backward: Vec<f32>,
}

impl HistogramSlab {
    /// Forward and backward histogram of the `i`-th voxel of the slab.
    pub fn voxel(&self, i: usize) -> (&[f32], &[f32]) {
        let r = i * self.bins..(i + 1) * self.bins;
        (&self.forward[r.clone()], &self.backward[r])
    }
}

/// Per-thread accumulators for one voxel (f64, so the reference is exact to
/// far below what an f32 GPU sum can show).
pub struct Scratch {
    forward: Vec<f64>,
    backward: Vec<f64>,
    lanes: LaneScratch,
}

/// Brute-force local histograms of one volume.
pub struct LocalHistograms<'v> {
    volume: &'v Volume,
    bins: usize,
    /// Intensity bin of every voxel.
    voxel_bins: Vec<u16>,
    stencil: SphereStencil,
    /// `voxel_bins` with a margin of the stencil's extent on every side that
    /// holds the extra bin `bins` ("outside"), so no neighbour needs a bounds
    /// check: what lands in the extra bin is dropped.
    padded_bins: Vec<u16>,
    padded_dims: UVec3,
    /// Stencil offsets as index differences in `padded_bins`.
    linear_offsets: Vec<isize>,
    /// The stencil as rows along x, and the runs of equal bin in
    /// `padded_bins` ([`BinRuns`]): what [`Self::voxel_into_by_rows`] walks
    /// one centre at a time and [`Self::x_run_into`] [`LANES`] at a time.
    rows: StencilRows,
    runs: BinRuns,
    /// The same rows laid out for [`LANES`] centres at once
    /// ([`Self::x_run_into`]).
    lanes: LaneRows,
    normalization: f64,
}

impl<'v> LocalHistograms<'v> {
    /// `bits` <= 15 (2^bits bins and the extra "outside" bin fit in u16).
    pub fn new(volume: &'v Volume, radius: u32, bits: u32) -> LocalHistograms<'v> {
        let bins = 1usize << bits.min(15);
        let voxel_bins: Vec<u16> =
            (0..volume.voxel_count()).map(|i| intensity_bin(volume.data.normalized(i), bins) as u16).collect();
        let stencil = SphereStencil::new(radius, volume.spacing);
        let e = stencil.extent;
        let padded_dims = volume.dims + 2 * e;
        let (px, py) = (padded_dims.x as usize, padded_dims.y as usize);
        let mut padded_bins = vec![bins as u16; px * py * padded_dims.z as usize];
        let (nx, ny) = (volume.dims.x as usize, volume.dims.y as usize);
        for z in 0..volume.dims.z as usize {
            for y in 0..ny {
                let from = (z * ny + y) * nx;
                let to = ((z + e.z as usize) * py + y + e.y as usize) * px + e.x as usize;
                padded_bins[to..to + nx].copy_from_slice(&voxel_bins[from..from + nx]);
            }
        }
        let linear_offsets = stencil
            .offsets
            .iter()
            .map(|o| (o.z as isize * py as isize + o.y as isize) * px as isize + o.x as isize)
            .collect();
        let normalization = 1.0 / stencil.voxel_count().max(1) as f64;
        let rows = StencilRows::new(&stencil, px as isize, (px * py) as isize);
        let runs = BinRuns::new(&padded_bins, px);
        let lanes = LaneRows::new(&rows);
        LocalHistograms {
            volume,
            bins,
            voxel_bins,
            padded_bins,
            padded_dims,
            stencil,
            linear_offsets,
            rows,
            runs,
            lanes,
            normalization,
        }
    }

    pub fn bins(&self) -> usize {
        self.bins
    }

    pub fn stencil(&self) -> &SphereStencil {
        &self.stencil
    }

    pub fn volume(&self) -> &'v Volume {
        self.volume
    }

    /// Intensity bin of every voxel.
    pub fn voxel_bins(&self) -> &[u16] {
        &self.voxel_bins
    }

    pub fn scratch(&self) -> Scratch {
        Scratch {
            forward: vec![0.0; self.bins + 1],
            backward: vec![0.0; self.bins + 1],
            lanes: self.lanes.scratch(self.bins + 1),
        }
    }

    /// Position of the voxel with linear index `index`.
    pub fn position(&self, index: usize) -> UVec3 {
        let d = self.volume.dims;
        let (nx, ny) = (d.x as usize, d.y as usize);
        UVec3::new((index % nx) as u32, ((index / nx) % ny) as u32, (index / (nx * ny)) as u32)
    }

    /// Padded index of voxel `p`.
    fn padded_index(&self, p: UVec3) -> usize {
        let q = p + self.stencil.extent;
        let (px, py) = (self.padded_dims.x as usize, self.padded_dims.y as usize);
        (q.z as usize * py + q.y as usize) * px + q.x as usize
    }

    /// The two normalized histograms of voxel `index`, as [`Self::voxel_into`]
    /// gives them, by stencil rows and runs of equal bin ([`super::row_runs`]):
    /// what the training set uses, and the preprocessing for the voxels of an
    /// x row that do not fill a group of [`LANES`].
    pub fn voxel_into_by_rows(&self, index: usize, scratch: &mut Scratch, forward: &mut [f32], backward: &mut [f32]) {
        let p = self.position(index);
        let g = central_gradient(self.volume, p);
        if !g.is_finite() {
            // The row split needs an ordered test; the brute force's rule for a
            // test that is not a number (half and half) is kept there.
            return self.voxel_into(index, scratch, forward, backward);
        }
        let (fw, bw) = (&mut scratch.forward, &mut scratch.backward);
        fw.fill(0.0);
        bw.fill(0.0);
        self.rows.accumulate(self.padded_index(p), g, &self.runs, fw, bw);
        self.normalized_into(scratch, forward, backward);
    }

    /// The normalized histograms of the voxels `first .. first + count` of one
    /// x row (linear indices), voxel after voxel into `forward` and `backward`
    /// (`count * bins` values each), as [`Self::voxel_into`] gives them: groups
    /// of [`LANES`] centres at once ([`super::lane_rows`]) where the CPU has a
    /// vector path for them, the rest by rows.
    pub fn x_run_into(
        &self,
        first: usize,
        count: usize,
        scratch: &mut Scratch,
        forward: &mut [f32],
        backward: &mut [f32],
    ) {
        let nx = self.volume.dims.x as usize;
        assert!(
            first % nx + count <= nx && forward.len() == count * self.bins && backward.len() == count * self.bins,
            "x_run_into takes voxels of one x row and room for their histograms"
        );
        let bins = self.bins;
        // Groups where they pay: with a vector path (docs/ao.md).
        let groups = if LaneRows::vectorized() { count / LANES } else { 0 };
        for group in 0..groups {
            let index = first + group * LANES;
            let p = self.position(index);
            let g: [Vec3; LANES] = std::array::from_fn(|j| central_gradient(self.volume, p + UVec3::X * j as u32));
            self.lanes.accumulate(self.padded_index(p), &g, &self.runs, &mut scratch.lanes);
            for j in 0..LANES {
                let at = (group * LANES + j) * bins;
                for k in 0..bins {
                    let (f, b) = scratch.lanes.lane(k, j);
                    forward[at + k] = (f * self.normalization) as f32;
                    backward[at + k] = (b * self.normalization) as f32;
                }
            }
        }
        for i in groups * LANES..count {
            let r = i * bins..(i + 1) * bins;
            self.voxel_into_by_rows(first + i, scratch, &mut forward[r.clone()], &mut backward[r]);
        }
    }

    /// The scratch sums, normalized by the sphere's voxel count, into
    /// `forward` and `backward` (the "outside" bin dropped).
    fn normalized_into(&self, scratch: &Scratch, forward: &mut [f32], backward: &mut [f32]) {
        for k in 0..self.bins {
            forward[k] = (scratch.forward[k] * self.normalization) as f32;
            backward[k] = (scratch.backward[k] * self.normalization) as f32;
        }
    }

    /// The two normalized histograms of voxel `index` into `forward` and
    /// `backward` (`bins` values each): the brute-force reference, one stencil
    /// voxel after the other.
    pub fn voxel_into(&self, index: usize, scratch: &mut Scratch, forward: &mut [f32], backward: &mut [f32]) {
        let p = self.position(index);
        let g = central_gradient(self.volume, p);
        let (fw, bw) = (&mut scratch.forward, &mut scratch.backward);
        fw.fill(0.0);
        bw.fill(0.0);
        let s = &self.stencil;
        let bins = &self.padded_bins;
        let centre = self.padded_index(p);
        // Neighbours come in runs of equal intensity (stencil rows are rows of
        // voxels): sum a run in registers and add it to its bin when the bin
        // changes, instead of one dependent memory update per neighbour.
        let (mut run_bin, mut run_forward, mut run_backward) = (0usize, 0f64, 0f64);
        for i in 0..s.offsets.len() {
            let k = bins[(centre as isize + self.linear_offsets[i]) as usize] as usize;
            if k != run_bin {
                fw[run_bin] += run_forward;
                bw[run_bin] += run_backward;
                (run_bin, run_forward, run_backward) = (k, 0.0, 0.0);
            }
            let o = s.directions[i];
            let side = g.x * o.x + g.y * o.y + g.z * o.z;
            let w = s.weights[i];
            if side < 0.0 {
                run_forward += w;
            } else if side > 0.0 {
                run_backward += w;
            } else {
                // On the plane, and everywhere when the gradient is zero.
                run_forward += 0.5 * w;
                run_backward += 0.5 * w;
            }
        }
        fw[run_bin] += run_forward;
        bw[run_bin] += run_backward;
        self.normalized_into(scratch, forward, backward);
    }

    /// Histograms of the voxels `voxels` (linear indices).
    pub fn slab(&self, voxels: Range<usize>, scratch: &mut Scratch) -> HistogramSlab {
        let n = voxels.len() * self.bins;
        let mut slab =
            HistogramSlab { voxels: voxels.clone(), bins: self.bins, forward: vec![0.0; n], backward: vec![0.0; n] };
        let nx = self.volume.dims.x as usize;
        let mut index = voxels.start;
        while index < voxels.end {
            // Up to the end of this x row.
            let count = (nx - index % nx).min(voxels.end - index);
            let r = (index - voxels.start) * self.bins..(index - voxels.start + count) * self.bins;
            self.x_run_into(index, count, scratch, &mut slab.forward[r.clone()], &mut slab.backward[r]);
            index += count;
        }
        slab
    }

    /// Splits the volume into runs of whole x-rows holding at most
    /// `max_slab_bytes` of unpacked histograms (at least one row), so that a
    /// stream never holds more than a few of them.
    pub fn slab_ranges(&self, max_slab_bytes: usize) -> Vec<Range<usize>> {
        let row = self.volume.dims.x as usize;
        let bytes_per_voxel = 2 * self.bins * std::mem::size_of::<f32>();
        let rows = (max_slab_bytes / (bytes_per_voxel * row)).max(1);
        let total = self.volume.voxel_count();
        (0..total).step_by(rows * row).map(|start| start..(start + rows * row).min(total)).collect()
    }

    /// Streams the histograms of every voxel, slab by slab, over all cores:
    /// `work(slab)` runs on a worker thread and its result goes to
    /// `consume(slab_index, result, done, total)` on the calling thread (in
    /// completion order). Only the slabs in flight exist.
    pub fn stream<R: Send>(
        &self,
        max_slab_bytes: usize,
        work: impl Fn(&HistogramSlab) -> R + Sync,
        consume: impl FnMut(usize, R, usize, usize),
    ) {
        self.stream_with(max_slab_bytes, || (), |_, slab| work(slab), consume);
    }

    /// As [`Self::stream`], with a state per worker thread (`init()`), which
    /// `work` may update and which is returned at the end.
    pub fn stream_with<S: Send, R: Send>(
        &self,
        max_slab_bytes: usize,
        init: impl Fn() -> S + Sync,
        work: impl Fn(&mut S, &HistogramSlab) -> R + Sync,
        mut consume: impl FnMut(usize, R, usize, usize),
    ) -> Vec<S> {
        let ranges = self.slab_ranges(max_slab_bytes);
        let states = super::parallel::for_each_chunk(
            ranges.len(),
            || (init(), self.scratch()),
            |(state, scratch), i| work(state, &self.slab(ranges[i].clone(), scratch)),
            |i, r, done| consume(i, r, done, ranges.len()),
        );
        states.into_iter().map(|(state, _)| state).collect()
    }
}

#[cfg(test)]
mod tests {
    use glam::{UVec3, Vec3};

    use super::super::lane_rows::LANES;
    use super::LocalHistograms;
    use crate::scene::{Volume, VoxelData};

    /// The lane sums of every path this CPU can run (AVX-512, AVX2) equal the
    /// portable path's bit for bit: the same additions in the same order.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn every_lane_path_gives_the_portable_sums() {
        let dims = UVec3::new(19, 9, 8);
        let mut state = 3u64;
        let data = (0..dims.x * dims.y * dims.z)
            .map(|i| {
                state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                // Few levels, so that runs, flat rows and zero gradients occur.
                if i % 23 < 9 {
                    40
                } else {
                    ((state >> 33) % 4) as u8 * 60
                }
            })
            .collect();
        let volume = Volume {
            name: "lanes".into(),
            dims,
            spacing: Vec3::new(1.0, 1.25, 0.8),
            data: VoxelData::U8(data),
            value_range: (0.0, 255.0),
            non_finite_voxels: 0,
            interpolation: Default::default(),
        };
        let h = LocalHistograms::new(&volume, 3, 6);
        let (mut fast, mut portable) = (h.scratch().lanes, h.scratch().lanes);
        let mut groups = [0; 2];
        for (path, groups) in ["avx512", "avx2"].into_iter().zip(&mut groups) {
            for z in 0..dims.z {
                for y in 0..dims.y {
                    for x in (0..dims.x - LANES as u32 + 1).step_by(3) {
                        let p = UVec3::new(x, y, z);
                        let g = std::array::from_fn(|j| super::central_gradient(&volume, p + UVec3::X * j as u32));
                        let centre = h.padded_index(p);
                        if !h.lanes.accumulate_by(path, centre, &g, &h.runs, &mut fast) {
                            eprintln!("this CPU has no {path} path");
                            continue;
                        }
                        assert!(h.lanes.accumulate_by("portable", centre, &g, &h.runs, &mut portable));
                        for k in 0..=h.bins {
                            for j in 0..LANES {
                                let (a, b) = (fast.lane(k, j), portable.lane(k, j));
                                assert!(
                                    a.0.to_bits() == b.0.to_bits() && a.1.to_bits() == b.1.to_bits(),
                                    "{path}, {p} lane {j} bin {k}: {a:?} against portable {b:?}"
                                );
                            }
                        }
                        *groups += 1;
                    }
                }
            }
        }
        // A CPU runs at least one of them (x86_64 CI machines have AVX2).
        assert!(groups.iter().any(|&n| n > 100), "groups checked per path: {groups:?}");
    }
}
