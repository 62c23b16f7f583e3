//! How a view march is split into dispatches (glsl/view_chunk.glsl). llvmpipe
//! silently ends an invocation after 65,535 loop iterations, so a march longer
//! than [`LOOP_BUDGET`] iterations runs as several dispatches of consecutive
//! sample ranges, the partial (colour, transmittance) carried from one to the
//! next behind a named barrier. The chunks ping-pong between the output image
//! and a state image of the same size, each reading one (bound readonly) and
//! writing the other (writeonly), so that synchronization validation sees a
//! missing barrier (it cannot on an image bound read-write); the last chunk
//! writes the output. At ordinary steps the plan is one chunk and the state
//! image a 1x1 placeholder the shader never reads.

use super::error::RenderError;
use super::gpu_scene::GpuScene;
use super::technique::ResourceNeed;
use crate::scene::Scene;
use crate::vk::barriers::{Access, Barrier};
use crate::vk::pipeline::ComputePipeline;
use crate::vk::{Image, Recorder};
use ash::vk;
use bytemuck::{Pod, Zeroable};
use std::sync::Arc;

/// Loop iterations one invocation may run per dispatch: below llvmpipe's 65,535.
pub const LOOP_BUDGET: u64 = 60_000;

/// Whether consecutive chunks are separated by their barrier.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ChunkSync {
    Barrier,
    /// RACY: no barrier between chunks. Only for proving that synchronization
    /// validation reports the missing barrier; its image is undefined.
    RacyNoBarrier,
}

/// Most view samples a ray may take: the sample index and position are computed
/// in f32, exact only up to 2^24; past that, samples would repeat or skip.
pub const MAX_VIEW_SAMPLES: u64 = 1 << 24;

/// The push constants of glsl/view_chunk.glsl.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
pub struct ViewChunkPush {
    pub first_sample: u32,
    pub sample_count: u32,
    pub is_first: u32,
    pub is_last: u32,
}

crate::assert_gpu_layout!(
    ViewChunkPush,
    crate::shaders::raycast::layout::VIEW_CHUNK,
    [first_sample, sample_count, is_first, is_last]
);

/// The view march of one frame, split into dispatches.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ViewChunks {
    /// Most view samples any ray can take.
    pub max_view_samples: u64,
    pub samples_per_chunk: u64,
    pub chunks: u64,
}

/// The volume box's diagonal in voxels: no view ray inside the box is longer.
pub fn diagonal_voxels(scene: &Scene) -> f64 {
    let bx = scene.volume_box();
    2.0 * bx.half_extent.as_dvec3().length() / bx.voxel_length as f64
}

/// The smallest `render.step` (voxels) whose longest ray stays within
/// [`MAX_VIEW_SAMPLES`].
pub fn smallest_view_step(scene: &Scene) -> f64 {
    diagonal_voxels(scene) / (MAX_VIEW_SAMPLES - 1) as f64
}

impl ViewChunks {
    /// `iterations_per_sample`: loop iterations one sample costs an invocation
    /// (its own and those of loops inside it).
    pub fn new(diagonal_voxels: f64, step_voxels: f64, iterations_per_sample: u64) -> ViewChunks {
        // +1: ceil of a length that is itself rounded in f32 on the GPU.
        let max_view_samples = (diagonal_voxels / step_voxels).ceil() as u64 + 1;
        // 16: the box test and the set-up before the march, with room to spare.
        let samples_per_chunk = ((LOOP_BUDGET - 16) / iterations_per_sample.max(1)).max(1);
        ViewChunks { max_view_samples, samples_per_chunk, chunks: max_view_samples.div_ceil(samples_per_chunk) }
    }

    /// The plan for `technique` marching `scene` at `render.step`, or an error
    /// naming the setting when the step is below [`smallest_view_step`].
    pub fn for_render(scene: &Scene, technique: &str, iterations_per_sample: u64) -> Result<ViewChunks, RenderError> {
        check_view_step(scene, technique)?;
        Ok(ViewChunks::new(diagonal_voxels(scene), scene.render.step_voxels as f64, iterations_per_sample))
    }

    pub fn push(&self, chunk: u64) -> ViewChunkPush {
        ViewChunkPush {
            first_sample: (chunk * self.samples_per_chunk) as u32,
            sample_count: self.samples_per_chunk as u32,
            is_first: (chunk == 0) as u32,
            is_last: (chunk + 1 == self.chunks) as u32,
        }
    }

    /// Size of the state image: the frame's with more than one chunk, else a
    /// 1x1 placeholder (bound, never read).
    pub fn state_extent(&self, width: u32, height: u32) -> [u32; 2] {
        if self.chunks > 1 {
            [width, height]
        } else {
            [1, 1]
        }
    }

    /// The state image the chunks ping-pong with the output (RGBA32F).
    pub fn state_image(&self, gpu: &GpuScene, name: &str, width: u32, height: u32) -> Result<Arc<Image>, RenderError> {
        let [w, h] = self.state_extent(width, height);
        let format = vk::Format::R32G32B32A32_SFLOAT;
        Ok(gpu.frame_images.storage_2d(gpu.ctx, name, format, (w, h), vk::ImageUsageFlags::empty())?)
    }

    /// What [`ViewChunks::state_image`] allocates.
    pub fn state_resource(&self, name: &str, width: u32, height: u32) -> ResourceNeed {
        let [w, h] = self.state_extent(width, height);
        ResourceNeed::image(name, [w, h, 1], 16)
    }

    /// Which set chunk `chunk` dispatches with: 0 writes the output (and reads
    /// the state image), 1 writes the state image (and reads the output), so
    /// that the last chunk writes the output.
    pub fn set_of(&self, chunk: u64) -> usize {
        ((self.chunks - 1 - chunk) % 2) as usize
    }

    /// Records the chunks' dispatches over a `width` x `height` image with
    /// `sets` (see [`ViewChunks::set_of`]), the pipeline bound. `sync` leaves
    /// the barrier out only to prove that validation reports it.
    pub fn record(
        &self,
        rec: &mut Recorder,
        pipeline: &ComputePipeline,
        sets: [vk::DescriptorSet; 2],
        (width, height): (u32, u32),
        sync: ChunkSync,
    ) {
        for chunk in 0..self.chunks {
            if chunk > 0 && sync == ChunkSync::Barrier {
                // The next chunk reads the colour and transmittance this one
                // wrote, and overwrites what the one before it read.
                rec.barrier(&Barrier::memory(
                    "view_chunk_write_to_next_chunk_read",
                    Access::COMPUTE_WRITE,
                    Access::COMPUTE_READ_WRITE,
                ));
            }
            rec.bind(pipeline, sets[self.set_of(chunk)]);
            rec.push(pipeline, &self.push(chunk));
            rec.dispatch(width.div_ceil(8), height.div_ceil(8), 1);
        }
    }
}

/// `render.step` refused, naming the technique and the smallest step it
/// supports for this scene, when a ray would take more than
/// [`MAX_VIEW_SAMPLES`] samples (or the step is not a positive number).
pub fn check_view_step(scene: &Scene, technique: &str) -> Result<(), RenderError> {
    let step = scene.render.step_voxels as f64;
    let smallest = smallest_view_step(scene);
    if !step.is_finite() || step < smallest {
        return Err(RenderError::Invalid(format!(
            "render.step = {:e} voxels is too small for {technique} on this scene: a view ray would take \
             more than {MAX_VIEW_SAMPLES} samples; the smallest step it supports here is {smallest:.3e} voxels",
            scene.render.step_voxels
        )));
    }
    Ok(())
}
