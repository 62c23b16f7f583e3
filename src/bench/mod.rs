//! Benchmark reports shared by every `sweeplab bench ...` sweep: one [`BenchRow`]
//! per run, written as CSV, JSON and a Markdown table; the Pareto front of
//! (GPU time, error); charts as PNG and SVG ([`charts`], by plotters); and a progress line
//! on stderr while the sweep runs. Configurations that are compared are
//! measured side by side in the shuffled rounds of [`Interleaved`] (the
//! [`protocol`]); [`Harness`] times one configuration's repeats in a block,
//! for what is compared with nothing else; [`frames`] times technique and
//! IPSVI frames, and [`experiments`] holds what the bench commands measure.

pub mod charts;
pub mod cpu_time;
pub mod error;
pub mod estimate;
pub mod experiment;
pub mod experiments;
pub mod frames;
pub mod harness;
pub mod interleaved;
pub mod out_folder;
pub mod pareto;
pub mod progress;
pub mod protocol;
pub mod rows;
pub mod run_info;
pub mod shift;
pub mod stats;

pub use charts::{
    palette_color, plot_error_map, plot_error_vs_time, plot_heat_map, plot_histogram, plot_lines, plot_point_panels,
    plot_points, plot_stacked_bars, render_error_map, render_error_vs_time, render_heat_map, render_histogram,
    render_lines, render_point_panels, render_stacked_bars, AxisScale, Chart, Distribution, ErrorMap, HeatCell,
    HeatLevel, HeatMap, Panel, Point, Series, StackedBar,
};
pub use error::BenchError;
pub use estimate::{Estimate, Verdict};
pub use experiment::Experiment;
pub use experiments::ExperimentError;
pub use frames::{ipsvi_frame, technique_frame, ProfiledFrame};
pub use harness::{Harness, HarnessError, Measurement, Sample};
pub use interleaved::{Interleaved, Timings};
pub use out_folder::{OutFolder, OutFolderError};
pub use pareto::pareto_front;
pub use progress::Progress;
pub use protocol::{Protocol, ProtocolError};
pub use rows::{BenchRow, BenchTable, BenchValue};
pub use run_info::RunInfo;
pub use stats::{fit_line, LineFit};
