//! `sweeplab bench ao` as a user runs it, at a tiny size: every configuration
//! a row with its measurements, the reports and charts written; bad list
//! values refused by name before any GPU work.

use crate::common;

use common::cli::*;
use sweeplab::bench::BenchTable;

#[test]
fn bench_ao_writes_a_row_per_configuration_with_its_figures() {
    let dir = temp_dir("bench-ao");
    let out = dir.join("report");
    let o = sweeplab(&[
        "bench",
        "ao",
        "--set",
        "volume.size=16",
        "--set",
        "ao.cache=false",
        "--size",
        "32x32",
        "--radii",
        "3",
        "--packed-dims",
        "16",
        "--clusters",
        "4,16",
        "--metrics",
        "l2,l1",
        "--reference-pairs",
        "4",
        "--repeat",
        "1",
        "--out-dir",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let table = BenchTable::read_json(out.join("ao.json")).unwrap();
    assert_eq!(table.rows.len(), 4, "2 n_c x 2 metrics");
    for key in
        ["preprocess_s", "assignment_distortion", "update_ms", "ao_ms", "phong_ms", "rmse_unclustered", "rmse_truth"]
    {
        let values = table.column_f64(key);
        assert_eq!(values.len(), 4, "{key}");
        assert!(values.iter().all(|v| v.is_finite() && *v >= 0.0), "{key}: {values:?}");
    }
    for file in ["ao.csv", "ao_table1.csv", "ao.md", "ao_error_vs_clusters.png", "ao_error_vs_preprocessing.png"] {
        assert!(out.join(file).is_file(), "{file} missing");
    }
    // The paper's Table 1 with our rows beside it: every paper row, then one
    // of ours per configuration, in the paper's columns.
    let md = std::fs::read_to_string(out.join("ao.md")).unwrap();
    assert!(md.contains("## Table 1 shape"), "{md}");
    let table1 = std::fs::read_to_string(out.join("ao_table1.csv")).unwrap();
    let rows: Vec<&str> = table1.lines().skip(1).collect();
    assert_eq!(rows.iter().filter(|r| r.starts_with("paper")).count(), 9, "{table1}");
    let ours: Vec<&&str> = rows.iter().filter(|r| r.starts_with("ours")).collect();
    assert_eq!(ours.len(), 4, "{table1}");
    assert!(ours.iter().all(|r| r.contains("16x16x16") && r.contains(",3.0,")), "size and r of ours: {table1}");
    assert!(
        table1.contains("101.6") || table1.contains("6096"),
        "the paper's head 256 brute force, in seconds: {table1}"
    );
    assert_every_output_names_its_run(&out);
}

#[test]
fn bench_ao_refuses_bad_lists_by_name() {
    let o = sweeplab(&["bench", "ao", "--metrics", "l2,l3", "--out-dir", temp_dir("bench-ao-bad").to_str().unwrap()]);
    assert_user_error(&o, "--metrics");
    assert!(stderr(&o).contains("did you mean"), "{}", stderr(&o));
    let o = sweeplab(&["bench", "ao", "--clusters", "4096", "--out-dir", temp_dir("bench-ao-bad2").to_str().unwrap()]);
    assert_user_error(&o, "ao.clusters = 4096");
}
