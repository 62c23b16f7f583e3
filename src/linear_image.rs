//! A linear-RGB float image: what every renderer returns and what the metrics compare.

use std::path::Path;

#[derive(Clone, Debug, PartialEq)]
pub struct LinearImage {
    pub width: u32,
    pub height: u32,
    /// Row-major, y down, linear RGB.
    pub pixels: Vec<[f32; 3]>,
}

#[derive(Debug, thiserror::Error)]
pub enum ImageWriteError {
    #[error("cannot write image {path}: {source}")]
    Write { path: String, source: image::ImageError },
}

impl LinearImage {
    pub fn new(width: u32, height: u32) -> Self {
        LinearImage { width, height, pixels: vec![[0.0; 3]; width as usize * height as usize] }
    }

    pub fn get(&self, x: u32, y: u32) -> [f32; 3] {
        self.pixels[y as usize * self.width as usize + x as usize]
    }

    pub fn set(&mut self, x: u32, y: u32, rgb: [f32; 3]) {
        self.pixels[y as usize * self.width as usize + x as usize] = rgb;
    }

    pub fn all_finite(&self) -> bool {
        self.pixels.iter().all(|p| p.iter().all(|c| c.is_finite()))
    }

    /// Largest channel value in the image.
    pub fn max_value(&self) -> f32 {
        self.pixels.iter().flat_map(|p| p.iter().copied()).fold(0.0, f32::max)
    }

    /// 8-bit sRGB, values clamped to [0, 1] (no tone mapping: the scene's light
    /// intensities decide the exposure).
    pub fn to_srgb8(&self) -> image::RgbImage {
        image::RgbImage::from_fn(self.width, self.height, |x, y| {
            let p = self.get(x, y);
            image::Rgb(p.map(|c| (linear_to_srgb(c) * 255.0 + 0.5) as u8))
        })
    }

    pub fn save_png(&self, path: &Path) -> Result<(), ImageWriteError> {
        self.to_srgb8().save(path).map_err(|source| ImageWriteError::Write { path: path.display().to_string(), source })
    }
}

pub fn linear_to_srgb(c: f32) -> f32 {
    let c = if c.is_finite() { c.clamp(0.0, 1.0) } else { 0.0 };
    if c <= 0.003_130_8 {
        c * 12.92
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}
