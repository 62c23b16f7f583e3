//! The sync study's verdict on real records (`tests/data/sync/`, see its
//! README): the NVIDIA H200 runs, where a barrier serializes the sweep by
//! hundreds of microseconds per line and costs about a microsecond of its
//! own, and the lavapipe runs, where nothing but a submission per block
//! costs anything. Each record is read as `sweeplab report` reads it, every
//! estimate recomputed from its raw per-round times; no GPU is needed.

use std::path::{Path, PathBuf};
use sweeplab::bench::estimate::Verdict;
use sweeplab::bench::experiments::sync::estimates::Serializes;
use sweeplab::bench::experiments::sync::{files, SyncReport, Workload, CONTROL};

const STRATEGIES: [&str; 5] = ["barrier-global", "barrier-image", "events", "secondary", "submits"];

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/sync").join(name)
}

fn record(name: &str) -> SyncReport {
    files::read(&data(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Every strategy's cost per sweep line is a cost with a half-width of at
/// most 10 % of it, in `range` us; the A/A control is within noise in both
/// workloads; no sweep line of the verdict reads "within noise".
fn assert_gpu_sweep_verdict(report: &SyncReport, range: std::ops::RangeInclusive<f64>) {
    for s in STRATEGIES {
        let row = report.row(Workload::Sweep, s).unwrap_or_else(|| panic!("no sweep row for {s}"));
        let e = row.serialization().unwrap_or_else(|| panic!("{s}: no serialization estimate"));
        assert_eq!(e.verdict(), Verdict::Cost, "{s}: {e:?}");
        assert!(range.contains(&e.value), "{s}: {e:?} outside {range:?}");
        assert!(e.half_width() <= 0.1 * e.value, "{s}: half-width {} of {}", e.half_width(), e.value);
        let share = row.frame_share.unwrap();
        assert!(share.value > 0.9, "{s}: synchronization is most of the frame here: {share:?}");
    }
    for w in [Workload::Empty, Workload::Sweep] {
        let control = report.row(w, CONTROL).and_then(|r| r.answer()).unwrap();
        assert!(control.within_noise(), "{} A/A control: {control:?}", w.name());
    }
    let verdict = report.verdict();
    let sweep_lines: Vec<&String> =
        verdict.iter().filter(|l| STRATEGIES.iter().any(|s| l.starts_with(&format!("  {s}: each line")))).collect();
    assert_eq!(sweep_lines.len(), STRATEGIES.len(), "{verdict:#?}");
    for l in sweep_lines {
        assert!(l.contains("serializes the sweep") && !l.contains("within noise"), "{l}");
    }
}

/// The record the issue was filed on: the old verdict printed "within noise
/// (95 % CI -0.888-135 us)" for barrier-global by joining the timestamped
/// in-frame pairing with the frame slopes.
#[test]
fn the_h200_record_reads_a_barrier_as_its_own_microsecond_and_the_sweeps_serialization() {
    let report = record("h200-cornell-512.json");
    assert_gpu_sweep_verdict(&report, 130.0..=150.0);
    let barrier = report.row(Workload::Sweep, "barrier-global").unwrap().serialization().unwrap();
    assert!((134.0..=136.0).contains(&barrier.value), "about 135 us per line: {barrier:?}");
    let fixed = report.row(Workload::Empty, "barrier-global").unwrap().fixed_cost().unwrap();
    assert_eq!(fixed.verdict(), Verdict::Cost, "{fixed:?}");
    assert!((0.9..=1.5).contains(&fixed.value), "about 1 us of its own: {fixed:?}");
    let submits = report.row(Workload::Empty, "submits").unwrap().fixed_cost().unwrap();
    assert!((10.0..=17.0).contains(&submits.value), "{submits:?}");
    let verdict = report.verdict().join("\n");
    assert!(
        verdict.contains("barrier-global: each line boundary costs 1.14 us (0.965-1.54) of its own and serializes the sweep: +135 us"),
        "{verdict}"
    );
    // The timestamps serialize the lines: the timestamped frame without
    // barriers adds more than a barrier after every line does.
    let stamps = report.timestamps_of(Workload::Sweep).unwrap();
    assert_eq!(stamps.serializes(), Serializes::Yes, "{stamps:?}");
    assert!(stamps.serialization_ratio.unwrap().value > 1.0, "{stamps:?}");
    assert!(verdict.contains("they serialize the lines on this device"), "{verdict}");
    assert!(verdict.contains("calibration (chain workload): not measured"), "the record predates the chain: {verdict}");
}

#[test]
fn the_h200_engine_record_without_timestamps_reads_every_strategy_as_a_cost() {
    let report = record("h200-engine-512-no-line-timestamps.json");
    assert_gpu_sweep_verdict(&report, 250.0..=290.0);
    assert!(report.timestamps.is_empty(), "run with --no-line-timestamps");
}

/// On lavapipe a dispatch runs to completion before the next starts: no
/// barrier, event or secondary costs anything measurable, a submission per
/// block does, and the sweep's 4-second frames vary more than any strategy
/// adds. Both committed runs keep that verdict.
#[test]
fn the_lavapipe_records_keep_their_verdicts() {
    for name in ["lavapipe-engine-256-run1.json", "lavapipe-engine-256-run2.json"] {
        let report = record(name);
        for s in ["barrier-global", "barrier-image", "events", "secondary"] {
            let fixed = report.row(Workload::Empty, s).unwrap().fixed_cost().unwrap();
            assert_ne!(fixed.verdict(), Verdict::Cost, "{name} {s}: {fixed:?}");
        }
        let submits = report.row(Workload::Empty, "submits").unwrap().fixed_cost().unwrap();
        assert_eq!(submits.verdict(), Verdict::Cost, "{name}: {submits:?}");
        assert!((10.0..=25.0).contains(&submits.value), "{name}: {submits:?}");
        for s in STRATEGIES {
            let e = report.row(Workload::Sweep, s).unwrap().serialization().unwrap();
            assert!(e.within_noise(), "{name} {s}: {e:?}");
        }
        let control = report.row(Workload::Empty, CONTROL).and_then(|r| r.fixed_cost()).unwrap();
        assert!(control.within_noise(), "{name}: {control:?}");
        let stamps = report.timestamps_of(Workload::Sweep).unwrap();
        assert_eq!(stamps.serializes(), Serializes::NothingToSerialize, "{name}: {stamps:?}");
    }
}

/// `sweeplab report` over the two devices: one row per device and strategy
/// with each quantity in its own columns, a chart per quantity, each
/// device's verdict.
#[test]
fn report_puts_lavapipe_and_the_h200_side_by_side() {
    let out = std::env::temp_dir().join(format!("sweeplab-sync-records-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let (lavapipe, h200) = (data("lavapipe-engine-256-run2.json"), data("h200-cornell-512.json"));
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_sweeplab"))
        .args(["report", lavapipe.to_str().unwrap(), h200.to_str().unwrap(), "--out-dir", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    let header = md.lines().find(|l| l.starts_with("| device")).expect("the table");
    for column in ["fixed_us", "fixed_verdict", "sweep_per_line_us", "sweep_verdict", "sweep_share"] {
        assert!(header.contains(column), "{header}");
    }
    for device in ["llvmpipe", "NVIDIA H200"] {
        for s in STRATEGIES {
            assert!(md.lines().any(|l| l.contains(device) && l.contains(&format!(" {s} "))), "{device} {s}: {md}");
        }
    }
    assert!(md.contains("serializes the sweep: +135 us"), "the H200's verdict: {md}");
    for chart in ["report_fixed_cost.png", "report_sweep.png"] {
        assert!(out.join(chart).exists() && out.join(chart).with_extension("svg").exists(), "{chart}");
    }
    let svg = std::fs::read_to_string(out.join("report_sweep.svg")).unwrap();
    assert!(svg.contains("barrier-global") && svg.contains("submits"), "strategies named on the axis");
    // A panel per device, each with its own axis from 0: the H200's 135 us per
    // line on a scale of its own (a tick at 140), not on lavapipe's thousands.
    let texts: Vec<&str> = svg
        .split("<text")
        .skip(1)
        .filter_map(|t| t.split_once('>').and_then(|(_, rest)| rest.split_once("</text>")).map(|(text, _)| text.trim()))
        .collect();
    assert_eq!(texts.iter().filter(|t| **t == "strategy").count(), 2, "two panels: {texts:?}");
    assert!(texts.contains(&"NVIDIA H200 (NVIDIA 580.159.4.0), cornell-box 512x512"), "{texts:?}");
    assert!(texts.contains(&"140") && texts.contains(&"1000"), "each panel's ticks: {texts:?}");
    let _ = std::fs::remove_dir_all(&out);
}
