//! The AO preprocessing before an `ao` frame, its progress on the terminal.

use anyhow::Context as _;
use sweeplab::scene::Scene;
use sweeplab::techniques::ao::terminal_progress::preprocess_on_terminal;
use sweeplab::techniques::Technique;
use sweeplab::vk::Context;

/// Runs (or loads) `scene`'s AO preprocessing when `technique` is `ao`, so the
/// frame finds it in memory; other techniques need nothing.
pub fn prepare(scene: &Scene, technique: Technique, device: &Context) -> anyhow::Result<()> {
    if technique == Technique::Ao {
        preprocess_on_terminal(&scene.volume, &scene.settings.get(), device).context("ao preprocessing")?;
    }
    Ok(())
}
