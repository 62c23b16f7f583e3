//! Line charts and the error-against-time scatter with its Pareto front; both
//! draw a point's interval as an error bar and its marker hollow when the
//! interval holds 0 (within noise).

use std::path::Path;

use image::RgbImage;
use plotters::coord::Shift;
use plotters::element::{Circle, ErrorBar, PathElement, Text};
use plotters::prelude::{DrawingArea, DrawingBackend};
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::Color;

use super::chart::Chart;
use super::figure::{render, write, Figure, Target};
use super::frame::{xy_frame, XyChart};
use super::legend::{Entry, Legend, Sample, MARKER_RADIUS};
use super::marker::draw_marker;
use super::scale::{AxisScale, ScaledAxis};
use super::series::{Point, Series};
use super::style::{label_size, palette_color, rgb, series_marker, text, FRONT};
use crate::bench::pareto::pareto_front;
use crate::bench::BenchError;

#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    Lines,
    /// Markers with their intervals, unjoined: estimates of separate things
    /// (one per strategy) that a line would wrongly connect.
    Points,
    ErrorVsTime,
}

pub(super) struct XyFigure<'a> {
    chart: &'a Chart,
    series: &'a [Series],
    kind: Kind,
}

/// Draws the line chart and writes it as PNG at `path` and SVG beside it.
pub fn plot_lines(path: impl AsRef<Path>, chart: &Chart, series: &[Series]) -> Result<(), BenchError> {
    chart.check_size()?;
    write(path.as_ref(), &XyFigure { chart, series, kind: Kind::Lines })
}

/// Draws each series' points as markers with their intervals, no lines, and
/// writes the chart as PNG at `path` and SVG beside it.
pub fn plot_points(path: impl AsRef<Path>, chart: &Chart, series: &[Series]) -> Result<(), BenchError> {
    chart.check_size()?;
    write(path.as_ref(), &XyFigure { chart, series, kind: Kind::Points })
}

/// One line per series through its points in order of x, a marker on each
/// point. Points an axis cannot show are left out and counted in the legend.
pub fn render_lines(chart: &Chart, series: &[Series]) -> Result<RgbImage, BenchError> {
    chart.check_size()?;
    render(&XyFigure { chart, series, kind: Kind::Lines })
}

/// Draws the error-against-time chart and writes it as PNG at `path` and SVG beside it.
pub fn plot_error_vs_time(path: impl AsRef<Path>, chart: &Chart, series: &[Series]) -> Result<(), BenchError> {
    chart.check_size()?;
    write(path.as_ref(), &XyFigure { chart, series, kind: Kind::ErrorVsTime })
}

/// Scatter of every series' (time, error) points; the Pareto front over all
/// series is joined by a step line (each front point's error holds until the
/// next, faster-to-slower) and its points are circled. Points an axis cannot
/// show are left out and counted in the legend; the front is that of the points shown.
pub fn render_error_vs_time(chart: &Chart, series: &[Series]) -> Result<RgbImage, BenchError> {
    chart.check_size()?;
    render(&XyFigure { chart, series, kind: Kind::ErrorVsTime })
}

impl<'a> XyFigure<'a> {
    /// Markers with their intervals, unjoined (a panel of [`super::panels`]).
    pub(super) fn points(chart: &'a Chart, series: &'a [Series]) -> Self {
        XyFigure { chart, series, kind: Kind::Points }
    }

    fn all_points(&self) -> impl Iterator<Item = &Point> {
        self.series.iter().flat_map(|s| s.points.iter())
    }

    fn legend(&self, hidden: usize) -> Legend {
        let mut entries: Vec<Entry> = self
            .series
            .iter()
            .enumerate()
            .map(|(i, s)| Entry {
                name: s.name.clone(),
                sample: Sample::Series {
                    color: s.color.unwrap_or(palette_color(i)),
                    marker: series_marker(i),
                    line: self.kind == Kind::Lines,
                },
            })
            .collect();
        if self.kind == Kind::ErrorVsTime {
            entries.push(Entry { name: "Pareto front".into(), sample: Sample::Front });
        }
        if self.all_points().any(Point::interval_holds_zero) {
            entries.push(Entry { name: "hollow: interval holds 0 (within noise)".into(), sample: Sample::Hollow });
        }
        if hidden > 0 {
            let name = format!("{hidden} point(s) not shown (axis cannot show them)");
            entries.push(Entry { name, sample: Sample::Note });
        }
        Legend { entries, text_size: label_size(self.chart.width, self.chart.height) }
    }

    fn draw_series<DB: DrawingBackend>(
        &self,
        context: &XyChart<DB>,
        shows: impl Fn(&Point) -> bool,
    ) -> Result<(), BenchError> {
        let area = context.plotting_area();
        let y_spec = *context.as_coord_spec().y_spec();
        let y_low = y_spec.low_value();
        for (index, s) in self.series.iter().enumerate() {
            let color = rgb(s.color.unwrap_or(palette_color(index)));
            let mut shown: Vec<&Point> = s.points.iter().filter(|p| shows(p)).collect();
            if self.kind == Kind::Lines {
                shown.sort_by(|a, b| a.x.total_cmp(&b.x));
                let path: Vec<(f64, f64)> = shown.iter().map(|p| (p.x, p.y)).collect();
                area.draw(&PathElement::new(path, color.stroke_width(2)))?;
            }
            for point in &shown {
                if let Some((low, high)) = point.interval {
                    if y_spec.shows(high) {
                        let low = if y_spec.shows(low) { low } else { y_low };
                        area.draw(&ErrorBar::new_vertical(point.x, low, point.y, high, color.stroke_width(1), 10))?;
                    }
                }
            }
            let radius = if self.kind == Kind::Lines { MARKER_RADIUS - 1 } else { MARKER_RADIUS };
            for point in &shown {
                draw_marker(
                    area,
                    (point.x, point.y),
                    series_marker(index),
                    color,
                    radius,
                    point.interval_holds_zero(),
                )?;
            }
        }
        Ok(())
    }
}

impl Figure for XyFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (self.chart.width, self.chart.height)
    }

    fn caption(&self) -> Option<&str> {
        self.chart.caption.as_deref()
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>, _: Target) -> Result<(), BenchError> {
        let (x_scale, y_scale) = (self.chart.x_scale, self.chart.y_scale);
        let shows = |p: &Point| x_scale.transform(p.x).is_some() && y_scale.transform(p.y).is_some();
        let hidden = self.all_points().filter(|p| !shows(p)).count();
        let shown = || self.all_points().filter(|p| shows(p));
        let x_axis = if self.chart.categories.is_empty() {
            ScaledAxis::fitting(x_scale, shown().map(|p| p.x))
        } else {
            ScaledAxis::between(AxisScale::Linear, -0.5, self.chart.categories.len() as f64 - 0.5)
        };
        let zero = (self.chart.y_from_zero && y_scale == AxisScale::Linear).then_some(0.0);
        let y_values = shown()
            .flat_map(|p| {
                let (low, high) = p.interval.unwrap_or((p.y, p.y));
                [p.y, low, high]
            })
            .chain(zero);
        let y_axis = ScaledAxis::fitting(y_scale, y_values);
        let legend = self.legend(hidden);
        let (context, plot_area) = xy_frame(root, self.chart, x_axis, y_axis, &legend)?;
        if shown().next().is_none() {
            let (width, height) = plot_area.dim_in_pixel();
            let style = text(label_size(self.chart.width, self.chart.height)).pos(Pos::new(HPos::Center, VPos::Center));
            plot_area.draw(&Text::new("no data to show", (width as i32 / 2, height as i32 / 2), style))?;
            return Ok(());
        }
        if self.kind == Kind::ErrorVsTime {
            let points: Vec<(f64, f64)> = shown().map(|p| (p.x, p.y)).collect();
            let front: Vec<(f64, f64)> = pareto_front(&points).into_iter().map(|i| points[i]).collect();
            let area = context.plotting_area();
            let mut steps = Vec::new();
            for pair in front.windows(2) {
                steps.extend([pair[0], (pair[1].0, pair[0].1)]);
            }
            steps.extend(front.last().copied());
            area.draw(&PathElement::new(steps, FRONT.stroke_width(2)))?;
            self.draw_series(&context, shows)?;
            for &point in &front {
                let ring = plotters::element::EmptyElement::at(point)
                    + Circle::new((0, 0), MARKER_RADIUS + 5, FRONT.stroke_width(2));
                context.plotting_area().draw(&ring)?;
            }
        } else {
            self.draw_series(&context, shows)?;
        }
        Ok(())
    }
}
