//! Ground truth: the optical models of docs/optical-model.md integrated brute
//! force, on the CPU in f64 (following the discretization written there to the
//! letter) and on the GPU (brute-force shadow rays, split into dispatches).
//!
//! Entry points: [`render_cpu`] for a whole image, [`render_pixel_cpu`] for one
//! ray (tests check single rays against closed forms), a [`CpuRenderer`] to
//! render many pixels of one prepared scene, and [`gpu::render`].

pub mod cpu;
pub mod filter_bound;
pub mod gpu;
pub mod medium;
mod parallel;
pub mod ray_start;
pub mod shadow;
pub mod sources;
pub mod validate;

pub use cpu::{render_cpu, render_pixel_cpu, CpuRenderKind, CpuRenderer, EARLY_TERMINATION_TRANSMITTANCE};
pub use filter_bound::{filter_bound_image, FilterBound};
pub use validate::CpuRenderError;
