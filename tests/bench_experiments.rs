//! The bench experiments called as a library, at tiny sizes: `bench table1`
//! (one data set, all line widths interleaved) and `bench stability` (one
//! case x technique and its convergence).

mod common;

use common::{assert_validation_clean, validated_context};
use sweeplab::bench::experiments::stability_bench::{self, StabilityPlan};
use sweeplab::bench::experiments::table1_bench::{self, Table1Plan};
use sweeplab::bench::{Harness, Interleaved, OutFolder, RunInfo};
use sweeplab::ipsvi::paper_table1::{CT_ENGINE, LINE_WIDTHS};
use sweeplab::scene::loaders::data_dir;

fn out(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("sweeplab-bench-experiments-{name}-{}", std::process::id()))
}

#[test]
fn table1_gives_a_row_per_size_and_line_width_with_its_rounds_recorded() {
    let ctx = validated_context();
    let plan = Table1Plan {
        sizes: vec![8, 16],
        interleaved: Interleaved::fixed(1, 5).unwrap(),
        set: Vec::new(),
        data_sets: vec![(data_dir().join("engine.vti"), &CT_ENGINE)],
    };
    let folder = OutFolder::prepare(&out("table1")).unwrap();
    let table = table1_bench::run(&ctx, &plan, RunInfo::collect(&ctx), &folder, 4096).unwrap();
    assert_eq!(table.rows.len(), 2 * LINE_WIDTHS.len());
    for r in &table.rows {
        assert!(r.get_f64("fps").is_some_and(|f| f.is_finite() && f > 0.0), "{r:?}");
        assert_eq!(r.get("fps_lo"), None, "one round gives no interval");
        assert_eq!(r.get_f64("line_width") == Some(1.0), r.get("fps_over_lw1").is_none(), "{r:?}");
    }
    assert!(table.rows[3..].iter().all(|r| r.get_f64("fps_over_half_size").is_some()), "16 is twice 8");
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
    let plan =
        StabilityPlan::choose(8, &names(&["baseline"]), &names(&["dvr"]), Harness::new(1, 1).unwrap(), out("cases"))
            .unwrap();
    let folder = OutFolder::prepare(&out("stability")).unwrap();
    let report = stability_bench::run(&ctx, &plan, RunInfo::collect(&ctx), &folder).unwrap();
    assert_eq!((report.table.rows.len(), report.orders.rows.len(), report.failed), (1, 1, 0));
    let cell = &report.table.rows[0];
    assert_eq!(cell.text("status"), "ok", "{cell:?}");
    assert!(cell.get_f64("gpu_ms").is_some() && cell.get("gpu_ms_lo").is_none(), "{cell:?}");
    assert!(report.orders.rows[0].get_f64("overall_order").is_some_and(|o| o > 1.5));
    assert_eq!(report.map.cells, [[report.map.cells[0][0].clone()]]);
    report.write(folder.path()).unwrap();
    assert!(folder.path().join("stability.png").is_file() && folder.path().join("stability.md").is_file());
    common::cli::assert_every_output_names_its_run(folder.path());
    assert!(!out("cases").exists(), "the cases' files are removed");
    assert_validation_clean(&ctx);
    let _ = std::fs::remove_dir_all(out("stability"));
}
