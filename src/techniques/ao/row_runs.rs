//! Local histograms by stencil rows and intensity runs: the same numbers as the
//! brute-force loop of [`super::histogram::LocalHistograms::voxel_into`], at a
//! cost per voxel of the stencil's rows and the runs of equal intensity bin
//! they cross instead of its voxels (docs/ao.md, "CPU histograms by rows and
//! runs").
//!
//! Why it is exact: along one stencil row (fixed y and z offsets) the
//! hemisphere test `g.x*o.x + g.y*o.y + g.z*o.z`, taken in f32 in that order, is
//! monotonic in o.x (each rounding step is), so the row splits into at most
//! three contiguous pieces: forward, on the plane, backward. Within a piece, a
//! run of voxels of one bin adds the sum of its weights, which a prefix sum of
//! the row's 1/d^2 weights gives in one subtraction (f64, as the brute force
//! sums). Only the order of the f64 additions differs, far below the f32 the
//! histograms are stored in (the test finds them bit-equal).
//!
//! Rows come in antipodal pairs (o and -o): the test is odd, so one split
//! serves both, and a pair of rows that are each one run of the same bin gives
//! both hemispheres its whole weight with no split at all (in homogeneous
//! surroundings, most of them).

use glam::Vec3;

use super::bin_runs::BinRuns;
use super::histogram::SphereStencil;

/// One row of the stencil: the offsets with equal y and z, as a contiguous
/// range of x (the centre, if the row holds it, with weight 0).
#[derive(Clone, Debug)]
struct StencilRow {
    /// Linear offset, in the padded bin volume, of the row's first voxel.
    start: isize,
    /// Offset in padded x rows (z * rows per slice + y).
    row_offset: isize,
    /// Voxels in the row.
    len: usize,
    /// Index of the row's first x direction in [`StencilRows::directions_x`]
    /// and of its first prefix sum in [`StencilRows::prefix`] (which has one
    /// more entry per row).
    first: usize,
    prefix_first: usize,
    /// The row's y and z directions (units of d_min), shared by its voxels.
    direction_y: f32,
    direction_z: f32,
    /// Largest |x offset| in the row.
    half: i32,
}

/// One stencil row as other walks read it.
pub struct RowView<'a> {
    /// Linear offset, in the padded bin volume, of the row's first voxel.
    pub start: isize,
    /// Offset in padded x rows.
    pub row_offset: isize,
    pub direction_y: f32,
    pub direction_z: f32,
    /// Per voxel of the row, first to last: x direction and weight.
    pub directions_x: &'a [f32],
    pub weights: &'a [f64],
    /// The weights' sum (the last prefix sum, what the walk adds for a whole
    /// row).
    pub total: f64,
}

/// The stencil grouped into rows along x, with prefix sums of the weights.
#[derive(Clone, Debug)]
pub struct StencilRows {
    rows: Vec<StencilRow>,
    /// x direction of every voxel of every row, row after row.
    directions_x: Vec<f32>,
    /// Weight of every voxel of every row, indexed as `directions_x`.
    weights: Vec<f64>,
    /// Per row: 0, w_0, w_0 + w_1, ... (len + 1 values).
    prefix: Vec<f64>,
    /// x spacing in units of d_min (the x direction per voxel of offset).
    scale_x: f32,
}

impl StencilRows {
    /// `padded_row` and `padded_slice`: index steps of y and z in the padded
    /// bin volume the rows will read.
    pub fn new(stencil: &SphereStencil, padded_row: isize, padded_slice: isize) -> StencilRows {
        let mut rows: Vec<StencilRow> = vec![];
        let (mut directions_x, mut weights, mut prefix) = (vec![], vec![], vec![]);
        let mut i = 0;
        let n = stencil.offsets.len();
        while i < n {
            let o = stencil.offsets[i];
            let mut end = i + 1;
            while end < n && stencil.offsets[end].y == o.y && stencil.offsets[end].z == o.z {
                end += 1;
            }
            // Offsets run from -half to +half in x (the sphere's row is an
            // interval); the centre row misses x = 0, which enters with weight 0.
            let half = -o.x;
            let len = (2 * half + 1) as usize;
            let (first, prefix_first) = (directions_x.len(), prefix.len());
            let mut sum = 0f64;
            prefix.push(0.0);
            let mut next = i;
            for x in -half..=half {
                let (direction_x, weight) = if next < end && stencil.offsets[next].x == x {
                    next += 1;
                    (stencil.directions[next - 1].x, stencil.weights[next - 1])
                } else {
                    debug_assert!(x == 0 && o.y == 0 && o.z == 0, "a stencil row has a gap off the centre");
                    (0.0, 0.0)
                };
                directions_x.push(direction_x);
                weights.push(weight);
                sum += weight;
                prefix.push(sum);
            }
            let d = stencil.directions[i];
            rows.push(StencilRow {
                start: o.z as isize * padded_slice + o.y as isize * padded_row - half as isize,
                row_offset: o.z as isize * (padded_slice / padded_row) + o.y as isize,
                len,
                first,
                prefix_first,
                direction_y: d.y,
                direction_z: d.z,
                half,
            });
            i = end;
        }
        // The stencil is symmetric under o -> -o and ordered by (z, y), so row i
        // and row n-1-i are mirrors: what `accumulate_pairs` relies on.
        debug_assert!((0..rows.len()).all(|i| {
            let (a, b) = (&rows[i], &rows[rows.len() - 1 - i]);
            a.len == b.len && a.direction_y == -b.direction_y && a.direction_z == -b.direction_z
        }));
        let scale_x =
            rows.iter().find(|r| r.half > 0).map_or(1.0, |r| directions_x[r.first + r.len - 1] / r.half as f32);
        StencilRows { rows, directions_x, weights, prefix, scale_x }
    }

    /// The rows, in stencil order (antipodal pairs at i and len - 1 - i).
    pub fn rows(&self) -> impl ExactSizeIterator<Item = RowView<'_>> {
        self.rows.iter().map(|row| RowView {
            start: row.start,
            row_offset: row.row_offset,
            direction_y: row.direction_y,
            direction_z: row.direction_z,
            directions_x: &self.directions_x[row.first..row.first + row.len],
            weights: &self.weights[row.first..row.first + row.len],
            total: self.prefix[row.prefix_first + row.len],
        })
    }

    /// Adds the weights of the stencil around padded index `centre` into
    /// `forward` and `backward` (indexed by bin; `runs` the padded bin volume's
    /// runs). `g`: the gradient, finite.
    pub fn accumulate(&self, centre: usize, g: Vec3, runs: &BinRuns, forward: &mut [f64], backward: &mut [f64]) {
        let voxels = Voxels { centre, centre_row: runs.row_of(centre), runs };
        if g.x > 0.0 {
            // The test rises along a row: forward (< 0) comes first.
            self.accumulate_pairs::<false>(&voxels, g, forward, backward);
        } else if g.x < 0.0 {
            // It falls: on the negated test backward comes first.
            self.accumulate_pairs::<true>(&voxels, g, backward, forward);
        } else {
            // Constant along every row; either order is right.
            self.accumulate_pairs::<false>(&voxels, g, forward, backward);
        }
    }

    /// Walks the rows in antipodal pairs (row i and row n-1-i hold o and -o;
    /// the middle row, through the centre, is its own). The test is odd,
    /// side(-o) = -side(o) exactly (negation commutes with rounding), so one
    /// split serves both rows of a pair, and a pair whose two rows are one run
    /// of the same bin gives each hemisphere the row's whole weight without a
    /// split at all: what one row gives one side, the other row gives the
    /// other.
    fn accumulate_pairs<const NEGATE: bool>(&self, voxels: &Voxels, g: Vec3, below: &mut [f64], above: &mut [f64]) {
        // Where the plane cuts a row, as a fractional index from its first
        // voxel: a first guess, settled by the exact test.
        let inverse = if g.x != 0.0 { 1.0 / (g.x * self.scale_x) } else { 0.0 };
        let n = self.rows.len();
        for i in 0..n.div_ceil(2) {
            let (row, mirror) = (&self.rows[i], &self.rows[n - 1 - i]);
            let prefix = &self.prefix[row.prefix_first..row.prefix_first + row.len + 1];
            if i != n - 1 - i {
                let (run, mirror_run) = (voxels.single_run(row), voxels.single_run(mirror));
                if let (Some(run), Some(mirror_run)) = (run, mirror_run) {
                    let k = voxels.runs.bin(run);
                    if k == voxels.runs.bin(mirror_run) {
                        let whole = prefix[row.len];
                        below[k as usize] += whole;
                        above[k as usize] += whole;
                        continue;
                    }
                }
            }
            let (cut, plane_end) = self.split::<NEGATE>(row, g, inverse);
            voxels.add_row(row, prefix, cut, plane_end, below, above);
            if i != n - 1 - i {
                // The mirror's voxel j is -o of the row's voxel len-1-j.
                let mirror_prefix = &self.prefix[mirror.prefix_first..mirror.prefix_first + mirror.len + 1];
                voxels.add_row(mirror, mirror_prefix, row.len - plane_end, row.len - cut, below, above);
            }
        }
    }

    /// Where the (for `NEGATE`, negated) test turns from negative to zero
    /// (`cut`) and from zero to positive (`plane_end`) along `row`.
    #[inline]
    fn split<const NEGATE: bool>(&self, row: &StencilRow, g: Vec3, inverse: f32) -> (usize, usize) {
        let xs = &self.directions_x[row.first..row.first + row.len];
        let (y_term, z_term) = (g.y * row.direction_y, g.z * row.direction_z);
        // The brute force's test, term for term, in the same order.
        let key = |j: usize| {
            let side = g.x * xs[j] + y_term + z_term;
            if NEGATE {
                -side
            } else {
                side
            }
        };
        if g.x == 0.0 {
            // The test does not change along the row: one piece (a walk
            // from the guess would cross the whole row).
            let side = key(0);
            return if side < 0.0 {
                (row.len, row.len)
            } else if side > 0.0 {
                (0, 0)
            } else {
                (0, row.len)
            };
        }
        let guess = -(y_term + z_term) * inverse + row.half as f32;
        let mut cut = if guess <= 0.0 {
            0
        } else if guess >= row.len as f32 {
            row.len
        } else {
            guess as usize + 1
        };
        while cut > 0 && key(cut - 1) >= 0.0 {
            cut -= 1;
        }
        while cut < row.len && key(cut) < 0.0 {
            cut += 1;
        }
        let mut plane_end = cut;
        while plane_end < row.len && key(plane_end) == 0.0 {
            plane_end += 1;
        }
        (cut, plane_end)
    }
}

/// The bin volume around one centre.
struct Voxels<'a> {
    centre: usize,
    /// The padded x row holding the centre.
    centre_row: usize,
    runs: &'a BinRuns,
}

impl Voxels<'_> {
    /// Padded index of `row`'s first voxel.
    #[inline]
    fn base(&self, row: &StencilRow) -> usize {
        (self.centre as isize + row.start) as usize
    }

    /// The padded x row `row` lies in.
    #[inline]
    fn padded_row(&self, row: &StencilRow) -> usize {
        (self.centre_row as isize + row.row_offset) as usize
    }

    /// The run holding all of `row`, if one does.
    #[inline]
    fn single_run(&self, row: &StencilRow) -> Option<usize> {
        let (base, padded_row) = (self.base(row), self.padded_row(row));
        let first = self.runs.run_in(padded_row, base);
        (first == self.runs.run_in(padded_row, base + row.len - 1)).then_some(first)
    }

    /// Adds a row run by run: its voxels `..cut` to `below`, `cut..plane_end`
    /// half to each, `plane_end..` to `above`.
    #[inline]
    fn add_row(
        &self,
        row: &StencilRow,
        prefix: &[f64],
        cut: usize,
        plane_end: usize,
        below: &mut [f64],
        above: &mut [f64],
    ) {
        let len = row.len;
        debug_assert!(cut <= plane_end && plane_end <= len);
        let walk = RowWalk { runs: self.runs, padded_row: self.padded_row(row), base: self.base(row), prefix };
        if cut > 0 {
            walk.add(0, cut, |k, w| below[k] += w);
        }
        if plane_end > cut {
            walk.add(cut, plane_end, |k, w| {
                below[k] += 0.5 * w;
                above[k] += 0.5 * w;
            });
        }
        if plane_end < len {
            walk.add(plane_end, len, |k, w| above[k] += w);
        }
    }
}

/// One stencil row's voxels in the padded volume, walked by runs.
struct RowWalk<'a> {
    runs: &'a BinRuns,
    padded_row: usize,
    /// Padded index of the row's first voxel.
    base: usize,
    /// The row's prefix sums of weights (len + 1 values).
    prefix: &'a [f64],
}

impl RowWalk<'_> {
    /// Gives `add(bin, weight)` the summed weight of every run piece of the
    /// row's voxels `from..to` (non-empty), in order.
    #[inline]
    fn add(&self, from: usize, to: usize, mut add: impl FnMut(usize, f64)) {
        let runs = self.runs;
        let (first, last) =
            (runs.run_in(self.padded_row, self.base + from), runs.run_in(self.padded_row, self.base + to - 1));
        // x of the row's first voxel: run ends are x positions in the row.
        let x0 = self.base - self.padded_row * runs.row_length();
        let mut start = from;
        for run in first..last {
            let end = runs.end_x(run) - x0;
            add(runs.bin(run) as usize, self.prefix[end] - self.prefix[start]);
            start = end;
        }
        add(runs.bin(last) as usize, self.prefix[to] - self.prefix[start]);
    }
}
