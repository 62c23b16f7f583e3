//! The `sweeplab` command line: render, compare against the ground truth, list
//! devices. Errors name the file or flag and the problem and exit non-zero.

mod cli;

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args = cli::args::Cli::parse();
    match cli::run(args) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {}", cli::error_report::error_text(&e));
            ExitCode::from(1)
        }
    }
}
