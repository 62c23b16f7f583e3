use super::args::RenderArgs;
use super::{scene_args, session};
use anyhow::Context as _;
use std::path::Path;
use std::process::ExitCode;
use sweeplab::output_paths;
use sweeplab::plural::count;
use sweeplab::render::GpuScene;
use sweeplab::techniques::{render, Technique};
use sweeplab::vk::Profiler;

pub fn run(args: &RenderArgs) -> anyhow::Result<ExitCode> {
    let technique: Technique = args.technique.parse().map_err(|e: String| anyhow::anyhow!("--technique: {e}"))?;
    output_paths::check_png("--out", &args.out)?;
    for (flag, path) in [("--profile-json", &args.profile_json), ("--trace", &args.trace)] {
        if let Some(path) = path {
            output_paths::check_file(flag, path)?;
        }
    }
    let scene = scene_args::load(&args.scene)?;
    technique.check(&scene).with_context(|| format!("rendering {technique}"))?;
    for warning in technique.warnings(&scene).into_iter().chain(technique.unused_settings(&scene)) {
        eprintln!("warning: {warning}");
    }
    let ctx = session::open(&args.gpu)?;
    session::report_long_waits(&ctx);
    super::ao_progress::prepare(&scene, technique, &ctx)?;
    let output = {
        let gpu =
            GpuScene::upload_with(&ctx, &scene, session::volume_texels(&args.gpu)).context("uploading the scene")?;
        let mut profiler = Profiler::new(&ctx, Profiler::FRAME_CAPACITY)?;
        // On unless --no-detail came last (each flag overrides the other).
        profiler.set_detail(args.detail || !args.no_detail);
        render(&gpu, technique, scene.render.width, scene.render.height, &mut profiler)
            .with_context(|| format!("rendering {technique}"))?
    };
    output.image.save_png(&args.out)?;
    print!("{}", output.profile.table());
    if let Some(note) = technique.settings_note(&scene) {
        println!("{note}");
    }
    if let Some(shape) = &output.shape {
        println!("{}", shape.summary());
    }
    println!(
        "{technique}: {}x{} -> {} ({}, {})",
        scene.render.width,
        scene.render.height,
        args.out.display(),
        count(output.dispatches, "dispatch", "dispatches"),
        count(output.barriers, "barrier", "barriers")
    );
    if let Some(path) = &args.profile_json {
        let mut profile = output.profile.to_json();
        if let (Some(shape), Some(fields)) = (&output.shape, profile.as_object_mut()) {
            fields.insert("line_shape".into(), serde_json::to_value(shape)?);
        }
        write_json(path, &profile)?;
        println!("wrote {} (per-pass GPU profile)", path.display());
    }
    if let Some(path) = &args.trace {
        write_json(path, &output.profile.chrome_trace())?;
        println!("wrote {} (Chrome trace)", path.display());
    }
    Ok(session::finish(&ctx))
}

pub fn write_json(path: &Path, value: &serde_json::Value) -> anyhow::Result<()> {
    let text = serde_json::to_string_pretty(value)?;
    std::fs::write(path, text).with_context(|| format!("cannot write {}", path.display()))
}
