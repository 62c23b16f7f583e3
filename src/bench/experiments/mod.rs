//! What the bench commands measure that is not argument wiring: scene
//! variants, update sequences and the loops that time them.

pub mod error;
pub mod lights;
pub mod stability;
pub mod stability_cases;

pub use error::ExperimentError;
