//! Histograms: bins even on the chart's x scale (log-spaced on a log axis),
//! one translucent outlined set of bars per sample so that overlapping
//! samples stay apart.

use std::path::Path;

use image::RgbImage;
use plotters::coord::Shift;
use plotters::element::{PathElement, Rectangle};
use plotters::prelude::{DrawingArea, DrawingBackend};
use plotters::style::Color;

use super::chart::Chart;
use super::figure::{render, write, Figure, Target};
use super::frame::xy_frame;
use super::legend::{Entry, Legend, Sample};
use super::scale::{AxisScale, ScaledAxis};
use super::series::Distribution;
use super::style::{label_size, palette_color, rgb};
use crate::bench::BenchError;

/// `bins` bins (at least 1) even on `scale` over the values it can show, as
/// (low, high) edges; empty when no value can be shown. The last bin holds its
/// high edge.
pub fn histogram_bins(values: impl IntoIterator<Item = f64>, scale: AxisScale, bins: usize) -> Vec<(f64, f64)> {
    let (mut low, mut high) = (f64::INFINITY, f64::NEG_INFINITY);
    for position in values.into_iter().filter_map(|v| scale.transform(v)) {
        low = low.min(position);
        high = high.max(position);
    }
    if low > high {
        return Vec::new();
    }
    if high == low {
        (low, high) = (low - 0.5, high + 0.5);
    }
    let bins = bins.max(1);
    let edge = |i: usize| scale.inverse(low + (high - low) * i as f64 / bins as f64);
    (0..bins).map(|i| (edge(i), edge(i + 1))).collect()
}

/// How many of `values` fall in each bin (`edges` from [`histogram_bins`]).
pub fn bin_counts(values: &[f64], edges: &[(f64, f64)]) -> Vec<usize> {
    let last = edges.len().saturating_sub(1);
    edges
        .iter()
        .enumerate()
        .map(|(i, &(low, high))| values.iter().filter(|&&v| v >= low && (v < high || (i == last && v <= high))).count())
        .collect()
}

struct HistogramFigure<'a> {
    chart: &'a Chart,
    samples: &'a [Distribution],
    bins: usize,
}

/// Draws the histogram and writes it as PNG at `path` and SVG beside it. The
/// chart's x scale spaces the bins; its y axis (counts) is linear.
pub fn plot_histogram(
    path: impl AsRef<Path>,
    chart: &Chart,
    samples: &[Distribution],
    bins: usize,
) -> Result<(), BenchError> {
    chart.check_size()?;
    write(path.as_ref(), &HistogramFigure { chart, samples, bins })
}

pub fn render_histogram(chart: &Chart, samples: &[Distribution], bins: usize) -> Result<RgbImage, BenchError> {
    chart.check_size()?;
    render(&HistogramFigure { chart, samples, bins })
}

impl Figure for HistogramFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (self.chart.width, self.chart.height)
    }

    fn caption(&self) -> Option<&str> {
        self.chart.caption.as_deref()
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>, _: Target) -> Result<(), BenchError> {
        let scale = self.chart.x_scale;
        let edges = histogram_bins(self.samples.iter().flat_map(|s| s.values.iter().copied()), scale, self.bins);
        let counts: Vec<Vec<usize>> = self.samples.iter().map(|s| bin_counts(&s.values, &edges)).collect();
        let most = counts.iter().flatten().copied().max().unwrap_or(0).max(1) as f64;
        let x_axis = match (edges.first(), edges.last()) {
            (Some(first), Some(last)) => ScaledAxis::between(scale, first.0, last.1),
            _ => ScaledAxis::fitting(scale, []),
        };
        let y_axis = ScaledAxis::between(AxisScale::Linear, 0.0, most * 1.08);
        let entries = self
            .samples
            .iter()
            .enumerate()
            .map(|(i, s)| Entry { name: s.name.clone(), sample: Sample::Swatch(palette_color(i)) })
            .collect();
        let legend = Legend { entries, text_size: label_size(self.chart.width, self.chart.height) };
        let (context, _) = xy_frame(root, self.chart, x_axis, y_axis, &legend)?;
        let area = context.plotting_area();
        for (index, counts) in counts.iter().enumerate() {
            let color = rgb(palette_color(index));
            let mut outline = Vec::new();
            for (&(low, high), &count) in edges.iter().zip(counts) {
                let count = count as f64;
                if count > 0.0 {
                    area.draw(&Rectangle::new([(low, 0.0), (high, count)], color.mix(0.25).filled()))?;
                }
                outline.extend([(low, count), (high, count)]);
            }
            area.draw(&PathElement::new(outline, color.stroke_width(2)))?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_bins_are_even_in_decades_and_count_every_value() {
        let values = [1.0, 10.0, 100.0, 50.0, 2.0];
        let edges = histogram_bins(values, AxisScale::Log10, 2);
        assert_eq!(edges.len(), 2);
        assert!((edges[0].1 - 10.0).abs() < 1e-9, "{edges:?}");
        assert_eq!(bin_counts(&values, &edges), vec![2, 3]);
    }

    #[test]
    fn values_a_log_axis_cannot_show_make_no_bins() {
        assert!(histogram_bins([0.0, -1.0, f64::NAN], AxisScale::Log10, 4).is_empty());
        assert_eq!(histogram_bins([3.0, 3.0], AxisScale::Linear, 1), vec![(2.5, 3.5)]);
    }
}
