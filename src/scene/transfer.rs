//! 1D piecewise-linear RGBA transfer functions and their baked lookup table.
//!
//! Opacity convention (docs/optical-model.md): a control point's alpha is the
//! opacity of a slab one voxel thick (the reference length). The lookup table
//! stores instead the optical depth per voxel, `sigma = -ln(1 - alpha)`, which
//! interpolates and scales with the step exactly: a step of `d` voxels has opacity
//! `1 - exp(-sigma * d)` (opacity correction for the step size).

use serde::{Deserialize, Serialize};

/// Alpha is clamped below 1 so that the optical depth stays finite.
pub const MAX_ALPHA: f32 = 0.999_999;

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ControlPoint {
    /// Normalized scalar in [0, 1].
    pub value: f32,
    /// Colour (linear RGB, the medium's albedo/emission colour) and opacity per voxel.
    pub rgba: [f32; 4],
}

#[derive(Clone, Debug, PartialEq)]
pub struct TransferFunction {
    /// Sorted by `value`; at least one point.
    pub points: Vec<ControlPoint>,
}

/// Why a list of control points is not a valid transfer function.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TransferError {
    #[error("a transfer function needs at least one control point")]
    Empty,
    #[error("control point {index}: value and rgba must be finite and in [0, 1]")]
    OutOfRange { index: usize },
    #[error(
        "control point {index}: value {value} is below the previous point's {previous}; points must be sorted by value"
    )]
    Unsorted { index: usize, value: f32, previous: f32 },
}

impl TransferFunction {
    /// Checked constructor: at least one point, every component finite and in
    /// [0, 1], values non-decreasing (equal neighbours make a step).
    pub fn new(points: Vec<ControlPoint>) -> Result<TransferFunction, TransferError> {
        if points.is_empty() {
            return Err(TransferError::Empty);
        }
        for (index, p) in points.iter().enumerate() {
            let in_unit = |x: f32| (0.0..=1.0).contains(&x);
            if !in_unit(p.value) || !p.rgba.iter().all(|&c| in_unit(c)) {
                return Err(TransferError::OutOfRange { index });
            }
            if index > 0 && p.value < points[index - 1].value {
                return Err(TransferError::Unsorted { index, value: p.value, previous: points[index - 1].value });
            }
        }
        Ok(TransferFunction { points })
    }

    /// Piecewise-linear evaluation, constant beyond the first and last points.
    pub fn eval(&self, s: f32) -> [f32; 4] {
        let p = &self.points;
        if p.is_empty() {
            return [0.0; 4];
        }
        if s <= p[0].value {
            return p[0].rgba;
        }
        for w in p.windows(2) {
            if s <= w[1].value {
                let span = w[1].value - w[0].value;
                let t = if span > 0.0 { (s - w[0].value) / span } else { 1.0 };
                let mut out = [0.0; 4];
                for (c, o) in out.iter_mut().enumerate() {
                    *o = w[0].rgba[c] + (w[1].rgba[c] - w[0].rgba[c]) * t;
                }
                return out;
            }
        }
        p[p.len() - 1].rgba
    }

    pub fn bake(&self, entries: usize) -> TransferLut {
        let n = entries.max(2);
        let texels = (0..n)
            .map(|i| {
                let s = (i as f32 + 0.5) / n as f32;
                let [r, g, b, a] = self.eval(s);
                let a = a.clamp(0.0, MAX_ALPHA);
                [r, g, b, -(1.0 - a).ln()]
            })
            .collect();
        TransferLut { texels }
    }
}

/// Baked table: `texels[i]` is (r, g, b, sigma) at s = (i + 0.5) / n. Uploaded as a
/// 1D RGBA32F image with a linear sampler; [`TransferLut::sample`] reproduces that
/// filtering on the CPU in f64.
#[derive(Clone, Debug, PartialEq)]
pub struct TransferLut {
    pub texels: Vec<[f32; 4]>,
}

impl TransferLut {
    pub const DEFAULT_SIZE: usize = 1024;

    pub fn sample(&self, s: f64) -> [f64; 4] {
        let n = self.texels.len();
        let t = (s * n as f64 - 0.5).clamp(0.0, (n - 1) as f64);
        let i0 = t.floor() as usize;
        let i1 = (i0 + 1).min(n - 1);
        let f = t - i0 as f64;
        let mut out = [0.0; 4];
        for (c, o) in out.iter_mut().enumerate() {
            *o = self.texels[i0][c] as f64 * (1.0 - f) + self.texels[i1][c] as f64 * f;
        }
        out
    }

    /// True where the transfer function has no extinction at all: such samples
    /// neither emit nor scatter, so renderers may skip their shadow rays.
    pub fn is_empty_at(&self, s: f64) -> bool {
        self.sample(s)[3] <= 0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(value: f32, a: f32) -> ControlPoint {
        ControlPoint { value, rgba: [1.0, 0.5, 0.0, a] }
    }

    #[test]
    fn new_accepts_sorted_points_with_steps() {
        let tf = TransferFunction::new(vec![point(0.0, 0.0), point(0.5, 0.0), point(0.5, 1.0), point(1.0, 1.0)]);
        assert!(tf.is_ok());
    }

    #[test]
    fn new_rejects_empty_unsorted_and_out_of_range_points() {
        assert_eq!(TransferFunction::new(vec![]), Err(TransferError::Empty));
        assert_eq!(
            TransferFunction::new(vec![point(0.6, 0.0), point(0.4, 0.0)]),
            Err(TransferError::Unsorted { index: 1, value: 0.4, previous: 0.6 })
        );
        assert_eq!(TransferFunction::new(vec![point(1.5, 0.0)]), Err(TransferError::OutOfRange { index: 0 }));
        assert_eq!(TransferFunction::new(vec![point(0.0, -0.1)]), Err(TransferError::OutOfRange { index: 0 }));
        assert_eq!(TransferFunction::new(vec![point(f32::NAN, 0.0)]), Err(TransferError::OutOfRange { index: 0 }));
    }
}
