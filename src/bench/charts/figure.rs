//! Drawing a chart once for each backend: a bitmap (PNG) and a vector (SVG)
//! file side by side, or an image in memory for tests.

use std::path::{Path, PathBuf};

use image::{ImageFormat, RgbImage};
use plotters::coord::Shift;
use plotters::prelude::{BitMapBackend, DrawingArea, DrawingBackend, IntoDrawingArea, SVGBackend};

use super::style::{ensure_font, text, BACKGROUND};

/// Height of the caption strip under a figure, pixels.
pub(super) const CAPTION_HEIGHT: u32 = 22;
/// Text size of the caption.
pub(super) const CAPTION_TEXT: f64 = 12.0;

/// Draws `figure` on `root`, above its caption where it has one.
fn draw_with_caption<DB: DrawingBackend>(
    figure: &impl Figure,
    root: &DrawingArea<DB, Shift>,
    target: Target,
) -> Result<(), BenchError> {
    match figure.caption() {
        Some(caption) => {
            let (_, height) = figure.size();
            let (main, foot) = root.split_vertically(height.saturating_sub(CAPTION_HEIGHT));
            foot.draw_text(caption, &text(CAPTION_TEXT), (8, 4))?;
            figure.draw(&main, target)
        }
        None => figure.draw(root, target),
    }
}
use crate::bench::BenchError;

/// Which backend a figure is drawn for (a vector file keeps dense data coarser).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Target {
    Bitmap,
    Vector,
}

pub(super) trait Figure {
    fn size(&self) -> (u32, u32);
    /// A line of small text under the figure.
    fn caption(&self) -> Option<&str> {
        None
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>, target: Target) -> Result<(), BenchError>;
}

pub(super) fn render(figure: &impl Figure) -> Result<RgbImage, BenchError> {
    ensure_font();
    let (width, height) = figure.size();
    let mut buffer = vec![255u8; width as usize * height as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, (width, height)).into_drawing_area();
        root.fill(&BACKGROUND)?;
        draw_with_caption(figure, &root, Target::Bitmap)?;
        root.present()?;
    }
    RgbImage::from_raw(width, height, buffer).ok_or_else(|| BenchError::Chart("bitmap buffer size".into()))
}

pub(super) fn render_svg(figure: &impl Figure) -> Result<String, BenchError> {
    ensure_font();
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, figure.size()).into_drawing_area();
        root.fill(&BACKGROUND)?;
        draw_with_caption(figure, &root, Target::Vector)?;
        root.present()?;
    }
    Ok(svg)
}

/// The SVG beside a chart's PNG: the same path with `.svg`.
pub fn svg_path(png: &Path) -> PathBuf {
    png.with_extension("svg")
}

/// Writes `path` as PNG and the same chart beside it as SVG.
pub(super) fn write(path: &Path, figure: &impl Figure) -> Result<(), BenchError> {
    let image = render(figure)?;
    image
        .save_with_format(path, ImageFormat::Png)
        .map_err(|source| BenchError::Png { path: path.to_owned(), source })?;
    let svg = svg_path(path);
    std::fs::write(&svg, render_svg(figure)?).map_err(|source| BenchError::Write { path: svg, source })
}
