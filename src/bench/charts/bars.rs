//! Stacked bars over a categorical x axis: one category per bar, its label
//! under it; segments coloured by name, with a legend.

use std::path::Path;

use image::RgbImage;
use plotters::coord::Shift;
use plotters::element::Rectangle;
use plotters::prelude::{ChartBuilder, DrawingArea, DrawingBackend, IntoSegmentedCoord, SegmentValue};
use plotters::style::{Color, TRANSPARENT};

use super::chart::Chart;
use super::figure::{render, write, Figure, Target};
use super::frame::fitting_size;
use super::legend::{Entry, Legend, Sample};
use super::scale::{tick_label, AxisScale, ScaledAxis};
use super::series::StackedBar;
use super::style::{label_size, palette_color, rgb, text, text_size, FRAME, GRID};
use crate::bench::BenchError;

struct BarsFigure<'a> {
    chart: &'a Chart,
    bars: &'a [StackedBar],
}

/// Draws the stacked bar chart and writes it as PNG at `path` and SVG beside it.
pub fn plot_stacked_bars(path: impl AsRef<Path>, chart: &Chart, bars: &[StackedBar]) -> Result<(), BenchError> {
    chart.check_size()?;
    write(path.as_ref(), &BarsFigure { chart, bars })
}

/// Bars side by side, each the stack of its segments' values from 0. A
/// negative segment (a step that measured faster than the one below it, within
/// noise) draws nothing and lowers nothing: the bar's top is the largest
/// running sum. The y axis is linear whatever the chart says (stacks add).
pub fn render_stacked_bars(chart: &Chart, bars: &[StackedBar]) -> Result<RgbImage, BenchError> {
    chart.check_size()?;
    render(&BarsFigure { chart, bars })
}

/// Each segment's (name, low, high), bottom up; negative ones are empty.
pub(super) fn stack(bar: &StackedBar) -> Vec<(&str, f64, f64)> {
    let (mut sum, mut top) = (0.0f64, 0.0f64);
    bar.segments
        .iter()
        .map(|(name, value)| {
            sum += value;
            let low = top;
            top = top.max(sum);
            (name.as_str(), low, top)
        })
        .collect()
}

impl BarsFigure<'_> {
    fn names(&self) -> Vec<&str> {
        let mut names: Vec<&str> = Vec::new();
        for (name, _) in self.bars.iter().flat_map(|b| b.segments.iter()) {
            if !names.contains(&name.as_str()) {
                names.push(name);
            }
        }
        names
    }
}

impl Figure for BarsFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (self.chart.width, self.chart.height)
    }

    fn caption(&self) -> Option<&str> {
        self.chart.caption.as_deref()
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>, _: Target) -> Result<(), BenchError> {
        let size = label_size(self.chart.width, self.chart.height);
        let names = self.names();
        let entries = names
            .iter()
            .enumerate()
            .map(|(i, n)| Entry { name: n.to_string(), sample: Sample::Swatch(palette_color(i)) })
            .collect();
        let legend = Legend { entries, text_size: size };
        let plot_area = legend.place(root)?;
        let highest = self.bars.iter().flat_map(|b| stack(b).into_iter().map(|s| s.2)).fold(0.0, f64::max);
        let y_axis = ScaledAxis::between(AxisScale::Linear, 0.0, if highest > 0.0 { highest * 1.08 } else { 1.0 });
        let (plot_width, _) = plot_area.dim_in_pixel();
        let title_size = fitting_size(&self.chart.title, size * 1.3, plot_width.saturating_sub(20));
        let widest_y = y_axis.key_values(10).iter().map(|v| text_size(&tick_label(*v), size).0).max().unwrap_or(0);
        // Category labels shrink until each fits under its bar.
        let slot = plot_width.saturating_sub(widest_y + 60) / (self.bars.len().max(1) as u32);
        let widest_label = self.bars.iter().map(|b| b.label.as_str()).max_by_key(|l| text_size(l, size).0);
        let category_size = widest_label.map_or(size, |l| fitting_size(l, size, slot.saturating_sub(6)));
        let count = self.bars.len().max(1) as i32;
        let mut builder = ChartBuilder::on(&plot_area);
        builder
            .caption(&self.chart.title, text(title_size))
            .margin(12)
            .x_label_area_size((size * 3.0) as u32)
            .y_label_area_size(widest_y + (size * 2.2) as u32);
        let mut context = builder.build_cartesian_2d((0..count - 1).into_segmented(), y_axis)?;
        let category = |v: &SegmentValue<i32>| match v {
            SegmentValue::CenterOf(i) => self.bars.get(*i as usize).map_or(String::new(), |b| b.label.clone()),
            _ => String::new(),
        };
        let value = |v: &f64| tick_label(*v);
        context
            .configure_mesh()
            .disable_x_mesh()
            .x_labels(self.bars.len().max(1))
            .x_desc(self.chart.x_label.as_str())
            .y_desc(self.chart.y_label.as_str())
            .x_label_formatter(&category)
            .y_label_formatter(&value)
            .x_label_style(text(category_size))
            .y_label_style(text(size))
            .axis_desc_style(text(size))
            .bold_line_style(GRID.mix(1.0))
            .light_line_style(TRANSPARENT)
            .axis_style(FRAME)
            .draw()?;
        let area = context.plotting_area();
        let margin = (slot as f64 * 0.15) as u32;
        for (index, bar) in self.bars.iter().enumerate() {
            for (name, low, high) in stack(bar) {
                if high <= low {
                    continue;
                }
                let color = rgb(palette_color(names.iter().position(|n| *n == name).unwrap_or(0)));
                let corners = [(SegmentValue::Exact(index as i32), low), (SegmentValue::Exact(index as i32 + 1), high)];
                let mut rectangle = Rectangle::new(corners, color.filled());
                rectangle.set_margin(0, 0, margin, margin);
                area.draw(&rectangle)?;
            }
        }
        Ok(())
    }
}
