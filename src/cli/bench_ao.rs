//! `sweeplab bench ao`: the arguments and the scene (the Cornell box without
//! `--scene`/`--volume`), then the experiment
//! (`sweeplab::bench::experiments::ao_bench`).

use super::args::BenchAoArgs;
use super::render_cmd::PROFILER_CAPACITY;
use super::{scene_args, session};
use std::process::ExitCode;
use sweeplab::bench::experiments::ao_bench::{self, AoPlan};
use sweeplab::scene::Scene;

const DEFAULT_IMAGE: u32 = 256;
const CORNELL_BOX: &str = include_str!("../../tests/scenes/cornell-box.toml");

fn load_scene(args: &BenchAoArgs) -> anyhow::Result<Scene> {
    let mut scene = if args.scene.scene.is_none() && args.scene.volume.is_none() {
        let base = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes");
        sweeplab::techniques::scene_from_toml_str(CORNELL_BOX, &base, "cornell-box", &args.scene.set)?
    } else {
        scene_args::load(&args.scene)?
    };
    let (w, h) = match &args.scene.size {
        Some(size) => scene_args::parse_size(size)?,
        None => (DEFAULT_IMAGE, DEFAULT_IMAGE),
    };
    (scene.render.width, scene.render.height) = (w, h);
    Ok(scene)
}

/// The data set's name in the tables: the scene or volume file's stem.
fn data_set_name(args: &BenchAoArgs) -> String {
    let path = args.scene.scene.as_ref().or(args.scene.volume.as_ref());
    path.and_then(|p| p.file_stem()).map_or("cornell-box".into(), |s| s.to_string_lossy().into_owned())
}

pub fn run(args: &BenchAoArgs) -> anyhow::Result<ExitCode> {
    let plan = AoPlan {
        radii: args.radii.clone(),
        bits: args.bits.clone(),
        packed_dims: args.packed_dims.clone(),
        clusters: args.clusters.clone(),
        metrics: args.metrics.clone(),
        reference_pairs: args.reference_pairs,
        rounds: session::interleaved(args.repeat, &args.rounds)?,
        data_set: data_set_name(args),
    };
    let scene = load_scene(args)?;
    ao_bench::configurations(&plan, &scene.settings.get())?;
    let out_folder = session::out_folder(&args.out, "bench-ao")?;
    let ctx = session::open(&args.gpu)?;
    let measured = ao_bench::run(&ctx, &scene, &plan, session::run_info(&ctx), &out_folder, PROFILER_CAPACITY);
    let report = session::watch(&out_folder, measured)?;
    ao_bench::print_summary(&report.table);
    println!(
        "wrote {}/ao.csv, ao.json, ao_table1.csv, ao.md (the full table), ao_error_vs_clusters.png, \
         ao_error_vs_preprocessing.png (and .svg)",
        out_folder.path().display()
    );
    out_folder.finish()?;
    Ok(session::finish(&ctx))
}
