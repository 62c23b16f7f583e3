//! `sweeplab view`: thin wiring from the arguments to `sweeplab::viewer`.

use super::args::{PreviewArg, ViewArgs};
use super::render_cmd::write_json;
use super::session;
use anyhow::Context as _;
use std::process::ExitCode;
use sweeplab::techniques::Technique;
use sweeplab::viewer::preview::PreviewMode;
use sweeplab::viewer::{self, SceneSource, Script, ViewerOptions};
use sweeplab::vk::validation_verdict::ValidationVerdict;

pub fn run(args: &ViewArgs) -> anyhow::Result<ExitCode> {
    let technique: Technique = args.technique.parse().map_err(|e: String| anyhow::anyhow!("--technique: {e}"))?;
    if args.screenshot.is_some() && args.frames.is_none() {
        anyhow::bail!("--screenshot needs --frames N (the screenshot is of the last frame)");
    }
    if args.frames == Some(0) {
        anyhow::bail!("--frames 0: at least one frame");
    }
    let overrides = super::scene_args::overrides(&args.scene)?;
    let source = match (&args.scene.scene, &args.scene.volume) {
        (Some(path), _) => SceneSource::File(path.clone()),
        (None, Some(path)) => SceneSource::Volume(path.clone()),
        (None, None) => SceneSource::Default,
    };
    let script = match &args.script {
        Some(path) => Script::load(path)?,
        None => Script::default(),
    };
    let options = ViewerOptions {
        technique,
        context: super::session::context_options(&args.gpu),
        texels: session::volume_texels(&args.gpu),
        present_mode: args.present_mode,
        frames: args.frames,
        screenshot: args.screenshot.clone(),
        script,
        out_dir: std::path::PathBuf::from("."),
        ui: !args.no_ui,
        hide_panel: args.hide_panel,
        handoff_barrier: !args.racy_no_handoff_barrier,
        preview: match args.preview {
            PreviewArg::On => PreviewMode::On,
            PreviewArg::Off => PreviewMode::Off,
            // Scripted runs (`--frames`) render every frame at full quality.
            PreviewArg::Auto if args.frames.is_some() => PreviewMode::Off,
            PreviewArg::Auto => PreviewMode::On,
        },
    };
    let (report, validation) = viewer::run(source, &overrides, &options).context("sweeplab view")?;
    let warm = report.frames.len().min(2);
    if let (Some(frame), Some(gpu)) = (report.mean(warm, |f| Some(f.frame_ms)), report.mean(warm, |f| Some(f.gpu_ms))) {
        let present = report.mean(warm, |f| f.present_gpu_ms).unwrap_or(0.0);
        println!(
            "{technique}: {} frames, mean frame {frame:.3} ms, technique GPU {gpu:.3} ms, present pass GPU {present:.3} ms \
             ({} present mode, first {warm} frames left out)",
            report.frames.len(),
            report.present_mode
        );
    }
    if let Some(path) = &args.log_json {
        write_json(path, &serde_json::to_value(&report)?)?;
    }
    let enabled = super::session::context_options(&args.gpu).validate;
    let verdict = ValidationVerdict::of(validation);
    for line in verdict.report_lines(enabled) {
        eprintln!("{line}");
    }
    Ok(if verdict.failed() { ExitCode::from(2) } else { ExitCode::SUCCESS })
}
