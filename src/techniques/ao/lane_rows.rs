//! Local histograms of [`LANES`] neighbouring centres along x at once: the
//! preprocessing's CPU path (docs/ao.md, "CPU histograms: centres in lanes").
//!
//! Why: at b = 8 the engine's runs of one bin are about two voxels long, so the
//! row walk of [`super::row_runs`] adds to a scattered bin for almost every
//! stencil voxel, one centre at a time. Centres x0 .. x0 + LANES - 1 read the
//! same source rows, shifted by one voxel each, so every source voxel has one
//! bin for all of them: each bin holds one value per lane, and one update of
//! a source run adds to all lanes at once (a vector), where the row walk made
//! LANES scattered updates.
//!
//! Per stencil row and group, over the window of source voxels the lanes' rows
//! cover: each voxel's weight per lane (0 where it lies outside that lane's
//! row) goes forward, backward or half to each by the brute force's hemisphere
//! test, term for term in f32 and in the same order, summed into per-lane
//! prefix sums (f64); each run of one bin then adds the difference of the
//! prefix sums at its ends. Only the order of the f64 additions differs from
//! the brute force, as in the row walk. A test that is not a number (a
//! gradient that is not finite) fails both comparisons and splits half and
//! half, as the brute force's does.
//!
//! Rows come in antipodal pairs (o and -o) with the same weights and x
//! directions, the test's y and z terms negated: one pass over the window
//! builds both rows' prefix sums. When both windows are one run of the same
//! bin, each hemisphere of every lane gets the row's whole weight, as in the
//! row walk, with no pass at all.

use std::collections::HashMap;

use glam::Vec3;

use super::bin_runs::BinRuns;
use super::row_runs::StencilRows;

/// Centres per group: 8 f64 lanes fill one AVX-512 register (two AVX2 ones).
pub const LANES: usize = 8;

/// One f64 per lane.
pub type Lanes = [f64; LANES];

/// Forward and backward, side by side (one address per bin or position),
/// aligned to cache lines: a vector access that crosses a line costs two.
#[derive(Clone, Copy, Debug, Default)]
#[repr(C, align(64))]
pub struct Sides([Lanes; 2]);

impl std::ops::Index<usize> for Sides {
    type Output = Lanes;
    #[inline(always)]
    fn index(&self, side: usize) -> &Lanes {
        &self.0[side]
    }
}

impl std::ops::IndexMut<usize> for Sides {
    #[inline(always)]
    fn index_mut(&mut self, side: usize) -> &mut Lanes {
        &mut self.0[side]
    }
}

const FORWARD: usize = 0;
const BACKWARD: usize = 1;

/// One stencil row, laid out for a group of lanes.
#[derive(Clone, Debug)]
struct LaneRow {
    /// Linear offset, in the padded bin volume, of lane 0's first row voxel.
    start: isize,
    /// Offset in padded x rows.
    row_offset: isize,
    /// Voxels of one lane's row.
    len: usize,
    /// Index of the row's first entry in `weights` and in `directions_x`.
    weights_first: usize,
    directions_first: usize,
    direction_y: f32,
    direction_z: f32,
    /// Sum of the row's weights.
    total: f64,
}

impl LaneRow {
    /// Source voxels the group's rows cover.
    #[inline]
    fn window(&self) -> usize {
        self.len + LANES - 1
    }
}

/// The stencil's rows with their weights and x directions reversed and padded
/// by LANES - 1 zeros on each side, so that the lanes' values at window
/// position t are one contiguous slice: entry m holds the row's voxel
/// `len + LANES - 2 - m`, and lane j reads entry `len + LANES - 2 - t + j`,
/// its voxel t - j.
#[derive(Clone, Debug)]
pub struct LaneRows {
    rows: Vec<LaneRow>,
    weights: Vec<f64>,
    directions_x: Vec<f32>,
    longest_window: usize,
}

/// Per-thread sums of one group: per bin, both sides' values per lane
/// (`sums[k][FORWARD][j]`), and the prefix sums of one row.
pub struct LaneScratch {
    sums: Vec<Sides>,
    prefix: Vec<Sides>,
    mirror_prefix: Vec<Sides>,
}

impl LaneScratch {
    /// Lane `j`'s forward and backward sums of bin `k`.
    #[inline]
    pub fn lane(&self, k: usize, j: usize) -> (f64, f64) {
        (self.sums[k][FORWARD][j], self.sums[k][BACKWARD][j])
    }
}

impl LaneRows {
    pub fn new(rows: &StencilRows) -> LaneRows {
        let mut lane_rows = LaneRows { rows: vec![], weights: vec![], directions_x: vec![], longest_window: 0 };
        // Rows with equal |y| and |z| offsets have equal weights, and rows of
        // one length equal x directions: each table is stored once (28 KB
        // instead of about 340 KB at r = 16), and a row and its mirror share
        // theirs, which `add_rows` relies on.
        let (mut weights_at, mut directions_at) = (HashMap::new(), HashMap::new());
        for row in rows.rows() {
            let len = row.weights.len();
            let weights: Vec<f64> =
                [0.0; LANES - 1].iter().chain(row.weights.iter().rev()).chain(&[0.0; LANES - 1]).copied().collect();
            let directions_x: Vec<f32> = [0.0; LANES - 1]
                .iter()
                .chain(row.directions_x.iter().rev())
                .chain(&[0.0; LANES - 1])
                .copied()
                .collect();
            let weights_first =
                *weights_at.entry(weights.iter().map(|w| w.to_bits()).collect::<Vec<_>>()).or_insert_with(|| {
                    lane_rows.weights.extend(&weights);
                    lane_rows.weights.len() - weights.len()
                });
            let directions_first = *directions_at
                .entry(directions_x.iter().map(|x| x.to_bits()).collect::<Vec<_>>())
                .or_insert_with(|| {
                    lane_rows.directions_x.extend(&directions_x);
                    lane_rows.directions_x.len() - directions_x.len()
                });
            lane_rows.rows.push(LaneRow {
                start: row.start,
                row_offset: row.row_offset,
                len,
                weights_first,
                directions_first,
                direction_y: row.direction_y,
                direction_z: row.direction_z,
                total: row.total,
            });
            lane_rows.longest_window = lane_rows.longest_window.max(len + LANES - 1);
        }
        // Row i and row n-1-i are mirrors (o and -o): equal lengths, weights
        // and x directions, so one table serves both (`add_rows`).
        let n = lane_rows.rows.len();
        assert!(
            (0..n).all(|i| {
                let (a, b) = (&lane_rows.rows[i], &lane_rows.rows[n - 1 - i]);
                a.len == b.len && a.weights_first == b.weights_first && a.directions_first == b.directions_first
            }),
            "a stencil row and its mirror share their tables"
        );
        lane_rows
    }

    /// Scratch for [`Self::accumulate`] with `bins` bins (the "outside" bin
    /// included).
    pub fn scratch(&self, bins: usize) -> LaneScratch {
        LaneScratch {
            sums: vec![Sides::default(); bins],
            prefix: vec![Sides::default(); self.longest_window + 1],
            mirror_prefix: vec![Sides::default(); self.longest_window + 1],
        }
    }

    /// Whether this CPU has a vector path (AVX-512 or AVX2). Without one the
    /// lanes cost more than the row walk: 24.6-25.0 against 19.5-20.1 us per
    /// voxel on the engine at r = 16, b = 8 (SSE2 only, forced on this
    /// machine; AVX2 11.6 us, AVX-512 7.0-7.5 us).
    pub fn vectorized() -> bool {
        #[cfg(target_arch = "x86_64")]
        return std::arch::is_x86_feature_detected!("avx2")
            || (std::arch::is_x86_feature_detected!("avx512f") && std::arch::is_x86_feature_detected!("avx512vl"));
        #[cfg(not(target_arch = "x86_64"))]
        false
    }

    /// Sets `scratch.sums` to the summed weights of the stencils around padded
    /// indices `centre .. centre + LANES` (one x row, each at least the
    /// stencil's x extent from the row's ends), lane j with gradient `g[j]`.
    pub fn accumulate(&self, centre: usize, g: &[Vec3; LANES], runs: &BinRuns, scratch: &mut LaneScratch) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx512f") && std::arch::is_x86_feature_detected!("avx512vl") {
            // SAFETY: the CPU has AVX-512F and VL, checked just above; the
            // function is safe code compiled for them.
            return unsafe { self.accumulate_avx512(centre, g, runs, scratch) };
        } else if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: as above, for AVX2.
            return unsafe { self.accumulate_avx2(centre, g, runs, scratch) };
        }
        self.accumulate_generic::<false>(centre, g, runs, scratch);
    }

    /// [`Self::accumulate`] by the path `path` names, if this CPU can run it:
    /// the tests check every path against the portable one.
    #[cfg(test)]
    pub fn accumulate_by(
        &self,
        path: &str,
        centre: usize,
        g: &[Vec3; LANES],
        runs: &BinRuns,
        scratch: &mut LaneScratch,
    ) -> bool {
        match path {
            "portable" => self.accumulate_generic::<false>(centre, g, runs, scratch),
            #[cfg(target_arch = "x86_64")]
            "avx2" if std::arch::is_x86_feature_detected!("avx2") => {
                // SAFETY: the CPU has AVX2, checked just above.
                unsafe { self.accumulate_avx2(centre, g, runs, scratch) }
            }
            #[cfg(target_arch = "x86_64")]
            "avx512"
                if std::arch::is_x86_feature_detected!("avx512f")
                    && std::arch::is_x86_feature_detected!("avx512vl") =>
            {
                // SAFETY: the CPU has AVX-512F and VL, checked just above.
                unsafe { self.accumulate_avx512(centre, g, runs, scratch) }
            }
            _ => return false,
        }
        true
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f,avx512vl")]
    fn accumulate_avx512(&self, centre: usize, g: &[Vec3; LANES], runs: &BinRuns, scratch: &mut LaneScratch) {
        self.accumulate_generic::<true>(centre, g, runs, scratch);
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn accumulate_avx2(&self, centre: usize, g: &[Vec3; LANES], runs: &BinRuns, scratch: &mut LaneScratch) {
        self.accumulate_generic::<false>(centre, g, runs, scratch);
    }

    /// `AVX512`: only from [`Self::accumulate_avx512`].
    #[inline(always)]
    fn accumulate_generic<const AVX512: bool>(
        &self,
        centre: usize,
        g: &[Vec3; LANES],
        runs: &BinRuns,
        scratch: &mut LaneScratch,
    ) {
        scratch.sums.fill(Sides::default());
        let gx: [f32; LANES] = std::array::from_fn(|j| g[j].x);
        let centre_row = runs.row_of(centre);
        let n = self.rows.len();
        for i in 0..n.div_ceil(2) {
            let (row, mirror) = (&self.rows[i], &self.rows[n - 1 - i]);
            if i != n - 1 - i {
                let bins = (single_bin(row, centre, centre_row, runs), single_bin(mirror, centre, centre_row, runs));
                if let (Some(k), Some(mirror_k)) = bins {
                    if k == mirror_k {
                        // Each lane's row and mirror give the row's whole
                        // weight to each side together.
                        let sums = &mut scratch.sums[k];
                        let whole = [row.total; LANES];
                        add_difference(&mut sums[FORWARD], &[0.0; LANES], &whole);
                        add_difference(&mut sums[BACKWARD], &[0.0; LANES], &whole);
                        continue;
                    }
                }
            }
            self.add_rows::<AVX512>(row, mirror, i != n - 1 - i, centre, centre_row, g, &gx, runs, scratch);
        }
    }

    /// Adds `row` and, if `with_mirror`, its mirror, of every lane, run by
    /// run. The two share their weights and x directions (the test's y and z
    /// terms change sign), so one pass over the window gives both rows'
    /// prefix sums.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn add_rows<const AVX512: bool>(
        &self,
        row: &LaneRow,
        mirror: &LaneRow,
        with_mirror: bool,
        centre: usize,
        centre_row: usize,
        g: &[Vec3; LANES],
        gx: &[f32; LANES],
        runs: &BinRuns,
        scratch: &mut LaneScratch,
    ) {
        let window = row.window();
        let entries = row.len + 2 * (LANES - 1);
        // The brute force's terms: g.x * o.x + g.y * o.y + g.z * o.z, in order.
        let terms = RowTerms {
            weights: &self.weights[row.weights_first..row.weights_first + entries],
            directions_x: &self.directions_x[row.directions_first..row.directions_first + entries],
            gx,
            y_term: std::array::from_fn(|j| g[j].y * row.direction_y),
            z_term: std::array::from_fn(|j| g[j].z * row.direction_z),
        };
        let prefix = &mut scratch.prefix[..window + 1];
        let mirror_prefix = &mut scratch.mirror_prefix[..window + 1];
        #[cfg(target_arch = "x86_64")]
        if AVX512 {
            // SAFETY: AVX512 is only true under `accumulate_avx512`, which
            // runs when the CPU has AVX-512F and VL.
            unsafe { prefix_sums_avx512(&terms, prefix, mirror_prefix) };
        } else {
            prefix_sums(&terms, prefix, mirror_prefix);
        }
        #[cfg(not(target_arch = "x86_64"))]
        prefix_sums(&terms, prefix, mirror_prefix);
        add_runs(row, centre, centre_row, runs, prefix, &mut scratch.sums);
        if with_mirror {
            add_runs(mirror, centre, centre_row, runs, mirror_prefix, &mut scratch.sums);
        }
    }
}

/// Adds the runs of `row`'s window around `centre`, each the difference of
/// the row's prefix sums at its ends, to the sums of their bins.
#[inline(always)]
fn add_runs(row: &LaneRow, centre: usize, centre_row: usize, runs: &BinRuns, prefix: &[Sides], sums: &mut [Sides]) {
    let window = row.window();
    let base = (centre as isize + row.start) as usize;
    let padded_row = (centre_row as isize + row.row_offset) as usize;
    let (first, last) = (runs.run_in(padded_row, base), runs.run_in(padded_row, base + window - 1));
    let x0 = base - padded_row * runs.row_length();
    let (ends, bins) = runs.ends_and_bins(first..last + 1);
    let prefix = &prefix[..window + 1];
    let mut from = &prefix[0];
    // Every run but the last ends inside the window; the last is cut at its
    // end.
    let ends = ends[..ends.len() - 1].iter().map(|&end| (end as usize - x0).min(window)).chain([window]);
    for (end, &k) in ends.zip(bins) {
        let to = &prefix[end];
        let sum = &mut sums[k as usize];
        add_difference(&mut sum[FORWARD], &from[FORWARD], &to[FORWARD]);
        add_difference(&mut sum[BACKWARD], &from[BACKWARD], &to[BACKWARD]);
        from = to;
    }
}

/// One row's tables for a group and the lanes' hemisphere terms: g.x per
/// lane, and g.y * o.y and g.z * o.z, the row's constant terms.
struct RowTerms<'a> {
    /// Laid out as in [`LaneRows`].
    weights: &'a [f64],
    directions_x: &'a [f32],
    gx: &'a [f32; LANES],
    y_term: [f32; LANES],
    z_term: [f32; LANES],
}

impl RowTerms<'_> {
    /// The lanes' weights and x directions at window position `t` of
    /// `window`.
    #[inline(always)]
    fn at(&self, window: usize, t: usize) -> (&[f64; LANES], &[f32; LANES]) {
        let at = window - 1 - t;
        (
            self.weights[at..at + LANES].try_into().expect("LANES entries"),
            self.directions_x[at..at + LANES].try_into().expect("LANES entries"),
        )
    }
}

/// Prefix sums over one row's window (`prefix.len() - 1` positions) of what
/// each position gives each lane's forward and backward hemisphere, and the
/// same for the mirror row (test terms g.y * -o.y and g.z * -o.z, exactly the
/// negated ones) into `mirror_prefix`; `weights` and `directions_x` laid out
/// as in [`LaneRows`].
#[inline(always)]
fn prefix_sums(terms: &RowTerms, prefix: &mut [Sides], mirror_prefix: &mut [Sides]) {
    let RowTerms { gx, y_term, z_term, .. } = terms;
    let window = prefix.len() - 1;
    let (mut sums, mut mirror_sums) = (Sides::default(), Sides::default());
    prefix[0] = sums;
    mirror_prefix[0] = mirror_sums;
    // Branch-free per lane (so that it vectorizes): the weight, half of it or
    // nothing, picked by bit masks.
    let add = |sums: &mut Sides, j: usize, side: f32, w: f64| {
        let (below, above) = (mask(side < 0.0), mask(side > 0.0));
        let on_plane = !(below | above);
        let (whole, half) = (w.to_bits(), (0.5 * w).to_bits());
        sums[FORWARD][j] += f64::from_bits((whole & below) | (half & on_plane));
        sums[BACKWARD][j] += f64::from_bits((whole & above) | (half & on_plane));
    };
    for t in 0..window {
        let (w, x) = terms.at(window, t);
        for j in 0..LANES {
            let x_term = gx[j] * x[j];
            add(&mut sums, j, x_term + y_term[j] + z_term[j], w[j]);
            add(&mut mirror_sums, j, x_term + -y_term[j] + -z_term[j], w[j]);
        }
        prefix[t + 1] = sums;
        mirror_prefix[t + 1] = mirror_sums;
    }
}

/// [`prefix_sums`] in AVX-512 (what LLVM makes of the portable loop takes
/// about three times the instructions): the same operations in the same
/// order per lane, so the same sums.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512vl")]
fn prefix_sums_avx512(terms: &RowTerms, prefix: &mut [Sides], mirror_prefix: &mut [Sides]) {
    use std::arch::x86_64::*;
    let window = prefix.len() - 1;
    assert_eq!(mirror_prefix.len(), window + 1);
    // SAFETY (every load and store below): the pointer comes from a reference
    // to LANES values, the bytes the unaligned access touches.
    let load_f32 = |v: &[f32; LANES]| unsafe { _mm256_loadu_ps(v.as_ptr()) };
    let (gx, y_term, z_term) = (load_f32(terms.gx), load_f32(&terms.y_term), load_f32(&terms.z_term));
    let (zero, one_half) = (_mm256_setzero_ps(), _mm512_set1_pd(0.5));
    // Exact negation: the sign bit flipped.
    let sign = _mm256_set1_ps(-0.0);
    let (mirror_y_term, mirror_z_term) = (_mm256_xor_ps(y_term, sign), _mm256_xor_ps(z_term, sign));
    let (mut forward, mut backward) = (_mm512_setzero_pd(), _mm512_setzero_pd());
    let (mut mirror_forward, mut mirror_backward) = (_mm512_setzero_pd(), _mm512_setzero_pd());
    prefix[0] = Sides::default();
    mirror_prefix[0] = Sides::default();
    let store = |to: &mut Sides, forward: __m512d, backward: __m512d| {
        let Sides([to_forward, to_backward]) = to;
        unsafe {
            _mm512_storeu_pd(to_forward.as_mut_ptr(), forward);
            _mm512_storeu_pd(to_backward.as_mut_ptr(), backward);
        }
    };
    for t in 0..window {
        let (w, x) = terms.at(window, t);
        let w = unsafe { _mm512_loadu_pd(w.as_ptr()) };
        let half = _mm512_mul_pd(one_half, w);
        let x_term = _mm256_mul_ps(gx, load_f32(x));
        // What one row's test gives its sums: the weight, half or nothing.
        let side_sums = |side: __m256, forward: &mut __m512d, backward: &mut __m512d| {
            let below = _mm256_cmp_ps_mask::<_CMP_LT_OQ>(side, zero);
            let above = _mm256_cmp_ps_mask::<_CMP_GT_OQ>(side, zero);
            let half = _mm512_maskz_mov_pd(!(below | above), half);
            *forward = _mm512_add_pd(*forward, _mm512_mask_mov_pd(half, below, w));
            *backward = _mm512_add_pd(*backward, _mm512_mask_mov_pd(half, above, w));
        };
        side_sums(_mm256_add_ps(_mm256_add_ps(x_term, y_term), z_term), &mut forward, &mut backward);
        side_sums(
            _mm256_add_ps(_mm256_add_ps(x_term, mirror_y_term), mirror_z_term),
            &mut mirror_forward,
            &mut mirror_backward,
        );
        store(&mut prefix[t + 1], forward, backward);
        store(&mut mirror_prefix[t + 1], mirror_forward, mirror_backward);
    }
}

/// All ones if `b`, else zero: a lane's select mask.
#[inline(always)]
fn mask(b: bool) -> u64 {
    (b as u64).wrapping_neg()
}

/// `sum += to - from`, lane by lane.
#[inline(always)]
fn add_difference(sum: &mut Lanes, from: &Lanes, to: &Lanes) {
    // Whole arrays in and out, so that the lanes are one vector each.
    let (s, a, b) = (*sum, *from, *to);
    *sum = std::array::from_fn(|j| s[j] + (b[j] - a[j]));
}

/// The bin of `row`'s window around `centre` if one run holds all of it.
#[inline(always)]
fn single_bin(row: &LaneRow, centre: usize, centre_row: usize, runs: &BinRuns) -> Option<usize> {
    let base = (centre as isize + row.start) as usize;
    let padded_row = (centre_row as isize + row.row_offset) as usize;
    let first = runs.run_in(padded_row, base);
    (first == runs.run_in(padded_row, base + row.window() - 1)).then(|| runs.bin(first) as usize)
}
