//! Light volume illumination (selective light updates, Jönsson/Ropinski et al.
//! 2015, sections 3-5; first part: full propagation every frame). An RGBA32F
//! illumination volume at 1, 1/2 or 1/4 of the data resolution holds the light
//! arriving at each voxel; lights are propagated through it slice by slice in
//! coherence-based groups (one per axis direction, [`groups`]), each group pass
//! recorded into its own secondary command buffer ([`propagation`]); a ray cast
//! then lights each sample by the interpolated volume ([`raycast`]).
//!
//! Approximates optical model (i) (docs/optical-model.md): the propagated
//! quantity is each light's transmittance (its colour, falloff and cone are
//! applied per voxel), so the paper's blend of the material colour into the
//! propagated light (model (ii)-like) is left out. Between slices the medium is
//! integrated in quarter-voxel sub-steps (exact for homogeneous media); a path
//! ends where the light enters the volume, through any face, or at the light.
//! Where it falls short of the model: light is known at illumination voxel
//! centres only, so shadows are blurred by the grid and by bilinear resampling
//! from slice to slice (which overestimates the convex exp(-depth), most for
//! oblique light), and surfaces sharper than a voxel are lit by interpolation
//! (log-space in the ray cast, which follows the exponential decay into a
//! surface). A light splits between two groups by the factors of equations
//! 5a/5b, each following the light's own direction. Light travelling against a
//! group's direction (only possible for the second group of a point or spot
//! light near or inside the volume) is not carried by that group.

pub mod groups;
pub mod illumination;
pub mod propagation;
pub mod raycast;
pub mod settings;

pub use groups::{propagation_groups, sequential_groups, PropagationGroup};
pub use illumination::IlluminationVolume;
pub use settings::LightVolumeSettings;

use crate::render::frame_params::{frame_params, MarchSteps};
use crate::render::technique::FrameResult;
use crate::render::{GpuScene, OutputImage, RenderError};
use crate::vk::commands::submit_and_wait;
use crate::vk::{Buffer, Profiler};
use ash::vk;
use glam::UVec3;
use propagation::Propagation;
use raycast::RayCast;

/// A frame and what the tests look at besides the image.
pub struct LightVolumeFrame {
    pub frame: FrameResult,
    /// Illumination volume size.
    pub grid: UVec3,
    /// The groups that were propagated, in order.
    pub groups: Vec<PropagationGroup>,
    /// The illumination volume (x fastest), when asked for.
    pub illumination: Option<Vec<[f32; 4]>>,
}

pub fn render(gpu: &GpuScene, width: u32, height: u32, profiler: &mut Profiler) -> Result<FrameResult, RenderError> {
    Ok(render_frame(gpu, width, height, profiler, false)?.frame)
}

/// Renders one frame; with `read_illumination` also reads the illumination
/// volume back.
pub fn render_frame(
    gpu: &GpuScene,
    width: u32,
    height: u32,
    profiler: &mut Profiler,
    read_illumination: bool,
) -> Result<LightVolumeFrame, RenderError> {
    let scene = gpu.scene;
    let settings = LightVolumeSettings::from_scene(scene)?;
    let ctx = gpu.ctx;
    let params = frame_params(scene, width, height, gpu.lut_size, MarchSteps::render(scene));
    let frame = Buffer::with_data(ctx, "frame params", &[params], vk::BufferUsageFlags::UNIFORM_BUFFER)?;
    let illumination = IlluminationVolume::new(ctx, scene.volume.dims, settings.scale)?;
    let output = OutputImage::new(ctx, "lightvolume output", width, height)?;
    let groups = if settings.coherent { propagation_groups(&scene.lights) } else { sequential_groups(&scene.lights) };
    let propagation =
        if groups.is_empty() { None } else { Some(Propagation::new(gpu, &frame, &illumination, groups.clone())?) };
    let secondaries = match &propagation {
        Some(p) => Some(p.record_secondaries(ctx)?),
        None => None,
    };
    let raycast = RayCast::new(gpu, &frame, &illumination, &output)?;
    let readback = output.readback_buffer(ctx)?;
    let illumination_readback = if read_illumination { Some(illumination.readback_buffer(ctx)?) } else { None };
    let (dispatches, barriers) = submit_and_wait(ctx, "frame", |rec| {
        output.prepare_for_compute_write(rec);
        illumination.record_clear(rec);
        if let (Some(p), Some(recorded)) = (&propagation, &secondaries) {
            p.record_prepare(rec);
            let scope = profiler.begin(rec, "lightvolume_propagation")?;
            for (i, group) in p.groups.iter().enumerate() {
                let group_scope = profiler.begin(rec, &group.scope_name())?;
                rec.execute(recorded, i);
                profiler.end(rec, group_scope)?;
            }
            profiler.end(rec, scope)?;
        }
        let scope = profiler.begin(rec, "lightvolume_raycast")?;
        raycast.record(rec, width, height);
        profiler.end(rec, scope)?;
        output.record_readback(rec, &readback);
        if let Some(buffer) = &illumination_readback {
            illumination.record_readback(rec, buffer);
        }
        Ok((rec.dispatch_count, rec.barrier_count))
    })?;
    let image = output.read(&readback)?;
    let volume = match &illumination_readback {
        Some(buffer) => Some(illumination.read(buffer)?),
        None => None,
    };
    drop(secondaries);
    Ok(LightVolumeFrame {
        frame: FrameResult { image, dispatches, barriers },
        grid: illumination.size,
        groups,
        illumination: volume,
    })
}
