//! How far a rendered image is from a reference: error statistics on linear RGB,
//! the shape of the error (stripes, grain), the per-pixel error field, and the
//! colour map that shows it.

pub mod colormap;
pub mod error;
pub mod error_structure;
pub mod pixel_errors;
pub mod stats;

pub use error::MetricsError;
pub use error_structure::{error_structure, ErrorStructure};
pub use pixel_errors::pixel_errors;
pub use stats::{compare, ErrorStats};
