//! Light volume illumination (selective light updates, Sundén and Ropinski
//! 2015, sections 3-6). An RGBA32F illumination volume at 1, 1/2 or 1/4 of the
//! data resolution holds the light arriving at each voxel; lights are
//! propagated through it slice by slice in coherence-based groups (one per axis
//! direction, [`groups`]), each pass recorded into its own secondary command
//! buffer ([`propagation`]) and replayed while its lights are unchanged
//! ([`pass_cache`]). The volume persists ([`renderer`]): a frame propagates
//! only what changed, subtracting old light states and adding new ones in the
//! same passes, unless the cost estimate of section 5 prefers an entire update
//! ([`plan`]); compensated sums keep subtraction from drifting. A ray cast then
//! lights each sample by the interpolated volume ([`raycast`]).
//!
//! Approximates optical model (i) (docs/optical-model.md), by default its
//! chromatic variant (`chromatic`: per-channel transmittance, the paper's
//! l_i = (1 - alpha) l_{i-1} + alpha c l_{i-1}); the propagated quantity is each
//! light's transmittance (its colour, falloff and cone are applied per voxel).
//! Between slices the medium is sampled once per voxel along the axis and
//! shared by every light of the pass (`shared_medium`, the default and the
//! paper's), or integrated along each light's own direction; the lights of a
//! pass are summed in registers (two-float) and written into the volume once
//! per voxel. A path ends where the light enters the volume, through any face,
//! or at the light (within four slices of a point light it is integrated to
//! the light). Lights inside the volume use all six groups, lights beside it
//! both directions of an axis ([`groups`]): no light is dropped.
//! Where it falls short of the model: light is known at illumination voxel
//! centres only, so shadows are blurred by the grid and by bilinear resampling
//! from slice to slice (which overestimates the convex exp(-depth), most for
//! oblique light), and surfaces sharper than a voxel are lit by interpolation
//! (log-space in the ray cast, which follows the exponential decay into a
//! surface, and extrapolates it over the half voxel next to the box faces).
//! A light outside splits between two groups by the factors of equations
//! 5a/5b, each following the light's own direction.

mod controls;
pub mod directional_step;
pub mod groups;
pub mod illumination;
pub mod pass_cache;
pub mod plan;
pub mod propagation;
pub mod raycast;
pub mod renderer;
pub mod session;
pub mod settings;
pub mod technique;

pub use groups::{contributions, group_passes, Contribution, PropagationGroup};
pub use illumination::{IlluminationReadback, IlluminationVolume};
pub use plan::{UpdateKind, UpdatePlan};
pub use renderer::{LightVolumeFrame, LightVolumeRenderer, UpdateReport};
pub use settings::{CostEstimate, LightVolumeSettings};
pub use technique::LightVolume;

use crate::render::{GpuScene, RenderError};
use crate::vk::Profiler;

/// Renders one frame of the scene's lights from an empty volume (an entire
/// update); with `read_illumination` also
/// reads the illumination volume back.
pub fn render_frame(
    gpu: &GpuScene,
    width: u32,
    height: u32,
    profiler: &mut Profiler,
    read_illumination: bool,
) -> Result<LightVolumeFrame, RenderError> {
    let lights: Vec<_> = gpu.scene.lights.iter().copied().map(Some).collect();
    LightVolumeRenderer::new(gpu)?.render(&lights, width, height, profiler, read_illumination)
}
