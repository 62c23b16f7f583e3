//! Benchmark reports shared by every `sweeplab bench ...` sweep: one [`BenchRow`]
//! per run, written as CSV, JSON and a Markdown table; the Pareto front of
//! (GPU time, error); PNG charts drawn without system fonts; and a progress line
//! on stderr while the sweep runs.

pub mod axis;
pub mod canvas;
pub mod error;
pub mod font;
pub mod pareto;
pub mod plot;
pub mod progress;
pub mod rows;
pub mod stats;

pub use axis::AxisScale;
pub use error::BenchError;
pub use pareto::pareto_front;
pub use plot::{palette_color, plot_error_vs_time, plot_lines, render_error_vs_time, render_lines, Chart, Series};
pub use progress::Progress;
pub use rows::{BenchRow, BenchTable, BenchValue};
pub use stats::{fit_line, median, LineFit};
