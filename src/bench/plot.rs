//! PNG charts for benchmark reports: error against GPU time with the Pareto
//! front marked, and line charts (e.g. time against image size per strategy).
//! Text uses the embedded bitmap font, so charts need no font on the system.

use std::path::Path;

use image::{ImageFormat, RgbImage};

use super::axis::{Axis, AxisScale, Tick};
use super::canvas::{Canvas, Marker, PixelRect, Rgb};
use super::error::BenchError;
use super::font::{text_width, ADVANCE, GLYPH_HEIGHT};
use super::pareto::pareto_front;

const MIN_WIDTH: u32 = 320;
const MIN_HEIGHT: u32 = 200;
const MAX_SIDE: u32 = 8192;

const BACKGROUND: Rgb = [255, 255, 255];
const INK: Rgb = [25, 25, 25];
const FRAME: Rgb = [90, 90, 90];
const GRID: Rgb = [228, 228, 228];
const FRONT: Rgb = [0, 0, 0];

/// Colour-blind-safe colours (Okabe–Ito, without yellow and black, which
/// vanish on white or clash with the Pareto front), then a brown and a grey.
const PALETTE: [Rgb; 8] = [
    [0, 114, 178],
    [213, 94, 0],
    [0, 158, 115],
    [204, 121, 167],
    [230, 159, 0],
    [86, 180, 233],
    [140, 86, 75],
    [127, 127, 127],
];
const MARKERS: [Marker; 4] = [Marker::Circle, Marker::Square, Marker::Triangle, Marker::Diamond];

/// Charts at least this big draw text at twice the font's size, smaller ones
/// at its own size, so legends and labels still fit.
const LARGE_TEXT_MIN_SIZE: (u32, u32) = (640, 400);
const MARKER_RADIUS: f64 = 5.0;
const TICK_LENGTH: i64 = 6;
const GAP: i64 = 10;

/// The colour of the `index`-th series when it names none.
pub fn palette_color(index: usize) -> [u8; 3] {
    PALETTE[index % PALETTE.len()]
}

fn series_marker(index: usize) -> Marker {
    MARKERS[index % MARKERS.len()]
}

/// Titles, axes and size of a chart.
#[derive(Debug, Clone, PartialEq)]
pub struct Chart {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub x_scale: AxisScale,
    pub y_scale: AxisScale,
    pub width: u32,
    pub height: u32,
}

impl Chart {
    /// A 900x600 chart with linear axes.
    pub fn new(title: impl Into<String>, x_label: impl Into<String>, y_label: impl Into<String>) -> Self {
        Chart {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            x_scale: AxisScale::Linear,
            y_scale: AxisScale::Linear,
            width: 900,
            height: 600,
        }
    }

    pub fn x_scale(mut self, scale: AxisScale) -> Self {
        self.x_scale = scale;
        self
    }

    pub fn y_scale(mut self, scale: AxisScale) -> Self {
        self.y_scale = scale;
        self
    }

    pub fn size(mut self, width: u32, height: u32) -> Self {
        self.width = width;
        self.height = height;
        self
    }

    fn check_size(&self) -> Result<(), BenchError> {
        let fits = (MIN_WIDTH..=MAX_SIDE).contains(&self.width) && (MIN_HEIGHT..=MAX_SIDE).contains(&self.height);
        if fits {
            Ok(())
        } else {
            Err(BenchError::ChartSize {
                width: self.width,
                height: self.height,
                min_width: MIN_WIDTH,
                min_height: MIN_HEIGHT,
                max_side: MAX_SIDE,
            })
        }
    }
}

/// One named set of (x, y) points, e.g. all runs of one strategy.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    /// `None` takes the next palette colour.
    pub color: Option<[u8; 3]>,
}

impl Series {
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series { name: name.into(), points, color: None }
    }

    pub fn with_color(mut self, color: [u8; 3]) -> Self {
        self.color = Some(color);
        self
    }
}

/// Draws the error-against-time scatter chart and writes it as PNG.
pub fn plot_error_vs_time(path: impl AsRef<Path>, chart: &Chart, series: &[Series]) -> Result<(), BenchError> {
    save_png(path.as_ref(), &render_error_vs_time(chart, series)?)
}

/// Draws the line chart and writes it as PNG.
pub fn plot_lines(path: impl AsRef<Path>, chart: &Chart, series: &[Series]) -> Result<(), BenchError> {
    save_png(path.as_ref(), &render_lines(chart, series)?)
}

pub(super) fn save_png(path: &Path, image: &RgbImage) -> Result<(), BenchError> {
    image.save_with_format(path, ImageFormat::Png).map_err(|source| BenchError::Png { path: path.to_owned(), source })
}

/// Scatter of every series' (time, error) points; the Pareto front over all
/// series is joined by a step line (each front point's error holds until the
/// next, faster-to-slower) and its points are circled. Points an axis cannot
/// show (NaN, or not positive on a log axis) are left out and counted in the
/// legend; on a log axis the front is that of the points shown.
pub fn render_error_vs_time(chart: &Chart, series: &[Series]) -> Result<RgbImage, BenchError> {
    let mut legend: Vec<LegendEntry> =
        series.iter().enumerate().map(|(i, s)| LegendEntry::series(i, s, false)).collect();
    legend.push(LegendEntry { name: "Pareto front".to_owned(), sample: LegendSample::Front });
    let mut frame = ChartFrame::new(chart, series, legend)?;

    let shown: Vec<(f64, f64)> =
        series.iter().flat_map(|s| s.points.iter().copied()).filter(|&p| frame.to_pixel(p).is_some()).collect();
    let front: Vec<(f64, f64)> = pareto_front(&shown).into_iter().filter_map(|i| frame.to_pixel(shown[i])).collect();

    frame.canvas.clip_to(frame.plot);
    for pair in front.windows(2) {
        let corner = (pair[1].0, pair[0].1);
        frame.canvas.line(pair[0], corner, 2, FRONT);
        frame.canvas.line(corner, pair[1], 2, FRONT);
    }
    for (index, s) in series.iter().enumerate() {
        let color = s.color.unwrap_or(palette_color(index));
        let pixels: Vec<(f64, f64)> = s.points.iter().filter_map(|&p| frame.to_pixel(p)).collect();
        for pixel in pixels {
            frame.canvas.marker(series_marker(index), pixel, MARKER_RADIUS, color);
        }
    }
    for &pixel in &front {
        frame.canvas.ring(pixel, MARKER_RADIUS + 5.0, 2.0, FRONT);
    }
    frame.canvas.unclip();
    Ok(frame.canvas.into_image())
}

/// One line per series through its points in order of x, with a marker on
/// each point. Points an axis cannot show are left out and counted in the legend.
pub fn render_lines(chart: &Chart, series: &[Series]) -> Result<RgbImage, BenchError> {
    let legend = series.iter().enumerate().map(|(i, s)| LegendEntry::series(i, s, true)).collect();
    let mut frame = ChartFrame::new(chart, series, legend)?;

    frame.canvas.clip_to(frame.plot);
    for (index, s) in series.iter().enumerate() {
        let color = s.color.unwrap_or(palette_color(index));
        let mut points: Vec<(f64, f64)> = s.points.iter().copied().filter(|&p| frame.to_pixel(p).is_some()).collect();
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        let pixels: Vec<(f64, f64)> = points.iter().filter_map(|&p| frame.to_pixel(p)).collect();
        for pair in pixels.windows(2) {
            frame.canvas.line(pair[0], pair[1], 2, color);
        }
        for &pixel in &pixels {
            frame.canvas.marker(series_marker(index), pixel, MARKER_RADIUS - 1.0, color);
        }
    }
    frame.canvas.unclip();
    Ok(frame.canvas.into_image())
}

/// One bar of a stacked bar chart: its label and its segments, bottom up, as
/// (segment name, value). Segment names are shared across bars (one legend
/// entry and colour each, in order of first appearance).
#[derive(Debug, Clone, PartialEq)]
pub struct StackedBar {
    pub label: String,
    pub segments: Vec<(String, f64)>,
}

/// Draws the stacked bar chart and writes it as PNG.
pub fn plot_stacked_bars(path: impl AsRef<Path>, chart: &Chart, bars: &[StackedBar]) -> Result<(), BenchError> {
    save_png(path.as_ref(), &render_stacked_bars(chart, bars)?)
}

/// Bars side by side (x: bar number, each bar's label above it), each the
/// stack of its segments' values from 0. A negative segment (a step that
/// measured faster than the one below it, within noise) draws nothing and
/// lowers nothing: the bar's top is the largest running sum.
pub fn render_stacked_bars(chart: &Chart, bars: &[StackedBar]) -> Result<RgbImage, BenchError> {
    let mut names: Vec<String> = Vec::new();
    for (name, _) in bars.iter().flat_map(|b| b.segments.iter()) {
        if !names.contains(name) {
            names.push(name.clone());
        }
    }
    let tops: Vec<f64> = bars
        .iter()
        .map(|b| b.segments.iter().fold((0.0f64, 0.0f64), |(sum, top), (_, v)| (sum + v, top.max(sum + v))).1)
        .collect();
    let highest = tops.iter().copied().fold(0.0, f64::max);
    // Invisible corner points make the axes span every bar and 0..highest.
    let extent = Series::new("", vec![(-0.6, 0.0), (bars.len() as f64 - 0.4, highest * 1.08)]);
    let legend = names
        .iter()
        .enumerate()
        .map(|(i, n)| LegendEntry::series(i, &Series::new(n.clone(), vec![]).with_color(palette_color(i)), false))
        .collect();
    let mut frame = ChartFrame::new(chart, std::slice::from_ref(&extent), legend)?;
    let text_scale = frame.text_scale;
    for (index, bar) in bars.iter().enumerate() {
        let x = index as f64;
        let (mut sum, mut top) = (0.0f64, 0.0f64);
        for (name, value) in &bar.segments {
            sum += value;
            let (low, high) = (top, top.max(sum));
            top = high;
            let color = palette_color(names.iter().position(|n| n == name).unwrap_or(0));
            let (Some(a), Some(b)) = (frame.to_pixel((x - 0.35, low)), frame.to_pixel((x + 0.35, high))) else {
                continue;
            };
            if b.1.round() < a.1.round() {
                let rect = PixelRect {
                    x0: a.0.round() as i64,
                    y0: b.1.round() as i64,
                    x1: b.0.round() as i64,
                    y1: a.1.round() as i64,
                };
                frame.canvas.fill_rect(rect, color);
            }
        }
        if let Some(label_at) = frame.to_pixel((x, top)) {
            let width = text_width(&bar.label, text_scale);
            let y = label_at.1 as i64 - i64::from(GLYPH_HEIGHT * text_scale) - 4;
            frame.canvas.text(label_at.0 as i64 - width / 2, y, &bar.label, text_scale, INK);
        }
    }
    Ok(frame.canvas.into_image())
}

enum LegendSample {
    Points { marker: Marker, color: Rgb, line: bool },
    Front,
}

struct LegendEntry {
    name: String,
    sample: LegendSample,
}

impl LegendEntry {
    fn series(index: usize, series: &Series, line: bool) -> Self {
        LegendEntry {
            name: series.name.clone(),
            sample: LegendSample::Points {
                marker: series_marker(index),
                color: series.color.unwrap_or(palette_color(index)),
                line,
            },
        }
    }
}

/// Everything but the data: title, axes with ticks, grid, labels and legend,
/// laid out so that the plot area takes whatever room the text leaves.
struct ChartFrame {
    canvas: Canvas,
    plot: PixelRect,
    x_axis: Axis,
    y_axis: Axis,
    text_scale: u32,
}

impl ChartFrame {
    fn new(chart: &Chart, series: &[Series], legend: Vec<LegendEntry>) -> Result<Self, BenchError> {
        chart.check_size()?;
        let all_points = || series.iter().flat_map(|s| s.points.iter().copied());
        let x_axis = Axis::fitting(chart.x_scale, all_points().map(|p| p.0));
        let y_axis = Axis::fitting(chart.y_scale, all_points().map(|p| p.1));
        let hidden = all_points()
            .filter(|&(x, y)| chart.x_scale.transform(x).is_none() || chart.y_scale.transform(y).is_none())
            .count();

        let (width, height) = (i64::from(chart.width), i64::from(chart.height));
        let large = chart.width >= LARGE_TEXT_MIN_SIZE.0 && chart.height >= LARGE_TEXT_MIN_SIZE.1;
        let text_scale = if large { 2 } else { 1 };
        let text_height = i64::from(GLYPH_HEIGHT * text_scale);
        let title_scale =
            if text_width(&chart.title, text_scale + 1) + 2 * GAP <= width { text_scale + 1 } else { text_scale };
        let title_height = i64::from(GLYPH_HEIGHT * title_scale);

        let top = GAP + title_height + 2 * GAP;
        let bottom = height - (TICK_LENGTH + 6 + text_height + GAP + text_height + GAP);
        let y_target = ((bottom - top) / (35 * i64::from(text_scale))).clamp(2, 10) as usize;
        let y_ticks = y_axis.ticks(y_target);

        let legend_layout = LegendLayout::new(legend, hidden, width, text_scale);
        let widest_y_label = y_ticks.iter().map(|t| text_width(&t.label, text_scale)).max().unwrap_or(0);
        let left = GAP + text_height + 2 * GAP + widest_y_label + 6 + TICK_LENGTH;
        let right = width - legend_layout.width - 2 * GAP;
        let plot = PixelRect { x0: left, y0: top, x1: right.max(left + 1), y1: bottom.max(top + 1) };
        let x_ticks = x_ticks_without_overlap(&x_axis, plot, text_scale);

        let mut frame =
            ChartFrame { canvas: Canvas::new(chart.width, chart.height, BACKGROUND), plot, x_axis, y_axis, text_scale };
        let title = fit_text(&chart.title, title_scale, width - 2 * GAP);
        frame.canvas.text((width - text_width(&title, title_scale)) / 2, GAP, &title, title_scale, INK);
        frame.draw_axes(&x_ticks, &y_ticks);
        frame.draw_axis_labels(chart, text_height);
        if all_points().all(|(x, y)| chart.x_scale.transform(x).is_none() || chart.y_scale.transform(y).is_none()) {
            let note = "no data to show";
            frame.canvas.text(
                plot.x0 + (plot.width() - text_width(note, text_scale)) / 2,
                plot.y0 + (plot.height() - text_height) / 2,
                note,
                text_scale,
                FRAME,
            );
        }
        legend_layout.draw(&mut frame.canvas, right + GAP, plot.y0);
        Ok(frame)
    }

    /// Pixel centre of a data point, or `None` when an axis cannot show it.
    fn to_pixel(&self, (x, y): (f64, f64)) -> Option<(f64, f64)> {
        let fx = self.x_axis.fraction(x)?;
        let fy = self.y_axis.fraction(y)?;
        let plot = &self.plot;
        Some((plot.x0 as f64 + fx * (plot.width() - 1) as f64, (plot.y1 - 1) as f64 - fy * (plot.height() - 1) as f64))
    }

    fn draw_axes(&mut self, x_ticks: &[Tick], y_ticks: &[Tick]) {
        let plot = self.plot;
        for tick in x_ticks {
            let Some(f) = self.x_axis.fraction(tick.value) else {
                continue;
            };
            let x = (plot.x0 as f64 + f * (plot.width() - 1) as f64).round() as i64;
            self.canvas.line((x as f64, plot.y0 as f64), (x as f64, (plot.y1 - 1) as f64), 1, GRID);
            self.canvas.line((x as f64, plot.y1 as f64), (x as f64, (plot.y1 + TICK_LENGTH) as f64), 1, FRAME);
            let label_x = x - text_width(&tick.label, self.text_scale) / 2;
            self.canvas.text(label_x, plot.y1 + TICK_LENGTH + 6, &tick.label, self.text_scale, INK);
        }
        for tick in y_ticks {
            let Some(f) = self.y_axis.fraction(tick.value) else {
                continue;
            };
            let y = ((plot.y1 - 1) as f64 - f * (plot.height() - 1) as f64).round() as i64;
            self.canvas.line((plot.x0 as f64, y as f64), ((plot.x1 - 1) as f64, y as f64), 1, GRID);
            self.canvas.line(((plot.x0 - TICK_LENGTH) as f64, y as f64), ((plot.x0 - 1) as f64, y as f64), 1, FRAME);
            let label_x = plot.x0 - TICK_LENGTH - 6 - text_width(&tick.label, self.text_scale);
            // Digits fill the top seven of the nine font rows; centre those.
            let label_y = y - i64::from(7 * self.text_scale) / 2;
            self.canvas.text(label_x, label_y, &tick.label, self.text_scale, INK);
        }
        self.canvas
            .outline_rect(PixelRect { x0: plot.x0 - 1, y0: plot.y0 - 1, x1: plot.x1 + 1, y1: plot.y1 + 1 }, FRAME);
    }

    fn draw_axis_labels(&mut self, chart: &Chart, text_height: i64) {
        let plot = self.plot;
        let x_label = fit_text(&chart.x_label, self.text_scale, plot.width());
        self.canvas.text(
            plot.x0 + (plot.width() - text_width(&x_label, self.text_scale)) / 2,
            plot.y1 + TICK_LENGTH + 6 + text_height + GAP,
            &x_label,
            self.text_scale,
            INK,
        );
        let y_label = fit_text(&chart.y_label, self.text_scale, plot.height());
        self.canvas.text_vertical(
            GAP,
            plot.y1 - (plot.height() - text_width(&y_label, self.text_scale)) / 2,
            &y_label,
            self.text_scale,
            INK,
        );
    }
}

/// As many x ticks as fit (up to one per 80 pixels) with labels that keep
/// clear of each other.
fn x_ticks_without_overlap(axis: &Axis, plot: PixelRect, text_scale: u32) -> Vec<Tick> {
    let most = (plot.width() / 80).clamp(2, 12) as usize;
    let pixel_x = |tick: &Tick| axis.fraction(tick.value).map(|f| f * plot.width() as f64);
    let clear = |ticks: &[Tick]| {
        ticks.windows(2).all(|pair| {
            let room = (text_width(&pair[0].label, text_scale) + text_width(&pair[1].label, text_scale)) as f64 / 2.0
                + 2.0 * GAP as f64;
            match (pixel_x(&pair[0]), pixel_x(&pair[1])) {
                (Some(a), Some(b)) => (b - a).abs() >= room,
                _ => true,
            }
        })
    };
    (2..=most).rev().map(|target| axis.ticks(target)).find(|ticks| clear(ticks)).unwrap_or_else(|| axis.ticks(2))
}

/// The legend box right of the plot: one line per entry, plus a count of
/// points that could not be shown.
struct LegendLayout {
    lines: Vec<(String, Option<LegendSample>)>,
    width: i64,
    text_scale: u32,
}

const SAMPLE_WIDTH: i64 = 28;

impl LegendLayout {
    fn new(entries: Vec<LegendEntry>, hidden: usize, chart_width: i64, text_scale: u32) -> Self {
        let mut lines: Vec<(String, Option<LegendSample>)> =
            entries.into_iter().map(|e| (e.name, Some(e.sample))).collect();
        if hidden > 0 {
            lines.push((format!("{hidden} not shown"), None));
        }
        // The legend may take at most a third of the chart; longer names are cut.
        let max_text = chart_width / 3 - SAMPLE_WIDTH - 3 * GAP;
        for (name, _) in &mut lines {
            *name = fit_text(name, text_scale, max_text);
        }
        let widest = lines.iter().map(|(name, _)| text_width(name, text_scale)).max().unwrap_or(0);
        let width = if lines.is_empty() { 0 } else { GAP + SAMPLE_WIDTH + GAP + widest + GAP };
        LegendLayout { lines, width, text_scale }
    }

    fn draw(&self, canvas: &mut Canvas, x: i64, y: i64) {
        if self.lines.is_empty() {
            return;
        }
        let line_height = i64::from(GLYPH_HEIGHT * self.text_scale) + 8;
        let height = GAP + line_height * self.lines.len() as i64 + GAP / 2;
        let rect = PixelRect { x0: x, y0: y, x1: x + self.width, y1: y + height };
        canvas.outline_rect(rect, FRAME);
        for (row, (name, sample)) in self.lines.iter().enumerate() {
            let top = y + GAP + row as i64 * line_height;
            let middle = top as f64 + f64::from(7 * self.text_scale) / 2.0;
            let sample_x0 = (x + GAP) as f64;
            let sample_centre = sample_x0 + SAMPLE_WIDTH as f64 / 2.0;
            match sample {
                Some(LegendSample::Points { marker, color, line }) => {
                    if *line {
                        canvas.line((sample_x0, middle), (sample_x0 + SAMPLE_WIDTH as f64, middle), 2, *color);
                    }
                    canvas.marker(*marker, (sample_centre, middle), MARKER_RADIUS, *color);
                }
                Some(LegendSample::Front) => {
                    canvas.line((sample_x0, middle), (sample_x0 + SAMPLE_WIDTH as f64, middle), 2, FRONT);
                    canvas.ring((sample_centre, middle), MARKER_RADIUS + 5.0, 2.0, FRONT);
                }
                None => {}
            }
            let text_color = if sample.is_some() { INK } else { FRAME };
            canvas.text(x + GAP + SAMPLE_WIDTH + GAP, top, name, self.text_scale, text_color);
        }
    }
}

/// `text`, shortened with ".." so that it fits in `max_width` pixels.
fn fit_text(text: &str, scale: u32, max_width: i64) -> String {
    if text_width(text, scale) <= max_width {
        return text.to_owned();
    }
    let per_char = i64::from(ADVANCE * scale);
    let keep = (max_width / per_char - 2).max(0) as usize;
    let mut short: String = text.chars().take(keep).collect();
    short.push_str("..");
    short
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_text_is_cut_to_fit() {
        let fitted = fit_text("a very long series name indeed", 2, 120);
        assert!(fitted.ends_with(".."));
        assert!(text_width(&fitted, 2) <= 120);
        assert_eq!(fit_text("short", 2, 120), "short");
    }

    #[test]
    fn stacked_bars_draw_each_segment_in_its_colour_and_skip_negative_ones() {
        let bar = |label: &str, a: f64, b: f64, c: f64| StackedBar {
            label: label.into(),
            segments: vec![("a".into(), a), ("b".into(), b), ("c".into(), c)],
        };
        let chart = Chart::new("t", "x", "y").size(640, 400);
        let image = render_stacked_bars(&chart, &[bar("one", 10.0, 20.0, 5.0), bar("two", 10.0, 30.0, -5.0)]).unwrap();
        let count = |color: [u8; 3]| image.pixels().filter(|p| p.0 == color).count();
        let (a, b, c) = (count(palette_color(0)), count(palette_color(1)), count(palette_color(2)));
        // Both bars share a (10 each), b is 20 and 30, c only 5 (the -5 draws nothing);
        // the legend adds a few pixels of each colour.
        assert!(a > 0 && b > 0 && c > 0, "{a} {b} {c}");
        assert!(b > 2 * a && b < 3 * a, "b (50 units) against a (20): {b} vs {a}");
        assert!(c < a, "c is 5 units against a's 20: {c} vs {a}");
    }

    #[test]
    fn charts_outside_the_size_limits_are_refused() {
        let chart = Chart::new("t", "x", "y").size(10, 10);
        assert!(matches!(render_lines(&chart, &[]), Err(BenchError::ChartSize { .. })));
    }
}
