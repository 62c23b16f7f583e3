//! Slice-by-slice propagation of each pass's lights through the volume
//! (glsl/lightvolume_slice.comp): per light a pair of slice buffers used as a
//! ping-pong, one dispatch per slice for all lights of the pass, each followed
//! by the barrier `slice_write_to_next_slice_read`. Every pass is recorded into
//! its own secondary command buffer. The lights a pass reads come from a slot
//! buffer (current states and, for subtractions, old ones) and its entries
//! (slot, signed factor, slice layer) from its own region of an entries buffer,
//! so a recorded pass stays valid as long as its slots and region keep their
//! contents.

use super::groups::PropagationGroup;
use super::illumination::IlluminationVolume;
use super::settings::LightVolumeSettings;
use crate::render::frame_params::{frame_params, GpuLight, MarchSteps};
use crate::render::gpu_scene::bindings_after_scene;
use crate::render::{GpuScene, RenderError};
use crate::shaders;
use crate::vk::barriers::{Access, Barrier};
use crate::vk::commands::SecondaryCommands;
use crate::vk::descriptors::{BindingKind, Resource};
use crate::vk::pipeline::{parity_pair, push_bytes, ComputePipeline, ComputePipelineDesc};
use crate::vk::resources::{as_bytes, GpuData, ImageDesc};
use crate::vk::{Buffer, Context, Image, Recorder};
use ash::vk;
use glam::UVec3;
use gpu_allocator::MemoryLocation;

/// Mirrors `GroupEntry` in glsl/lightvolume_slice.comp.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GroupEntry {
    /// Slot of the light's state in the slot buffer.
    pub light: u32,
    /// Signed contribution factor.
    pub factor: f32,
    /// Layer of the slice buffers.
    pub slot: u32,
    /// 1: the factor is weighted per voxel by cos^2 between the light's travel
    /// and the axis (a light inside the volume, in all six groups).
    pub per_voxel: u32,
}

impl GpuData for GroupEntry {}

/// Mirrors the `Pass` push constants.
#[repr(C)]
#[derive(Clone, Copy)]
struct SlicePush {
    axis: [i32; 4],
    grid: [i32; 4],
}

/// After the scene bindings (render::gpu_scene::SCENE_BINDINGS; binding 3, the
/// scene's lights, is replaced by the slot buffer).
const OWN_BINDINGS: [BindingKind; 7] = [
    BindingKind::StorageBuffer,
    BindingKind::StorageImage,
    BindingKind::StorageImage,
    BindingKind::StorageImage,
    BindingKind::StorageImage,
    BindingKind::StorageImage,
    BindingKind::StorageImage,
];

const GROUP_SIZE: u32 = 8;

/// How much a [`Propagation`] holds: slice layers (lights per pass), light
/// slots and pass entries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Capacity {
    pub layers: u32,
    pub slots: usize,
    pub entries: usize,
}

impl Capacity {
    pub fn holds(&self, other: &Capacity) -> bool {
        self.layers >= other.layers && self.slots >= other.slots && self.entries >= other.entries
    }
}

pub struct Propagation {
    pub capacity: Capacity,
    grid: UVec3,
    pipelines: [ComputePipeline; 2],
    set: vk::DescriptorSet,
    /// Slice buffer sides a and b: x, y a slice texel, z the light's layer in
    /// its pass (a 3D image stands in for a 2D array: one layer per light).
    slices: [Image; 2],
    slots: Buffer,
    entries: Buffer,
    _frame: Buffer,
}

impl Propagation {
    pub fn new(
        gpu: &GpuScene,
        illumination: &IlluminationVolume,
        capacity: Capacity,
        settings: &LightVolumeSettings,
    ) -> Result<Propagation, RenderError> {
        let ctx = gpu.ctx;
        let scene = gpu.scene;
        // Only the box geometry is read: any image size will do.
        let params = frame_params(scene, 1, 1, gpu.lut_size, MarchSteps::render(scene));
        let frame =
            Buffer::with_data(ctx, "lightvolume frame params", &[params], vk::BufferUsageFlags::UNIFORM_BUFFER)?;
        let host_buffer = |name: &str, bytes: usize| {
            Buffer::new(ctx, name, bytes as u64, vk::BufferUsageFlags::STORAGE_BUFFER, MemoryLocation::CpuToGpu)
        };
        let slots = host_buffer("lightvolume light slots", capacity.slots * std::mem::size_of::<GpuLight>())?;
        let entries = host_buffer("lightvolume pass entries", capacity.entries * std::mem::size_of::<GroupEntry>())?;
        let grid = illumination.size;
        // Every slice of every group fits: lateral sizes are at most the largest axis.
        let side = grid.max_element();
        let slice_image = |name: &str| {
            Image::new(
                ctx,
                name,
                ImageDesc {
                    image_type: vk::ImageType::TYPE_3D,
                    format: vk::Format::R32G32B32A32_SFLOAT,
                    extent: vk::Extent3D { width: side, height: side, depth: capacity.layers },
                    usage: vk::ImageUsageFlags::STORAGE,
                },
            )
        };
        let slices = [slice_image("lightvolume slice a")?, slice_image("lightvolume slice b")?];
        let bindings = bindings_after_scene(&OWN_BINDINGS);
        let mut scene_resources = gpu.scene_resources(&frame);
        scene_resources[3] = Resource::StorageBuffer(&slots);
        let compensated = illumination.compensated as u32;
        let desc = ComputePipelineDesc {
            name: "lightvolume_slice",
            spirv: &[],
            bindings: &bindings,
            push_constant_bytes: std::mem::size_of::<SlicePush>() as u32,
            specialization: &[
                (0, compensated),
                (1, settings.substep_data_voxels().to_bits()),
                (2, settings.shared_medium as u32),
                (3, settings.chromatic as u32),
            ],
            max_sets: 1,
        };
        // Slice parity 0 reads side a and writes b; parity 1 the opposite.
        let mut pipelines =
            parity_pair(ctx, &desc, shaders::LIGHTVOLUME_SLICE_READ_A, shaders::LIGHTVOLUME_SLICE_READ_B)?;
        // Slots: a_in, b_in, a_out, b_out, then the illumination volume's two words.
        let set = pipelines[0].create_set(
            &[
                &scene_resources[..],
                &[
                    Resource::StorageBuffer(&entries),
                    Resource::StorageImage(&slices[0]),
                    Resource::StorageImage(&slices[1]),
                    Resource::StorageImage(&slices[0]),
                    Resource::StorageImage(&slices[1]),
                    Resource::StorageImage(&illumination.image),
                    Resource::StorageImage(&illumination.low),
                ],
            ]
            .concat(),
        )?;
        Ok(Propagation { capacity, grid, pipelines, set, slices, slots, entries, _frame: frame })
    }

    /// Writes light states into the slot buffer from slot `first` on (between
    /// frames: the previous frame has completed).
    pub fn write_slots(&mut self, first: usize, states: &[GpuLight]) -> Result<(), RenderError> {
        Ok(self.slots.write_bytes(first * std::mem::size_of::<GpuLight>(), as_bytes(states))?)
    }

    pub fn write_entries(&mut self, first: usize, entries: &[GroupEntry]) -> Result<(), RenderError> {
        Ok(self.entries.write_bytes(first * std::mem::size_of::<GroupEntry>(), as_bytes(entries))?)
    }

    /// Before the first pass of a frame: the slice buffers' old contents are
    /// discarded (the first slice of every pass writes before anything reads).
    pub fn record_prepare(&self, rec: &mut Recorder) {
        rec.discard_for_compute("slice_buffers_discard_to_propagation", &[&self.slices[0], &self.slices[1]]);
    }

    /// Slices of `group`: the illumination volume's size along its axis.
    pub fn slice_count(&self, group: &PropagationGroup) -> u32 {
        self.grid[group.axis]
    }

    /// Records `group` into a secondary command buffer; its entries lie at
    /// `first_entry` of the entries buffer. `racy` leaves the barriers between
    /// slices out (only the last, toward the next pass, stays).
    pub fn record_pass(
        &self,
        ctx: &Context,
        group: &PropagationGroup,
        first_entry: u32,
        racy: bool,
    ) -> Result<SecondaryCommands, RenderError> {
        let dependency =
            Barrier::memory("slice_write_to_next_slice_read", Access::COMPUTE_WRITE, Access::COMPUTE_READ_WRITE);
        let grid = self.grid.as_ivec3();
        let name = group.scope_name();
        let slices = self.slice_count(group);
        Ok(SecondaryCommands::record(ctx, &name, 1, |_, rec| {
            let (u, v) = ((group.axis + 1) % 3, (group.axis + 2) % 3);
            rec.bind(&self.pipelines[0], self.set);
            for k in 0..slices {
                let pipeline = &self.pipelines[(k % 2) as usize];
                rec.bind_pipeline(pipeline);
                let push = SlicePush {
                    axis: [group.axis as i32, group.travel, k as i32, group.members.len() as i32],
                    grid: [grid.x, grid.y, grid.z, first_entry as i32],
                };
                rec.push(pipeline, push_bytes(&push));
                rec.dispatch(self.grid[u].div_ceil(GROUP_SIZE), self.grid[v].div_ceil(GROUP_SIZE), 1);
                // This slice's buffer and illumination writes are what the next
                // slice (or the next pass, or the ray cast) reads.
                if !racy || k + 1 == slices {
                    rec.barrier(&dependency);
                }
            }
            Ok(())
        })?)
    }
}
