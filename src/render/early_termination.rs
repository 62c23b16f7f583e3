//! The transmittance below which view rays stop, shared by the CPU renderers and
//! every shader: build.rs compiles this file too and defines
//! `EARLY_TERMINATION_TRANSMITTANCE` in the GLSL from it (glsl/view_ray.glsl).

/// DVR, Phong, the light volume's ray cast and IPSVI's view rays (when early
/// termination is on) stop once their transmittance falls below this. The
/// ground truth stops at `reference.min_transmittance` instead.
pub const EARLY_TERMINATION_TRANSMITTANCE: f64 = 1e-4;
