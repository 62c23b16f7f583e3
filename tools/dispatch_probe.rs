//! Probe (`cargo run --release --example dispatch_probe N`): GPU time of N
//! back-to-back 1x1 dispatches of the DVR pipeline, with and without a
//! barrier between them, and with a descriptor-set bind, a pipeline bind, a
//! push-constant update or a pipeline switch before each. Median of 5 frames.
//! Then the ping-pong blocks of issue 24: parity pipelines, one pipeline with
//! a small set 1 bound per block, or pushed per block, interleaved over 12
//! rounds (GPU and process CPU time per block, medians with 95 % intervals).
//! The measurement is `sweeplab::bench::experiments::dispatch_probe` (tested
//! in the suite); `sweeplab bench sync --workloads empty` measures the sync
//! strategies themselves with intervals.
use sweeplab::bench::experiments::dispatch_probe::{probe, probe_ping_pong, PingPong, ProbeCase};
use sweeplab::vk::{Context, ContextOptions};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n: u32 = match std::env::args().nth(1) {
        Some(a) => a.parse().map_err(|_| format!("dispatch count {a:?}: give a whole number, e.g. 200"))?,
        None => 100,
    };
    let ctx = Context::new(&ContextOptions::default().with_env())?;
    println!("{}", ctx.summary());
    for row in probe(&ctx, &ProbeCase::all(), n, 5)? {
        println!(
            "barrier {:5}, before each dispatch: {:32} {n} dispatches, median of 5: gpu {:.1} us each (host wall {:.1} us)",
            row.case.barrier,
            row.case.before_each.name(),
            row.gpu_us_per_dispatch,
            row.wall_us_per_dispatch
        );
    }
    for row in probe_ping_pong(&ctx, &PingPong::ALL, n, 12)? {
        println!(
            "ping-pong {:32} {n} blocks, 12 rounds: gpu {} us per block, process cpu {} us per block",
            row.variant.name(),
            row.gpu_us_per_block.describe(""),
            row.cpu_us_per_block.describe("")
        );
    }
    Ok(())
}
