use std::path::PathBuf;

/// Everything that can go wrong while writing or reading a benchmark report.
#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    #[error("cannot write {path}: {source}")]
    Write { path: PathBuf, source: std::io::Error },
    #[error("cannot read {path}: {source}")]
    Read { path: PathBuf, source: std::io::Error },
    #[error("{path} is not a benchmark table in JSON (an array of flat objects): {source}")]
    Json { path: PathBuf, source: serde_json::Error },
    #[error("{path} is not a sync.json written by `sweeplab bench sync`: {source}")]
    NotSyncReport { path: PathBuf, source: serde_json::Error },
    #[error("cannot write the chart {path}: {source}")]
    Png { path: PathBuf, source: image::ImageError },
    #[error(
        "chart size {width}x{height} is outside the supported range \
         {min_width}x{min_height} to {max_side}x{max_side} pixels"
    )]
    ChartSize { width: u32, height: u32, min_width: u32, min_height: u32, max_side: u32 },
    #[error("cannot draw the chart: {0}")]
    Chart(String),
    #[error("a heat map of {rows} row label(s) and {columns} column label(s) needs as many rows of as many cells")]
    HeatMapShape { rows: usize, columns: usize },
}

impl<E: std::error::Error + Send + Sync> From<plotters::drawing::DrawingAreaErrorKind<E>> for BenchError {
    fn from(error: plotters::drawing::DrawingAreaErrorKind<E>) -> Self {
        BenchError::Chart(error.to_string())
    }
}
