//! The `bench ipsvi` experiments called as library code at 8x8 with six
//! rounds: every file written, intervals on the times and ratios, no
//! published step cost at or below 0.
use crate::common;

use common::cli::{bench_rows, temp_dir};
use common::{directional, sphere_volume};
use glam::Vec3;
use sweeplab::bench::experiments::ipsvi::breakdown::{self as ipsvi_breakdown, BreakdownPlan};
use sweeplab::bench::experiments::ipsvi::{self as ipsvi_bench, IpsviPlan, DEFAULT_GROUP_BYTES};
use sweeplab::bench::out_folder::OutTarget;
use sweeplab::bench::{Interleaved, OutFolder, RunInfo};
use sweeplab::render::VolumeTexels;
use sweeplab::techniques::ipsvi::{IpsviSettings, LineKernel};

fn scene() -> sweeplab::scene::Scene {
    common::scene_with(sphere_volume(16, 0.4), vec![directional(Vec3::new(0.3, -1.0, 0.2), 1.0)], 8, 8)
}

#[test]
fn bench_ipsvi_at_8x8_with_six_rounds_writes_intervals_and_paired_ratios() {
    let dir = temp_dir("ipsvi-experiment");
    let plan = IpsviPlan {
        sizes: vec![8],
        line_widths: vec![1, 4],
        cache_sizes: vec![64],
        one_at_a_time: true,
        half_angle_slices: vec![1.0],
        interleaved: Interleaved::fixed(6, 11).unwrap(),
        volume_texels: VolumeTexels::Native,
        group_bytes: DEFAULT_GROUP_BYTES,
        kernels: vec![LineKernel::Auto],
    };
    let ctx = common::validated_context();
    let out = OutFolder::prepare(OutTarget::Named { folder: &dir, force: true }).unwrap();
    // A small light cache for the scene's own settings (by default 256 texels
    // on this 8x8 image): the files, intervals and ratios do not depend on it.
    let mut scene = scene();
    scene.settings.get_mut::<IpsviSettings>().cache_size = 16;
    let report = ipsvi_bench::run(&ctx, &scene, &plan, RunInfo::collect(&ctx), &out, 64).unwrap();
    common::assert_validation_clean(&ctx);
    out.finish().unwrap();
    for file in ["ipsvi.csv", "ipsvi.md", "ipsvi_8_error_vs_time.png", "ipsvi_8_error_vs_time.svg"] {
        assert!(dir.join(file).is_file(), "{file} missing");
    }
    let rows = bench_rows(&dir.join("ipsvi.json"));
    common::cli::assert_every_output_names_its_run(&dir);
    assert_eq!(rows.len(), report.table.rows.len());
    let ipsvi: Vec<_> = rows.iter().filter(|r| r["technique"] == "ipsvi").collect();
    assert!(!ipsvi.is_empty());
    for r in rows.iter().filter(|r| r["technique"] != "reference") {
        let (lo, v, hi) =
            (r["gpu_ms_lo"].as_f64().unwrap(), r["gpu_ms"].as_f64().unwrap(), r["gpu_ms_hi"].as_f64().unwrap());
        assert!(lo <= v && v <= hi, "{r}");
    }
    for r in &ipsvi {
        let (lo, hi) = (r["time_over_dvr_lo"].as_f64().unwrap(), r["time_over_dvr_hi"].as_f64().unwrap());
        assert!(lo > 0.0 && lo <= hi, "{r}");
        // Paired with the scene's own settings, which the one-at-a-time grid starts with.
        let (lo, v, hi) = (
            r["time_over_scene_settings_lo"].as_f64().unwrap(),
            r["time_over_scene_settings"].as_f64().unwrap(),
            r["time_over_scene_settings_hi"].as_f64().unwrap(),
        );
        assert!(lo > 0.0 && lo <= v && v <= hi, "{r}");
        assert!(r["cache_texel_px"].as_f64().is_some_and(|px| px > 0.0), "{r}");
    }
    let own = &ipsvi[0];
    assert_eq!(own["time_over_scene_settings"].as_f64(), Some(1.0), "the scene's settings against themselves: {own}");
    let text = std::fs::read_to_string(dir.join("ipsvi.md")).unwrap();
    assert!(text.contains("- seed: `11`") && text.contains("- rounds: `6`"), "{text}");
}

/// A light inside the volume: half-angle slicing cannot light it, so its
/// rows are left out, and the run says why (the summary, the run's inputs);
/// a `compare` of half-angle refuses it before any GPU work.
#[test]
fn half_angle_rows_are_left_out_by_name_where_the_light_is_inside_the_volume() {
    let dir = temp_dir("ipsvi-light-inside");
    let plan = IpsviPlan {
        sizes: vec![8],
        line_widths: vec![1],
        cache_sizes: vec![16],
        one_at_a_time: true,
        half_angle_slices: vec![1.0],
        interleaved: Interleaved::fixed(1, 1).unwrap(),
        volume_texels: VolumeTexels::Native,
        group_bytes: DEFAULT_GROUP_BYTES,
        kernels: vec![LineKernel::Serial],
    };
    let mut scene = scene();
    scene.lights = vec![common::point(Vec3::ZERO)];
    scene.settings.get_mut::<IpsviSettings>().cache_size = 16;
    let refused = sweeplab::techniques::Technique::HalfAngle.check(&scene).unwrap_err().to_string();
    assert!(refused.contains("outside the volume's bounding sphere"), "{refused}");
    let ctx = common::validated_context();
    let out = OutFolder::prepare(OutTarget::Named { folder: &dir, force: true }).unwrap();
    let report = ipsvi_bench::run(&ctx, &scene, &plan, RunInfo::collect(&ctx), &out, 64).unwrap();
    common::assert_validation_clean(&ctx);
    out.finish().unwrap();
    let why = report.half_angle_left_out.expect("the reason the half-angle rows are left out");
    assert!(why.contains("outside the volume's bounding sphere"), "{why}");
    let rows = bench_rows(&dir.join("ipsvi.json"));
    assert!(!rows.is_empty() && rows.iter().all(|r| r["technique"] != "half-angle"), "{rows:?}");
    let json = std::fs::read_to_string(dir.join("ipsvi.json")).unwrap();
    assert!(json.contains("left out: half-angle slicing needs the light outside"), "the run's inputs say why");
}

/// Without half-angle runs (`--half-angle-slices` with no value) the run
/// renders no model (i) truth and still writes every mode's rows.
#[test]
fn bench_ipsvi_without_half_angle_runs_measures_every_mode() {
    let dir = temp_dir("ipsvi-no-half-angle");
    let plan = IpsviPlan {
        sizes: vec![8],
        line_widths: vec![1],
        cache_sizes: vec![32],
        one_at_a_time: true,
        half_angle_slices: vec![],
        interleaved: Interleaved::fixed(1, 3).unwrap(),
        volume_texels: VolumeTexels::Native,
        group_bytes: DEFAULT_GROUP_BYTES,
        kernels: vec![LineKernel::Serial, LineKernel::Segmented],
    };
    let ctx = common::validated_context();
    let out = OutFolder::prepare(OutTarget::Named { folder: &dir, force: true }).unwrap();
    // A small light cache for the scene's own settings, as above.
    let mut scene = scene();
    scene.settings.get_mut::<IpsviSettings>().cache_size = 16;
    ipsvi_bench::run(&ctx, &scene, &plan, RunInfo::collect(&ctx), &out, 64).unwrap();
    common::assert_validation_clean(&ctx);
    out.finish().unwrap();
    let rows = bench_rows(&dir.join("ipsvi.json"));
    assert!(rows.iter().all(|r| r["technique"] != "half-angle"));
    // Both kernels, each row naming the one it ran and its frame's shape.
    for (kernel, label) in [("serial", "serial"), ("segmented", "segmented x8")] {
        for mode in ["view samples, non-empty", "view samples, every-sample", "light rays"] {
            let mode = format!("{mode}, {kernel}");
            let at_32: Vec<_> =
                rows.iter().filter(|r| r["mode"] == mode && r["cache_size"].as_f64() == Some(32.0)).collect();
            assert_eq!(at_32.len(), 1, "{mode} at cache 32: {rows:?}");
            assert_eq!(at_32[0]["line_kernel"], label, "{mode}");
            assert!(at_32[0]["longest_chain"].as_u64().is_some_and(|c| c > 0), "{mode}: {}", at_32[0]);
        }
    }
}

#[test]
fn the_breakdown_at_8x8_with_six_rounds_publishes_no_cost_within_noise() {
    let dir = temp_dir("breakdown-experiment");
    let plan = BreakdownPlan {
        sizes: vec![8],
        line_widths: vec![1, 2],
        interleaved: Interleaved::fixed(6, 5).unwrap(),
        volume_texels: VolumeTexels::Native,
        kernels: vec![LineKernel::Serial],
    };
    // Without validation: step b has no barriers between blocks by design.
    let ctx = common::unvalidated_context();
    let out = OutFolder::prepare(OutTarget::Named { folder: &dir, force: true }).unwrap();
    // A small light cache: the verdicts' consistency does not depend on its size.
    let mut scene = scene();
    scene.settings.get_mut::<IpsviSettings>().cache_size = 16;
    let report = ipsvi_breakdown::run(&ctx, &scene, &plan, RunInfo::collect(&ctx), &out, 64).unwrap();
    out.finish().unwrap();
    let rows = bench_rows(&dir.join("ipsvi_breakdown.json"));
    common::cli::assert_every_output_names_its_run(&dir);
    // a-f, e1-e5 for view samples under each write rule and write pass; a-f for light rays.
    assert_eq!(rows.len(), 4 * 11 + 6);
    for r in &rows {
        let verdict = r["step_ms_verdict"].as_str().unwrap();
        assert!(["cost", "within noise", "below baseline"].contains(&verdict), "{r}");
        assert_eq!(r["step_ms"].is_number(), verdict == "cost", "{r}");
        assert!(r["step_ms"].as_f64().is_none_or(|v| v > 0.0) && r["step_ms_lo"].is_number(), "{r}");
    }
    for bar in &report.bars {
        assert!(bar.segments.iter().all(|(_, v)| *v >= 0.0), "{bar:?}");
        let zero = bar.segments.iter().any(|(_, v)| *v == 0.0);
        assert_eq!(zero, bar.label.contains("within noise"), "{bar:?}");
    }
    let widths = bench_rows(&dir.join("ipsvi_line_widths.json"));
    for r in widths.iter().filter(|r| r["line_width"] == 1) {
        assert_eq!(
            (r["speedup_over_lw1_lo"].as_f64(), r["speedup_over_lw1_hi"].as_f64()),
            (Some(1.0), Some(1.0)),
            "{r}"
        );
    }
}
