//! The bench experiments called as a library, at tiny sizes: `bench table1`
//! (one data set, all line widths interleaved), `bench stability` (one
//! case x technique and its convergence) and `bench lights` (each part's
//! configurations in shared rounds).

use crate::common;

use common::cli::bench_rows;
use common::{assert_validation_clean, validated_context};
use sweeplab::bench::experiments::lights::{self as lights_bench, LightsPlan};
use sweeplab::bench::experiments::stability::bench::{self as stability_bench, StabilityPlan};
use sweeplab::bench::experiments::table1::paper::{CT_ENGINE, LINE_WIDTHS};
use sweeplab::bench::experiments::table1::{self as table1_bench, SegmentCount, Table1Plan};
use sweeplab::bench::out_folder::OutTarget;
use sweeplab::bench::{BenchRow, Harness, Interleaved, OutFolder, RunInfo};
use sweeplab::scene::loaders::data_dir;
use sweeplab::techniques::ipsvi::LineKernel;

fn out(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("sweeplab-bench-experiments-{name}-{}", std::process::id()))
}

#[test]
fn table1_gives_a_row_per_size_kernel_and_line_width_with_its_rounds_recorded() {
    let ctx = validated_context();
    let plan = Table1Plan {
        sizes: vec![8, 16],
        interleaved: Interleaved::fixed(1, 5).unwrap(),
        // A small light cache (256 texels otherwise, on 8 and 16 px): the
        // rows and what they record do not depend on it.
        set: vec!["ipsvi.cache_size=16".into()],
        data_sets: vec![(data_dir().join("engine.vti"), &CT_ENGINE)],
        // The segmented kernel at the device's count (8) and at 16 (across subgroups).
        kernels: Table1Plan::kernels_at(
            &[LineKernel::Serial, LineKernel::Segmented],
            &[SegmentCount::DEVICE, "16".parse().unwrap()],
        ),
        errors: true,
    };
    let folder = OutFolder::prepare(OutTarget::Named { folder: &out("table1"), force: true }).unwrap();
    let table = table1_bench::run(&ctx, &plan, RunInfo::collect(&ctx), &folder, 4096).unwrap();
    assert_eq!(table.rows.len(), 2 * 3 * LINE_WIDTHS.len());
    for (i, r) in table.rows.iter().enumerate() {
        assert!(r.get_f64("fps").is_some_and(|f| f.is_finite() && f > 0.0), "{r:?}");
        assert_eq!(r.get("fps_lo"), None, "one round gives no interval");
        assert_eq!(r.get_f64("line_width") == Some(1.0), r.get("fps_over_lw1").is_none(), "{r:?}");
        // Per size: the serial kernel's line widths, then the segmented one's beside them.
        let kernel = ["serial", "segmented x8", "segmented x16, texels x2"][i % 9 / 3];
        assert_eq!(r.text("line_kernel"), kernel, "{r:?}");
        assert_eq!(r.get("fps_over_first_kernel").is_some(), kernel != "serial", "{r:?}");
        assert!(r.get_f64("longest_chain").is_some_and(|c| c > 0.0), "{r:?}");
        // The frame over its shading lines (a line of width w holds w image lines).
        let lines = r.get_f64("line_dispatches").unwrap();
        let width = r.get_f64("width").unwrap() / r.get_f64("line_width").unwrap();
        assert!(lines >= width && lines <= 4.0 * width, "{r:?}");
        let per_line = r.get_f64("frame_us_per_line").unwrap();
        assert!((per_line - r.get_f64("gpu_ms").unwrap() * 1e3 / lines).abs() <= 1e-9 * per_line, "{r:?}");
        // The segmented kernel's view-stops pass, once a frame: its chain beside the line's.
        assert_eq!(r.get_f64("view_stops_chain").is_some_and(|c| c > 0.0), kernel != "serial", "{r:?}");
        // The error against the size's ground truth, and over the serial kernel's at this line
        // width: the same image but for the summation order, within the goal's 2 %.
        let rmse = r.get_f64("rmse").unwrap();
        assert!(rmse.is_finite() && rmse > 0.0 && r.get_f64("reference_gpu_ms").unwrap() > 0.0, "{r:?}");
        let serial = &table.rows[i / 9 * 9 + i % 3];
        assert_eq!(r.get_f64("rmse_over_serial"), Some(rmse / serial.get_f64("rmse").unwrap()), "{r:?}");
        assert!((r.get_f64("rmse_over_serial").unwrap() - 1.0).abs() < 0.02, "{r:?}");
    }
    // Each row against the fastest kernel at its size and line width: one of
    // the three, named alike in its rows, its own ratio 1, the others' above.
    for size in table.rows.chunks(9) {
        for lw in 0..LINE_WIDTHS.len() {
            let rows: Vec<_> = size.iter().skip(lw).step_by(LINE_WIDTHS.len()).collect();
            let fastest = rows[0].text("fastest_kernel");
            assert!(rows.iter().all(|r| r.text("fastest_kernel") == fastest), "{rows:?}");
            let ms = |r: &BenchRow| r.get_f64("gpu_ms").unwrap();
            let by_time = rows.iter().min_by(|a, b| ms(a).total_cmp(&ms(b))).unwrap();
            assert_eq!(by_time.text("line_kernel"), fastest, "{rows:?}");
            for r in &rows {
                // One round: the ratio of the two times (a tie is 1 too).
                let ratio = r.get_f64("gpu_ms_over_fastest").unwrap();
                assert_eq!(ratio, ms(r) / ms(by_time), "{r:?}");
                assert_eq!(ratio == 1.0, ms(r) == ms(by_time), "{r:?}");
            }
        }
    }
    assert!(table.rows[9..].iter().all(|r| r.get_f64("fps_over_half_size").is_some()), "16 is twice 8");
    let inputs = &table.run.as_ref().unwrap().inputs;
    assert!(inputs.iter().any(|(k, v)| k == "seed" && v == "5"), "{inputs:?}");
    assert!(folder.path().join("table1.json").is_file(), "saved as measured");
    common::cli::assert_every_output_names_its_run(folder.path());
    assert_validation_clean(&ctx);
    let _ = std::fs::remove_dir_all(out("table1"));
}

#[test]
fn stability_rates_each_cell_and_each_convergence_row() {
    let ctx = validated_context();
    let names = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    let plan = StabilityPlan::choose(
        8,
        &names(&["baseline"]),
        &names(&["dvr", "ipsvi"]),
        Harness::new(1, 1).unwrap(),
        out("cases"),
    )
    .unwrap();
    let folder = OutFolder::prepare(OutTarget::Named { folder: &out("stability"), force: true }).unwrap();
    let report = stability_bench::run(&ctx, &plan, RunInfo::collect(&ctx), &folder).unwrap();
    // DVR, and IPSVI in both cache updates.
    assert_eq!((report.table.rows.len(), report.orders.rows.len(), report.failed), (3, 3, 0));
    for cell in &report.table.rows {
        assert_eq!(cell.text("status"), "ok", "{cell:?}");
        assert!(cell.get_f64("gpu_ms").is_some() && cell.get("gpu_ms_lo").is_none(), "{cell:?}");
        // IPSVI's rows name the line kernel its frames ran (`auto`: serial on lavapipe).
        let kernel = if cell.text("technique").starts_with("ipsvi") { "serial" } else { "" };
        assert_eq!(cell.text("line_kernel"), kernel, "{cell:?}");
    }
    assert!(report.orders.rows.iter().all(|r| r.get_f64("overall_order").is_some_and(|o| o > 1.5)));
    assert_eq!(report.map.cells.len(), 1, "one case");
    assert_eq!(report.map.cells[0].len(), 3, "three techniques");
    report.write(folder.path()).unwrap();
    assert!(folder.path().join("stability.png").is_file() && folder.path().join("stability.md").is_file());
    common::cli::assert_every_output_names_its_run(folder.path());
    assert!(!out("cases").exists(), "the cases' files are removed");
    assert_validation_clean(&ctx);
    let _ = std::fs::remove_dir_all(out("stability"));
}

#[test]
fn lights_run_each_parts_configurations_in_shuffled_rounds_with_intervals_from_six() {
    let ctx = validated_context();
    let scene = sweeplab::techniques::default_scene(&[]).unwrap();
    let plan = LightsPlan::smallest(Interleaved::fixed(6, 11).unwrap(), (8, 8));
    let folder = OutFolder::prepare(OutTarget::Named { folder: &out("lights"), force: true }).unwrap();
    let report = lights_bench::run(&ctx, &scene, &plan, RunInfo::collect(&ctx), &folder, 4096).unwrap();
    // Table 1's four updates, the point light at the centre and outside, two
    // light counts by two propagations, the entire update beside one
    // incremental run, DVR beside three light volume frames.
    let sizes: Vec<usize> = report.orders().iter().map(|(_, order)| order.len() / 6).collect();
    assert_eq!(sizes, [4, 2, 4, 2, 4], "{:?}", report.orders());
    for ((label, order), n) in report.orders().iter().zip(sizes) {
        let rounds: Vec<&[usize]> = order.chunks(n).collect();
        for round in &rounds {
            let mut sorted = round.to_vec();
            sorted.sort();
            assert_eq!(sorted, (0..n).collect::<Vec<_>>(), "{label}: each configuration once a round: {order:?}");
        }
        assert!(rounds.iter().any(|r| r != &rounds[0]), "{label}: one order every round, not shuffled: {order:?}");
    }
    let rows = bench_rows(&folder.path().join("lights.json"));
    let has_interval = |r: &serde_json::Value, key: &str| {
        let (lo, v, hi) = (r[format!("{key}_lo")].as_f64(), r[key].as_f64(), r[format!("{key}_hi")].as_f64());
        matches!((lo, v, hi), (Some(lo), Some(v), Some(hi)) if lo <= v && v <= hi)
    };
    let part = |p: &'static str| rows.iter().filter(move |r| r["part"] == p);
    let ours = part("table1").find(|r| r["source"] == "ours (lavapipe)").unwrap();
    for key in ["sequential_ms", "coherent_ms", "state_change_ms", "toggle_ms", "sequential_over_coherent"] {
        assert!(has_interval(ours, key), "{key}: {ours}");
    }
    for (p, key) in [
        ("update", "gpu_ms"),
        ("inside", "gpu_ms"),
        ("scaling", "gpu_ms"),
        ("incremental", "total_ms"),
        ("incremental", "total_over_entire"),
        ("error", "gpu_ms"),
    ] {
        assert!(part(p).all(|r| has_interval(r, key)), "{p} {key}: {:?}", part(p).collect::<Vec<_>>());
    }
    // The slopes (a tiny volume's may hold 0, and then so may a round's
    // coherent slope, which leaves the slope ratio without an interval).
    let fit: Vec<_> = part("scaling_fit").filter(|r| r["propagation"] != "sequential/coherent").collect();
    assert!(fit.len() == 2 && fit.iter().all(|r| has_interval(r, "ms_per_added_light")), "{fit:?}");
    assert!(fit.iter().all(|r| r["ms_per_added_light_verdict"].is_string()), "{fit:?}");
    let centre = part("inside").next().unwrap();
    assert!(has_interval(centre, "over_outside"), "{centre}");
    let markdown = std::fs::read_to_string(folder.path().join("lights.md")).unwrap();
    assert!(markdown.contains("6 (after 1 warm-up)") && markdown.contains("shuffled order"), "{markdown}");
    assert_validation_clean(&ctx);
    let _ = std::fs::remove_dir_all(out("lights"));
}
