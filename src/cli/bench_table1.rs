//! `sweeplab bench table1`: the IPSVI paper's Table 1 on our data and device.

use super::args::BenchTable1Args;
use super::render_cmd::PROFILER_CAPACITY;
use super::{bench_args, session};
use anyhow::Context as _;
use std::process::ExitCode;
use sweeplab::bench::{ipsvi_frame, BenchRow, BenchTable, OutFolder, Progress};
use sweeplab::ipsvi::paper_table1::{PaperColumn, CT_ENGINE, CT_GIRAFFE, LINE_WIDTHS, US_BABY};
use sweeplab::ipsvi::renderer::IpsviRenderer;
use sweeplab::ipsvi::{IpsviSettings, SyncStrategy};
use sweeplab::render::GpuScene;
use sweeplab::scene::loaders::data_dir;
use sweeplab::techniques::scene_for_volume_file;
use sweeplab::vk::Profiler;

/// Our data set and the paper column it stands beside.
const PAIRS: [(&str, &PaperColumn); 3] =
    [("engine.vti", &CT_ENGINE), ("aneurism.vti", &US_BABY), ("LIDC2.mha", &CT_GIRAFFE)];

pub fn run(args: &BenchTable1Args) -> anyhow::Result<ExitCode> {
    // One untimed frame first: llvmpipe compiles shader variants on first use.
    let harness = session::harness(1, args.repeat)?;
    bench_args::check_sizes("--sizes", &args.sizes)?;
    let out_folder = OutFolder::prepare(&args.out)?;
    let ctx = session::open(&args.gpu)?;
    let mut profiler = Profiler::new(&ctx, PROFILER_CAPACITY)?;
    let mut progress = Progress::weighted(step_weights(&args.sizes));
    let mut table = BenchTable::with_run(session::run_info(&ctx));
    for (file, paper) in PAIRS {
        let path = data_dir().join(file);
        let scene = scene_for_volume_file(&path, &args.set).with_context(|| format!("loading {}", path.display()))?;
        let base = IpsviSettings { piecewise: true, ..scene.settings.get::<IpsviSettings>().into_owned() };
        let gpu = GpuScene::upload(&ctx, &scene).context("uploading the scene")?;
        let mut fps = std::collections::BTreeMap::new();
        for &size in &args.sizes {
            for lw in LINE_WIDTHS {
                progress.start_step(&format!("{file} {size}x{size} lw={lw}"));
                let s = IpsviSettings { line_width: lw, ..base.clone() };
                let mut renderer = IpsviRenderer::new(&gpu, &s, size, size)?;
                let measured =
                    harness.measure(|| ipsvi_frame(&ctx, &mut renderer, &mut profiler, SyncStrategy::BarrierGlobal))?;
                progress.finish_step();
                fps.insert((size, lw), 1000.0 / measured.median());
            }
        }
        for &size in &args.sizes {
            for lw in LINE_WIDTHS {
                let ours = fps[&(size, lw)];
                let mut row = BenchRow::new();
                row.set("data_set", file)
                    .set("paper_data_set", paper.data_set)
                    .set("width", size)
                    .set("line_width", lw);
                row.set("fps", ours).set("paper_fps", paper.fps_at(size, lw).unwrap_or(f64::NAN));
                if lw != 1 {
                    row.set("fps_over_lw1", ours / fps[&(size, 1)]);
                    row.set(
                        "paper_fps_over_lw1",
                        paper.fps_at(size, lw).unwrap_or(f64::NAN) / paper.fps_at(size, 1).unwrap_or(f64::NAN),
                    );
                }
                if let Some(&half) = args.sizes.iter().find(|&&h| h * 2 == size) {
                    row.set("fps_over_half_size", ours / fps[&(half, lw)]);
                    row.set(
                        "paper_fps_over_half_size",
                        paper.fps_at(size, lw).unwrap_or(f64::NAN) / paper.fps_at(half, lw).unwrap_or(f64::NAN),
                    );
                }
                table.push(row);
            }
        }
        out_folder.save_rows("table1", &table)?;
    }
    progress.finish();
    table.write_csv(args.out.join("table1.csv"))?;
    table.write_json(args.out.join("table1.json"))?;
    std::fs::write(args.out.join("table1.md"), table.to_markdown_report()).context("writing table1.md")?;
    for r in &table.rows {
        println!(
            "{} {}x{} lw={}: {:.2} fps (paper, {}: {:.1} fps)",
            r.text("data_set"),
            r.text("width"),
            r.text("width"),
            r.text("line_width"),
            r.get_f64("fps").unwrap_or(f64::NAN),
            r.text("paper_data_set"),
            r.get_f64("paper_fps").unwrap_or(f64::NAN)
        );
    }
    println!("wrote {}/table1.csv, table1.json, table1.md (the full table)", args.out.display());
    out_folder.finish()?;
    Ok(session::finish(&ctx))
}

/// The relative size of each progress step: pixels times the cube root of the
/// data set's file size (a ray's length in voxels), so the time left counts
/// large images and large volumes as such.
fn step_weights(sizes: &[u32]) -> Vec<f64> {
    let mut weights = Vec::new();
    for (file, _) in PAIRS {
        let bytes = std::fs::metadata(data_dir().join(file)).map(|m| m.len() as f64).unwrap_or(1.0);
        for &size in sizes {
            let pixels = f64::from(size) * f64::from(size);
            weights.extend(std::iter::repeat_n(pixels * bytes.max(1.0).cbrt(), LINE_WIDTHS.len()));
        }
    }
    weights
}
