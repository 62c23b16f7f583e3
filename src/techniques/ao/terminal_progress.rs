//! The AO preprocessing with its progress on a terminal (stderr), for the
//! command line: one line per step, rewritten in place at most every 200 ms,
//! each with the time it estimates is left, then where the result came from.

use super::error::AoError;
use super::progress::Progress;
use super::settings::AoSettings;
use super::technique::preprocessed_telling;
use super::CacheOutcome;
use crate::scene::Volume;
use crate::vk::Context;
use std::io::Write;
use std::time::{Duration, Instant};

/// Runs (or loads) the preprocessing of `volume` with `settings`, so that the
/// next AO frame finds it in memory, telling the terminal how far it is.
pub fn preprocess_on_terminal(volume: &Volume, settings: &AoSettings, device: &Context) -> Result<(), AoError> {
    let mut step = String::new();
    let mut last_print = Instant::now() - Duration::from_secs(1);
    let mut stderr = std::io::stderr();
    let mut report = |p: &Progress| {
        let new_step = p.step != step;
        if new_step && !step.is_empty() {
            let _ = writeln!(stderr);
        }
        if new_step || p.fraction >= 1.0 || last_print.elapsed() >= Duration::from_millis(200) {
            let _ = write!(stderr, "\r{:<72}", p.line());
            let _ = stderr.flush();
            last_print = Instant::now();
            step = p.step.to_string();
        }
    };
    let (_, outcome) = preprocessed_telling(volume, settings, Some(device), &mut report)?;
    if !step.is_empty() {
        let _ = writeln!(stderr);
    }
    if let Some(outcome) = outcome {
        eprintln!("{}", cache_line(&outcome));
    }
    Ok(())
}

/// Where the preprocessing came from, in one line.
fn cache_line(outcome: &CacheOutcome) -> String {
    match outcome {
        CacheOutcome::Hit(path) => format!("ao: loaded preprocessing from cache {}", path.display()),
        CacheOutcome::Stored(path, _) => format!("ao: computed preprocessing, cached at {}", path.display()),
        CacheOutcome::Disabled => "ao: computed preprocessing (ao.cache = false: not cached)".to_string(),
    }
}
