//! RMSE, maximum absolute error and PSNR between two linear-RGB images.

use serde::Serialize;

use super::MetricsError;
use crate::linear_image::LinearImage;

/// Error of a test image against a reference, over all channels of all pixels.
///
/// `psnr = 20 log10(peak / rmse)` in dB with `peak` the largest channel value of
/// the reference (HDR images have no fixed white): `+inf` when `rmse == 0`,
/// `-inf` when the reference is black everywhere but the test is not.
/// serde_json writes infinities as `null`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ErrorStats {
    pub rmse: f64,
    pub max_abs: f64,
    pub psnr: f64,
}

/// Compares `test` with `reference`. Non-finite values in either image are an
/// error ([`MetricsError::NonFinite`]), never folded into the statistics.
pub fn compare(test: &LinearImage, reference: &LinearImage) -> Result<ErrorStats, MetricsError> {
    check_pair(test, reference)?;
    let mut sum_sq = 0.0f64;
    let mut max_abs = 0.0f64;
    let mut peak = 0.0f64;
    for (t, r) in test.pixels.iter().zip(&reference.pixels) {
        for c in 0..3 {
            let e = (t[c] as f64 - r[c] as f64).abs();
            sum_sq += e * e;
            max_abs = max_abs.max(e);
            peak = peak.max(r[c] as f64);
        }
    }
    let rmse = (sum_sq / (3 * test.pixels.len()) as f64).sqrt();
    let psnr = if rmse == 0.0 { f64::INFINITY } else { 20.0 * (peak / rmse).log10() };
    Ok(ErrorStats { rmse, max_abs, psnr })
}

/// Same size, well formed, not empty, all values finite.
pub(super) fn check_pair(test: &LinearImage, reference: &LinearImage) -> Result<(), MetricsError> {
    if (test.width, test.height) != (reference.width, reference.height) {
        return Err(MetricsError::SizeMismatch {
            test_width: test.width,
            test_height: test.height,
            reference_width: reference.width,
            reference_height: reference.height,
        });
    }
    for (which, image) in [("test", test), ("reference", reference)] {
        check_image(which, image)?;
    }
    if test.pixels.is_empty() {
        return Err(MetricsError::Empty);
    }
    Ok(())
}

fn check_image(which: &'static str, image: &LinearImage) -> Result<(), MetricsError> {
    if image.pixels.len() != image.width as usize * image.height as usize {
        return Err(MetricsError::Malformed {
            which,
            width: image.width,
            height: image.height,
            pixels: image.pixels.len(),
        });
    }
    match image.pixels.iter().position(|p| p.iter().any(|c| !c.is_finite())) {
        None => Ok(()),
        Some(i) => Err(MetricsError::NonFinite {
            which,
            x: (i % image.width as usize) as u32,
            y: (i / image.width as usize) as u32,
            value: image.pixels[i],
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(width: u32, height: u32, pixels: Vec<[f32; 3]>) -> LinearImage {
        LinearImage { width, height, pixels }
    }

    #[test]
    fn hand_computed_two_pixels() {
        let reference = image(2, 1, vec![[1.0, 0.5, 0.0], [2.0, 0.0, 0.25]]);
        let test = image(2, 1, vec![[1.0, 0.5, 0.5], [1.0, 0.0, 0.25]]);
        // Errors: 0, 0, 0.5, 1, 0, 0 -> mean square (0.25 + 1) / 6.
        let s = compare(&test, &reference).unwrap();
        let rmse = (1.25f64 / 6.0).sqrt();
        assert!((s.rmse - rmse).abs() < 1e-15);
        assert_eq!(s.max_abs, 1.0);
        // Peak is the reference's largest channel, 2.
        assert!((s.psnr - 20.0 * (2.0 / rmse).log10()).abs() < 1e-12);
    }

    #[test]
    fn uniform_offset_gives_that_offset() {
        let reference = image(3, 2, vec![[0.5, 1.0, 0.25]; 6]);
        let test = image(3, 2, vec![[0.75, 1.25, 0.5]; 6]);
        let s = compare(&test, &reference).unwrap();
        assert_eq!(s.rmse, 0.25);
        assert_eq!(s.max_abs, 0.25);
        // peak 1, rmse 1/4: 20 log10(4).
        assert!((s.psnr - 12.041_199_826_559_248).abs() < 1e-12);
    }

    #[test]
    fn identical_images_have_zero_error_and_infinite_psnr() {
        let a = image(2, 2, vec![[0.1, 0.2, 0.3]; 4]);
        let s = compare(&a, &a.clone()).unwrap();
        assert_eq!(s.rmse, 0.0);
        assert_eq!(s.max_abs, 0.0);
        assert_eq!(s.psnr, f64::INFINITY);
    }

    #[test]
    fn black_reference_with_error_has_minus_infinite_psnr() {
        let reference = image(1, 1, vec![[0.0; 3]]);
        let test = image(1, 1, vec![[0.0, 0.0, 0.5]]);
        assert_eq!(compare(&test, &reference).unwrap().psnr, f64::NEG_INFINITY);
    }

    #[test]
    fn size_mismatch_is_an_error() {
        let a = image(2, 1, vec![[0.0; 3]; 2]);
        let b = image(1, 2, vec![[0.0; 3]; 2]);
        assert!(matches!(compare(&a, &b), Err(MetricsError::SizeMismatch { .. })));
    }

    #[test]
    fn non_finite_values_are_reported_with_their_pixel() {
        let good = image(2, 2, vec![[0.0; 3]; 4]);
        let mut bad = good.clone();
        bad.pixels[3] = [0.0, f32::NAN, 0.0];
        match compare(&bad, &good) {
            Err(MetricsError::NonFinite { which: "test", x: 1, y: 1, .. }) => {}
            other => panic!("{other:?}"),
        }
        bad.pixels[3] = [f32::INFINITY, 0.0, 0.0];
        assert!(matches!(compare(&good, &bad), Err(MetricsError::NonFinite { which: "reference", .. })));
    }

    #[test]
    fn malformed_and_empty_images_are_errors() {
        let short = image(2, 2, vec![[0.0; 3]; 3]);
        let ok = image(2, 2, vec![[0.0; 3]; 4]);
        assert!(matches!(compare(&short, &ok), Err(MetricsError::Malformed { .. })));
        let empty = image(0, 0, vec![]);
        assert!(matches!(compare(&empty, &empty), Err(MetricsError::Empty)));
    }

    #[test]
    fn stats_serialize_to_json() {
        let s = ErrorStats { rmse: 0.5, max_abs: 1.0, psnr: f64::INFINITY };
        let json = serde_json::to_string(&s).unwrap();
        assert_eq!(json, r#"{"rmse":0.5,"max_abs":1.0,"psnr":null}"#);
    }
}
