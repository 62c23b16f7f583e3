//! Why two images could not be compared.

#[derive(Debug, thiserror::Error)]
pub enum MetricsError {
    #[error(
        "image sizes differ: test is {test_width}x{test_height}, \
         reference is {reference_width}x{reference_height}"
    )]
    SizeMismatch { test_width: u32, test_height: u32, reference_width: u32, reference_height: u32 },
    #[error("{which} image is {width}x{height} but holds {pixels} pixels")]
    Malformed { which: &'static str, width: u32, height: u32, pixels: usize },
    #[error("images have no pixels to compare")]
    Empty,
    /// NaN or infinity: an error rather than a silently meaningless statistic.
    #[error("{which} image has a non-finite value {value:?} at pixel ({x}, {y})")]
    NonFinite { which: &'static str, x: u32, y: u32, value: [f32; 3] },
}
