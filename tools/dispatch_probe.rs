//! Probe (`cargo run --release --example dispatch_probe N`): GPU time of N back-to-back dispatches of the DVR pipeline at 1x1, with
//! and without a barrier between them, and with a descriptor-set bind, a pipeline bind or a
//! push-constant update before each (lavapipe's per-dispatch costs). Median of 5 frames.
use std::time::Instant;
use sweeplab::render::frame_params::{frame_params, MarchSteps};
use sweeplab::render::{GpuScene, OutputImage};
use sweeplab::scene::default_scene::default_scene;
use sweeplab::shaders::raycast;
use sweeplab::vk::barriers::{Access, Barrier};
use sweeplab::vk::commands::submit_and_wait;
use sweeplab::vk::descriptors::Resource;
use sweeplab::vk::interface::ShaderInterface;
use sweeplab::vk::pipeline::{ComputePipeline, ComputePipelineDesc};
use sweeplab::vk::{Buffer, Context, ContextOptions, Profiler};

fn main() {
    let n: u32 = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(100);
    let ctx = Context::new(&ContextOptions::default().with_env()).unwrap();
    let scene = default_scene(&["volume.size=8".into()]).unwrap();
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let params = frame_params(&scene, 1, 1, gpu.lut_size, MarchSteps::render(&scene));
    let frame = Buffer::with_data(&ctx, "frame", &[params], ash::vk::BufferUsageFlags::UNIFORM_BUFFER).unwrap();
    let out = OutputImage::new(&ctx, "out", 1, 1).unwrap();
    // The DVR shader with a 16-byte push-constant range it does not read: the
    // cost of a push-constant update alone.
    let shader = ShaderInterface { push_constant_bytes: 16, ..raycast::INTERFACE };
    let mut p = ComputePipeline::new(
        &ctx,
        &ComputePipelineDesc { name: "probe", shader: &shader, specialization: &[(0, 0)], max_sets: 1 },
    )
    .unwrap();
    let set = p
        .create_set(&[
            (raycast::FRAME, Resource::UniformBuffer(&frame)),
            (raycast::VOLUME_TEX, Resource::SampledImage(&gpu.volume, &gpu.sampler)),
            (raycast::TRANSFER_LUT, Resource::StorageBuffer(&gpu.lut)),
            (raycast::LIGHTS, Resource::StorageBuffer(&gpu.lights)),
            (raycast::OUT_IMAGE, Resource::StorageImage(&out.image)),
        ])
        .unwrap();
    let mut profiler = Profiler::new(&ctx, 16).unwrap();
    let p2 = ComputePipeline::new(
        &ctx,
        &ComputePipelineDesc { name: "probe2", shader: &shader, specialization: &[(0, 1)], max_sets: 1 },
    )
    .unwrap();
    for (barrier, rebind) in [(true, 0), (true, 1), (true, 2), (true, 3), (true, 4), (false, 0)] {
        let mut samples = Vec::new();
        let mut walls = Vec::new();
        for _ in 0..5 {
            profiler.reset();
            let t = Instant::now();
            submit_and_wait(&ctx, "probe", |rec| {
                out.prepare_for_compute_write(rec);
                let s = profiler.begin(rec, "dispatches")?;
                rec.bind(&p, set);
                for _ in 0..n {
                    match rebind {
                        1 => rec.bind_set(&p, set),
                        2 => rec.bind(&p, set),
                        3 => rec.push(&p, &[0u32; 4]),
                        4 => rec.bind_pipeline(if rec.dispatch_count % 2 == 0 { &p } else { &p2 }),
                        _ => {}
                    }
                    rec.dispatch(1, 1, 1);
                    if barrier {
                        rec.barrier(&Barrier::memory("probe", Access::COMPUTE_WRITE, Access::COMPUTE_READ_WRITE));
                    }
                }
                profiler.end(rec, s)?;
                Ok(())
            })
            .unwrap();
            walls.push(t.elapsed().as_secs_f64() * 1e3);
            samples.push(profiler.resolve(0).unwrap().gpu_ms_total);
        }
        samples.sort_by(f64::total_cmp);
        walls.sort_by(f64::total_cmp);
        let (gpu_ms, wall) = (samples[2], walls[2]);
        let what = ["nothing", "descriptor set", "pipeline + set", "push constants", "alternating pipelines, same set"]
            [rebind];
        println!(
            "barrier {barrier:5}, before each dispatch: {what:32} {n} dispatches, median of 5: gpu {gpu_ms:.3} ms = {:.1} us each (host wall {wall:.3} ms)",
            gpu_ms * 1e3 / n as f64
        );
    }
}
