//! Slice-by-slice propagation of each pass's lights through the volume
//! (glsl/lightvolume_slice.comp): per light a pair of slice buffers used as a
//! ping-pong, one dispatch per slice for all lights of the pass, each followed
//! by the barrier `slice_write_to_next_slice_read`. Every pass is recorded into
//! its own secondary command buffer. The lights a pass reads come from a slot
//! buffer (current states and, for subtractions, old ones) and its entries
//! (slot, signed factor, slice layer) from its own region of an entries buffer,
//! so a recorded pass stays valid as long as its slots and region keep their
//! contents.

use super::directional_step::DirectionalStep;
use super::groups::{GroupMember, PropagationGroup};
use super::illumination::IlluminationVolume;
use super::settings::LightVolumeSettings;
use crate::render::frame_params::{frame_params, GpuLight, MarchSteps};
use crate::render::{GpuScene, RenderError, ResourceNeed};
use crate::shaders::lightvolume_slice as shader;
use crate::vk::barriers::{Access, Barrier};
use crate::vk::commands::SecondaryCommands;
use crate::vk::descriptors::Resource;
use crate::vk::pipeline::{ComputePipeline, ComputePipelineDesc};
use crate::vk::resources::ImageDesc;
use crate::vk::{Buffer, Context, Image, Recorder};
use ash::vk;
use bytemuck::{Pod, Zeroable};
use glam::UVec3;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

/// Mirrors `GroupEntry` in glsl/lightvolume_slice.comp.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
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
    /// A directional light's step ([`DirectionalStep`]), unused otherwise.
    pub radiance_path: [f32; 4],
    pub lateral_step: [f32; 4],
}

crate::assert_gpu_layout!(
    GroupEntry,
    shader::layout::GROUP_ENTRY,
    [light, factor, slot, per_voxel, radiance_path, lateral_step]
);

/// Mirrors the `Pass` push constants.
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct SlicePush {
    axis: i32,
    travel: i32,
    slice: i32,
    entry_count: i32,
    grid: [i32; 3],
    first_entry: i32,
}

crate::assert_gpu_layout!(SlicePush, shader::layout::PASS, [axis, travel, slice, entry_count, grid, first_entry]);

/// Entries the shader's uniform block `GroupEntries` holds: the most
/// contributions one update can propagate (at least [`SCENE_MAX_ENTRIES`]).
pub const MAX_ENTRIES: usize = (shader::layout::GROUP_ENTRIES.size / shader::layout::GROUP_ENTRY.size) as usize;

/// The most contributions a scene's update can need: six groups per light,
/// twice in a selective update (subtracted and added).
pub const SCENE_MAX_ENTRIES: usize = 12 * crate::scene::scene_schema::MAX_LIGHTS;

const _: () = assert!(SCENE_MAX_ENTRIES <= MAX_ENTRIES);

const GROUP_SIZE: u32 = 8;
/// Within this many slices of a point or spot light the slice shader
/// integrates the path to the light (its `NEAR_LIGHT_SLICES`, set from here).
const NEAR_LIGHT_SLICES: f32 = 4.0;
/// Light travelling this close to perpendicular to a group's axis (a cosine)
/// is not carried along it (the slice shader's `MIN_AXIS_COSINE`, set from
/// here; the host-computed directional step uses the same value).
pub(super) const MIN_AXIS_COSINE: f32 = 1e-4;

/// `pos_type.w` of a directional light (`LIGHT_DIRECTIONAL` in glsl/lights.glsl).
fn is_directional(state: &GpuLight) -> bool {
    state.pos_type[3] == 0.0
}

/// Whether a light in `state` can come within `NEAR_LIGHT_SLICES` of a slice
/// centre of `group` (what the shader's near-light integration handles): a
/// point or spot light less than that (plus one slice of margin against
/// rounding) before the first slice centre along the travel direction, or
/// inside the box. Depends only on the light's state and the group, and a
/// pass without such a light runs the build without that integration.
fn may_come_near(state: &GpuLight, group: &PropagationGroup, box_half: [f32; 3], grid: UVec3) -> bool {
    if is_directional(state) {
        return false; // infinitely far
    }
    let a = group.axis;
    let dstep = 2.0 * box_half[a] / grid[a] as f32;
    let first_centre = -box_half[a] + 0.5 * dstep;
    let before_first = first_centre - state.pos_type[a] * group.travel as f32;
    before_first <= (NEAR_LIGHT_SLICES + 1.0) * dstep
}

/// Which build of the slice shader a pass runs, by its lights: each leaves out
/// code its lights never need (llvmpipe runs both sides of every branch).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum LightMix {
    /// Directional lights only: no per-voxel direction, falloff or cone.
    Directional = 0,
    /// No light within reach of the near-light integration.
    Far = 1,
    /// A point or spot light that may come near a slice (`may_come_near`).
    Near = 2,
}

impl LightMix {
    fn of(group: &PropagationGroup, box_half: [f32; 3], grid: UVec3) -> LightMix {
        if group.members.iter().any(|m| may_come_near(&m.state, group, box_half, grid)) {
            LightMix::Near
        } else if group.members.iter().all(|m| is_directional(&m.state)) {
            LightMix::Directional
        } else {
            LightMix::Far
        }
    }
}

/// How much a [`Propagation`] holds: slice layers (lights per pass), light
/// slots and pass entries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Capacity {
    pub layers: u32,
    pub slots: usize,
    pub entries: usize,
}

impl Capacity {
    /// What `passes` need: slice layers for the largest pass, a slot per
    /// distinct light state, an entry per member.
    pub fn needed(passes: &[PropagationGroup]) -> Capacity {
        let mut distinct: Vec<GpuLight> = Vec::new();
        for m in passes.iter().flat_map(|p| &p.members) {
            if !distinct.contains(&m.state) {
                distinct.push(m.state);
            }
        }
        Capacity {
            layers: passes.iter().map(|p| p.members.len()).max().unwrap_or(1) as u32,
            slots: distinct.len(),
            entries: passes.iter().map(|p| p.members.len()).sum(),
        }
    }

    /// The buffers to create for this need, beside an `old` capacity that is
    /// too small: powers of two with room to grow, so that later frames rarely
    /// re-create them (at most `pass_lights` layers).
    pub fn grown(&self, old: Option<Capacity>, pass_lights: u32) -> Capacity {
        let grow = |now: Option<usize>, needed: usize, least: usize| {
            needed.max(now.unwrap_or(0)).max(least).next_power_of_two()
        };
        Capacity {
            layers: grow(old.map(|c| c.layers as usize), self.layers as usize, 1)
                .min(pass_lights as usize)
                .max(self.layers as usize) as u32,
            slots: grow(old.map(|c| c.slots), self.slots, 8),
            // The uniform block is allocated whole.
            entries: MAX_ENTRIES,
        }
    }

    /// The slice images (a and b, RGBA32F) and the slot and entry buffers
    /// [`Propagation::new`] creates for this capacity.
    pub fn resources(&self, grid: UVec3) -> [ResourceNeed; 4] {
        let side = grid.max_element();
        [
            ResourceNeed::image("lightvolume slice a", [side, side, self.layers], 16),
            ResourceNeed::image("lightvolume slice b", [side, side, self.layers], 16),
            ResourceNeed::of::<GpuLight>("lightvolume light slots", self.slots),
            ResourceNeed::of::<GroupEntry>("lightvolume pass entries", self.entries),
        ]
    }

    pub fn holds(&self, other: &Capacity) -> bool {
        self.layers >= other.layers && self.slots >= other.slots && self.entries >= other.entries
    }
}

pub struct Propagation {
    pub capacity: Capacity,
    grid: UVec3,
    /// Indexed by [`LightMix`].
    pipelines: [ComputePipeline; 3],
    box_half: [f32; 3],
    set: vk::DescriptorSet,
    /// Set 1 per slice parity: 0 reads slice side a and writes b, 1 the opposite.
    sides: [vk::DescriptorSet; 2],
    /// Slice buffer sides a and b: x, y a slice texel, z the light's layer in
    /// its pass (a 3D image stands in for a 2D array: one layer per light).
    slices: [Arc<Image>; 2],
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
            Buffer::with_data(ctx, "lightvolume frame params", &[params], vk::BufferUsageFlags::STORAGE_BUFFER)?;
        let host_buffer = |name: &str, bytes: usize, usage: vk::BufferUsageFlags| {
            Buffer::new(ctx, name, bytes as u64, usage, MemoryLocation::CpuToGpu)
        };
        let slots = host_buffer(
            "lightvolume light slots",
            capacity.slots * std::mem::size_of::<GpuLight>(),
            vk::BufferUsageFlags::STORAGE_BUFFER,
        )?;
        let entries_bytes = shader::layout::GROUP_ENTRIES.size as usize;
        if entries_bytes > ctx.limits.max_uniform_buffer_range as usize {
            return Err(RenderError::Invalid(format!(
                "lightvolume: the pass entries' uniform block ({entries_bytes} bytes) exceeds this device's \
                 maxUniformBufferRange ({})",
                ctx.limits.max_uniform_buffer_range
            )));
        }
        // The whole block, whatever the capacity: the shader declares it so.
        let entries = host_buffer("lightvolume pass entries", entries_bytes, vk::BufferUsageFlags::UNIFORM_BUFFER)?;
        let grid = illumination.size;
        // Every slice of every group fits: lateral sizes are at most the largest axis.
        let side = grid.max_element();
        let slice_image = |name: &str| {
            gpu.frame_images.image(
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
        let compensated = illumination.compensated as u32;
        let build = |mix: LightMix| {
            let desc = ComputePipelineDesc {
                name: "lightvolume_slice",
                shader: &shader::INTERFACE,
                specialization: &[
                    (0, compensated),
                    (1, settings.substep_data_voxels().to_bits()),
                    (2, settings.shared_medium as u32),
                    (3, settings.chromatic as u32),
                    (4, (mix == LightMix::Near) as u32),
                    (5, (mix == LightMix::Directional) as u32),
                    (6, MIN_AXIS_COSINE.to_bits()),
                    (7, NEAR_LIGHT_SLICES.to_bits()),
                ],
                max_sets: 1,
            };
            ComputePipeline::new(ctx, &desc)
        };
        let mut pipelines = [build(LightMix::Directional)?, build(LightMix::Far)?, build(LightMix::Near)?];
        // All three share one layout: one set serves them all.
        let set = pipelines[0].create_set(&[
            (shader::FRAME_BUFFER, Resource::StorageBuffer(&frame)),
            (shader::VOLUME_TEX, Resource::SampledImage(&gpu.volume, &gpu.sampler)),
            (shader::TRANSFER_LUT, Resource::StorageBuffer(&gpu.lut)),
            // The lights a pass propagates: current states and, for subtractions, old ones.
            (shader::LIGHTS, Resource::StorageBuffer(&slots)),
            (shader::GROUP_ENTRIES, Resource::UniformBuffer(&entries)),
            (shader::ILLUMINATION, Resource::StorageImage(&illumination.image)),
            (shader::ILLUMINATION_LOW, Resource::StorageImage(&illumination.low)),
        ])?;
        let mut side = |from: usize, to: usize| {
            pipelines[0].create_set1(&[
                (shader::SLICE_IN, Resource::StorageImage(&slices[from])),
                (shader::SLICE_OUT, Resource::StorageImage(&slices[to])),
            ])
        };
        let sides = [side(0, 1)?, side(1, 0)?];
        let box_half = params.box_half;
        Ok(Propagation { capacity, grid, pipelines, box_half, set, sides, slices, slots, entries, _frame: frame })
    }

    /// Writes light states into the slot buffer from slot `first` on (between
    /// frames: the previous frame has completed).
    pub fn write_slots(&mut self, first: usize, states: &[GpuLight]) -> Result<(), RenderError> {
        Ok(self.slots.write_bytes(first * std::mem::size_of::<GpuLight>(), bytemuck::cast_slice(states))?)
    }

    pub fn write_entries(&mut self, first: usize, entries: &[GroupEntry]) -> Result<(), RenderError> {
        Ok(self.entries.write_bytes(first * std::mem::size_of::<GroupEntry>(), bytemuck::cast_slice(entries))?)
    }

    /// Before the first pass of a frame: the slice buffers' old contents are
    /// discarded (the first slice of every pass writes before anything reads).
    pub fn record_prepare(&self, rec: &mut Recorder) {
        rec.discard_for_compute("slice_buffers_discard_to_propagation", &[&self.slices[0], &self.slices[1]]);
    }

    /// The entry of `member` of `group`: its light state at `light_slot` of
    /// the slot buffer, its slice buffer layer `layer`, and for a directional
    /// light its step, computed here once for every voxel.
    pub fn entry(&self, group: &PropagationGroup, member: &GroupMember, light_slot: u32, layer: u32) -> GroupEntry {
        let step = if is_directional(&member.state) {
            DirectionalStep::of(member, group, self.box_half, self.grid)
        } else {
            DirectionalStep::NONE
        };
        GroupEntry {
            light: light_slot,
            factor: member.factor,
            slot: layer,
            per_voxel: member.per_voxel as u32,
            radiance_path: step.radiance_path,
            lateral_step: step.lateral_step,
        }
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
        let pipeline = &self.pipelines[LightMix::of(group, self.box_half, self.grid) as usize];
        Ok(SecondaryCommands::record(ctx, &name, 1, |_, rec| {
            let (u, v) = ((group.axis + 1) % 3, (group.axis + 2) % 3);
            rec.bind(pipeline, self.set);
            for k in 0..slices {
                rec.bind_set1(pipeline, self.sides[(k % 2) as usize]);
                let push = SlicePush {
                    axis: group.axis as i32,
                    travel: group.travel,
                    slice: k as i32,
                    entry_count: group.members.len() as i32,
                    grid: grid.to_array(),
                    first_entry: first_entry as i32,
                };
                rec.push(pipeline, &push);
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

#[cfg(test)]
mod tests {
    use super::*;

    fn light(kind: f32, position: [f32; 3]) -> GpuLight {
        GpuLight { pos_type: [position[0], position[1], position[2], kind], ..GpuLight::default() }
    }

    /// A -y group (light travelling down) on a 32-slice grid of half extent 0.5
    /// along y: slices 1/32 apart, the first centre at y = 0.5 - 1/64.
    fn down() -> PropagationGroup {
        PropagationGroup { axis: 1, travel: -1, members: Vec::new() }
    }

    #[test]
    fn only_point_and_spot_lights_within_reach_of_the_first_slices_take_the_near_build() {
        let (half, grid) = ([0.5; 3], UVec3::new(32, 32, 32));
        let dstep = 1.0 / 32.0;
        let first = 0.5 - 0.5 * dstep;
        let near = |kind: f32, y: f32| may_come_near(&light(kind, [0.0, y, 0.0]), &down(), half, grid);
        // Directional lights are never near, wherever pos_type points.
        assert!(!near(0.0, first + dstep));
        for kind in [1.0, 2.0] {
            assert!(near(kind, 0.0), "inside the box");
            assert!(near(kind, first + 4.0 * dstep), "4 slices before the first: the shader integrates");
            assert!(near(kind, first + 4.9 * dstep), "within the one-slice margin");
            assert!(!near(kind, first + 5.1 * dstep), "beyond the margin");
            assert!(!near(kind, 3.0), "far above");
        }
        // A +y group (travelling up): a point light 3 slices below the first centre is near.
        let up = PropagationGroup { axis: 1, travel: 1, members: Vec::new() };
        assert!(may_come_near(&light(1.0, [0.0, -first - 3.0 * dstep, 0.0]), &up, half, grid));
        assert!(!may_come_near(&light(1.0, [0.0, -3.0, 0.0]), &up, half, grid));
    }

    #[test]
    fn a_pass_takes_the_directional_build_only_when_every_light_is_directional() {
        let (half, grid) = ([0.5; 3], UVec3::new(32, 32, 32));
        let pass = |lights: &[GpuLight]| {
            let members = lights
                .iter()
                .enumerate()
                .map(|(i, &state)| GroupMember { light: i, factor: 1.0, state, per_voxel: false })
                .collect();
            LightMix::of(&PropagationGroup { members, ..down() }, half, grid)
        };
        let directional = light(0.0, [0.3, -1.0, 0.1]);
        let (far_point, far_spot, near_point) =
            (light(1.0, [0.0, 3.0, 0.0]), light(2.0, [0.0, 3.0, 0.0]), light(1.0, [0.0, 0.0, 0.0]));
        assert_eq!(pass(&[directional, directional]), LightMix::Directional);
        assert_eq!(pass(&[directional, far_point]), LightMix::Far);
        assert_eq!(pass(&[far_spot]), LightMix::Far);
        assert_eq!(pass(&[directional, far_point, near_point]), LightMix::Near);
    }
}
