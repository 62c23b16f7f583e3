//! The frame shared by the x-y charts: title fitted to the width, axes with
//! round ticks and labels, grid, and the legend beside or under the plot.

use plotters::coord::Shift;
use plotters::prelude::{Cartesian2d, ChartBuilder, ChartContext, DrawingArea, DrawingBackend};
use plotters::style::{Color, TRANSPARENT};

use super::chart::Chart;
use super::legend::Legend;
use super::scale::{tick_label, ScaledAxis};
use super::style::{label_size, text, text_size, FRAME, GRID};
use crate::bench::BenchError;

pub(super) type XyChart<'a, DB> = ChartContext<'a, DB, Cartesian2d<ScaledAxis, ScaledAxis>>;

/// The largest text size (at most `size`) at which `label` fits in `width` pixels.
pub(super) fn fitting_size(label: &str, size: f64, width: u32) -> f64 {
    let mut size = size;
    while size > 9.0 && text_size(label, size).0 > width {
        size -= 1.0;
    }
    size
}

/// Draws title, axes, grid and legend; the returned chart draws the data.
pub(super) fn xy_frame<'a, DB: DrawingBackend>(
    root: &'a DrawingArea<DB, Shift>,
    chart: &Chart,
    x_axis: ScaledAxis,
    y_axis: ScaledAxis,
    legend: &Legend,
) -> Result<(XyChart<'a, DB>, DrawingArea<DB, Shift>), BenchError> {
    let size = label_size(chart.width, chart.height);
    let plot_area = legend.place(root)?;
    let (plot_width, _) = plot_area.dim_in_pixel();
    let title_size = fitting_size(&chart.title, size * 1.3, plot_width.saturating_sub(20));
    let widest_y = y_axis.key_values(10).iter().map(|v| text_size(&tick_label(*v), size).0).max().unwrap_or(0);
    let mut builder = ChartBuilder::on(&plot_area);
    builder
        .caption(&chart.title, text(title_size))
        .margin(12)
        .x_label_area_size((size * 3.0) as u32)
        .y_label_area_size(widest_y + (size * 2.2) as u32);
    let mut context = builder.build_cartesian_2d(x_axis, y_axis)?;
    let format = |v: &f64| tick_label(*v);
    // A categorical axis ticks on whole numbers (at most ten categories take
    // a step of 1) and names each.
    let category = |v: &f64| {
        let i = v.round();
        let named = (v - i).abs() < 1e-6 && i >= 0.0;
        named.then(|| chart.categories.get(i as usize).cloned()).flatten().unwrap_or_default()
    };
    let x_format: &dyn Fn(&f64) -> String = if chart.categories.is_empty() { &format } else { &category };
    let x_labels = if chart.categories.is_empty() { 10 } else { chart.categories.len().clamp(1, 10) };
    context
        .configure_mesh()
        .x_desc(chart.x_label.as_str())
        .y_desc(chart.y_label.as_str())
        .x_labels(x_labels)
        .x_label_formatter(x_format)
        .y_label_formatter(&format)
        .label_style(text(size))
        .axis_desc_style(text(size))
        .bold_line_style(GRID.mix(1.0))
        .light_line_style(TRANSPARENT)
        .axis_style(FRAME)
        .draw()?;
    Ok((context, plot_area))
}
