//! The `sweeplab` command line: render, compare against the ground truth, list
//! devices. Errors name the file or flag and the problem and exit non-zero.

mod cli;

use clap::error::{ContextKind, ContextValue, ErrorKind};
use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args = match cli::args::Cli::try_parse() {
        Ok(args) => args,
        Err(e) => return argument_error(e),
    };
    match cli::run(args) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {}", cli::error_report::error_text(&e));
            ExitCode::from(1)
        }
    }
}

/// clap's report, except that a missing argument is named on the error's
/// first line (clap lists it on the lines below, which a log that keeps one
/// line per error loses).
fn argument_error(e: clap::Error) -> ExitCode {
    if e.kind() == ErrorKind::MissingRequiredArgument {
        if let Some(ContextValue::Strings(missing)) = e.get(ContextKind::InvalidArg) {
            let usage = match e.get(ContextKind::Usage) {
                Some(ContextValue::StyledStr(usage)) => format!("\n\n{usage}"),
                _ => String::new(),
            };
            eprintln!("error: missing {}{usage}\n\nFor more information, try '--help'.", missing.join(", "));
            return ExitCode::from(2);
        }
    }
    e.exit()
}
