//! The AO preprocessing before an `ao` frame, with its progress on the
//! terminal (stderr): one line per step, rewritten in place at most every
//! 200 ms, each with the time it estimates is left.

use std::io::Write;
use std::time::{Duration, Instant};
use sweeplab::ao::AoSettings;

use anyhow::Context as _;
use sweeplab::ao::technique::preprocessed_telling;
use sweeplab::ao::{CacheOutcome, Progress};
use sweeplab::scene::Scene;
use sweeplab::techniques::Technique;
use sweeplab::vk::Context;

/// Runs (or loads) `scene`'s AO preprocessing when `technique` is `ao`, so the
/// frame finds it in memory; other techniques need nothing.
pub fn prepare(scene: &Scene, technique: Technique, device: &Context) -> anyhow::Result<()> {
    if technique != Technique::Ao {
        return Ok(());
    }
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
    let (_, outcome) =
        preprocessed_telling(&scene.volume, &scene.settings.get::<AoSettings>(), Some(device), &mut report)
            .context("ao preprocessing")?;
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
