use super::args::CompareArgs;
use super::render_cmd::{write_json, PROFILER_CAPACITY};
use super::{output_paths, scene_args, session};
use anyhow::Context as _;
use std::process::ExitCode;
use std::time::Instant;
use sweeplab::bench::{plot_error_map, ErrorMap};
use sweeplab::metrics::{compare, pixel_errors};
use sweeplab::reference::cpu::{render_cpu, CpuRenderKind};
use sweeplab::render::GpuScene;
use sweeplab::techniques::{render, Technique};
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
    let mut scene = scene_args::load(&args.scene)?;
    // Each technique is compared against the model it approximates.
    scene.reference.model = technique.reference_model(&scene);
    scene.reference.chromatic = technique.reference_chromatic(&scene);
    let (w, h) = (scene.render.width, scene.render.height);
    technique.check(&scene).with_context(|| format!("rendering {technique}"))?;
    for warning in technique.warnings(&scene).into_iter().chain(technique.unused_settings(&scene)) {
        eprintln!("warning: {warning}");
    }
    let ctx = session::open(&args.gpu)?;
    session::report_long_waits(&ctx);
    let gpu = GpuScene::upload_with(&ctx, &scene, session::volume_texels(&args.gpu)).context("uploading the scene")?;
    let mut profiler = Profiler::new(&ctx, PROFILER_CAPACITY)?;
    let tested = render(&gpu, technique, w, h, &mut profiler).with_context(|| format!("rendering {technique}"))?;
    let (reference, reference_gpu_ms, reference_cpu_s) = if args.reference == "cpu" {
        let start = Instant::now();
        let image = render_cpu(&scene, CpuRenderKind::reference_of(&scene), w, h).context("CPU reference")?;
        (image, None, Some(start.elapsed().as_secs_f64()))
    } else {
        let out = render(&gpu, Technique::Reference, w, h, &mut profiler).context("GPU reference")?;
        (out.image, Some(out.profile.gpu_ms_total), None)
    };
    drop(gpu);
    let stats = compare(&tested.image, &reference).context("comparing against the reference")?;
    println!("technique        {technique}");
    let coloured = if scene.reference.chromatic { ", chromatic" } else { "" };
    println!("reference        {} ({:?} model{coloured})", args.reference, scene.reference.model);
    println!("image            {w}x{h}");
    println!("rmse             {:.6e}", stats.rmse);
    println!("max_abs          {:.6e}", stats.max_abs);
    println!("psnr             {:.2} dB", stats.psnr);
    println!("gpu_ms           {:.3}", tested.profile.gpu_ms_total);
    if let Some(ms) = reference_gpu_ms {
        println!("reference_gpu_ms {ms:.3}");
    }
    if let Some(s) = reference_cpu_s {
        println!("reference_cpu_s  {s:.3}");
    }
    println!("dispatches       {}", tested.dispatches);
    println!("gpu_memory_bytes {}", tested.profile.gpu_memory_bytes);
    if let Some(path) = &args.json {
        let value = serde_json::json!({
            "technique": technique.name(),
            "reference": args.reference,
            "model": format!("{:?}", scene.reference.model),
            "width": w, "height": h,
            "rmse": stats.rmse, "max_abs": stats.max_abs,
            "psnr": if stats.psnr.is_finite() { serde_json::json!(stats.psnr) } else { serde_json::json!("inf") },
            "gpu_ms": tested.profile.gpu_ms_total,
            "reference_gpu_ms": reference_gpu_ms,
            "reference_cpu_s": reference_cpu_s,
            "dispatches": tested.dispatches,
            "gpu_memory_bytes": tested.profile.gpu_memory_bytes,
            "device": tested.profile.device,
        });
        write_json(path, &value)?;
    }
    if let Some(path) = &args.heatmap {
        let title = format!("{}: largest channel error against the reference", technique.name());
        let errors = pixel_errors(&tested.image, &reference)?;
        plot_error_map(path, &ErrorMap { title, width: w, height: h, errors })?;
    }
    if let Some(path) = &args.out {
        tested.image.save_png(path)?;
    }
    if let Some(path) = &args.reference_out {
        reference.save_png(path)?;
    }
    Ok(session::finish(&ctx))
}
