//! Slice-by-slice propagation of each group's lights through the volume
//! (glsl/lightvolume_slice.comp): per light a pair of slice buffers used as a
//! ping-pong, one dispatch per slice for all lights of the group, each followed
//! by the barrier `slice_write_to_next_slice_read`. Every group pass is recorded
//! into its own secondary command buffer.

use super::groups::PropagationGroup;
use super::illumination::IlluminationVolume;
use crate::render::gpu_scene::bindings_after_scene;
use crate::render::{GpuScene, RenderError};
use crate::shaders;
use crate::vk::barriers::{Access, Barrier};
use crate::vk::commands::SecondaryCommands;
use crate::vk::descriptors::{BindingKind, Resource};
use crate::vk::pipeline::{parity_pair, push_bytes, ComputePipeline, ComputePipelineDesc};
use crate::vk::resources::{GpuData, ImageDesc};
use crate::vk::{Buffer, Context, Image, Recorder};
use ash::vk;
use glam::UVec3;

/// Mirrors `GroupEntry` in glsl/lightvolume_slice.comp.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
struct GroupEntry {
    light: u32,
    factor: f32,
    slot: u32,
    pad: u32,
}

impl GpuData for GroupEntry {}

/// Mirrors the `Pass` push constants.
#[repr(C)]
#[derive(Clone, Copy)]
struct SlicePush {
    axis: [i32; 4],
    grid: [i32; 4],
}

/// After the scene bindings (render::gpu_scene::SCENE_BINDINGS).
const OWN_BINDINGS: [BindingKind; 6] = [
    BindingKind::StorageBuffer,
    BindingKind::StorageImage,
    BindingKind::StorageImage,
    BindingKind::StorageImage,
    BindingKind::StorageImage,
    BindingKind::StorageImage,
];

const GROUP_SIZE: u32 = 8;

pub struct Propagation {
    pub groups: Vec<PropagationGroup>,
    grid: UVec3,
    first_entry: Vec<u32>,
    pipelines: [ComputePipeline; 2],
    set: vk::DescriptorSet,
    /// Slice buffer sides a and b: x, y a slice texel, z the light's slot in
    /// its group (a 3D image stands in for a 2D array: one layer per light).
    slices: [Image; 2],
    _entries: Buffer,
}

impl Propagation {
    /// Resources and pipelines for `groups` (non-empty, each with members).
    pub fn new(
        gpu: &GpuScene,
        frame: &Buffer,
        illumination: &IlluminationVolume,
        groups: Vec<PropagationGroup>,
    ) -> Result<Propagation, RenderError> {
        let ctx = gpu.ctx;
        let mut entries = Vec::new();
        let mut first_entry = Vec::new();
        for g in &groups {
            first_entry.push(entries.len() as u32);
            for (slot, m) in g.members.iter().enumerate() {
                entries.push(GroupEntry { light: m.light as u32, factor: m.factor, slot: slot as u32, pad: 0 });
            }
        }
        if entries.is_empty() {
            return Err(RenderError::Invalid("light volume propagation without lights".into()));
        }
        let entries_buffer =
            Buffer::with_data(ctx, "lightvolume group entries", &entries, vk::BufferUsageFlags::STORAGE_BUFFER)?;
        let grid = illumination.size;
        // Every slice of every group fits: lateral sizes are at most the largest axis.
        let side = grid.max_element();
        let layers = groups.iter().map(|g| g.members.len() as u32).max().unwrap_or(1).max(1);
        let slice_image = |name: &str| {
            Image::new(
                ctx,
                name,
                ImageDesc {
                    image_type: vk::ImageType::TYPE_3D,
                    format: vk::Format::R32G32B32A32_SFLOAT,
                    extent: vk::Extent3D { width: side, height: side, depth: layers },
                    usage: vk::ImageUsageFlags::STORAGE,
                },
            )
        };
        let slices = [slice_image("lightvolume slice a")?, slice_image("lightvolume slice b")?];
        let bindings = bindings_after_scene(&OWN_BINDINGS);
        let scene = gpu.scene_resources(frame);
        let desc = ComputePipelineDesc {
            name: "lightvolume_slice",
            spirv: &[],
            bindings: &bindings,
            push_constant_bytes: std::mem::size_of::<SlicePush>() as u32,
            specialization: &[],
            max_sets: 1,
        };
        // Slice parity 0 reads side a and writes b; parity 1 the opposite.
        let mut pipelines =
            parity_pair(ctx, &desc, shaders::LIGHTVOLUME_SLICE_READ_A, shaders::LIGHTVOLUME_SLICE_READ_B)?;
        // Slots: a_in, b_in, a_out, b_out, then the illumination volume.
        let set = pipelines[0].create_set(
            &[
                &scene[..],
                &[
                    Resource::StorageBuffer(&entries_buffer),
                    Resource::StorageImage(&slices[0]),
                    Resource::StorageImage(&slices[1]),
                    Resource::StorageImage(&slices[0]),
                    Resource::StorageImage(&slices[1]),
                    Resource::StorageImage(&illumination.image),
                ],
            ]
            .concat(),
        )?;
        Ok(Propagation { groups, grid, first_entry, pipelines, set, slices, _entries: entries_buffer })
    }

    /// Before the first group pass: the slice buffers' old contents are discarded
    /// (the first slice of every pass writes before anything reads).
    pub fn record_prepare(&self, rec: &mut Recorder) {
        rec.discard_for_compute("slice_buffers_discard_to_propagation", &[&self.slices[0], &self.slices[1]]);
    }

    /// Slices of `group`: the illumination volume's size along its axis.
    pub fn slice_count(&self, group: &PropagationGroup) -> u32 {
        self.grid[group.axis]
    }

    /// One secondary command buffer per group, in the order of `groups`.
    pub fn record_secondaries(&self, ctx: &Context) -> Result<SecondaryCommands, RenderError> {
        let dependency =
            Barrier::memory("slice_write_to_next_slice_read", Access::COMPUTE_WRITE, Access::COMPUTE_READ_WRITE);
        let grid = self.grid.as_ivec3();
        Ok(SecondaryCommands::record(ctx, "lightvolume group", self.groups.len(), |i, rec| {
            let group = &self.groups[i];
            let (u, v) = ((group.axis + 1) % 3, (group.axis + 2) % 3);
            rec.bind(&self.pipelines[0], self.set);
            for k in 0..self.slice_count(group) {
                let pipeline = &self.pipelines[(k % 2) as usize];
                rec.bind_pipeline(pipeline);
                let push = SlicePush {
                    axis: [group.axis as i32, group.travel, k as i32, group.members.len() as i32],
                    grid: [grid.x, grid.y, grid.z, self.first_entry[i] as i32],
                };
                rec.push(pipeline, push_bytes(&push));
                rec.dispatch(self.grid[u].div_ceil(GROUP_SIZE), self.grid[v].div_ceil(GROUP_SIZE), 1);
                // This slice's buffer and illumination writes are what the next
                // slice (or the next group, or the ray cast) reads.
                rec.barrier(&dependency);
            }
            Ok(())
        })?)
    }
}
