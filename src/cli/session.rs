//! A Vulkan context for one command, and the validation verdict at its end.

use super::args::GpuArgs;
use anyhow::Context as _;
use std::process::ExitCode;
use sweeplab::bench::Harness;
use sweeplab::render::VolumeTexels;
use sweeplab::vk::{Context, ContextOptions};

pub fn open(gpu: &GpuArgs) -> anyhow::Result<Context> {
    let options = ContextOptions { device: gpu.device.clone(), validate: gpu.validate }.with_env();
    let ctx = Context::new(&options).context("cannot start Vulkan")?;
    eprintln!("{}", ctx.summary());
    Ok(ctx)
}

/// Prints the validation messages, if any, and turns them into a failing exit code.
pub fn finish(ctx: &Context) -> ExitCode {
    let messages = ctx.take_validation_messages();
    if messages.is_empty() {
        if ctx.validation_enabled() {
            eprintln!("validation: clean");
        }
        return ExitCode::SUCCESS;
    }
    eprintln!("validation: {} message(s)", messages.len());
    for m in &messages {
        eprintln!("{m}");
    }
    ExitCode::from(2)
}

pub fn volume_texels(gpu: &GpuArgs) -> VolumeTexels {
    if gpu.float_volume {
        VolumeTexels::Float32
    } else {
        VolumeTexels::Native
    }
}

/// `--repeat` timed runs after `warm_up` untimed ones; 0 repeats is refused.
pub fn harness(warm_up: u32, repeat: u32) -> anyhow::Result<Harness> {
    Harness::new(warm_up, repeat).map_err(|e| anyhow::anyhow!("--repeat: {e}"))
}
