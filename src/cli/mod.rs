mod ao_progress;
pub mod args;
mod bench_ao;
mod bench_ipsvi;
mod bench_lights;
mod bench_stability;
mod bench_sync;
mod bench_table1;
mod compare_cmd;
mod devices_cmd;
pub mod error_report;
mod experiment_runner;
mod keys_cmd;
mod render_cmd;
mod report_cmd;
mod scene_args;
mod session;
mod view_cmd;

use std::process::ExitCode;

pub fn run(cli: args::Cli) -> anyhow::Result<ExitCode> {
    match cli.command {
        args::Command::Devices(a) => devices_cmd::run(&a),
        args::Command::Render(a) => render_cmd::run(&a),
        args::Command::Compare(a) => compare_cmd::run(&a),
        args::Command::View(a) => view_cmd::run(&a),
        args::Command::Report(a) => report_cmd::run(&a),
        args::Command::Keys(a) => keys_cmd::run(&a),
        args::Command::Bench(args::BenchCommand::Ipsvi(a)) => bench_ipsvi::run(&a),
        args::Command::Bench(args::BenchCommand::Sync(a)) => bench_sync::run(&a),
        args::Command::Bench(args::BenchCommand::Table1(a)) => bench_table1::run(&a),
        args::Command::Bench(args::BenchCommand::Lights(a)) => bench_lights::run(&a),
        args::Command::Bench(args::BenchCommand::Stability(a)) => bench_stability::run(&a),
        args::Command::Bench(args::BenchCommand::Ao(a)) => bench_ao::run(&a),
    }
}
