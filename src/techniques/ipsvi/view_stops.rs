//! The view-stops pass of the segmented line kernel: before the sweeps, where
//! every view ray stops under early ray termination (glsl/ipsvi_view_stops.comp).
//! A ray's opacity depends on the volume and the view, never on the light, so
//! its stop waits for no line: found once per frame, with the serial march's
//! rule and integer sums (the same sample), it lets each line's segments split
//! only the samples up to it. The serial kernel finds its stop as it marches,
//! as the paper does, and records no such pass. Recorded in every frame, as
//! the exit-point pre-pass is: a frame stands for a view just moved to.

use crate::render::{GpuScene, RenderError};
use crate::shaders::ipsvi_view_stops;
use crate::vk::descriptors::Resource;
use crate::vk::pipeline::{ComputePipeline, ComputePipelineDesc};
use crate::vk::{Buffer, Image, Profiler, Recorder, VkError};
use ash::vk;
use bytemuck::{Pod, Zeroable};
use gpu_allocator::MemoryLocation;

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct StopsPush {
    ert_scale: f32,
}

crate::assert_gpu_layout!(StopsPush, ipsvi_view_stops::layout::PUSH, [ert_scale]);

/// What the pass needs from its renderer.
pub struct ViewStopsInputs<'r> {
    pub frame: &'r Buffer,
    pub lmax: &'r Image,
    pub shape: &'r Buffer,
    pub width: u32,
    pub height: u32,
    /// The line kernel's specialization constants TERMINATION (7),
    /// SEGMENTS (16) and CROSS_SUBGROUPS (19), and its workgroup size (8).
    pub termination: u32,
    pub segments: u32,
    pub cross_subgroups: bool,
    pub line_group: u32,
    pub ert_scale: u32,
}

struct StopsPass {
    pipeline: ComputePipeline,
    set: vk::DescriptorSet,
    /// Workgroups in rows (the shader numbers them row by row): more than one
    /// dispatch dimension holds at 512x512 and 128 segments.
    groups: [u32; 2],
    group_size: u32,
    ert_scale: f32,
}

pub struct ViewStops {
    /// Per pixel (row-major) the view samples its ray marches; one word
    /// where rays never stop (the line kernel binds it all the same).
    pub stops: Buffer,
    pass: Option<StopsPass>,
}

impl ViewStops {
    /// The pass where rays may stop (`termination` not 0), else only the
    /// one-word buffer the segmented kernel's binding needs.
    pub fn new(gpu: &GpuScene, inputs: &ViewStopsInputs) -> Result<ViewStops, RenderError> {
        let ctx = gpu.ctx;
        let pixels = u64::from(inputs.width) * u64::from(inputs.height);
        let words = if inputs.termination == 0 { 1 } else { pixels };
        let usage = vk::BufferUsageFlags::STORAGE_BUFFER;
        let stops = Buffer::new(ctx, "ipsvi view stops", 4 * words, usage, MemoryLocation::GpuOnly)?;
        if inputs.termination == 0 {
            return Ok(ViewStops { stops, pass: None });
        }
        let specialization = [
            (7, inputs.termination),
            (8, inputs.line_group),
            (16, inputs.segments),
            (19, inputs.cross_subgroups as u32),
        ];
        let mut pipeline = ComputePipeline::new(
            ctx,
            &ComputePipelineDesc {
                name: "ipsvi_view_stops",
                shader: &ipsvi_view_stops::INTERFACE,
                specialization: &specialization,
                max_sets: 1,
            },
        )?;
        let set = pipeline.create_set(&[
            (ipsvi_view_stops::FRAME_BUFFER, Resource::StorageBuffer(inputs.frame)),
            (ipsvi_view_stops::VOLUME_TEX, Resource::SampledImage(&gpu.volume, &gpu.sampler)),
            (ipsvi_view_stops::TRANSFER_LUT, Resource::StorageBuffer(&gpu.lut)),
            (ipsvi_view_stops::LMAX, Resource::StorageImage(inputs.lmax)),
            (ipsvi_view_stops::SHAPE, Resource::StorageBuffer(inputs.shape)),
            (ipsvi_view_stops::VIEW_STOPS, Resource::StorageBuffer(&stops)),
        ])?;
        let invocations = pixels * u64::from(inputs.segments);
        let groups = invocations.div_ceil(u64::from(inputs.line_group));
        let [max_x, max_y, _] = ctx.limits.max_compute_work_group_count;
        // As few rows as fit, each as short as they allow: the padding, idle
        // workgroups past the last pixel, stays under one per row.
        let rows = groups.div_ceil(u64::from(max_x)).max(1);
        let x = groups.div_ceil(rows);
        if rows > u64::from(max_y) {
            return Err(RenderError::Invalid(format!(
                "ipsvi.segments = {}: the view-stops pass of a {}x{} image needs {groups} workgroups, more than \
                 this device dispatches at once; use fewer segments",
                inputs.segments, inputs.width, inputs.height
            )));
        }
        let groups = [x as u32, rows as u32];
        let pass =
            StopsPass { pipeline, set, groups, group_size: inputs.line_group, ert_scale: inputs.ert_scale as f32 };
        Ok(ViewStops { stops, pass: Some(pass) })
    }

    /// The pass's invocations (workgroups times their size), where it runs.
    pub fn invocations(&self) -> Option<u64> {
        self.pass.as_ref().map(|p| u64::from(p.groups[0]) * u64::from(p.groups[1]) * u64::from(p.group_size))
    }

    pub fn pipeline(&self) -> Option<vk::Pipeline> {
        self.pass.as_ref().map(|p| p.pipeline.raw)
    }

    /// The pass, where rays may stop (returns whether it recorded it).
    /// After l_max (exit points) and the shape counters' clear, both behind
    /// barriers; the renderer's first cache initialisation follows, and the
    /// barrier after it hands the stops to the line dispatches
    /// (`cache_init_and_view_stops_write_to_first_line_read`).
    pub fn record(&self, rec: &mut Recorder, profiler: &mut Profiler) -> Result<bool, VkError> {
        let Some(pass) = &self.pass else { return Ok(false) };
        let scope = profiler.begin(rec, "ipsvi_view_stops")?;
        rec.bind(&pass.pipeline, pass.set);
        rec.push(&pass.pipeline, &StopsPush { ert_scale: pass.ert_scale });
        rec.dispatch(pass.groups[0], pass.groups[1], 1);
        profiler.end(rec, scope)?;
        Ok(true)
    }
}
