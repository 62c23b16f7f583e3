//! Vector quantization of packed local histograms (section 3.2): LBG training
//! (Linde, Buzo, Gray 1980) and the nearest-codeword assignment, for the L2, L1
//! and Lmax metrics the paper compares (figure 6).
//!
//! - Distances: L2 is the squared Euclidean distance (LBG's mean squared
//!   error; the same nearest codeword as the Euclidean one), L1 the sum and Lmax
//!   the largest of the absolute component differences. The distortion of a
//!   codebook is the mean distance of the training vectors to their codewords.
//! - Centroids: the paper does not say how the training represents a cluster
//!   under L1 or Lmax. We use each metric's own optimum: the mean for L2 (it
//!   minimizes the summed squared distance), the component-wise median for L1
//!   (it minimizes the summed L1 distance, which separates by component; for an
//!   even count the middle of the two central values) and the component-wise
//!   midrange for Lmax (it minimizes the largest Lmax distance of any member,
//!   the Chebyshev centre; the summed Lmax distance has no closed form). The
//!   final codebook is the mean of the *unpacked* members whatever the metric,
//!   as the paper says ("averaging over its elements"): see [`super::preprocess`].
//! - LBG: start with one codeword (the centroid of all), run Lloyd iterations
//!   (assign, re-centre) until the relative distortion change falls below the
//!   threshold, then split every codeword c into c (1 + e) and c (1 - e), e =
//!   0.01, and repeat until n_c codewords. When fewer than twice the codewords
//!   are wanted, only those with the largest summed distortion split. A codeword
//!   left without vectors moves onto the training vector farthest from its own
//!   codeword (the usual repair; without it a split of a cluster of identical
//!   vectors stays empty forever).
//! - The paper sped its training up by "sorting more than one vector in each
//!   iteration"; our Lloyd iterations are batch updates (every vector assigned,
//!   then every centroid moved), over all cores.
//! - Search: partial distance elimination, started from a hint (the previous
//!   iteration's codeword, or the neighbouring voxel's). The result is the exact
//!   nearest codeword, ties to the lowest index, whatever the hint.
//! - Lloyd iterations skip the search of a vector whose codeword provably stays
//!   its unique nearest (Hamerly's bounds, see [`super::lloyd_bounds`]): the
//!   same assignment, codebook and distortion as searching every vector.

use super::codebook_lanes::CodebookLanes;
use super::lloyd_bounds::{drift, LowerBounds};
use super::parallel::for_each_chunk;
use super::settings::Metric;

/// Relative perturbation of an LBG split.
const SPLIT_EPSILON: f32 = 0.01;
/// Training vectors per parallel chunk of an assignment.
const CHUNK: usize = 512;

/// Distance of `a` and `b` under `metric` (L2: squared).
pub fn distance(metric: Metric, a: &[f32], b: &[f32]) -> f32 {
    distance_within(metric, a, b, f32::INFINITY)
}

/// As [`distance`], but may stop early and return a partial value `> bound`
/// once the distance is known to exceed `bound`.
///
/// Index loops rather than iterator adapters: without thin LTO across the
/// crate's codegen units (Cargo.toml) and with the MIR inliner off (the test
/// build compiles through clippy-driver), `zip`'s and `chunks`' methods stayed
/// out-of-line calls and AO's preprocessing ran twice as long.
#[inline]
pub fn distance_within(metric: Metric, a: &[f32], b: &[f32], bound: f32) -> f32 {
    let (n, mut sum, mut start) = (a.len().min(b.len()), 0.0f32, 0);
    while start < n {
        let end = (start + 8).min(n);
        match metric {
            Metric::L2 => {
                let mut chunk = 0.0f32;
                for i in start..end {
                    chunk += (a[i] - b[i]) * (a[i] - b[i]);
                }
                sum += chunk;
            }
            Metric::L1 => {
                let mut chunk = 0.0f32;
                for i in start..end {
                    chunk += (a[i] - b[i]).abs();
                }
                sum += chunk;
            }
            Metric::Lmax => {
                for i in start..end {
                    sum = sum.max((a[i] - b[i]).abs());
                }
            }
        }
        if sum > bound {
            return sum;
        }
        start = end;
    }
    sum
}

/// `len` codewords of dimension `dim`, row after row.
#[derive(Clone, Debug, PartialEq)]
pub struct Codebook {
    pub dim: usize,
    pub words: Vec<f32>,
}

impl Codebook {
    pub fn len(&self) -> usize {
        self.words.len() / self.dim.max(1)
    }

    pub fn is_empty(&self) -> bool {
        self.words.is_empty()
    }

    pub fn word(&self, i: usize) -> &[f32] {
        &self.words[i * self.dim..(i + 1) * self.dim]
    }

    fn word_mut(&mut self, i: usize) -> &mut [f32] {
        &mut self.words[i * self.dim..(i + 1) * self.dim]
    }

    /// Index of the nearest codeword to `x` (ties: the lowest index) and its
    /// distance; `hint` is where the search starts (any index is correct, a
    /// good one is fast).
    pub fn nearest(&self, metric: Metric, x: &[f32], hint: usize) -> (usize, f32) {
        let n = self.len();
        let mut best = hint.min(n - 1);
        let mut best_d = distance(metric, x, self.word(best));
        for j in 0..n {
            if j == best {
                continue;
            }
            let d = distance_within(metric, x, self.word(j), best_d);
            if d < best_d || (d == best_d && j < best) {
                best = j;
                best_d = d;
            }
        }
        (best, best_d)
    }
}

/// LBG parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LbgParams {
    pub metric: Metric,
    pub clusters: usize,
    /// Most Lloyd iterations per codebook size.
    pub max_iterations: u32,
    /// Stop a size's iterations once (D_prev - D) <= threshold * D.
    pub threshold: f64,
}

#[derive(Clone, Debug)]
pub struct Training {
    pub codebook: Codebook,
    /// Codeword of every training vector.
    pub assignment: Vec<u32>,
    /// Mean distance of the training vectors to their codewords.
    pub distortion: f64,
    /// Lloyd iterations over all codebook sizes.
    pub iterations: u32,
    /// (codebook size, distortion) at the end of each size.
    pub history: Vec<(usize, f64)>,
    /// Vector assignments over all iterations, and those whose search the
    /// bounds skipped.
    pub assignments: u64,
    pub searches_skipped: u64,
}

/// Trains a codebook of `params.clusters` words on `vectors` (rows of `dim`,
/// at least one); `progress(fraction)` after every codebook size.
pub fn train_lbg(vectors: &[f32], dim: usize, params: LbgParams, progress: &mut dyn FnMut(f64)) -> Training {
    train(vectors, dim, params, true, progress)
}

/// [`train_lbg`]; `bounded = false` searches every vector in every iteration
/// (what the tests compare the bounds with).
fn train(vectors: &[f32], dim: usize, params: LbgParams, bounded: bool, progress: &mut dyn FnMut(f64)) -> Training {
    let n = vectors.len() / dim;
    assert!(n > 0 && dim > 0, "LBG needs at least one training vector");
    let metric = params.metric;
    let target = params.clusters.max(1);
    let mut codebook = Codebook { dim, words: vec![0.0; dim] };
    let mut assignment = vec![0u32; n];
    update_centroids(metric, vectors, dim, &assignment, &mut codebook);

    // Sizes 1, 2, 4, ..., target: the work of a size grows with it.
    let mut sizes = vec![1usize];
    while *sizes.last().unwrap_or(&target) < target {
        let s = *sizes.last().unwrap_or(&target);
        sizes.push((2 * s).min(target));
    }
    let total_work: usize = sizes.iter().sum();
    let mut done_work = 0;

    let mut history = Vec::new();
    let (mut iterations, mut assignments, mut searches_skipped) = (0, 0, 0);
    let mut distances = vec![0f32; n];
    let mut distortion;
    loop {
        // Lloyd iterations at this size; the first searches every vector.
        let mut previous = f64::INFINITY;
        let mut iteration = 0;
        let mut bounds: Option<LowerBounds> = None;
        loop {
            let known = bounds.as_ref().filter(|_| bounded);
            let assigned = assign_all(metric, vectors, &codebook, &assignment, known);
            (assignment, distances) = (assigned.ids, assigned.distances);
            assignments += n as u64;
            searches_skipped += assigned.skipped;
            bounds = Some(assigned.lower);
            distortion = distances.iter().map(|&d| d as f64).sum::<f64>() / n as f64;
            iterations += 1;
            iteration += 1;
            let converged = distortion == 0.0 || previous - distortion <= params.threshold * distortion;
            if converged || iteration >= params.max_iterations {
                break;
            }
            previous = distortion;
            let before = codebook.clone();
            update_centroids(metric, vectors, dim, &assignment, &mut codebook);
            relocate_empty(vectors, dim, &assignment, &distances, &mut codebook);
            if let Some(lower) = bounds.as_mut() {
                lower.codewords_moved(&assignment, &drift(metric, &before, &codebook));
            }
        }
        let size = codebook.len();
        history.push((size, distortion));
        done_work += size;
        progress(done_work as f64 / total_work as f64);
        if size >= target {
            break;
        }
        split(&mut codebook, &assignment, &distances, target);
    }
    Training { codebook, assignment, distortion, iterations, history, assignments, searches_skipped }
}

/// What [`assign_all`] gives: each vector's codeword and distance, the lower
/// bounds on its distance to every other codeword, and how many searches the
/// bounds skipped.
struct Assigned {
    ids: Vec<u32>,
    distances: Vec<f32>,
    lower: LowerBounds,
    skipped: u64,
}

/// Nearest codeword and distance of every vector, over all cores, each search
/// started at the vector's previous codeword. With `known` (the lower bounds of
/// the previous assignment, moved by the codewords' drift since), a vector whose
/// distance to its previous codeword is below its bound keeps that codeword
/// unsearched: no other can be as near.
fn assign_all(
    metric: Metric,
    vectors: &[f32],
    codebook: &Codebook,
    previous: &[u32],
    known: Option<&LowerBounds>,
) -> Assigned {
    let dim = codebook.dim;
    let n = vectors.len() / dim;
    let mut ids = vec![0u32; n];
    let mut distances = vec![0f32; n];
    let mut lower = LowerBounds::unknown(n, dim);
    let mut skipped = 0;
    let lanes = CodebookLanes::new(codebook);
    for_each_chunk(
        n.div_ceil(CHUNK),
        || (),
        |_, c| {
            let range = c * CHUNK..((c + 1) * CHUNK).min(n);
            range
                .map(|i| {
                    let (x, hint) = (&vectors[i * dim..(i + 1) * dim], previous[i] as usize);
                    if let Some(known) = known {
                        let d = distance(metric, x, codebook.word(hint));
                        if known.keeps(i, metric, d) {
                            return (hint as u32, d, known.get(i), true);
                        }
                    }
                    let (j, d, second) = lanes.nearest_two(metric, codebook, x, hint);
                    (j as u32, d, LowerBounds::from_second(metric, second, dim), false)
                })
                .collect::<Vec<_>>()
        },
        |c, result, _| {
            for (k, (j, d, bound, kept)) in result.into_iter().enumerate() {
                ids[c * CHUNK + k] = j;
                distances[c * CHUNK + k] = d;
                lower.set(c * CHUNK + k, bound);
                skipped += kept as u64;
            }
        },
    );
    Assigned { ids, distances, lower, skipped }
}

/// Moves every codeword that has members to its metric's centroid of them.
fn update_centroids(metric: Metric, vectors: &[f32], dim: usize, assignment: &[u32], codebook: &mut Codebook) {
    let k = codebook.len();
    // Members of each cluster, by a counting sort.
    let mut start = vec![0usize; k + 1];
    for &a in assignment {
        start[a as usize + 1] += 1;
    }
    for j in 0..k {
        start[j + 1] += start[j];
    }
    let mut fill = start.clone();
    let mut members = vec![0usize; assignment.len()];
    for (i, &a) in assignment.iter().enumerate() {
        members[fill[a as usize]] = i;
        fill[a as usize] += 1;
    }
    let mut values = Vec::new();
    for j in 0..k {
        let m = &members[start[j]..start[j + 1]];
        if m.is_empty() {
            continue;
        }
        let word = codebook.word_mut(j);
        // Index loops, as in `distance_within`.
        for c in 0..dim {
            word[c] = match metric {
                Metric::L2 => {
                    let mut sum = 0.0f64;
                    for &i in m {
                        sum += vectors[i * dim + c] as f64;
                    }
                    (sum / m.len() as f64) as f32
                }
                Metric::L1 => {
                    values.clear();
                    for &i in m {
                        values.push(vectors[i * dim + c]);
                    }
                    median(&mut values)
                }
                Metric::Lmax => {
                    let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
                    for &i in m {
                        (lo, hi) = (lo.min(vectors[i * dim + c]), hi.max(vectors[i * dim + c]));
                    }
                    0.5 * (lo + hi)
                }
            };
        }
    }
}

/// Median of `values` (not empty); for an even count the middle of the two
/// central values.
fn median(values: &mut [f32]) -> f32 {
    let m = values.len();
    let (lower, upper, _) = values.select_nth_unstable_by(m / 2, f32::total_cmp);
    let upper = *upper;
    if m % 2 == 1 {
        return upper;
    }
    let below = lower.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    0.5 * (below + upper)
}

/// Puts every codeword without members onto one of the training vectors
/// farthest from their codewords (each used once), if any is not already on it.
fn relocate_empty(vectors: &[f32], dim: usize, assignment: &[u32], distances: &[f32], codebook: &mut Codebook) {
    let mut used = vec![false; codebook.len()];
    for &a in assignment {
        used[a as usize] = true;
    }
    let empty: Vec<usize> = (0..used.len()).filter(|&j| !used[j]).collect();
    if empty.is_empty() {
        return;
    }
    let mut far: Vec<usize> = (0..distances.len()).filter(|&i| distances[i] > 0.0).collect();
    far.sort_by(|&a, &b| distances[b].total_cmp(&distances[a]).then(a.cmp(&b)));
    for (j, i) in empty.into_iter().zip(far) {
        codebook.word_mut(j).copy_from_slice(&vectors[i * dim..(i + 1) * dim]);
    }
}

/// Splits codewords until the codebook has min(2 len, target) words: all of
/// them, or those with the largest summed distortion when fewer are needed.
fn split(codebook: &mut Codebook, assignment: &[u32], distances: &[f32], target: usize) {
    let k = codebook.len();
    let count = k.min(target - k);
    let mut order: Vec<usize> = (0..k).collect();
    if count < k {
        let mut cost = vec![0f64; k];
        for (&a, &d) in assignment.iter().zip(distances) {
            cost[a as usize] += d as f64;
        }
        order.sort_by(|&a, &b| cost[b].total_cmp(&cost[a]).then(a.cmp(&b)));
    }
    for &j in &order[..count] {
        let word = codebook.word(j).to_vec();
        codebook.words.extend(word.iter().map(|v| v * (1.0 - SPLIT_EPSILON)));
        for v in codebook.word_mut(j) {
            *v *= 1.0 + SPLIT_EPSILON;
        }
    }
}

/// Both cluster ids of a voxel in one 32-bit value, as the paper stores them
/// ("two cluster identifiers can be fetched from a 32-bit volume
/// simultaneously"): forward hemisphere in the low 16 bits, backward in the high.
pub fn pack_cluster_ids(forward: u32, backward: u32) -> u32 {
    debug_assert!(forward <= 0xFFFF && backward <= 0xFFFF);
    (forward & 0xFFFF) | (backward << 16)
}

/// (forward, backward) of a [`pack_cluster_ids`] value.
pub fn unpack_cluster_ids(ids: u32) -> (u32, u32) {
    (ids & 0xFFFF, ids >> 16)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Deterministic pseudo-random vectors around `centres` blobs.
    fn blobs(n: usize, dim: usize, centres: usize) -> Vec<f32> {
        let mut state = 12345u64;
        let mut next = || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        let centre: Vec<f32> = (0..centres * dim).map(|_| next()).collect();
        (0..n)
            .flat_map(|i| {
                let c = i % centres;
                (0..dim).map(|d| centre[c * dim + d] + 0.1 * (next() - 0.5)).collect::<Vec<_>>()
            })
            .collect()
    }

    #[test]
    fn distances_follow_their_metric() {
        let (a, b) = ([0.0, 1.0, 3.0], [1.0, 1.0, 1.0]);
        assert_eq!(distance(Metric::L2, &a, &b), 5.0);
        assert_eq!(distance(Metric::L1, &a, &b), 3.0);
        assert_eq!(distance(Metric::Lmax, &a, &b), 2.0);
        // Early exit returns something above the bound, never below the truth.
        let long: Vec<f32> = (0..32).map(|i| i as f32).collect();
        let zero = vec![0.0; 32];
        assert!(distance_within(Metric::L1, &long, &zero, 10.0) > 10.0);
    }

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&mut [4.0, 1.0, 3.0, 2.0]), 2.5);
        assert_eq!(median(&mut [7.0]), 7.0);
    }

    #[test]
    fn nearest_is_the_exhaustive_argmin_whatever_the_hint() {
        let dim = 12;
        let words = blobs(40, dim, 40);
        let codebook = Codebook { dim, words };
        let queries = blobs(200, dim, 7);
        for metric in Metric::ALL {
            for q in queries.chunks(dim) {
                let exhaustive = (0..codebook.len())
                    .map(|j| (j, distance(metric, q, codebook.word(j))))
                    .fold((0, f32::INFINITY), |b, (j, d)| if d < b.1 { (j, d) } else { b });
                for hint in [0, 17, 39] {
                    assert_eq!(codebook.nearest(metric, q, hint), exhaustive, "{metric:?} hint {hint}");
                }
            }
        }
        // Ties go to the lowest index.
        let twins = Codebook { dim: 2, words: vec![1.0, 0.0, 0.0, 1.0, 1.0, 0.0] };
        assert_eq!(twins.nearest(Metric::L2, &[1.0, 0.0], 2).0, 0);
    }

    #[test]
    fn lbg_finds_well_separated_blobs_and_distortion_falls_with_size() {
        let dim = 8;
        let data = blobs(2000, dim, 16);
        for metric in Metric::ALL {
            let params = |clusters| LbgParams { metric, clusters, max_iterations: 30, threshold: 1e-4 };
            let d: Vec<f64> =
                [2, 4, 16, 64].iter().map(|&k| train_lbg(&data, dim, params(k), &mut |_| {}).distortion).collect();
            assert!(d.windows(2).all(|w| w[1] < w[0]), "{metric:?}: {d:?}");
            let t = train_lbg(&data, dim, params(16), &mut |_| {});
            assert_eq!(t.codebook.len(), 16);
            // Every vector sits on its nearest codeword.
            for (i, v) in data.chunks(dim).enumerate() {
                assert_eq!(t.codebook.nearest(metric, v, 0).0, t.assignment[i] as usize);
            }
        }
    }

    /// The bounds skip searches and change nothing: the same codebook,
    /// assignment and distortion at every size as searching every vector.
    #[test]
    fn bounded_training_is_the_training_that_searches_every_vector() {
        let dim = 12;
        let data = blobs(3000, dim, 40);
        for metric in Metric::ALL {
            let params = LbgParams { metric, clusters: 37, max_iterations: 25, threshold: 1e-5 };
            let bounded = train(&data, dim, params, true, &mut |_| {});
            let searched = train(&data, dim, params, false, &mut |_| {});
            assert_eq!(bounded.codebook, searched.codebook, "{metric:?}");
            assert_eq!(bounded.assignment, searched.assignment, "{metric:?}");
            assert_eq!(bounded.history, searched.history, "{metric:?}");
            assert_eq!(bounded.iterations, searched.iterations, "{metric:?}");
            assert_eq!(searched.searches_skipped, 0);
            assert!(
                bounded.searches_skipped * 5 > bounded.assignments,
                "{metric:?}: {} of {} searches skipped",
                bounded.searches_skipped,
                bounded.assignments
            );
        }
    }

    #[test]
    fn a_codebook_size_that_is_no_power_of_two_is_reached() {
        let data = blobs(500, 4, 10);
        let params = LbgParams { metric: Metric::L2, clusters: 11, max_iterations: 10, threshold: 1e-3 };
        let mut fractions = vec![];
        let t = train_lbg(&data, 4, params, &mut |f| fractions.push(f));
        assert_eq!(t.codebook.len(), 11);
        assert_eq!(t.history.iter().map(|h| h.0).collect::<Vec<_>>(), vec![1, 2, 4, 8, 11]);
        assert_eq!(fractions.last(), Some(&1.0));
    }

    #[test]
    fn identical_vectors_leave_split_codewords_empty_without_harm() {
        let data = vec![0.5f32; 4 * 100];
        let params = LbgParams { metric: Metric::L1, clusters: 8, max_iterations: 5, threshold: 1e-3 };
        let t = train_lbg(&data, 4, params, &mut |_| {});
        assert_eq!(t.distortion, 0.0);
        assert_eq!(t.codebook.len(), 8);
    }

    #[test]
    fn cluster_ids_pack_into_one_u32() {
        assert_eq!(pack_cluster_ids(3, 2047), 3 | (2047 << 16));
        assert_eq!(unpack_cluster_ids(pack_cluster_ids(2047, 5)), (2047, 5));
    }
}
