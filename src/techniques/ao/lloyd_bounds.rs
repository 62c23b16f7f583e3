//! Hamerly's bounds for LBG's Lloyd iterations (G. Hamerly, "Making k-means
//! even faster", SDM 2010): every training vector keeps a lower bound on its
//! distance to every codeword but its own. When the codewords move, the bound
//! falls by the largest distance any other codeword moved (triangle
//! inequality); while the vector's distance to its own codeword stays below the
//! bound, no other codeword can be as near, and the search over all of them is
//! skipped. Late in a codebook size few vectors change cluster, so most
//! searches go.
//!
//! The skip is exact for the distances as computed: a margin covers the f32
//! rounding of a computed distance, so a kept codeword is the unique nearest
//! by the computed distances too; any vector the margin cannot decide is
//! searched. L2 distances are squared; the bounds hold Euclidean lengths, where
//! the triangle inequality holds (L1 and Lmax are metrics as they are).

use super::quantize::Codebook;
use super::settings::Metric;

/// Relative margin for rounding in `dim` components: a computed distance is
/// within (dim + 3) u of the exact one (u = 2^-24: the difference, its square
/// or absolute value and each addition of non-negative terms round once);
/// four times that, and no less than 1e-4.
fn margin(dim: usize) -> f64 {
    (4.0 * (dim as f64 + 3.0) * f64::from(f32::EPSILON) / 2.0).max(1e-4)
}

/// A distance in the units where the triangle inequality holds.
fn length(metric: Metric, d: f32) -> f64 {
    match metric {
        Metric::L2 => (d as f64).sqrt(),
        Metric::L1 | Metric::Lmax => d as f64,
    }
}

/// Per training vector: no codeword other than its own is nearer than this.
pub(super) struct LowerBounds {
    lower: Vec<f64>,
    margin: f64,
}

impl LowerBounds {
    /// `n` vectors of `dim` components, nothing known yet.
    pub fn unknown(n: usize, dim: usize) -> LowerBounds {
        LowerBounds { lower: vec![0.0; n], margin: margin(dim) }
    }

    /// The bound a search leaves: `second` is no larger than the computed
    /// distance to any codeword but the nearest.
    pub fn from_second(metric: Metric, second: f32, dim: usize) -> f64 {
        length(metric, second) * (1.0 - margin(dim))
    }

    pub fn get(&self, i: usize) -> f64 {
        self.lower[i]
    }

    pub fn set(&mut self, i: usize, bound: f64) {
        self.lower[i] = bound;
    }

    /// Whether vector `i`, at computed distance `d` from its own codeword, has
    /// no other codeword as near.
    pub fn keeps(&self, i: usize, metric: Metric, d: f32) -> bool {
        length(metric, d) < self.lower[i] * (1.0 - self.margin)
    }

    /// The codewords moved by `drift` (each codeword's, [`drift`]): every
    /// bound falls by the largest move of a codeword other than its vector's.
    pub fn codewords_moved(&mut self, assignment: &[u32], drift: &[f64]) {
        let (mut first, mut first_at, mut second) = (0.0f64, usize::MAX, 0.0f64);
        for (j, &d) in drift.iter().enumerate() {
            if d > first {
                (first, first_at, second) = (d, j, first);
            } else if d > second {
                second = d;
            }
        }
        for (bound, &own) in self.lower.iter_mut().zip(assignment) {
            let others = if own as usize == first_at { second } else { first };
            *bound -= others * (1.0 + self.margin);
        }
    }
}

/// How far each codeword moved from `before` to `after` (codebooks of one
/// length), in the units of [`LowerBounds`], in f64.
pub(super) fn drift(metric: Metric, before: &Codebook, after: &Codebook) -> Vec<f64> {
    (0..after.len())
        .map(|j| {
            let moves = before.word(j).iter().zip(after.word(j)).map(|(&a, &b)| (a as f64 - b as f64).abs());
            match metric {
                Metric::L2 => moves.map(|m| m * m).sum::<f64>().sqrt(),
                Metric::L1 => moves.sum(),
                Metric::Lmax => moves.fold(0.0, f64::max),
            }
        })
        .collect()
}
