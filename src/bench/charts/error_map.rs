//! A per-pixel error field as a false-colour heat map (inferno) with pixel
//! axes and a colour scale in error units. A vector file keeps the field
//! coarser (each cell the worst error of its block), so it stays small.

use std::path::Path;

use image::RgbImage;
use plotters::coord::Shift;
use plotters::element::Rectangle;
use plotters::prelude::{ChartBuilder, DrawingArea, DrawingBackend};
use plotters::style::Color;

use super::figure::{render, write, Figure, Target};
use super::frame::fitting_size;
use super::scale::{tick_label, AxisScale, ScaledAxis};
use super::style::{rgb, text, text_size, FRAME};
use crate::bench::BenchError;
use crate::metrics::colormap::inferno;

const TEXT: f64 = 15.0;
const BITMAP_CELLS: u32 = 768;
const VECTOR_CELLS: u32 = 96;
const BAR_WIDTH: u32 = 170;

/// `errors[y * width + x]`, row 0 at the top, all finite and at least 0.
#[derive(Debug, Clone, PartialEq)]
pub struct ErrorMap {
    pub title: String,
    pub width: u32,
    pub height: u32,
    pub errors: Vec<f32>,
}

/// Draws the error map and writes it as PNG at `path` and SVG beside it.
pub fn plot_error_map(path: impl AsRef<Path>, map: &ErrorMap) -> Result<(), BenchError> {
    write(path.as_ref(), &ErrorFigure::of(map)?)
}

/// The colour scale runs from 0 to the largest error (the worst pixel is the brightest).
pub fn render_error_map(map: &ErrorMap) -> Result<RgbImage, BenchError> {
    render(&ErrorFigure::of(map)?)
}

struct ErrorFigure<'a> {
    map: &'a ErrorMap,
    largest: f32,
    plot: (u32, u32),
}

impl<'a> ErrorFigure<'a> {
    fn of(map: &'a ErrorMap) -> Result<Self, BenchError> {
        if map.width == 0 || map.height == 0 || map.errors.len() != map.width as usize * map.height as usize {
            return Err(BenchError::Chart(format!(
                "an error map of {}x{} pixels needs {} errors, got {}",
                map.width,
                map.height,
                map.width as usize * map.height as usize,
                map.errors.len()
            )));
        }
        let largest = map.errors.iter().copied().filter(|e| e.is_finite()).fold(0.0, f32::max);
        // The longer side drawn at 384 to 768 pixels, whole pixels per image pixel.
        let longest = map.width.max(map.height);
        let zoom = (384 / longest).max(1) as f64;
        let shrink = (longest as f64 / BITMAP_CELLS as f64).max(1.0);
        let plot = ((map.width as f64 * zoom / shrink) as u32, (map.height as f64 * zoom / shrink) as u32);
        Ok(ErrorFigure { map, largest, plot })
    }

    /// Cells of `block` x `block` pixels, each the largest error in it.
    fn cells(&self, block: u32) -> Vec<(u32, u32, f32)> {
        let (w, h) = (self.map.width, self.map.height);
        let mut cells = Vec::new();
        for y0 in (0..h).step_by(block as usize) {
            for x0 in (0..w).step_by(block as usize) {
                let mut worst = 0.0f32;
                for y in y0..(y0 + block).min(h) {
                    for x in x0..(x0 + block).min(w) {
                        worst = worst.max(self.map.errors[(y * w + x) as usize]);
                    }
                }
                cells.push((x0, y0, worst));
            }
        }
        cells
    }
}

impl Figure for ErrorFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (self.plot.0 + 110 + BAR_WIDTH, self.plot.1 + 120)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>, target: Target) -> Result<(), BenchError> {
        let (w, h) = (self.map.width, self.map.height);
        let (width, _) = self.size();
        let (image_area, bar_area) = root.split_horizontally(width - BAR_WIDTH);
        let title_size = fitting_size(&self.map.title, TEXT * 1.2, width - 20);
        let x_axis = ScaledAxis::between(AxisScale::Linear, 0.0, f64::from(w));
        let y_axis = ScaledAxis::between(AxisScale::Linear, 0.0, f64::from(h));
        let mut builder = ChartBuilder::on(&image_area);
        builder.caption(&self.map.title, text(title_size)).margin(10).x_label_area_size(45).y_label_area_size(60);
        let mut context = builder.build_cartesian_2d(x_axis, y_axis)?;
        let column = |v: &f64| tick_label(*v);
        let row = |v: &f64| tick_label(f64::from(h) - *v);
        context
            .configure_mesh()
            .disable_mesh()
            .x_desc("x (pixels)")
            .y_desc("y (pixels from the top)")
            .x_label_formatter(&column)
            .y_label_formatter(&row)
            .label_style(text(TEXT))
            .axis_desc_style(text(TEXT))
            .axis_style(FRAME)
            .draw()?;
        let limit = if target == Target::Vector { VECTOR_CELLS } else { BITMAP_CELLS };
        let block = w.max(h).div_ceil(limit).max(1);
        let inverse = if self.largest > 0.0 { 1.0 / self.largest } else { 0.0 };
        let area = context.plotting_area();
        for (x0, y0, worst) in self.cells(block) {
            let (x1, y1) = ((x0 + block).min(w), (y0 + block).min(h));
            let corners = [(f64::from(x0), f64::from(h - y0)), (f64::from(x1), f64::from(h - y1))];
            area.draw(&Rectangle::new(corners, rgb(inferno(worst * inverse)).filled()))?;
        }
        // The colour scale: 0 to the largest error, in the image's units.
        let top = f64::from(self.largest.max(f32::MIN_POSITIVE));
        let scale_axis = ScaledAxis::between(AxisScale::Linear, 0.0, top);
        let widest = scale_axis.key_values(8).iter().map(|v| text_size(&tick_label(*v), TEXT).0).max().unwrap_or(0);
        let mut builder = ChartBuilder::on(&bar_area);
        builder
            .margin_top(10 + (title_size * 1.8) as u32)
            .margin_bottom(55)
            .margin_right(BAR_WIDTH.saturating_sub(widest + 70))
            .y_label_area_size(widest + 40);
        let mut bar = builder.build_cartesian_2d(ScaledAxis::between(AxisScale::Linear, 0.0, 1.0), scale_axis)?;
        let value = |v: &f64| tick_label(*v);
        let nothing = |_: &f64| String::new();
        bar.configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .x_label_formatter(&nothing)
            .y_label_formatter(&value)
            .y_desc("largest channel error")
            .label_style(text(TEXT))
            .axis_desc_style(text(TEXT))
            .axis_style(FRAME)
            .draw()?;
        let steps = 64;
        for i in 0..steps {
            let (a, b) = (i as f64 / steps as f64, (i + 1) as f64 / steps as f64);
            let color = rgb(inferno(((a + b) / 2.0) as f32));
            bar.plotting_area().draw(&Rectangle::new([(0.0, a * top), (1.0, b * top)], color.filled()))?;
        }
        Ok(())
    }
}
