//! What the pieces of a line sweep cost on their own: N back-to-back 1x1
//! dispatches of the DVR pipeline, with and without a barrier between them,
//! and with a descriptor-set bind, a pipeline bind, a push-constant update or
//! a switch between two pipelines before each (`cargo run --release --example
//! dispatch_probe N`). On lavapipe a dispatch costs tens of microseconds and a
//! set bind far more, which is why IPSVI binds its set once per sweep.

use super::ExperimentError;
use crate::bench::estimate::median_of;
use crate::render::frame_params::{frame_params, MarchSteps};
use crate::render::{GpuScene, OutputImage};
use crate::shaders::raycast;
use crate::techniques::default_scene;
use crate::vk::barriers::{Access, Barrier};
use crate::vk::commands::submit_and_wait;
use crate::vk::descriptors::Resource;
use crate::vk::pipeline::{ComputePipeline, ComputePipelineDesc};
use crate::vk::{Buffer, Context, Profiler};
use std::time::Instant;

/// What is recorded before each dispatch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BeforeEach {
    Nothing,
    DescriptorSet,
    PipelineAndSet,
    PushConstants,
    AlternatingPipelines,
}

impl BeforeEach {
    pub const ALL: [BeforeEach; 5] = [
        BeforeEach::Nothing,
        BeforeEach::DescriptorSet,
        BeforeEach::PipelineAndSet,
        BeforeEach::PushConstants,
        BeforeEach::AlternatingPipelines,
    ];

    pub fn name(self) -> &'static str {
        match self {
            BeforeEach::Nothing => "nothing",
            BeforeEach::DescriptorSet => "descriptor set",
            BeforeEach::PipelineAndSet => "pipeline + set",
            BeforeEach::PushConstants => "push constants",
            BeforeEach::AlternatingPipelines => "alternating pipelines, same set",
        }
    }
}

/// One case: a barrier between dispatches or not, and what comes before each.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ProbeCase {
    pub barrier: bool,
    pub before_each: BeforeEach,
}

impl ProbeCase {
    /// Every case with barriers, then dispatches alone with no barrier (racy).
    pub fn all() -> Vec<ProbeCase> {
        let mut cases: Vec<ProbeCase> =
            BeforeEach::ALL.into_iter().map(|before_each| ProbeCase { barrier: true, before_each }).collect();
        cases.push(ProbeCase { barrier: false, before_each: BeforeEach::Nothing });
        cases
    }
}

/// A case's result: GPU and host wall time per dispatch (medians of the frames).
#[derive(Clone, Copy, Debug)]
pub struct ProbeRow {
    pub case: ProbeCase,
    pub dispatches: u32,
    pub gpu_us_per_dispatch: f64,
    pub wall_us_per_dispatch: f64,
}

/// Runs each of `cases`: `frames` frames of `dispatches` dispatches.
pub fn probe(
    ctx: &Context,
    cases: &[ProbeCase],
    dispatches: u32,
    frames: u32,
) -> Result<Vec<ProbeRow>, ExperimentError> {
    let scene = default_scene(&["volume.size=8".into()]).map_err(|e| ExperimentError::Invalid(e.to_string()))?;
    let gpu = GpuScene::upload(ctx, &scene)?;
    let params = frame_params(&scene, 1, 1, gpu.lut_size, MarchSteps::render(&scene));
    let frame = Buffer::with_data(ctx, "probe frame", &[params], ash::vk::BufferUsageFlags::UNIFORM_BUFFER)?;
    let out = OutputImage::new(ctx, "probe out", 1, 1)?;
    // Read only where a chunk is not the first; every probe dispatch is.
    let state = OutputImage::new(ctx, "probe state", 1, 1)?;
    let pipeline = |name: &'static str, shading: u32| {
        ComputePipeline::new(
            ctx,
            &ComputePipelineDesc { name, shader: &raycast::INTERFACE, specialization: &[(0, shading)], max_sets: 1 },
        )
    };
    let mut first = pipeline("probe", 0)?;
    let second = pipeline("probe second", 1)?;
    let set = first.create_set(&[
        (raycast::FRAME, Resource::UniformBuffer(&frame)),
        (raycast::VOLUME_TEX, Resource::SampledImage(&gpu.volume, &gpu.sampler)),
        (raycast::TRANSFER_LUT, Resource::StorageBuffer(&gpu.lut)),
        (raycast::LIGHTS, Resource::StorageBuffer(&gpu.lights)),
        (raycast::OUT_IMAGE, Resource::StorageImage(&out.image)),
        (raycast::STATE_IN, Resource::StorageImage(&state.image)),
    ])?;
    // A first chunk of no samples: the dispatch itself is the whole cost.
    let chunk = [0u32, 0, 1, 1];
    let mut profiler = Profiler::new(ctx, 16)?;
    let mut rows = Vec::new();
    for &case in cases {
        let (mut gpu_ms, mut wall_ms) = (Vec::new(), Vec::new());
        for _ in 0..frames.max(1) {
            profiler.reset();
            let t = Instant::now();
            submit_and_wait(ctx, "dispatch probe", |rec| {
                out.prepare_for_compute_write(rec);
                state.prepare_for_compute_read_write(rec);
                let scope = profiler.begin(rec, "dispatches")?;
                rec.bind(&first, set);
                rec.push(&first, &chunk);
                for n in 0..dispatches {
                    match case.before_each {
                        BeforeEach::Nothing => {}
                        BeforeEach::DescriptorSet => rec.bind_set(&first, set),
                        BeforeEach::PipelineAndSet => rec.bind(&first, set),
                        BeforeEach::PushConstants => rec.push(&first, &chunk),
                        BeforeEach::AlternatingPipelines => {
                            rec.bind_pipeline(if n % 2 == 0 { &first } else { &second })
                        }
                    }
                    rec.dispatch(1, 1, 1);
                    if case.barrier {
                        // The barrier under measurement: the 1x1 output is
                        // never read, so it protects nothing the probe needs.
                        rec.barrier(&Barrier::memory(
                            "probe_barrier_under_measurement",
                            Access::COMPUTE_WRITE,
                            Access::COMPUTE_READ_WRITE,
                        ));
                    }
                }
                profiler.end(rec, scope)
            })?;
            wall_ms.push(t.elapsed().as_secs_f64() * 1e3);
            gpu_ms.push(profiler.resolve(0)?.gpu_ms_total);
        }
        let median = |mut v: Vec<f64>| {
            v.sort_by(f64::total_cmp);
            median_of(&v)
        };
        let per = |ms: f64| ms * 1e3 / dispatches.max(1) as f64;
        rows.push(ProbeRow {
            case,
            dispatches,
            gpu_us_per_dispatch: per(median(gpu_ms)),
            wall_us_per_dispatch: per(median(wall_ms)),
        });
    }
    Ok(rows)
}
