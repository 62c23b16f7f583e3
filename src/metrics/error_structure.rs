//! The shape of an image's error against its reference, beside its size: stripes
//! (the error's mean varying column to column, or row to row, faster than the
//! image does) and grain (error that changes pixel to pixel). RMSE counts both
//! the same as a smooth bias; these two name the artefacts a reader sees.
//!
//! Both work on the signed error `e = mean_c (test_c - reference_c)`:
//! - stripes along columns: the per-column means of `e`, minus their running
//!   mean over [`STRIPE_WINDOW`] columns, as an RMS over the columns. A smooth
//!   error (a bias, a blurred shadow edge) has smooth column means and scores
//!   near 0; columns alternating in error (a cache texel grid beating against
//!   the pixels) score their amplitude. Rows alike.
//! - grain: `e` minus its 3x3 box mean, as an RMS over the pixels: the error at
//!   the pixel scale.
//!
//! Isotropic noise gives the same column and row stripe figures, so a column
//! figure well above the row one is a stripe pattern along columns.

use super::stats::check_pair;
use super::MetricsError;
use crate::linear_image::LinearImage;
use serde::Serialize;

/// Columns (rows) over which the per-column (per-row) means are smoothed: a
/// stripe narrower than this stands out of its running mean.
pub const STRIPE_WINDOW: usize = 7;

#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ErrorStructure {
    /// RMS over the columns of the column means' departure from their running mean.
    pub column_stripes: f64,
    /// The same over the rows.
    pub row_stripes: f64,
    /// RMS over the pixels of the error's departure from its 3x3 box mean.
    pub grain: f64,
    /// Largest channel value of the reference, to state the figures against.
    pub peak: f64,
}

/// The error structure of `test` against `reference`; errors as for
/// [`super::compare`].
pub fn error_structure(test: &LinearImage, reference: &LinearImage) -> Result<ErrorStructure, MetricsError> {
    check_pair(test, reference)?;
    let (w, h) = (test.width as usize, test.height as usize);
    let e: Vec<f64> = test
        .pixels
        .iter()
        .zip(&reference.pixels)
        .map(|(t, r)| (0..3).map(|c| t[c] as f64 - r[c] as f64).sum::<f64>() / 3.0)
        .collect();
    let peak = reference.pixels.iter().flat_map(|p| p.iter()).fold(0.0f32, |m, &v| m.max(v)) as f64;
    let column_means: Vec<f64> = (0..w).map(|x| (0..h).map(|y| e[y * w + x]).sum::<f64>() / h as f64).collect();
    let row_means: Vec<f64> = (0..h).map(|y| e[y * w..(y + 1) * w].iter().sum::<f64>() / w as f64).collect();
    let mut grain = 0.0;
    for y in 0..h {
        for x in 0..w {
            let (ys, xs) = (centred(y, 1, h), centred(x, 1, w));
            let n = (ys.len() * xs.len()) as f64;
            let sum: f64 = ys.map(|yy| e[yy * w + xs.start..yy * w + xs.end].iter().sum::<f64>()).sum();
            grain += (e[y * w + x] - sum / n).powi(2);
        }
    }
    Ok(ErrorStructure {
        column_stripes: departure_from_running_mean(&column_means),
        row_stripes: departure_from_running_mean(&row_means),
        grain: (grain / (w * h) as f64).sqrt(),
        peak,
    })
}

/// Indices within `radius` of `i` in `0..len`, as many on each side (fewer near
/// the ends), so that the mean of a linear ramp over them is its value at `i`.
fn centred(i: usize, radius: usize, len: usize) -> std::ops::Range<usize> {
    let r = radius.min(i).min(len - 1 - i);
    i - r..i + r + 1
}

/// RMS of `v` minus its running mean over [`STRIPE_WINDOW`] entries.
fn departure_from_running_mean(v: &[f64]) -> f64 {
    let sum: f64 = (0..v.len())
        .map(|i| {
            let window = &v[centred(i, STRIPE_WINDOW / 2, v.len())];
            (v[i] - window.iter().sum::<f64>() / window.len() as f64).powi(2)
        })
        .sum();
    (sum / v.len().max(1) as f64).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(w: u32, h: u32, f: impl Fn(u32, u32) -> f32) -> LinearImage {
        let mut im = LinearImage::new(w, h);
        for y in 0..h {
            for x in 0..w {
                im.set(x, y, [f(x, y); 3]);
            }
        }
        im
    }

    #[test]
    fn stripes_show_along_their_own_axis_and_grain_at_the_pixel_scale() {
        let reference = image(32, 32, |x, y| (x + y) as f32 / 64.0);
        // A smooth bias is neither stripes nor grain.
        let biased = image(32, 32, |x, y| (x + y) as f32 / 64.0 + 0.1 + x as f32 * 1e-3);
        let s = error_structure(&biased, &reference).unwrap();
        assert!(s.column_stripes < 1e-6 && s.row_stripes < 1e-6 && s.grain < 1e-6, "{s:?}");
        // Every fourth column off by 0.1: column stripes, no row stripes.
        let striped = image(32, 32, |x, y| (x + y) as f32 / 64.0 + if x % 4 == 0 { 0.1 } else { 0.0 });
        let s = error_structure(&striped, &reference).unwrap();
        assert!(s.column_stripes > 0.03 && s.row_stripes < 1e-6, "{s:?}");
        let transposed = image(32, 32, |x, y| (x + y) as f32 / 64.0 + if y % 4 == 0 { 0.1 } else { 0.0 });
        let t = error_structure(&transposed, &reference).unwrap();
        assert!((t.row_stripes - s.column_stripes).abs() < 1e-9 && t.column_stripes < 1e-6, "{t:?}");
        // A checkerboard is grain, and no stripe.
        let grainy = image(32, 32, |x, y| (x + y) as f32 / 64.0 + if (x + y) % 2 == 0 { 0.05 } else { -0.05 });
        let g = error_structure(&grainy, &reference).unwrap();
        assert!(g.grain > 0.04 && g.column_stripes < 0.01 && g.row_stripes < 0.01, "{g:?}");
        assert_eq!(g.peak, 62.0 / 64.0);
    }

    #[test]
    fn bad_inputs_are_errors() {
        let a = image(2, 2, |_, _| 0.0);
        let b = image(3, 2, |_, _| 0.0);
        assert!(matches!(error_structure(&a, &b), Err(MetricsError::SizeMismatch { .. })));
    }
}
