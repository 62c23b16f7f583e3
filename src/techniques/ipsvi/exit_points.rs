//! Early ray termination as in the IPSVI paper's section 5.1: a low-resolution
//! pre-pass records where each ray turns opaque (s_f) and where its farthest
//! structure lies (s_b); an exit-point sweep toward the light turns them into
//! l_max, how far each ray must go on so that the illumination cache stays
//! complete; the main pass stops a ray once it is opaque and past l_max.
//! Allocated and recorded only in `early_termination = "exit-points"` mode.

use super::light_anchor::LightAnchor;
use super::settings::IpsviSettings;
use super::sweep_plan::{plan, LineAxis, SweepPlan};
use crate::render::image_space::PixelRect;
use crate::render::{GpuScene, RenderError};
use crate::shaders::{ipsvi_ert_depths, ipsvi_ert_sweep};
use crate::vk::barriers::{Access, Barrier};
use crate::vk::descriptors::Resource;
use crate::vk::pipeline::{parity_pair, ComputePipeline, ComputePipelineDesc};
use crate::vk::{Buffer, Image, Profiler, Recorder, VkError};
use ash::vk;
use bytemuck::{Pod, Zeroable};
use glam::Vec2;
use std::sync::Arc;

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct DepthsPush {
    scale: u32,
    width: u32,
    height: u32,
}

crate::assert_gpu_layout!(DepthsPush, ipsvi_ert_depths::layout::PUSH, [scale, width, height]);

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct SweepPush {
    anchor: [f32; 2],
    line: u32,
    previous: i32,
    span_start: u32,
    span_len: u32,
    columns: u32,
    zone: u32,
}

crate::assert_gpu_layout!(
    SweepPush,
    ipsvi_ert_sweep::layout::PUSH,
    [anchor, line, previous, span_start, span_len, columns, zone]
);

fn image(gpu: &GpuScene, name: &str, format: vk::Format, width: u32, height: u32) -> Result<Arc<Image>, VkError> {
    gpu.frame_images.storage_2d(gpu.ctx, name, format, (width, height), vk::ImageUsageFlags::empty())
}

/// The 1x1 image bound where the main pass would read l_max when this mode is off.
pub fn placeholder(gpu: &GpuScene) -> Result<Arc<Image>, VkError> {
    image(gpu, "ipsvi lmax placeholder", vk::Format::R32_SFLOAT, 1, 1)
}

pub struct ExitPoints {
    pub scale: u32,
    pub width: u32,
    pub height: u32,
    depths: Arc<Image>,
    pair: [Arc<Image>; 2],
    /// l_max per pre-pass pixel, read by the main pass.
    pub lmax: Arc<Image>,
    plan: SweepPlan,
    depths_pipeline: ComputePipeline,
    depths_set: vk::DescriptorSet,
    /// Reads side a and writes b, and the opposite (glsl/ipsvi_ert_sweep.comp).
    sweep_pipelines: [ComputePipeline; 2],
    sweep_set: vk::DescriptorSet,
}

impl ExitPoints {
    /// The pre-pass's pipelines.
    pub fn pipelines(&self) -> [vk::Pipeline; 3] {
        [self.depths_pipeline.raw, self.sweep_pipelines[0].raw, self.sweep_pipelines[1].raw]
    }

    /// For the light of `main_plan` (the full-resolution sweep).
    pub fn new(
        gpu: &GpuScene,
        frame: &Buffer,
        width: u32,
        height: u32,
        settings: &IpsviSettings,
        main_plan: &SweepPlan,
    ) -> Result<ExitPoints, RenderError> {
        let (scale, bbox, anchor) = (settings.ert_scale.max(1), main_plan.bbox, main_plan.anchor);
        let (w, h) = (width.div_ceil(scale), height.div_ceil(scale));
        let depths = image(gpu, "ipsvi ert depths", vk::Format::R32G32_SFLOAT, w, h)?;
        let pair = [
            image(gpu, "ipsvi lmax a", vk::Format::R32_SFLOAT, w, h)?,
            image(gpu, "ipsvi lmax b", vk::Format::R32_SFLOAT, w, h)?,
        ];
        let lmax = image(gpu, "ipsvi lmax", vk::Format::R32_SFLOAT, w, h)?;
        let low = PixelRect {
            x0: bbox.x0 / scale,
            y0: bbox.y0 / scale,
            x1: bbox.x1.div_ceil(scale),
            y1: bbox.y1.div_ceil(scale),
        };
        let low_anchor = match anchor {
            LightAnchor::AtInfinity(d) => LightAnchor::AtInfinity(d),
            LightAnchor::Source(p) => LightAnchor::Source(p / scale as f32),
            LightAnchor::Sink(p) => LightAnchor::Sink(p / scale as f32),
        };
        let plan = plan(low, low_anchor, 1, 0.0);
        let mut depths_pipeline = ComputePipeline::new(
            gpu.ctx,
            &ComputePipelineDesc {
                name: "ipsvi_ert_prepass",
                shader: &ipsvi_ert_depths::INTERFACE,
                specialization: &[],
                max_sets: 1,
            },
        )?;
        let depths_set = depths_pipeline.create_set(&[
            (ipsvi_ert_depths::FRAME_BUFFER, Resource::StorageBuffer(frame)),
            (ipsvi_ert_depths::VOLUME_TEX, Resource::SampledImage(&gpu.volume, &gpu.sampler)),
            (ipsvi_ert_depths::TRANSFER_LUT, Resource::StorageBuffer(&gpu.lut)),
            (ipsvi_ert_depths::DEPTHS, Resource::StorageImage(&depths)),
        ])?;
        let sweep_desc = ComputePipelineDesc {
            name: "ipsvi_exit_sweep",
            shader: &ipsvi_ert_sweep::INTERFACE,
            specialization: &[],
            max_sets: 1,
        };
        let mut sweep_pipelines = parity_pair(gpu.ctx, &sweep_desc)?;
        let sweep_set = sweep_pipelines[0].create_set(&[
            (ipsvi_ert_sweep::DEPTHS, Resource::StorageImage(&depths)),
            (ipsvi_ert_sweep::LMAX_A_READ, Resource::StorageImage(&pair[0])),
            (ipsvi_ert_sweep::LMAX_B_READ, Resource::StorageImage(&pair[1])),
            (ipsvi_ert_sweep::LMAX_A_WRITE, Resource::StorageImage(&pair[0])),
            (ipsvi_ert_sweep::LMAX_B_WRITE, Resource::StorageImage(&pair[1])),
            (ipsvi_ert_sweep::LMAX, Resource::StorageImage(&lmax)),
        ])?;
        Ok(ExitPoints {
            scale,
            width: w,
            height: h,
            depths,
            pair,
            lmax,
            plan,
            depths_pipeline,
            depths_set,
            sweep_pipelines,
            sweep_set,
        })
    }

    pub fn lines(&self) -> u32 {
        self.plan.lines()
    }

    /// Pre-pass, then the exit-point sweep, one dispatch and barrier per line.
    pub fn record(&self, rec: &mut Recorder, profiler: &mut Profiler) -> Result<(), VkError> {
        rec.discard_for_compute(
            "ert_discard_to_compute_access",
            &[&self.depths, &self.pair[0], &self.pair[1], &self.lmax],
        );
        let scope = profiler.begin(rec, "ipsvi_ert_prepass")?;
        rec.bind(&self.depths_pipeline, self.depths_set);
        let push = DepthsPush { scale: self.scale, width: self.width, height: self.height };
        rec.push(&self.depths_pipeline, &push);
        rec.dispatch(self.width.div_ceil(8), self.height.div_ceil(8), 1);
        profiler.end(rec, scope)?;
        rec.barrier(&Barrier::memory(
            "ert_depths_write_to_exit_sweep_read",
            Access::COMPUTE_WRITE,
            Access::COMPUTE_READ,
        ));

        let scope = profiler.begin(rec, "ipsvi_exit_sweep")?;
        // One set for both pipelines (identical layouts): only the pipeline changes per line.
        rec.bind(&self.sweep_pipelines[0], self.sweep_set);
        let anchor = match self.plan.anchor {
            LightAnchor::Source(p) | LightAnchor::Sink(p) => p,
            LightAnchor::AtInfinity(_) => Vec2::ZERO,
        };
        for sweep in &self.plan.sweeps {
            // Toward the light: the main sweep's lines in reverse.
            let mut previous = -1i32;
            for (k, block) in sweep.blocks.iter().rev().enumerate() {
                let pipeline = &self.sweep_pipelines[k % 2];
                rec.bind_pipeline(pipeline);
                let line_scope = profiler.begin_detail(rec, "ipsvi_exit_line")?;
                let push = SweepPush {
                    anchor: anchor.to_array(),
                    line: block.first,
                    previous,
                    span_start: block.span_start,
                    span_len: block.span_len,
                    columns: (sweep.axis == LineAxis::Columns) as u32,
                    zone: sweep.zone as u32,
                };
                rec.push(pipeline, &push);
                rec.dispatch(block.span_len.div_ceil(64), 1, 1);
                profiler.end(rec, line_scope)?;
                rec.barrier(&Barrier::memory(
                    "lmax_write_to_next_line_read",
                    Access::COMPUTE_WRITE,
                    Access::COMPUTE_READ_WRITE,
                ));
                previous = block.first as i32;
            }
        }
        profiler.end(rec, scope)?;
        Ok(())
    }
}
