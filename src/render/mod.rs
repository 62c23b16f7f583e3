//! What every GPU technique shares: the scene uploaded once ([`GpuScene`]), the
//! frame parameters, the output image and its readback, and the list of
//! techniques the CLI can name. Each technique lives in its own module.

pub mod error;
pub mod frame_params;
pub mod gpu_scene;
pub mod output;
pub mod technique;

pub use error::RenderError;
pub use gpu_scene::{GpuScene, VolumeTexels};
pub use output::OutputImage;
pub use technique::{render, RenderOutput, Technique};
