//! What a technique is: a name, the optical model it approximates, the GPU
//! memory a frame allocates, and the recording of a frame. Each technique's
//! module has one small type implementing [`RenderTechnique`]; the list of
//! them, which the command line names, is [`crate::techniques::registry`].

use super::error::RenderError;
use super::frame_result::FrameResult;
use super::gpu_scene::GpuScene;
use super::recorded_frame::RecordedFrame;
use super::session::FrameSession;
use crate::scene::{OpticalModel, Scene};
use crate::vk::{Profiler, Recorder};

pub trait RenderTechnique: Sync {
    /// What `--technique` calls it.
    fn name(&self) -> &'static str;

    /// One line for the `--technique` help.
    fn summary(&self) -> &'static str;

    /// The ground-truth model it is compared with (docs/optical-model.md).
    fn reference_model(&self, scene: &Scene) -> OpticalModel;

    /// Whether that ground truth uses coloured extinction along shadow rays
    /// (`reference.chromatic`); by default the scene's choice.
    fn reference_chromatic(&self, scene: &Scene) -> bool {
        scene.reference.chromatic
    }

    /// The device memory one frame allocates, by resource, beside the scene's
    /// own (volume, transfer LUT, lights).
    fn resources(&self, scene: &Scene, width: u32, height: u32) -> Vec<ResourceNeed>;

    /// Records, runs and reads back one frame of `gpu.scene`, with its settings
    /// (`gpu.scene.settings`) checked first.
    fn render(
        &self,
        gpu: &GpuScene,
        width: u32,
        height: u32,
        profiler: &mut Profiler,
    ) -> Result<FrameResult, RenderError>;

    /// Records one frame of `gpu.scene` into `rec`, a command buffer its caller
    /// submits (the viewer: with its present pass, in one submission), leaving
    /// it in an output image ([`RecordedFrame`]). `render` is this plus a
    /// read-back where a technique has it. `None`: the technique cannot
    /// (it submits several times, or finishes the image on the host), and the
    /// viewer uploads what `render` returns.
    fn record(
        &self,
        _gpu: &GpuScene,
        _rec: &mut Recorder,
        _width: u32,
        _height: u32,
        _profiler: &mut Profiler,
    ) -> Result<Option<RecordedFrame>, RenderError> {
        Ok(None)
    }

    /// A session that keeps state across frames of `gpu` (the viewer), for a
    /// technique that has such state; `None`: each frame is rendered anew by
    /// `render` ([`crate::techniques::registry::session`] does that).
    fn session<'s>(&self, _gpu: &'s GpuScene<'s>) -> Result<Option<Box<dyn FrameSession + 's>>, RenderError> {
        Ok(None)
    }

    /// Refuses what the technique cannot honour of `scene` (a step past what
    /// its march can take), naming the setting; run before any GPU work.
    fn check(&self, _scene: &Scene) -> Result<(), RenderError> {
        Ok(())
    }

    /// What of `scene` the technique renders only approximately, beyond its
    /// stated bound against the reference of its model, each naming the
    /// cause ([`super::light_grid_limits`]); printed as warnings, never silent.
    fn warnings(&self, _scene: &Scene) -> Vec<String> {
        Vec::new()
    }

    /// A line worth printing beside the frame's figures (IPSVI's sync strategy).
    fn settings_note(&self, _scene: &Scene) -> Option<String> {
        None
    }
}

/// One GPU resource a frame allocates.
#[derive(Clone, Debug, PartialEq)]
pub struct ResourceNeed {
    pub name: String,
    /// Bytes of its contents (a driver may pad an image's rows and layers).
    pub bytes: u64,
    /// For an image: texels along x, y, z and bytes per texel.
    pub image: Option<([u32; 3], u32)>,
}

impl ResourceNeed {
    pub fn buffer(name: &str, bytes: u64) -> ResourceNeed {
        ResourceNeed { name: name.to_string(), bytes, image: None }
    }

    /// `count` values of `T` (a parameter buffer).
    pub fn of<T>(name: &str, count: usize) -> ResourceNeed {
        ResourceNeed::buffer(name, (count * std::mem::size_of::<T>()) as u64)
    }

    pub fn image(name: &str, extent: [u32; 3], texel_bytes: u32) -> ResourceNeed {
        let bytes = extent.iter().map(|&e| e as u64).product::<u64>() * texel_bytes as u64;
        ResourceNeed { name: name.to_string(), bytes, image: Some((extent, texel_bytes)) }
    }

    /// An RGBA32F image of `width` x `height` (render::OutputImage).
    pub fn output_image(name: &str, width: u32, height: u32) -> ResourceNeed {
        ResourceNeed::image(name, [width, height, 1], 16)
    }
}

/// Bytes of all `needs`.
pub fn total_bytes(needs: &[ResourceNeed]) -> u64 {
    needs.iter().map(|n| n.bytes).sum()
}
