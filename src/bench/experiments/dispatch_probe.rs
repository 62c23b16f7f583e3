//! What the pieces of a line sweep cost on their own: N back-to-back 1x1
//! dispatches of the DVR pipeline, with and without a barrier between them,
//! and with a descriptor-set bind, a pipeline bind, a push-constant update or
//! a switch between two pipelines before each (`cargo run --release --example
//! dispatch_probe N`). On lavapipe a dispatch costs tens of microseconds and a
//! set bind far more, which is why IPSVI binds its set once per sweep.

use super::ExperimentError;
use crate::bench::cpu_time::{cpu_ms_between, process_cpu_time};
use crate::bench::estimate::{median_estimate, median_of, Estimate};
use crate::render::frame_params::{frame_params, MarchSteps};
use crate::render::{GpuScene, OutputImage};
use crate::shaders::{probe_parity, probe_sets, raycast};
use crate::techniques::default_scene;
use crate::vk::barriers::{Access, Barrier};
use crate::vk::commands::submit_and_wait;
use crate::vk::descriptors::{DescriptorAllocator, Resource};
use crate::vk::error::VkResultExt;
use crate::vk::pipeline::{layout_bindings, parity_pair, specialized_pipeline, ComputePipeline, ComputePipelineDesc};
use crate::vk::{Buffer, Context, Profiler};
use ash::vk;
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
    let frame = Buffer::with_data(ctx, "probe frame", &[params], ash::vk::BufferUsageFlags::STORAGE_BUFFER)?;
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
        (raycast::FRAME_BUFFER, Resource::StorageBuffer(&frame)),
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

/// How a ping-pong block switches sides (issue 24): what the block pays
/// before its dispatch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PingPong {
    /// Today's passes: one pipeline per parity (each its own SPIR-V build),
    /// both images in the one big set, bound once.
    ParityPipelines,
    /// One pipeline; the big set bound once at set 0, and a small set 1 of the
    /// two images ({in = a, out = b} or {in = b, out = a}) bound per block.
    SmallSets,
    /// One pipeline; the small set pushed per block (VK_KHR_push_descriptor).
    PushedSet,
}

impl PingPong {
    pub const ALL: [PingPong; 3] = [PingPong::ParityPipelines, PingPong::SmallSets, PingPong::PushedSet];

    pub fn name(self) -> &'static str {
        match self {
            PingPong::ParityPipelines => "parity pipelines",
            PingPong::SmallSets => "one pipeline, small set bound",
            PingPong::PushedSet => "one pipeline, small set pushed",
        }
    }
}

/// One variant's per-block cost over the rounds: GPU time and process CPU
/// time per block, medians with 95 % intervals.
#[derive(Clone, Copy, Debug)]
pub struct PingPongRow {
    pub variant: PingPong,
    pub blocks: u32,
    pub gpu_us_per_block: Estimate,
    pub cpu_us_per_block: Estimate,
}

/// The set-1 pipeline of `probe_sets.comp`, made here by hand: sweeplab's
/// [`ComputePipeline`] has set 0 only. Its set 1 is a push-descriptor layout
/// when `pushed`.
struct TwoSetPipeline<'a> {
    ctx: &'a Context,
    raw: vk::Pipeline,
    layout: vk::PipelineLayout,
    set_layouts: [vk::DescriptorSetLayout; 2],
}

impl Drop for TwoSetPipeline<'_> {
    fn drop(&mut self) {
        // SAFETY: the probe waited for every submission using these objects
        // (submit_and_wait); null handles (a failed creation) are no-ops.
        unsafe {
            self.ctx.device.destroy_pipeline(self.raw, None);
            self.ctx.device.destroy_pipeline_layout(self.layout, None);
            for l in self.set_layouts {
                self.ctx.device.destroy_descriptor_set_layout(l, None);
            }
        }
    }
}

impl<'a> TwoSetPipeline<'a> {
    fn new(ctx: &'a Context, pushed: bool) -> Result<TwoSetPipeline<'a>, ExperimentError> {
        let shader = &probe_sets::INTERFACE;
        let mut p = TwoSetPipeline {
            ctx,
            raw: vk::Pipeline::null(),
            layout: vk::PipelineLayout::null(),
            set_layouts: [vk::DescriptorSetLayout::null(); 2],
        };
        for (i, bindings) in [shader.bindings, shader.set1].into_iter().enumerate() {
            let list = layout_bindings(bindings);
            let mut info = vk::DescriptorSetLayoutCreateInfo::default().bindings(&list);
            if i == 1 && pushed {
                info = info.flags(vk::DescriptorSetLayoutCreateFlags::PUSH_DESCRIPTOR_KHR);
            }
            // SAFETY: valid device and create info (push flag only with the extension enabled).
            p.set_layouts[i] =
                unsafe { ctx.device.create_descriptor_set_layout(&info, None) }.call("vkCreateDescriptorSetLayout")?;
        }
        let info = vk::PipelineLayoutCreateInfo::default().set_layouts(&p.set_layouts);
        // SAFETY: valid device; both set layouts were just created.
        p.layout = unsafe { ctx.device.create_pipeline_layout(&info, None) }.call("vkCreatePipelineLayout")?;
        // volume_fetch.glsl's filter constant, as every pipeline gets it.
        p.raw = specialized_pipeline(ctx, shader.builds[0], p.layout, &ctx.shared_specialization())?;
        Ok(p)
    }
}

/// Runs `rounds` rounds; each round runs every variant of `variants` in turn
/// (A B C A B C: what the machine does during a round falls on all of them),
/// one frame of `blocks` ping-pong blocks each, a barrier between blocks (each
/// block reads what the previous one wrote). [`PingPong::PushedSet`] needs
/// VK_KHR_push_descriptor and is left out where the device lacks it.
pub fn probe_ping_pong(
    ctx: &Context,
    variants: &[PingPong],
    blocks: u32,
    rounds: u32,
) -> Result<Vec<PingPongRow>, ExperimentError> {
    let variants: Vec<PingPong> =
        variants.iter().copied().filter(|v| *v != PingPong::PushedSet || ctx.push_descriptor.is_some()).collect();
    let scene = default_scene(&["volume.size=8".into()]).map_err(|e| ExperimentError::Invalid(e.to_string()))?;
    let gpu = GpuScene::upload(ctx, &scene)?;
    let params = frame_params(&scene, 1, 1, gpu.lut_size, MarchSteps::render(&scene));
    let frame = Buffer::with_data(ctx, "probe frame", &[params], ash::vk::BufferUsageFlags::STORAGE_BUFFER)?;
    let a = OutputImage::new(ctx, "probe ping-pong a", 1, 1)?;
    let b = OutputImage::new(ctx, "probe ping-pong b", 1, 1)?;
    let desc = |name| ComputePipelineDesc { name, shader: &probe_parity::INTERFACE, specialization: &[], max_sets: 1 };
    let mut parity = parity_pair(ctx, &desc("probe parity"))?;
    let parity_set = parity[0].create_set(&[
        (probe_parity::FRAME_BUFFER, Resource::StorageBuffer(&frame)),
        (probe_parity::VOLUME_TEX, Resource::SampledImage(&gpu.volume, &gpu.sampler)),
        (probe_parity::TRANSFER_LUT, Resource::StorageBuffer(&gpu.lut)),
        (probe_parity::LIGHTS, Resource::StorageBuffer(&gpu.lights)),
        (probe_parity::A_READ, Resource::StorageImage(&a.image)),
        (probe_parity::B_READ, Resource::StorageImage(&b.image)),
        (probe_parity::A_WRITE, Resource::StorageImage(&a.image)),
        (probe_parity::B_WRITE, Resource::StorageImage(&b.image)),
    ])?;
    let shader = &probe_sets::INTERFACE;
    let bound = TwoSetPipeline::new(ctx, false)?;
    let pushed = if ctx.push_descriptor.is_some() { Some(TwoSetPipeline::new(ctx, true)?) } else { None };
    let mut big_sets = DescriptorAllocator::new(ctx, shader.bindings, 1)?;
    let big = big_sets.create_set(
        shader.name,
        bound.set_layouts[0],
        shader.bindings,
        &[
            (probe_sets::FRAME_BUFFER, Resource::StorageBuffer(&frame)),
            (probe_sets::VOLUME_TEX, Resource::SampledImage(&gpu.volume, &gpu.sampler)),
            (probe_sets::TRANSFER_LUT, Resource::StorageBuffer(&gpu.lut)),
            (probe_sets::LIGHTS, Resource::StorageBuffer(&gpu.lights)),
        ],
    )?;
    let mut small_sets = DescriptorAllocator::new(ctx, shader.set1, 2)?;
    let mut small = |from: &OutputImage, to: &OutputImage| {
        small_sets.create_set(
            shader.name,
            bound.set_layouts[1],
            shader.set1,
            &[
                (probe_sets::IMAGE_IN, Resource::StorageImage(&from.image)),
                (probe_sets::IMAGE_OUT, Resource::StorageImage(&to.image)),
            ],
        )
    };
    let small = [small(&a, &b)?, small(&b, &a)?];
    // The push variant's writes: parity 0 reads a and writes b.
    let views = [[a.image.view, b.image.view], [b.image.view, a.image.view]];
    let mut profiler = Profiler::new(ctx, 4)?;
    let (mut gpu_us, mut cpu_us) = (vec![Vec::new(); variants.len()], vec![Vec::new(); variants.len()]);
    for _ in 0..rounds.max(1) {
        for (v, &variant) in variants.iter().enumerate() {
            profiler.reset();
            let cpu_start = process_cpu_time();
            submit_and_wait(ctx, "ping-pong probe", |rec| {
                rec.discard_for_compute("pingpong_discard_to_compute_access", &[&a.image, &b.image]);
                let scope = profiler.begin(rec, "blocks")?;
                // SAFETY (each call below): the pipelines, layouts and sets belong
                // to this device and match (set 0 the big set, set 1 the small
                // one); cb is recording; the pushed writes point into `views`.
                match variant {
                    PingPong::ParityPipelines => rec.bind_set(&parity[0], parity_set),
                    PingPong::SmallSets | PingPong::PushedSet => {
                        let p = if variant == PingPong::SmallSets { &bound } else { pushed.as_ref().unwrap_or(&bound) };
                        unsafe {
                            ctx.device.cmd_bind_pipeline(rec.cb, vk::PipelineBindPoint::COMPUTE, p.raw);
                            ctx.device.cmd_bind_descriptor_sets(
                                rec.cb,
                                vk::PipelineBindPoint::COMPUTE,
                                p.layout,
                                0,
                                &[big],
                                &[],
                            );
                        }
                    }
                }
                for n in 0..blocks as usize {
                    let side = n % 2;
                    match variant {
                        PingPong::ParityPipelines => rec.bind_pipeline(&parity[side]),
                        PingPong::SmallSets => unsafe {
                            ctx.device.cmd_bind_descriptor_sets(
                                rec.cb,
                                vk::PipelineBindPoint::COMPUTE,
                                bound.layout,
                                1,
                                &[small[side]],
                                &[],
                            )
                        },
                        PingPong::PushedSet => {
                            let (Some(push), Some(p)) = (&ctx.push_descriptor, &pushed) else { unreachable!() };
                            let infos = views[side].map(|view| {
                                [vk::DescriptorImageInfo::default()
                                    .image_view(view)
                                    .image_layout(vk::ImageLayout::GENERAL)]
                            });
                            let writes: Vec<vk::WriteDescriptorSet> = shader
                                .set1
                                .iter()
                                .zip(&infos)
                                .map(|(binding, info)| {
                                    vk::WriteDescriptorSet::default()
                                        .dst_binding(binding.index)
                                        .descriptor_type(binding.kind.vk_type())
                                        .image_info(info)
                                })
                                .collect();
                            unsafe {
                                push.cmd_push_descriptor_set(
                                    rec.cb,
                                    vk::PipelineBindPoint::COMPUTE,
                                    p.layout,
                                    1,
                                    &writes,
                                )
                            };
                        }
                    }
                    rec.dispatch(1, 1, 1);
                    // The next block reads what this one wrote.
                    rec.barrier(&Barrier::memory(
                        "probe_block_write_to_next_block_read",
                        Access::COMPUTE_WRITE,
                        Access::COMPUTE_READ_WRITE,
                    ));
                }
                profiler.end(rec, scope)
            })?;
            let per = |ms: f64| ms * 1e3 / blocks.max(1) as f64;
            cpu_us[v].push(per(cpu_ms_between(cpu_start, process_cpu_time())));
            gpu_us[v].push(per(profiler.resolve(0)?.gpu_ms_total));
        }
    }
    let estimate = |samples: &[f64]| median_estimate(samples).map_err(|e| ExperimentError::Invalid(e.to_string()));
    variants
        .iter()
        .enumerate()
        .map(|(v, &variant)| {
            Ok(PingPongRow {
                variant,
                blocks,
                gpu_us_per_block: estimate(&gpu_us[v])?,
                cpu_us_per_block: estimate(&cpu_us[v])?,
            })
        })
        .collect()
}
