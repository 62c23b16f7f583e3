//! Ground truth on the GPU (glsl/reference.comp): every view sample traces a
//! brute-force shadow ray to every light. llvmpipe silently ends an invocation
//! after 65,535 loop iterations, so the view rays are marched in chunks of
//! samples, one dispatch per chunk, each within a loop budget; the partial sums
//! travel between dispatches through a ping-pong pair of images. Shadow rays
//! step over the volume's empty cells ([`crate::render::empty_cells`]), where every
//! sample would add exactly 0: the same image as marching every sample.

use crate::render::empty_cells::EmptyCells;
use crate::render::frame_params::{frame_params, FrameParams, MarchSteps};
use crate::render::view_chunks::{ChunkSync, LOOP_BUDGET};
use crate::render::{
    render_recorded, FrameResult, GpuScene, RecordedFrame, RenderError, RenderTechnique, ResourceNeed,
};
use crate::scene::{OpticalModel, Scene};
use crate::shaders::reference as shader;
use crate::vk::barriers::{Access, Barrier};
use crate::vk::descriptors::Resource;
use crate::vk::pipeline::{ComputePipeline, ComputePipelineDesc};
use crate::vk::{Buffer, Profiler, Recorder};
use ash::vk;
use bytemuck::{Pod, Zeroable};

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct ChunkPush {
    first_sample: u32,
    sample_count: u32,
    is_first: u32,
    is_last: u32,
}

crate::assert_gpu_layout!(ChunkPush, shader::layout::CHUNK, [first_sample, sample_count, is_first, is_last]);

/// How the view rays are split into dispatches.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ChunkPlan {
    /// Most view samples any ray can take.
    pub max_view_samples: u64,
    /// Most shadow samples any shadow ray can take.
    pub max_shadow_samples: u64,
    pub samples_per_chunk: u64,
    pub chunks: u64,
}

impl ChunkPlan {
    pub fn new(diagonal_voxels: f64, view_step_voxels: f64, shadow_step_voxels: f64, lights: u64) -> ChunkPlan {
        // +1: ceil of a length that is itself rounded in f32 on the GPU.
        let max_view_samples = (diagonal_voxels / view_step_voxels).ceil() as u64 + 1;
        let max_shadow_samples = (diagonal_voxels / shadow_step_voxels).ceil() as u64 + 1;
        // Per view sample: the sample itself, and per light the box test (3) and the shadow march.
        let per_sample = 1 + lights * (max_shadow_samples + 3);
        let samples_per_chunk = (LOOP_BUDGET / per_sample).max(1);
        ChunkPlan {
            max_view_samples,
            max_shadow_samples,
            samples_per_chunk,
            chunks: max_view_samples.div_ceil(samples_per_chunk),
        }
    }

    /// Loop iterations of one invocation in one dispatch, at most.
    pub fn iterations_per_dispatch(&self, lights: u64) -> u64 {
        self.samples_per_chunk * (1 + lights * (self.max_shadow_samples + 3))
    }
}

pub fn plan_for(gpu: &GpuScene) -> ChunkPlan {
    let bx = gpu.scene.volume_box();
    let diagonal_voxels = (2.0 * bx.half_extent.length() / bx.voxel_length) as f64;
    ChunkPlan::new(
        diagonal_voxels,
        gpu.scene.reference.step_voxels as f64,
        gpu.scene.reference.shadow_step_voxels as f64,
        gpu.scene.lights.len() as u64,
    )
}

/// Ground truth on the GPU, of the model the scene names.
pub struct Reference;

impl RenderTechnique for Reference {
    fn name(&self) -> &'static str {
        "reference"
    }
    fn summary(&self) -> &'static str {
        "ground truth: brute-force shadow rays per sample (model of [reference])"
    }
    fn reference_model(&self, scene: &Scene) -> OpticalModel {
        scene.reference.model
    }
    fn resources(&self, scene: &Scene, width: u32, height: u32) -> Vec<ResourceNeed> {
        vec![
            ResourceNeed::output_image("reference accum a", width, height),
            ResourceNeed::output_image("reference accum b", width, height),
            ResourceNeed::of::<FrameParams>("frame params", 1),
            ResourceNeed::of::<u32>("reference empty cells", EmptyCells::buffer_len(&scene.volume)),
        ]
    }
    fn render(
        &self,
        gpu: &GpuScene,
        width: u32,
        height: u32,
        profiler: &mut Profiler,
    ) -> Result<FrameResult, RenderError> {
        render_with(gpu, width, height, profiler, ChunkSync::Barrier)
    }
    fn record(
        &self,
        gpu: &GpuScene,
        rec: &mut Recorder,
        width: u32,
        height: u32,
        profiler: &mut Profiler,
    ) -> Result<Option<RecordedFrame>, RenderError> {
        record_with(gpu, (width, height), rec, profiler, ChunkSync::Barrier, EmptyCells::of_scene(gpu)).map(Some)
    }
}

pub fn render_with(
    gpu: &GpuScene,
    width: u32,
    height: u32,
    profiler: &mut Profiler,
    sync: ChunkSync,
) -> Result<FrameResult, RenderError> {
    render_with_cells(gpu, (width, height), profiler, sync, EmptyCells::of_scene(gpu))
}

/// As [`render_with`], the shadow rays stepping over `cells`' empty cells
/// ([`EmptyCells::none_empty`]: every sample, the brute-force march itself).
pub fn render_with_cells(
    gpu: &GpuScene,
    size: (u32, u32),
    profiler: &mut Profiler,
    sync: ChunkSync,
    cells: &EmptyCells,
) -> Result<FrameResult, RenderError> {
    render_recorded(gpu, |rec| record_with(gpu, size, rec, profiler, sync, cells))
}

/// Records the frame into `rec` (see [`RecordedFrame`]): the image the last
/// chunk wrote is the output.
pub fn record_with(
    gpu: &GpuScene,
    (width, height): (u32, u32),
    rec: &mut Recorder,
    profiler: &mut Profiler,
    sync: ChunkSync,
    cells: &EmptyCells,
) -> Result<RecordedFrame, RenderError> {
    let ctx = gpu.ctx;
    let scene = gpu.scene;
    let params = frame_params(scene, width, height, gpu.lut_size, MarchSteps::reference(scene));
    let frame = Buffer::with_data(ctx, "frame params", &[params], vk::BufferUsageFlags::STORAGE_BUFFER)?;
    // Written by the host before the submission: no barrier.
    let cells =
        Buffer::with_data(ctx, "reference empty cells", &cells.buffer_words(), vk::BufferUsageFlags::STORAGE_BUFFER)?;
    let accum = [
        gpu.frame_images.output(ctx, "reference accum a", width, height)?,
        gpu.frame_images.output(ctx, "reference accum b", width, height)?,
    ];
    if scene.reference.chromatic && scene.reference.model != OpticalModel::SingleScattering {
        return Err(RenderError::Invalid(
            "reference.chromatic = true needs reference.model = \"single-scattering\"".into(),
        ));
    }
    let model = match scene.reference.model {
        OpticalModel::SingleScattering => 0,
        OpticalModel::EmissiveScattering => 1,
    };
    let mut pipeline = ComputePipeline::new(
        ctx,
        &ComputePipelineDesc {
            name: "reference",
            shader: &shader::INTERFACE,
            specialization: &[(0, model), (1, scene.reference.chromatic as u32)],
            max_sets: 2,
        },
    )?;
    let mut sets = Vec::new();
    for (src, dst) in [(0, 1), (1, 0)] {
        sets.push(pipeline.create_set(&[
            (shader::FRAME_BUFFER, Resource::StorageBuffer(&frame)),
            (shader::VOLUME_TEX, Resource::SampledImage(&gpu.volume, &gpu.sampler)),
            (shader::TRANSFER_LUT, Resource::StorageBuffer(&gpu.lut)),
            (shader::LIGHTS, Resource::StorageBuffer(&gpu.lights)),
            (shader::ACCUM_IN, Resource::StorageImage(&accum[src].image)),
            (shader::ACCUM_OUT, Resource::StorageImage(&accum[dst].image)),
            (shader::EMPTY_CELLS, Resource::StorageBuffer(&cells)),
        ])?);
    }
    let plan = plan_for(gpu);
    let mut last_written = 0;
    for a in &accum {
        a.prepare_for_compute_read_write(rec);
    }
    let scope = profiler.begin(rec, "reference")?;
    for chunk in 0..plan.chunks {
        if chunk > 0 && sync == ChunkSync::Barrier {
            // The next chunk reads what this one wrote, and overwrites what the
            // one before read: a write->read and read->write dependency.
            rec.barrier(&Barrier::memory(
                "accum_write_to_next_chunk_read",
                Access::COMPUTE_WRITE,
                Access::COMPUTE_READ_WRITE,
            ));
        }
        let detail = profiler.begin_detail(rec, "reference_chunk")?;
        let set_index = (chunk % 2) as usize;
        rec.bind(&pipeline, sets[set_index]);
        let push = ChunkPush {
            first_sample: (chunk * plan.samples_per_chunk) as u32,
            sample_count: plan.samples_per_chunk as u32,
            is_first: (chunk == 0) as u32,
            is_last: (chunk + 1 == plan.chunks) as u32,
        };
        rec.push(&pipeline, &push);
        rec.dispatch(width.div_ceil(8), height.div_ceil(8), 1);
        profiler.end(rec, detail)?;
        last_written = 1 - set_index;
    }
    profiler.end(rec, scope)?;
    let [a, b] = accum;
    let (output, other) = if last_written == 0 { (a, b) } else { (b, a) };
    Ok(RecordedFrame::counted(rec, output, vec![Box::new(other), Box::new(frame), Box::new(cells), Box::new(pipeline)]))
}
