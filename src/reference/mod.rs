//! Ground truth: the optical models of docs/optical-model.md integrated brute
//! force, on the CPU in f64 and on the GPU.

pub mod gpu;
