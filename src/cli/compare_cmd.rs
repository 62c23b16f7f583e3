//! `sweeplab compare`: the flags, then `sweeplab::techniques::comparison`.

use super::args::CompareArgs;
use super::render_cmd::write_json;
use super::{scene_args, session};
use anyhow::Context as _;
use std::process::ExitCode;
use sweeplab::bench::{plot_error_map, ErrorMap};
use sweeplab::metrics::pixel_errors;
use sweeplab::output_paths;
use sweeplab::techniques::comparison::{compare_with_reference, comparison_scene, ReferenceSource};
use sweeplab::techniques::ground_truth_cache::GroundTruthCache;
use sweeplab::techniques::Technique;
use sweeplab::vk::Profiler;

pub fn run(args: &CompareArgs) -> anyhow::Result<ExitCode> {
    let technique: Technique = args.technique.parse().map_err(|e: String| anyhow::anyhow!("--technique: {e}"))?;
    for (flag, path) in [("--heatmap", &args.heatmap), ("--out", &args.out), ("--reference-out", &args.reference_out)] {
        if let Some(path) = path {
            output_paths::check_png(flag, path)?;
        }
    }
    if let Some(path) = &args.json {
        output_paths::check_file("--json", path)?;
    }
    let source: ReferenceSource = args.reference.parse().map_err(|e: String| anyhow::anyhow!("--reference: {e}"))?;
    let scene = comparison_scene(&scene_args::load(&args.scene)?, technique);
    technique.check(&scene).with_context(|| format!("rendering {technique}"))?;
    for warning in technique.warnings(&scene).into_iter().chain(technique.unused_settings(&scene)) {
        eprintln!("warning: {warning}");
    }
    if let Some(note) = technique.settings_note(&scene) {
        eprintln!("{note}");
    }
    let ctx = session::open(&args.gpu)?;
    session::report_long_waits(&ctx);
    let texels = session::volume_texels(&args.gpu);
    let cache = args.reference_cache.as_ref().map(GroundTruthCache::new);
    let capacity = Profiler::FRAME_CAPACITY;
    let c = compare_with_reference(&ctx, &scene, technique, source, texels, capacity, cache.as_ref())?;
    for line in c.lines() {
        println!("{line}");
    }
    if let Some(path) = &args.json {
        write_json(path, &serde_json::to_value(&c)?)?;
        println!("wrote {} (the figures)", path.display());
    }
    if let Some(path) = &args.heatmap {
        let title = format!("{}: largest channel error against the reference", technique.name());
        let errors = pixel_errors(&c.image, &c.reference_image)?;
        plot_error_map(path, &ErrorMap { title, width: c.width, height: c.height, errors })?;
        println!("wrote {} and {} (error heat map)", path.display(), path.with_extension("svg").display());
    }
    if let Some(path) = &args.out {
        c.image.save_png(path)?;
        println!("wrote {} ({technique})", path.display());
    }
    if let Some(path) = &args.reference_out {
        c.reference_image.save_png(path)?;
        println!("wrote {} (the reference)", path.display());
    }
    Ok(session::finish(&ctx))
}
