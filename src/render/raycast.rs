//! The plain ray cast of glsl/raycast.comp, one dispatch per chunk of view
//! samples ([`ViewChunks`]), variant chosen by specialization constant: the DVR and Phong baselines, and the emission term
//! alone that a lit technique renders for a scene without lights.

use super::frame_params::{frame_params, FrameParams, MarchSteps};
use super::frame_result::FrameResult;
use super::recorded_frame::{render_recorded, RecordedFrame};
use super::technique::ResourceNeed;
use super::view_chunks::ChunkSync;
use super::view_chunks::ViewChunks;
use super::{GpuScene, RenderError};
use crate::scene::Scene;
use crate::shaders::raycast;
use crate::vk::descriptors::Resource;
use crate::vk::interface::Binding;
use crate::vk::pipeline::{ComputePipeline, ComputePipelineDesc};
use crate::vk::{Buffer, Profiler, Recorder};
use ash::vk;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shading {
    Unshaded = 0,
    BlinnPhong = 1,
    /// The emission term `emission * rgb` alone: a lit technique with no lights.
    EmissionOnly = 2,
}

impl Shading {
    pub fn pass_name(self) -> &'static str {
        match self {
            Shading::Unshaded => "dvr",
            Shading::BlinnPhong => "phong",
            Shading::EmissionOnly => "emission_only",
        }
    }
}

pub fn render(
    gpu: &GpuScene,
    shading: Shading,
    width: u32,
    height: u32,
    profiler: &mut Profiler,
) -> Result<FrameResult, RenderError> {
    render_with(gpu, shading, (width, height), profiler, ChunkSync::Barrier)
}

/// [`render`] with the barrier between view chunks chosen: `RacyNoBarrier`
/// only proves that validation reports it.
pub fn render_with(
    gpu: &GpuScene,
    shading: Shading,
    size: (u32, u32),
    profiler: &mut Profiler,
    sync: ChunkSync,
) -> Result<FrameResult, RenderError> {
    render_recorded(gpu, |rec| record_with(gpu, shading, size, rec, profiler, sync))
}

/// Records the frame into `rec` (see [`RecordedFrame`]).
pub fn record_with(
    gpu: &GpuScene,
    shading: Shading,
    (width, height): (u32, u32),
    rec: &mut Recorder,
    profiler: &mut Profiler,
    sync: ChunkSync,
) -> Result<RecordedFrame, RenderError> {
    let ctx = gpu.ctx;
    let name = shading.pass_name();
    let chunks = ViewChunks::for_render(gpu.scene, name, iterations_per_sample(gpu.scene, shading))?;
    let params = frame_params(gpu.scene, width, height, gpu.lut_size, MarchSteps::render(gpu.scene));
    let frame = Buffer::with_data(ctx, "frame params", &[params], vk::BufferUsageFlags::STORAGE_BUFFER)?;
    let pipeline = ComputePipeline::new(
        ctx,
        &ComputePipelineDesc { name, shader: &raycast::INTERFACE, specialization: &[(0, shading as u32)], max_sets: 2 },
    )?;
    let shared = [
        (raycast::FRAME_BUFFER, Resource::StorageBuffer(&frame)),
        (raycast::VOLUME_TEX, Resource::SampledImage(&gpu.volume, &gpu.sampler)),
        (raycast::TRANSFER_LUT, Resource::StorageBuffer(&gpu.lut)),
        (raycast::LIGHTS, Resource::StorageBuffer(&gpu.lights)),
    ];
    let march = ChunkedMarch { name, chunks, size: (width, height), sync };
    let mut recorded = march.record(gpu, pipeline, &shared, [raycast::OUT_IMAGE, raycast::STATE_IN], rec, profiler)?;
    recorded.keep_alive.push(Box::new(frame));
    Ok(recorded)
}

/// One frame's view march in chunks ([`ViewChunks`]), ping-ponging between
/// the output and the state image: what every ray caster of
/// [`ViewChunks`] records the same way.
pub struct ChunkedMarch<'a> {
    /// Pass name: debug label, profiler scope, and the images' names.
    pub name: &'a str,
    pub chunks: ViewChunks,
    pub size: (u32, u32),
    pub sync: ChunkSync,
}

impl ChunkedMarch<'_> {
    /// Takes the output and the state image ([`super::FrameImages`]), binds them with `shared` (the
    /// bindings besides the two images, named `[output, state]` by
    /// `image_bindings`) and records the chunks into `rec` in one profiler
    /// scope. The caller adds what `shared` refers to to the frame's
    /// `keep_alive`.
    pub fn record(
        &self,
        gpu: &GpuScene,
        mut pipeline: ComputePipeline,
        shared: &[(Binding, Resource)],
        [out_binding, state_binding]: [Binding; 2],
        rec: &mut Recorder,
        profiler: &mut Profiler,
    ) -> Result<RecordedFrame, RenderError> {
        let ctx = gpu.ctx;
        let (name, (width, height)) = (self.name, self.size);
        let output = gpu.frame_images.output(ctx, &format!("{name} output"), width, height)?;
        let state = self.chunks.state_image(gpu, &format!("{name} view chunk state"), width, height)?;
        // Set 0 writes the output and reads the state image, set 1 the opposite.
        let mut sets = [vk::DescriptorSet::null(); 2];
        for (i, (write, read)) in [(&output.image, &*state), (&*state, &output.image)].into_iter().enumerate() {
            let mut bindings = shared.to_vec();
            bindings.push((out_binding, Resource::StorageImage(write)));
            bindings.push((state_binding, Resource::StorageImage(read)));
            sets[i] = pipeline.create_set(&bindings)?;
        }
        output.prepare_for_compute_read_write(rec);
        rec.discard_for_compute("view_chunk_state_discard_to_compute_access", &[&state]);
        let scope = profiler.begin(rec, name)?;
        self.chunks.record(rec, &pipeline, sets, (width, height), self.sync);
        profiler.end(rec, scope)?;
        Ok(RecordedFrame::counted(rec, output, vec![Box::new(state), Box::new(pipeline)]))
    }
}

/// A lit technique's frame for a scene without lights: no light, nothing to
/// sweep or propagate, so the emission-absorption ray cast alone.
pub fn emission_only(
    gpu: &GpuScene,
    width: u32,
    height: u32,
    profiler: &mut Profiler,
) -> Result<FrameResult, RenderError> {
    render(gpu, Shading::EmissionOnly, width, height, profiler)
}

/// What [`render`] allocates.
pub fn resources(scene: &Scene, shading: Shading, width: u32, height: u32) -> Vec<ResourceNeed> {
    let name = shading.pass_name();
    let mut needs = vec![
        ResourceNeed::output_image(&format!("{name} output"), width, height),
        ResourceNeed::of::<FrameParams>("frame params", 1),
    ];
    if let Ok(chunks) = ViewChunks::for_render(scene, name, iterations_per_sample(scene, shading)) {
        needs.push(chunks.state_resource(&format!("{name} view chunk state"), width, height));
    }
    needs
}

/// Loop iterations one view sample costs: the sample, and for Blinn-Phong the
/// loop over the lights, which llvmpipe counts as one iteration more than it
/// runs (measured).
fn iterations_per_sample(scene: &Scene, shading: Shading) -> u64 {
    1 + if shading == Shading::BlinnPhong { scene.lights.len() as u64 + 1 } else { 0 }
}
