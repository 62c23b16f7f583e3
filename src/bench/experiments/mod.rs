//! What the bench commands measure that is not argument wiring: scene
//! variants, update sequences and the loops that time them.

pub mod ao_bench;
pub mod dispatch_probe;
pub mod error;
pub mod image_sizes;
pub mod ipsvi_bench;
pub mod ipsvi_breakdown;
pub mod lights;
pub mod lights_bench;
pub mod stability;
pub mod stability_bench;
pub mod stability_cases;
pub mod sync;
pub mod table1_bench;

pub use error::ExperimentError;
