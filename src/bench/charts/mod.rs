//! Benchmark charts, drawn by `plotters` as PNG and, beside each, SVG: lines,
//! points with intervals (alone, or in panels each on its own axis), error
//! against time with the Pareto front, stacked bars over categories,
//! histograms, a verdict heat map and a per-pixel error map with its colour
//! scale. Points may carry an interval (an error bar; hollow when it holds 0).
//! Our code only lays charts out; plotters draws them, text through ab_glyph.

mod bars;
mod chart;
mod error_map;
mod figure;
mod frame;
mod heat_map;
mod histogram;
mod legend;
mod marker;
mod panels;
mod scale;
mod series;
mod style;
mod xy;

pub use bars::{plot_stacked_bars, render_stacked_bars};
pub use chart::Chart;
pub use error_map::{plot_error_map, render_error_map, ErrorMap};
pub use figure::svg_path;
pub use heat_map::{plot_heat_map, render_heat_map, HeatCell, HeatLevel, HeatMap};
pub use histogram::{bin_counts, histogram_bins, plot_histogram, render_histogram};
pub use panels::{plot_point_panels, render_point_panels, Panel};
pub use scale::AxisScale;
pub use series::{Distribution, Point, Series, StackedBar};
pub use style::palette_color;
pub use xy::{plot_error_vs_time, plot_lines, plot_points, render_error_vs_time, render_lines};
