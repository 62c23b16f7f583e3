//! The codebook in groups of [`LANES`] codewords, component-major, for LBG's
//! assignment: one pass over a vector's components gives the distances to a
//! whole group at once, in vector registers. Each lane adds its terms in the
//! order [`super::quantize::distance_within`] does (components in chunks of 8,
//! each chunk summed from zero, then added to the total; Lmax a running max),
//! so every distance is bit for bit the scalar one, and the search finds the
//! codeword the scalar search finds. The scalar search's per-component add
//! chain made it latency-bound: the training of a 2048-word codebook was most
//! of an AO preprocessing.

use super::quantize::{distance, Codebook};
use super::settings::Metric;

/// Codewords per group: two SSE registers (x86-64's baseline), one AVX one.
const LANES: usize = 8;
/// Components per partial sum, as in `distance_within`.
const CHUNK: usize = 8;

pub(super) struct CodebookLanes {
    dim: usize,
    len: usize,
    /// Group g's component c, codeword g * LANES + l in lane l; lanes past the
    /// end are infinite (and never compared).
    groups: Vec<[f32; LANES]>,
}

impl CodebookLanes {
    pub fn new(codebook: &Codebook) -> CodebookLanes {
        let (dim, len) = (codebook.dim, codebook.len());
        let mut groups = vec![[f32::INFINITY; LANES]; len.div_ceil(LANES) * dim];
        for j in 0..len {
            for (c, &v) in codebook.word(j).iter().enumerate() {
                groups[(j / LANES) * dim + c][j % LANES] = v;
            }
        }
        CodebookLanes { dim, len, groups }
    }

    /// As [`Codebook::nearest`] on the codebook this was made from (the same
    /// codeword and distance), and a distance no larger than that of any other
    /// codeword (infinite for a codebook of one word).
    pub fn nearest_two(&self, metric: Metric, codebook: &Codebook, x: &[f32], hint: usize) -> (usize, f32, f32) {
        let start = hint.min(self.len - 1);
        let (mut best, mut best_d, mut second_d) = (start, distance(metric, x, codebook.word(start)), f32::INFINITY);
        for g in 0..self.len.div_ceil(LANES) {
            // None: every lane is above second_d, so none is the nearest or the second.
            let Some(lanes) = self.group_distances(metric, x, g, second_d) else { continue };
            for (l, &d) in lanes.iter().enumerate() {
                let j = g * LANES + l;
                if j >= self.len || j == start {
                    continue;
                }
                if d < best_d || (d == best_d && j < best) {
                    (best, best_d, second_d) = (j, d, best_d);
                } else if d < second_d {
                    second_d = d;
                }
            }
        }
        (best, best_d, second_d)
    }

    /// The distances of `x` to group `g`'s codewords, or None once every lane
    /// is known to exceed `bound` (checked after each chunk, as the scalar
    /// search checks its one distance).
    fn group_distances(&self, metric: Metric, x: &[f32], g: usize, bound: f32) -> Option<[f32; LANES]> {
        let words = &self.groups[g * self.dim..(g + 1) * self.dim];
        match metric {
            Metric::L2 => sum_lanes(x, words, bound, |d| d * d),
            Metric::L1 => sum_lanes(x, words, bound, f32::abs),
            Metric::Lmax => max_lanes(x, words, bound),
        }
    }
}

/// Per lane: the sum over chunks of the chunk's sum of `term(x - w)`. Index
/// loops, as in `distance_within` (iterator adapters stayed out-of-line calls
/// in the test build).
#[inline(always)]
fn sum_lanes(x: &[f32], words: &[[f32; LANES]], bound: f32, term: impl Fn(f32) -> f32) -> Option<[f32; LANES]> {
    let (n, mut total, mut start) = (x.len().min(words.len()), [0f32; LANES], 0);
    while start < n {
        let end = (start + CHUNK).min(n);
        let mut chunk = [0f32; LANES];
        for c in start..end {
            let (xv, w) = (x[c], &words[c]);
            for l in 0..LANES {
                chunk[l] += term(xv - w[l]);
            }
        }
        for l in 0..LANES {
            total[l] += chunk[l];
        }
        if all_above(&total, bound) {
            return None;
        }
        start = end;
    }
    Some(total)
}

/// Per lane: the largest |x - w|.
#[inline(always)]
fn max_lanes(x: &[f32], words: &[[f32; LANES]], bound: f32) -> Option<[f32; LANES]> {
    let (n, mut total, mut start) = (x.len().min(words.len()), [0f32; LANES], 0);
    while start < n {
        let end = (start + CHUNK).min(n);
        for c in start..end {
            let (xv, w) = (x[c], &words[c]);
            for l in 0..LANES {
                total[l] = total[l].max((xv - w[l]).abs());
            }
        }
        if all_above(&total, bound) {
            return None;
        }
        start = end;
    }
    Some(total)
}

#[inline(always)]
fn all_above(lanes: &[f32; LANES], bound: f32) -> bool {
    let mut all = true;
    for &t in lanes {
        all &= t > bound;
    }
    all
}

#[cfg(test)]
mod tests {
    use super::super::search::tests::pseudo_random;
    use super::*;

    /// What a search must find: the nearest codeword by the computed
    /// distances (ties: the lowest index) and the smallest distance of any
    /// other, every distance computed in full.
    fn exhaustive(metric: Metric, codebook: &Codebook, x: &[f32]) -> (usize, f32, f32) {
        let d: Vec<f32> = (0..codebook.len()).map(|j| distance(metric, x, codebook.word(j))).collect();
        let best = (0..d.len()).fold(0, |b, j| if d[j] < d[b] { j } else { b });
        let second = (0..d.len()).filter(|&j| j != best).map(|j| d[j]).fold(f32::INFINITY, f32::min);
        (best, d[best], second)
    }

    #[test]
    fn lanes_find_the_codeword_distance_and_bound_of_the_exhaustive_search() {
        for dim in [3, 8, 12, 64] {
            for len in [1, 7, 8, 13, 40] {
                let mut words = pseudo_random(len * dim, (dim * 100 + len) as u64);
                if len > 2 {
                    // Two equal codewords: a tie for whatever is nearest to them.
                    let first = words[..dim].to_vec();
                    words[(len - 1) * dim..].copy_from_slice(&first);
                }
                let codebook = Codebook { dim, words };
                let lanes = CodebookLanes::new(&codebook);
                let queries = pseudo_random(50 * dim, 7);
                for metric in Metric::ALL {
                    for x in queries.chunks(dim).chain([codebook.word(0)]) {
                        let expected = exhaustive(metric, &codebook, x);
                        for hint in [0, len / 2, len - 1] {
                            let lane = lanes.nearest_two(metric, &codebook, x, hint);
                            assert_eq!(
                                (lane.0, lane.1.to_bits(), lane.2.to_bits()),
                                (expected.0, expected.1.to_bits(), expected.2.to_bits()),
                                "{metric:?} dim {dim} len {len} hint {hint}"
                            );
                        }
                    }
                }
            }
        }
    }
}
