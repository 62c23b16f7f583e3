//! Point charts stacked in one figure under one title, each panel with its
//! own y axis: one quantity measured on devices whose values differ by orders
//! of magnitude (a GPU's microsecond beside a CPU driver's noise of
//! milliseconds), each readable on its own scale instead of flattened onto
//! the widest one.

use std::path::Path;

use image::RgbImage;
use plotters::coord::Shift;
use plotters::prelude::{DrawingArea, DrawingBackend};

use super::chart::{check_size, Chart};
use super::figure::{render, write, Figure, Target};
use super::frame::fitting_size;
use super::series::Series;
use super::style::text;
use super::xy::XyFigure;
use crate::bench::BenchError;

/// Height of the strip holding the figure's title, pixels.
const TITLE_HEIGHT: u32 = 40;
const TITLE_TEXT: f64 = 20.0;

/// One panel: its chart (title, axis labels, scales, width and height) and
/// the series it shows.
#[derive(Debug, Clone)]
pub struct Panel {
    pub chart: Chart,
    pub series: Vec<Series>,
}

struct PanelsFigure<'a> {
    title: &'a str,
    panels: &'a [Panel],
}

impl PanelsFigure<'_> {
    fn check(&self) -> Result<(), BenchError> {
        if self.panels.is_empty() {
            return Err(BenchError::Chart("a figure of panels needs at least one panel".into()));
        }
        for panel in self.panels {
            panel.chart.check_size()?;
        }
        let (width, height) = self.size();
        check_size(width, height, 1, 1)
    }
}

impl Figure for PanelsFigure<'_> {
    fn size(&self) -> (u32, u32) {
        let width = self.panels.iter().map(|p| p.chart.width).max().unwrap_or(0);
        // Saturating: a stack past the largest side is refused by `check`.
        let height = self.panels.iter().fold(TITLE_HEIGHT, |h, p| h.saturating_add(p.chart.height));
        (width, height)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>, target: Target) -> Result<(), BenchError> {
        let (width, _) = root.dim_in_pixel();
        let (title, mut rest) = root.split_vertically(TITLE_HEIGHT);
        let size = fitting_size(self.title, TITLE_TEXT, width.saturating_sub(20));
        title.draw_text(self.title, &text(size), (10, 10))?;
        for panel in self.panels {
            let (area, below) = rest.split_vertically(panel.chart.height);
            XyFigure::points(&panel.chart, &panel.series).draw(&area, target)?;
            rest = below;
        }
        Ok(())
    }
}

/// Draws `panels` one under the other below `title`, each series' points as
/// markers with their intervals on the panel's own axes, and writes the
/// figure as PNG at `path` and SVG beside it.
pub fn plot_point_panels(path: impl AsRef<Path>, title: &str, panels: &[Panel]) -> Result<(), BenchError> {
    let figure = PanelsFigure { title, panels };
    figure.check()?;
    write(path.as_ref(), &figure)
}

/// The figure of [`plot_point_panels`] as an image.
pub fn render_point_panels(title: &str, panels: &[Panel]) -> Result<RgbImage, BenchError> {
    let figure = PanelsFigure { title, panels };
    figure.check()?;
    render(&figure)
}
