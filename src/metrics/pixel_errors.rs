//! Where two images differ: per pixel, the largest absolute channel error (the
//! field the compare command's error map shows).

use super::stats::check_pair;
use super::MetricsError;
use crate::linear_image::LinearImage;

/// Per-pixel `max_c |test - reference|`, row by row from the top.
/// Errors as for [`super::compare`].
pub fn pixel_errors(test: &LinearImage, reference: &LinearImage) -> Result<Vec<f32>, MetricsError> {
    check_pair(test, reference)?;
    Ok(test
        .pixels
        .iter()
        .zip(&reference.pixels)
        .map(|(t, r)| (0..3).map(|c| (t[c] - r[c]).abs()).fold(0.0, f32::max))
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(pixels: Vec<[f32; 3]>) -> LinearImage {
        LinearImage { width: pixels.len() as u32, height: 1, pixels }
    }

    #[test]
    fn each_pixel_holds_its_largest_channel_error() {
        let reference = image(vec![[0.0; 3]; 3]);
        let test = image(vec![[0.0; 3], [0.0, -0.25, 0.1], [0.0, 0.0, 0.5]]);
        assert_eq!(pixel_errors(&test, &reference).unwrap(), vec![0.0, 0.25, 0.5]);
    }

    #[test]
    fn identical_images_have_no_error() {
        let a = image(vec![[0.3; 3]; 4]);
        assert!(pixel_errors(&a, &a).unwrap().iter().all(|&e| e == 0.0));
    }

    #[test]
    fn bad_inputs_are_errors() {
        let a = image(vec![[0.0; 3]; 2]);
        let b = image(vec![[0.0; 3]; 3]);
        assert!(matches!(pixel_errors(&a, &b), Err(MetricsError::SizeMismatch { .. })));
        let nan = image(vec![[f32::NAN, 0.0, 0.0], [0.0; 3]]);
        assert!(matches!(pixel_errors(&nan, &a), Err(MetricsError::NonFinite { .. })));
    }
}
