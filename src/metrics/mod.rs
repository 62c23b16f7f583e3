//! How far a rendered image is from a reference: error statistics on linear RGB
//! and a false-colour map of where the error is.

pub mod colormap;
pub mod error;
pub mod heatmap;
pub mod stats;

pub use error::MetricsError;
pub use heatmap::{error_heatmap, save_heatmap};
pub use stats::{compare, ErrorStats};
