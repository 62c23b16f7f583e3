//! The integration tests, one binary (`cargo test --release --test suite`):
//! every file of `tests/` is a module here, so the tests compile and link
//! once (not once per file); `tools/test.sh` runs it one module per process
//! (tools/suite_processes.sh). A new
//! test file is added as a `mod` line below (the last test checks that none
//! is left out). One file's tests: `cargo test --release --test suite
//! ipsvi_view_samples::`; one test: `... -- --exact MODULE::NAME`.

mod common;
/// Mutations of valid inputs, shared by the scene and volume-file fuzzers.
#[path = "fuzz/mutation.rs"]
mod mutation;

mod ao_gpu;
mod ao_preprocess;
mod ao_reference;
mod ao_render;
mod bench_ao;
mod bench_breakdown_line_widths;
mod bench_experiments;
mod bench_ipsvi_experiment;
mod bench_reports;
mod bench_sync;
mod best_practices;
mod charts;
mod clean_images;
mod cli;
mod cli_flags;
mod data_render;
mod device_limits;
mod far_lights;
mod finished_frames;
mod gpu_check;
mod gpu_smoke;
mod gpu_vs_cpu;
mod half_angle;
mod ipsvi;
mod ipsvi_line_group;
mod ipsvi_merged_sweeps;
mod ipsvi_segmented;
mod ipsvi_segmented_modes;
mod ipsvi_view_samples;
mod ipsvi_visible_box;
mod layers;
mod lightvolume;
mod lightvolume_coarse_error;
mod lightvolume_cpu_cost;
mod lightvolume_updates;
mod loaders;
mod long_march;
mod pipeline_cache;
mod profiler;
mod ray_jitter;
mod readme_gallery;
mod reference_convergence;
mod reference_cpu;
mod reference_empty_cells;
mod scene_examples_render;
mod scene_files;
mod scene_fuzz;
mod scene_warnings;
mod shader_interface;
mod stability;
mod suite_processes;
mod sync_records;
mod sync_strategies;
mod test_summary_line;
mod toy_technique;
mod validated_threads;
mod viewer;
mod wait_report;

/// Every file of `tests/` is a module of this binary: `autotests = false` in
/// Cargo.toml, so a file left out of the list above would never run.
#[test]
fn every_test_file_is_a_module_of_the_suite() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let main = std::fs::read_to_string(dir.join("main.rs")).unwrap();
    let mut missing = Vec::new();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let Some(name) = path.file_name().and_then(|n| n.to_str()).and_then(|n| n.strip_suffix(".rs")) else {
            continue;
        };
        if name != "main" && !main.lines().any(|line| line.trim() == format!("mod {name};")) {
            missing.push(format!("tests/{name}.rs"));
        }
    }
    assert!(missing.is_empty(), "not modules of tests/main.rs, so never run: {missing:?}");
}
