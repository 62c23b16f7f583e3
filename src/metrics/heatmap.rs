//! Where two images differ: per-pixel largest absolute channel error as a
//! false-colour image.

use std::path::Path;

use super::colormap::inferno;
use super::stats::check_pair;
use super::MetricsError;
use crate::linear_image::LinearImage;

/// Per-pixel `max_c |test - reference|` divided by `scale` (default: the largest
/// such error in the image, so the worst pixel is the brightest) and mapped
/// through [`inferno`]. Identical images are black-purple (t = 0) everywhere.
/// Errors as for [`super::compare`], plus a scale that is not finite and above 0.
pub fn error_heatmap(
    test: &LinearImage,
    reference: &LinearImage,
    scale: Option<f32>,
) -> Result<image::RgbImage, MetricsError> {
    check_pair(test, reference)?;
    let errors: Vec<f32> = test
        .pixels
        .iter()
        .zip(&reference.pixels)
        .map(|(t, r)| (0..3).map(|c| (t[c] - r[c]).abs()).fold(0.0, f32::max))
        .collect();
    let scale = match scale {
        Some(s) if s.is_finite() && s > 0.0 => s,
        Some(s) => return Err(MetricsError::InvalidScale(s)),
        None => errors.iter().copied().fold(0.0, f32::max),
    };
    // A zero default scale means no error anywhere: every pixel maps to t = 0.
    let inv = if scale > 0.0 { 1.0 / scale } else { 0.0 };
    let width = test.width as usize;
    Ok(image::RgbImage::from_fn(test.width, test.height, |x, y| {
        let e = errors[y as usize * width + x as usize];
        image::Rgb(inferno(e * inv))
    }))
}

/// Writes a heatmap as PNG.
pub fn save_heatmap(heatmap: &image::RgbImage, path: &Path) -> Result<(), MetricsError> {
    heatmap.save(path).map_err(|source| MetricsError::Write { path: path.display().to_string(), source })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(pixels: Vec<[f32; 3]>) -> LinearImage {
        LinearImage { width: pixels.len() as u32, height: 1, pixels }
    }

    #[test]
    fn worst_pixel_is_brightest_by_default() {
        let reference = image(vec![[0.0; 3]; 3]);
        let test = image(vec![[0.0; 3], [0.0, -0.25, 0.1], [0.0, 0.0, 0.5]]);
        let map = error_heatmap(&test, &reference, None).unwrap();
        assert_eq!(map.get_pixel(0, 0).0, inferno(0.0));
        assert_eq!(map.get_pixel(1, 0).0, inferno(0.5));
        assert_eq!(map.get_pixel(2, 0).0, inferno(1.0));
    }

    #[test]
    fn explicit_scale_saturates() {
        let reference = image(vec![[1.0; 3]; 2]);
        let test = image(vec![[1.0, 0.75, 1.0], [3.0, 1.0, 1.0]]);
        let map = error_heatmap(&test, &reference, Some(0.5)).unwrap();
        assert_eq!(map.get_pixel(0, 0).0, inferno(0.5));
        assert_eq!(map.get_pixel(1, 0).0, inferno(1.0));
    }

    #[test]
    fn identical_images_map_to_the_low_end() {
        let a = image(vec![[0.3; 3]; 4]);
        let map = error_heatmap(&a, &a, None).unwrap();
        assert!(map.pixels().all(|p| p.0 == inferno(0.0)));
    }

    #[test]
    fn bad_inputs_are_errors() {
        let a = image(vec![[0.0; 3]; 2]);
        let b = image(vec![[0.0; 3]; 3]);
        assert!(matches!(error_heatmap(&a, &b, None), Err(MetricsError::SizeMismatch { .. })));
        for s in [0.0, -1.0, f32::NAN, f32::INFINITY] {
            assert!(matches!(error_heatmap(&a, &a, Some(s)), Err(MetricsError::InvalidScale(_))));
        }
        let nan = image(vec![[f32::NAN, 0.0, 0.0], [0.0; 3]]);
        assert!(matches!(error_heatmap(&nan, &a, None), Err(MetricsError::NonFinite { .. })));
    }

    #[test]
    fn saves_a_png_and_names_the_path_on_failure() {
        let a = image(vec![[0.0; 3]; 2]);
        let map = error_heatmap(&a, &a, None).unwrap();
        let dir = std::env::temp_dir().join(format!("sweeplab-heatmap-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("map.png");
        save_heatmap(&map, &path).unwrap();
        assert_eq!(image::open(&path).unwrap().to_rgb8(), map);
        std::fs::remove_dir_all(&dir).unwrap();
        let bad = Path::new("/nonexistent-dir-for-sweeplab/map.png");
        let err = save_heatmap(&map, bad).unwrap_err();
        assert!(err.to_string().contains("/nonexistent-dir-for-sweeplab/map.png"));
    }
}
