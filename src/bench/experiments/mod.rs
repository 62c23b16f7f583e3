//! What the bench commands measure that is not argument wiring: scene
//! variants, update sequences and the loops that time them.

pub mod ao;
pub mod dispatch_probe;
pub mod error;
pub mod image_sizes;
pub mod ipsvi;
pub mod lights;
pub mod stability;
pub mod sync;
pub mod table1;

pub use error::ExperimentError;
