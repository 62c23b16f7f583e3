//! Nearest-codeword search for the assignment of every voxel: exact, and fast
//! when the search starts near the answer, which spatial coherence gives
//! (a voxel's histogram is close to its neighbour's).
//!
//! L2 (Euclidean), L1 and Lmax are metrics, so by the triangle inequality a
//! codeword c_j can only beat the best distance `best` found so far if
//! d(c_h, c_j) < best + d(x, c_h), c_h the codeword the search started at. Each
//! codeword keeps all others sorted by distance to it; the search walks the
//! start's list and stops at the first one beyond that bound. A small relative
//! slack on the bound absorbs float rounding, so the result is exactly
//! [`Codebook::nearest`]'s (ties to the lowest index). The same inequality
//! skips the codewords nearer to c_h than d(x, c_h) - best.

use super::parallel::for_each_chunk;
use super::quantize::{distance, distance_within, Codebook};
use super::settings::Metric;

/// Relative slack on the pruning bound (float rounding of the distances).
pub const SLACK: f32 = 1e-4;

pub struct CodebookSearch<'c> {
    codebook: &'c Codebook,
    metric: Metric,
    /// Row h: all codewords by ascending distance to codeword h.
    order: Vec<u16>,
    /// Row h: those distances (true metric, L2 not squared).
    distances: Vec<f32>,
}

/// The true metric from a [`distance`] value (L2 is squared there).
fn true_distance(metric: Metric, raw: f32) -> f32 {
    match metric {
        Metric::L2 => raw.sqrt(),
        Metric::L1 | Metric::Lmax => raw,
    }
}

impl<'c> CodebookSearch<'c> {
    /// Sorted distance lists of every codeword (at most 65,536), over all cores.
    pub fn new(codebook: &'c Codebook, metric: Metric) -> CodebookSearch<'c> {
        let n = codebook.len();
        assert!(n <= 1 << 16, "cluster ids are 16-bit");
        let mut order = vec![0u16; n * n];
        let mut distances = vec![0f32; n * n];
        for_each_chunk(
            n,
            || (),
            |_, h| {
                let mut row: Vec<(f32, u16)> = (0..n)
                    .map(|j| (true_distance(metric, distance(metric, codebook.word(h), codebook.word(j))), j as u16))
                    .collect();
                row.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                row
            },
            |h, row, _| {
                for (k, (d, j)) in row.into_iter().enumerate() {
                    order[h * n + k] = j;
                    distances[h * n + k] = d;
                }
            },
        );
        CodebookSearch { codebook, metric, order, distances }
    }

    /// Row h: all codewords by ascending distance to codeword h (the GPU
    /// search walks the same lists).
    pub fn order(&self) -> &[u16] {
        &self.order
    }

    /// Row h: the distances of [`Self::order`] (true metric).
    pub fn order_distances(&self) -> &[f32] {
        &self.distances
    }

    /// As [`Codebook::nearest`] (same index, same distance value), searching
    /// only the codewords that can win.
    pub fn nearest(&self, x: &[f32], hint: usize) -> (usize, f32) {
        let (codebook, metric) = (self.codebook, self.metric);
        let n = codebook.len();
        let h = hint.min(n - 1);
        let mut best = h;
        let mut best_raw = distance(metric, x, codebook.word(h));
        let to_hint = true_distance(metric, best_raw);
        let row = h * n..(h + 1) * n;
        for k in row {
            let (j, apart) = (self.order[k], self.distances[k]);
            let best_true = true_distance(metric, best_raw);
            // d(x, c_j) >= |d(c_h, c_j) - d(x, c_h)|: only the shell
            // to_hint - best < apart < to_hint + best can hold a better codeword.
            if apart > (best_true + to_hint) * (1.0 + SLACK) + f32::MIN_POSITIVE {
                break;
            }
            let j = j as usize;
            if j == best || apart < (to_hint - best_true) * (1.0 - SLACK) - f32::MIN_POSITIVE {
                continue;
            }
            let d = distance_within(metric, x, codebook.word(j), best_raw);
            if d < best_raw || (d == best_raw && j < best) {
                best = j;
                best_raw = d;
            }
        }
        (best, best_raw)
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// Deterministic values in [0, 1) (also the codebook lanes' test data).
    pub(in crate::techniques::ao) fn pseudo_random(n: usize, seed: u64) -> Vec<f32> {
        let mut state = seed;
        (0..n)
            .map(|_| {
                state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                // Coarse values, so that exact ties happen.
                ((state >> 40) % 16) as f32 / 16.0
            })
            .collect()
    }

    #[test]
    fn the_pruned_search_equals_the_full_search_for_every_metric_and_hint() {
        let dim = 6;
        let codebook = Codebook { dim, words: pseudo_random(64 * dim, 1) };
        let queries = pseudo_random(300 * dim, 2);
        for metric in Metric::ALL {
            let search = CodebookSearch::new(&codebook, metric);
            for (i, q) in queries.chunks(dim).enumerate() {
                for hint in [0, i % 64, 63] {
                    assert_eq!(search.nearest(q, hint), codebook.nearest(metric, q, hint), "{metric:?} query {i}");
                }
            }
        }
    }
}
