//! The ambient-occlusion ground truth ([`super`]) on the GPU
//! (glsl/ao_reference.comp): one invocation per voxel, the direction pairs
//! split into dispatches so that no invocation runs past llvmpipe's
//! 65,535-iteration cap, each dispatch adding to the sums the one before left,
//! behind a named barrier. The sums ping-pong between two buffers (one read,
//! the other written), so that synchronization validation sees a missing
//! barrier.

use ash::vk;
use bytemuck::{Pod, Zeroable};
use gpu_allocator::MemoryLocation;

use super::{direction_pairs, step_scale, AoReferenceParams};
use crate::render::view_chunks::{ChunkSync, LOOP_BUDGET};
use crate::render::{GpuScene, RenderError};
use crate::shaders::ao_reference as shader;
use crate::vk::barriers::{Access, Barrier};
use crate::vk::commands::submit_and_wait;
use crate::vk::descriptors::Resource;
use crate::vk::pipeline::{ComputePipeline, ComputePipelineDesc};
use crate::vk::staging::{copy_buffer, device_buffer_with_data, readback_buffer};
use crate::vk::{Buffer, Profiler};

/// The pass's name: debug label and profiler scope.
pub const PASS: &str = "ao_reference";

/// `AoReferenceParams` of glsl/ao_reference.comp (a std140 storage buffer).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuAoReferenceParams {
    pub dims: [u32; 4],
    pub step_scale: [f32; 4],
    pub radius: f32,
    pub lut_size: f32,
    pub steps: u32,
    pub inv_pairs: f32,
}

crate::assert_gpu_layout!(
    GpuAoReferenceParams,
    shader::layout::AO_REFERENCE_PARAMS,
    [dims, step_scale, radius, lut_size, steps, inv_pairs]
);

/// The push constants of glsl/ao_reference.comp.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Pod, Zeroable)]
pub struct AoReferenceChunk {
    pub first_pair: u32,
    pub pair_count: u32,
    pub is_first: u32,
    pub pad: u32,
}

crate::assert_gpu_layout!(AoReferenceChunk, shader::layout::CHUNK, [first_pair, pair_count, is_first, pad]);

/// Direction pairs per dispatch: an invocation's loop iterations (two rays of
/// `steps` samples and the pair itself) within [`LOOP_BUDGET`].
pub fn pairs_per_dispatch(params: &AoReferenceParams) -> u32 {
    let (steps, _) = params.samples();
    let per_pair = 2 * (steps as u64 + 1) + 1;
    ((LOOP_BUDGET - 16) / per_pair).clamp(1, u32::MAX as u64) as u32
}

/// The ground truth of `gpu`'s scene on the GPU: per voxel
/// `[forward, backward]` `(E rgb, O)` (entry 2 v + h). `pairs_per_chunk`
/// smaller than [`pairs_per_dispatch`] splits finer (tests); `sync` leaves the
/// barrier out only to prove that validation reports it.
pub fn reference_gpu(
    gpu: &GpuScene,
    params: &AoReferenceParams,
    pairs_per_chunk: Option<u32>,
    profiler: &mut Profiler,
    sync: ChunkSync,
) -> Result<Vec<[f32; 4]>, RenderError> {
    let ctx = gpu.ctx;
    let volume = &gpu.scene.volume;
    let (steps, h) = params.samples();
    let scale = step_scale(volume);
    let gpu_params = GpuAoReferenceParams {
        dims: [volume.dims.x, volume.dims.y, volume.dims.z, 0],
        step_scale: [scale.x as f32, scale.y as f32, scale.z as f32, h as f32],
        radius: params.radius as f32,
        lut_size: gpu.lut_size as f32,
        steps,
        inv_pairs: 1.0 / params.pairs.max(1) as f32,
    };
    let directions: Vec<[f32; 4]> = direction_pairs(params.pairs).iter().map(|w| [w[0], w[1], w[2], 0.0]).collect();
    let usage = vk::BufferUsageFlags::STORAGE_BUFFER;
    let params_buffer = Buffer::with_data(ctx, "ao reference params", &[gpu_params], usage)?;
    let directions = device_buffer_with_data(ctx, "ao reference directions", &directions, usage)?;
    let entries = 2 * volume.voxel_count();
    let bytes = entries as u64 * 16;
    // Device-local working sums; the last written goes to the host by a copy.
    let sums_usage = usage | vk::BufferUsageFlags::TRANSFER_SRC;
    let sums = [
        Buffer::new(ctx, "ao reference sums a", bytes, sums_usage, MemoryLocation::GpuOnly)?,
        Buffer::new(ctx, "ao reference sums b", bytes, sums_usage, MemoryLocation::GpuOnly)?,
    ];
    let readback = readback_buffer(ctx, "ao reference sums readback", bytes)?;
    let mut pipeline = ComputePipeline::new(
        ctx,
        &ComputePipelineDesc { name: PASS, shader: &shader::INTERFACE, specialization: &[], max_sets: 2 },
    )?;
    // Set i writes sums[i] and reads the other.
    let mut sets = [vk::DescriptorSet::null(); 2];
    for (i, set) in sets.iter_mut().enumerate() {
        *set = pipeline.create_set(&[
            (shader::PARAMS_BUFFER, Resource::StorageBuffer(&params_buffer)),
            (shader::VOLUME_TEX, Resource::SampledImage(&gpu.volume, &gpu.sampler)),
            (shader::TRANSFER_LUT, Resource::StorageBuffer(&gpu.lut)),
            (shader::DIRECTIONS, Resource::StorageBuffer(&directions)),
            (shader::SUMS_IN, Resource::StorageBuffer(&sums[1 - i])),
            (shader::SUMS_OUT, Resource::StorageBuffer(&sums[i])),
        ])?;
    }
    let per_chunk = pairs_per_chunk.unwrap_or(u32::MAX).min(pairs_per_dispatch(params)).max(1);
    let chunks = params.pairs.div_ceil(per_chunk).max(1);
    let d = volume.dims;
    submit_and_wait(ctx, PASS, |rec| {
        let scope = profiler.begin(rec, PASS)?;
        for chunk in 0..chunks {
            if chunk > 0 && sync == ChunkSync::Barrier {
                // The next dispatch adds to the sums this one wrote, and
                // overwrites those the one before read.
                rec.barrier(&Barrier::memory(
                    "ao_reference_sums_write_to_next_directions",
                    Access::COMPUTE_READ_WRITE,
                    Access::COMPUTE_READ_WRITE,
                ));
            }
            rec.bind(&pipeline, sets[(chunk % 2) as usize]);
            let push = AoReferenceChunk {
                first_pair: chunk * per_chunk,
                pair_count: per_chunk,
                is_first: (chunk == 0) as u32,
                pad: 0,
            };
            rec.push(&pipeline, &push);
            rec.dispatch(d.x.div_ceil(4), d.y.div_ceil(4), d.z.div_ceil(4));
        }
        profiler.end(rec, scope)?;
        rec.barrier(&Barrier::memory(
            "ao_reference_sums_write_to_readback_copy",
            Access::COMPUTE_WRITE,
            Access::TRANSFER_READ,
        ));
        copy_buffer(rec, &sums[((chunks - 1) % 2) as usize], &readback, bytes);
        rec.barrier(&Barrier::memory("readback_copy_to_host_read", Access::TRANSFER_WRITE, Access::HOST_READ));
        Ok(())
    })?;
    Ok(readback.read(entries)?)
}
