//! `bench sync` at tiny sizes: the protocol's rounds (shuffled, recorded,
//! per workload), the equal-work baseline and its A/A control, hazards of the
//! racy arms counted while every other message fails the run, the chain
//! workload's calibration, one trace per strategy and workload, metadata in
//! every output, `sweeplab report` over two devices, and the dispatch probe.
use crate::common;

use common::cli::*;
use common::validated_context;
use serde_json::Value;
use std::path::Path;
use sweeplab::bench::experiments::dispatch_probe::{probe, BeforeEach, ProbeCase};

fn bench(dir: &Path, extra: &[&str]) -> std::process::Output {
    let mut args = vec![
        "bench",
        "sync",
        "--size",
        "12x12",
        // A small light cache: the sweep's lines stay short (13 ms frames, not 900).
        "--set",
        "ipsvi.cache_size=16",
        "--line-widths",
        "1,2",
        "--strategies",
        "barrier-global,events,secondary",
        "--repeat",
        "6",
        "--max-rounds",
        "6",
        "--seed",
        "7",
        "--out-dir",
        dir.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    sweeplab(&args)
}

fn json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())))
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn the_study_runs_shuffled_paired_rounds_against_an_equal_work_baseline() {
    let dir = temp_dir("sync-study");
    let o = bench(&dir, &["--workloads", "empty,sweep"]);
    // With validation on (sweeplab() sets it): the racy arms' hazards are
    // expected and counted, anything else would fail the run.
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("validation: clean"), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    for line in ["(a) the fixed cost of a line boundary", "(b) what each strategy costs the sweep", "(c) per-line"] {
        assert!(stdout.contains(line), "verdict lacks {line:?}: {stdout}");
    }
    for line in ["  barrier-global: ", "  events: ", "no-barriers-again (A/A control)"] {
        assert_eq!(stdout.matches(line).count(), 2, "{line:?} in both workloads: {stdout}");
    }
    let report = json(&dir.join("sync.json"));
    assert_eq!(report["complete"], true);
    assert_every_output_names_its_run(&dir);
    // The line kernel as it ran (`auto` is serial on lavapipe): in the verdict,
    // the run's inputs and beside every row of the workloads that run it.
    assert!(stdout.contains("(sweep workload, line kernel serial, line width 1"), "{stdout}");
    assert!(report["run"]["inputs"].to_string().contains(r#""line_kernel","serial""#), "{}", report["run"]);
    for file in ["sync.csv", "sync_configurations.csv"] {
        let text = std::fs::read_to_string(dir.join(file)).unwrap();
        let mut lines = text.lines().filter(|l| !l.starts_with('#'));
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let column = header.iter().position(|h| *h == "line_kernel").unwrap_or_else(|| panic!("{file}: {header:?}"));
        assert!(lines.all(|l| l.split(',').nth(column) == Some("serial")), "{file}: {text}");
    }
    let configs = report["configurations"].as_array().unwrap();
    // 2 workloads x (baseline, A/A control, 3 strategies) x 2 line widths, and
    // per workload the baseline with per-line timestamps at line width 1.
    assert_eq!(configs.len(), 2 * 5 * 2 + 2, "{configs:?}");
    for w in report["workloads"].as_array().unwrap() {
        assert_eq!(w["rounds"], 6);
        let name = w["workload"].as_str().unwrap();
        let mut members: Vec<u64> =
            (0..configs.len() as u64).filter(|&i| configs[i as usize]["workload"] == name).collect();
        members.sort();
        let orders = w["orders"].as_array().unwrap();
        assert_eq!(orders.len(), 6);
        let mut distinct = std::collections::BTreeSet::new();
        for order in orders {
            let mut o: Vec<u64> = order.as_array().unwrap().iter().map(|v| v.as_u64().unwrap()).collect();
            distinct.insert(o.clone());
            o.sort();
            assert_eq!(o, members, "each round runs each of {name}'s configurations once");
        }
        assert!(distinct.len() > 1, "the rounds are shuffled: {orders:?}");
    }
    for c in configs {
        assert_eq!(c["frames"], 6, "{c}");
        assert_eq!(c["gpu_ms_runs"].as_array().unwrap().len(), 6);
        let racy = c["racy"].as_bool().unwrap();
        let hazards = c["hazards_ignored"].as_u64().unwrap();
        // The empty workload's shaders touch nothing, so nothing can race.
        if racy && c["workload"] == "sweep" && c["line_width"] == 1 {
            assert!(hazards > 0, "the baseline has no barriers, validation must see hazards: {c}");
        }
        if !racy {
            assert_eq!(hazards, 0, "{c}");
        }
        // Equal work: every arm dispatches the same blocks at a line width.
        let same = configs.iter().filter(|o| o["line_width"] == c["line_width"] && o["workload"] == c["workload"]);
        for o in same {
            assert_eq!(o["blocks"], c["blocks"]);
            assert_eq!(o["lines"], c["lines"]);
        }
    }
    let strategies = report["strategies"].as_array().unwrap();
    for workload in ["empty", "sweep"] {
        for arm in ["no-barriers", "no-barriers-again", "barrier-global", "events"] {
            let r = strategies
                .iter()
                .find(|r| r["workload"] == workload && r["strategy"] == arm)
                .unwrap_or_else(|| panic!("no {arm} row in {workload}"));
            let b = &r["boundary_us"];
            assert!(b["lo"].as_f64().unwrap() <= b["value"].as_f64().unwrap(), "{r}");
            assert!(b["value"].as_f64().unwrap() <= b["hi"].as_f64().unwrap(), "{r}");
            if arm == "no-barriers" {
                assert!(r["sync_us"].is_null() && r["frame_sync_us"].is_null(), "{r}");
            } else {
                // The frame slopes and the frame difference at line width 1:
                // two estimators of one quantity, each its own column.
                assert_eq!(r["sync_us"]["n"], 6, "{r}");
                assert_eq!(r["frame_sync_us"]["n"], 6, "{r}");
                assert_eq!(
                    r["boundaries"],
                    configs.iter().find(|c| c["workload"] == workload && c["line_width"] == 1).unwrap()["blocks"]
                );
            }
        }
    }
    // The per-line timestamps' effect: the baseline with and without them, per workload.
    for t in report["timestamps"].as_array().unwrap() {
        assert_eq!(t["added_ms"]["n"], 6, "{t}");
        assert_eq!(t["reference"], "barrier-global", "{t}");
    }
    assert_eq!(report["timestamps"].as_array().unwrap().len(), 2);
    // One trace per strategy and workload: a frame with every line a slice.
    for workload in ["empty", "sweep"] {
        let lines =
            configs.iter().find(|c| c["workload"] == workload && c["line_width"] == 1).unwrap()["blocks"].clone();
        for strategy in ["no-barriers", "barrier-global", "events", "secondary"] {
            let trace = json(&dir.join(format!("trace_{workload}_{strategy}.json")));
            let slices = trace["traceEvents"].as_array().unwrap().iter().filter(|e| e["name"] == "ipsvi_line").count();
            // A slice per line record: each block, and the claim-only record a sweep starts with.
            assert!(slices as u64 >= lines.as_u64().unwrap(), "{workload} {strategy}: {slices} slices, {lines} blocks");
            assert_eq!(trace["otherData"]["strategy"], strategy);
            assert!(trace["otherData"]["run"]["device"].is_string(), "the trace names its run");
            let summary = report["traces"]
                .as_array()
                .unwrap()
                .iter()
                .find(|t| t["workload"] == workload && t["strategy"] == strategy)
                .unwrap_or_else(|| panic!("no summary of trace_{workload}_{strategy}"));
            assert_eq!(summary["lines"], slices as u64, "{summary}");
        }
    }
    // Non-racy strategies render barrier-global's image; so does the racy
    // baseline on lavapipe, which runs each line's dispatch to completion
    // before the next (a GPU that overlaps lines does not: the verdict says which).
    for c in configs.iter().filter(|c| c["workload"] == "sweep") {
        assert_eq!(c["rmse_vs_barrier_global"], 0.0, "{c}");
    }
    assert!(stdout.contains("its image (no barriers: racy): barrier-global's bit for bit"), "{stdout}");
    // The tables count the barriers between line blocks apart from the
    // frame's own (set-up, read-back): none for no barriers.
    let csv = std::fs::read_to_string(dir.join("sync_configurations.csv")).unwrap();
    let mut lines = csv.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap_or_else(|| panic!("{name}: {header:?}"));
    let (strategy, boundary, frame) = (column("strategy"), column("boundary_barriers"), column("frame_barriers"));
    for line in lines {
        let cells: Vec<&str> = line.split(',').collect();
        let (b, f): (u64, u64) = (cells[boundary].parse().unwrap(), cells[frame].parse().unwrap());
        match cells[strategy] {
            "no-barriers" | "no-barriers-again" => assert!(b == 0 && f > 0, "{line}"),
            _ => assert!(b > 0 && f > b, "{line}"),
        }
    }
}

/// The calibration on lavapipe: every arm's chain of known length, its
/// latency measured alone, a line per arm fitted. lavapipe runs each dispatch
/// to completion before the next starts, so every arm, the baseline without
/// barriers included, exposes about the whole chain at each boundary
/// (fraction near 1; the record in docs/sync-study.md, since a loaded host
/// moves the medians of six rounds). Every frame's result is checked (a chain cut short or
/// a line that read early fails the run), validation is clean but for the
/// baseline's hazards, and every arm's frame is traced.
#[test]
fn the_chain_workload_fits_a_fraction_near_one_for_every_arm_on_lavapipe() {
    let dir = temp_dir("sync-chain");
    let mut args = vec!["bench", "sync", "--size", "12x12", "--workloads", "chain", "--min-rounds", "6"];
    args.extend(["--max-rounds", "6", "--seed", "7", "--out-dir", dir.to_str().unwrap()]);
    let o = sweeplab(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("validation: clean"), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("calibration: time per line boundary = fixed cost + serialized fraction"), "{stdout}");
    let report = json(&dir.join("sync.json"));
    let chain = &report["chain"];
    let trips: Vec<u64> = chain["trips"].as_array().unwrap().iter().map(|t| t.as_u64().unwrap()).collect();
    assert!(trips.len() >= 3 && trips[0] == 0, "{chain}");
    assert!(trips.iter().all(|&t| t <= 65_535), "within lavapipe's loop cap: {chain}");
    let configs = report["configurations"].as_array().unwrap();
    // Baseline, five strategies and one line alone at every length.
    assert_eq!(configs.len(), 7 * trips.len(), "{configs:?}");
    for c in configs {
        let hazards = c["hazards_ignored"].as_u64().unwrap();
        match c["arm"].as_str().unwrap() {
            "no-barriers" if c["chain_trips"] == 0 => assert!(hazards > 0, "racy lines reported: {c}"),
            "no-barriers" => {}
            _ => assert_eq!(hazards, 0, "{c}"),
        }
    }
    let fits = report["calibration"].as_array().unwrap();
    assert_eq!(fits.len(), 6, "{fits:?}");
    // The run header's load: above the cores the fractions rise past 1
    // (docs/sync-study.md, the calibration), so a failure says what it was.
    let load = &report["run"]["host_load"];
    assert_eq!(load.as_array().map(Vec::len), Some(3), "{load}");
    for f in fits {
        // Each interval reaches the whole chain: no arm can be told to overlap
        // its lines here.
        let fraction = &f["fraction"];
        assert!(fraction["hi"].as_f64().unwrap() >= 0.8, "lavapipe exposes every line's chain: {f}; host load {load}");
        assert!(fraction["lo"].as_f64().unwrap() <= 1.2, "{f}; host load {load}");
        assert!(!f["latencies_us"].as_array().unwrap().is_empty());
        let strategy = f["strategy"].as_str().unwrap();
        let trace = json(&dir.join(format!("trace_chain_{strategy}.json")));
        let lines = trace["traceEvents"].as_array().unwrap().iter().filter(|e| e["name"] == "sync_chain_line").count();
        assert_eq!(lines as u64, chain["lines"].as_u64().unwrap(), "{strategy}");
    }
    assert!(dir.join("sync_calibration.png").exists() && dir.join("sync_calibration.csv").exists());
}

/// Where the fewest rounds of every configuration would run past the time
/// budget, a workload measures fewer line widths (interior ones, then the
/// widest) and says what it left out, instead of overrunning; the A/A control
/// and the timestamped baseline stay.
#[test]
fn a_budget_too_short_for_every_configuration_leaves_some_out_and_says_so() {
    let dir = temp_dir("sync-budget");
    let run = |minutes: &str, line_widths: &str| {
        let mut args =
            vec!["bench", "sync", "--size", "12x12", "--set", "ipsvi.cache_size=16", "--strategies", "barrier-global"];
        args.extend(["--repeat", "6", "--max-rounds", "6", "--seed", "7", "--workloads", "sweep"]);
        args.extend(["--line-widths", line_widths, "--max-minutes", minutes, "--out-dir", dir.to_str().unwrap()]);
        args.push("--force");
        sweeplab(&args)
    };
    // 0.06 s for set-up, warm-up and six rounds: nothing fits, so the least
    // that still answers stays (the narrowest line width, its control and
    // the timestamped baseline).
    let o = run("0.001", "1,2,4");
    assert!(o.status.success(), "{}", stderr(&o));
    let warning = "warning: sweep workload: line width(s) 2, 4 left out to fit the time budget";
    assert!(stderr(&o).contains(warning), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("  line width(s) 2, 4 left out"), "the verdict says it: {stdout}");
    assert!(stdout.contains("frame differences at it (no slopes)"), "{stdout}");
    let report = json(&dir.join("sync.json"));
    let sweep = &report["workloads"][0];
    assert_eq!(sweep["line_widths"], serde_json::json!([1]), "{sweep}");
    assert_eq!(sweep["left_out"]["line_widths"], serde_json::json!([2, 4]), "{sweep}");
    assert_eq!(sweep["rounds"], 6, "the fewest rounds still run");
    let configs = report["configurations"].as_array().unwrap();
    assert!(configs.iter().all(|c| c["line_width"] == 1), "{configs:?}");
    // no-barriers, its control and barrier-global at 1, and the timestamped baseline.
    assert_eq!(configs.len(), 3 + 1, "{configs:?}");
    assert!(configs.iter().all(|c| c["frames"] == 6), "{configs:?}");
    let rows = report["strategies"].as_array().unwrap();
    let barrier = rows.iter().find(|r| r["strategy"] == "barrier-global").unwrap();
    assert_eq!(barrier["frame_sync_us"]["n"], 6, "{barrier}");
    assert!(barrier["boundary_us"].is_null(), "no slope from one line width: {barrier}");
    let md = std::fs::read_to_string(dir.join("sync.md")).unwrap();
    assert!(md.contains("line width(s) 2, 4 left out"), "{md}");
    // Cut short by its budget, the run is named partial.
    let marker = std::fs::read_to_string(dir.join("PARTIAL")).unwrap();
    assert!(marker.contains("measured less than planned: sweep workload: line width(s) 2, 4"), "{marker}");
    assert!(stderr(&o).contains("partial: sweep workload"), "{}", stderr(&o));
    assert_every_output_names_its_run(&dir);
    // A budget that holds every configuration leaves nothing out.
    let o = run("10", "1,2,4");
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stderr(&o).contains("left out"), "{}", stderr(&o));
    let report = json(&dir.join("sync.json"));
    assert!(report["workloads"][0]["left_out"].is_null(), "{}", report["workloads"][0]);
    assert_eq!(report["configurations"].as_array().unwrap().len(), 3 * 3 + 1);
    assert!(!dir.join("PARTIAL").exists(), "a whole run is not partial");
}

#[test]
fn every_output_names_its_run_and_report_puts_two_devices_side_by_side() {
    let dir = temp_dir("sync-metadata");
    let o = bench(&dir, &["--workloads", "empty", "--no-line-timestamps"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let report = json(&dir.join("sync.json"));
    let run = &report["run"];
    for key in
        ["device", "vendor_id", "device_id", "driver_name", "driver_version", "api_version", "git_commit", "date"]
    {
        assert!(run[key].as_str().is_some_and(|v| !v.is_empty()), "run.{key} in {run}");
    }
    assert!(run["validation_layer"].as_str().is_some_and(|v| v.starts_with("1.")), "validated: {run}");
    assert!(run["timestamp_period_ns"].as_f64().is_some_and(|v| v > 0.0), "{run}");
    assert!(run["host_cores"].as_u64().is_some_and(|v| v > 0), "{run}");
    assert!(run["command"].as_str().unwrap().contains("--line-widths 1,2"), "{run}");
    for file in ["sync.csv", "sync_configurations.csv"] {
        let text = std::fs::read_to_string(dir.join(file)).unwrap();
        for key in RUN_KEYS {
            assert!(text.contains(&format!("# {key}: ")), "{file} lacks {key}");
        }
    }
    for file in ["sync.md", "sync_configurations.md"] {
        let text = std::fs::read_to_string(dir.join(file)).unwrap();
        for key in RUN_KEYS {
            assert!(text.contains(&format!("- {key}: ")), "{file} lacks {key}");
        }
    }
    assert!(!dir.join("trace_empty_no-barriers.json").exists(), "--no-line-timestamps traces nothing");
    // A second "device": the same report under another name.
    let mut other = report.clone();
    other["run"]["device"] = Value::from("Fake GPU 9000");
    other["run"]["driver_version"] = Value::from("1.2.3");
    let (a, b) = (dir.join("a.json"), dir.join("b.json"));
    std::fs::write(&a, report.to_string()).unwrap();
    std::fs::write(&b, other.to_string()).unwrap();
    let out = dir.join("report");
    let o = sweeplab(&["report", a.to_str().unwrap(), b.to_str().unwrap(), "--out-dir", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    let device = run["device"].as_str().unwrap();
    for strategy in ["no-barriers", "barrier-global", "events"] {
        for d in [device, "Fake GPU 9000"] {
            assert!(
                md.lines().any(|l| l.contains(d) && l.contains(&format!(" {strategy} "))),
                "no {strategy} row for {d}: {md}"
            );
        }
    }
    // Every cost is read with its verdict beside it, so a negative one is never taken as a cost.
    let header = md.lines().find(|l| l.contains("| fixed_us")).expect("the table's header");
    assert!(header.contains("fixed_verdict"), "no fixed_verdict column: {header}");
    assert!(out.join("report_fixed_cost.png").exists(), "the chart of (a)");
    let bad = dir.join("not-a-report.json");
    std::fs::write(&bad, "[1, 2]").unwrap();
    assert_user_error(&sweeplab(&["report", bad.to_str().unwrap(), "--out-dir", out.to_str().unwrap()]), "sync.json");
}

#[test]
fn bad_plans_are_refused_before_any_gpu_work() {
    let dir = temp_dir("sync-refused");
    let out = dir.to_str().unwrap();
    for (args, mention) in [
        (vec!["--repeat", "3"], "95 %"),
        // The name --repeat replaced still works.
        (vec!["--min-rounds", "3"], "95 %"),
        (vec!["--line-widths", "4"], "two line widths"),
        (vec!["--strategies", "racy"], "baseline"),
        (vec!["--workloads", "full"], "unknown workload"),
        (vec!["--max-rounds", "5", "--repeat", "6"], "most rounds"),
    ] {
        let mut all = vec!["bench", "sync", "--out-dir", out];
        all.extend(args);
        let o = sweeplab(&all);
        assert_user_error(&o, mention);
        assert!(!stderr(&o).contains("device:"), "{all:?}: opened the GPU before refusing: {}", stderr(&o));
    }
}

/// Every case of the probe runs validation-clean and gives a time per
/// dispatch. (Its barrier is what it measures, not a protection: the 1x1
/// output is never read back, and this layer version reports no
/// write-after-write between dispatches of a write-only image.)
#[test]
fn the_dispatch_probe_runs_every_case() {
    let ctx = validated_context();
    let rows = probe(&ctx, &ProbeCase::all(), 4, 1).unwrap();
    assert_eq!(rows.len(), BeforeEach::ALL.len() + 1);
    for r in &rows {
        assert!(r.gpu_us_per_dispatch > 0.0 && r.wall_us_per_dispatch > 0.0, "{r:?}");
        assert_eq!(r.dispatches, 4);
    }
    assert!(rows.iter().any(|r| !r.case.barrier), "the dispatches alone are a case too");
    common::assert_validation_clean(&ctx);
}

/// Every ping-pong variant of the probe (issue 24) runs validation-clean, one
/// row each, with its per-block times. The blocks ping-pong through a
/// barrier, and a block reads what the previous one wrote, so a variant that
/// bound the wrong side would be reported by synchronization validation.
#[test]
fn the_ping_pong_probe_runs_every_variant() {
    use sweeplab::bench::experiments::dispatch_probe::{probe_ping_pong, PingPong};
    let ctx = validated_context();
    let rows = probe_ping_pong(&ctx, &PingPong::ALL, 4, 6).unwrap();
    let expected = if ctx.push_descriptor.is_some() { 3 } else { 2 };
    assert_eq!(rows.len(), expected, "{rows:?}");
    for r in &rows {
        assert!(r.gpu_us_per_block.value > 0.0 && r.cpu_us_per_block.value >= 0.0, "{r:?}");
        assert_eq!((r.blocks, r.gpu_us_per_block.n), (4, 6));
    }
    common::assert_validation_clean(&ctx);
}

/// Where frames are long (here: every frame, with no shortest run), the
/// warm-up runs two frames per set of shaders (the compile is not a frame's
/// length): every arm and line width of a
/// workload shares the line pipelines, so one frame per workload compiles
/// them all. The timed rounds still run every configuration.
#[test]
fn a_warm_up_of_long_frames_runs_each_set_of_shaders_once() {
    use std::time::Duration;
    use sweeplab::bench::experiments::sync::{self, Eta, SyncObserver, SyncPlan, SyncReport, Workload};
    use sweeplab::bench::experiments::ExperimentError;
    use sweeplab::bench::{Protocol, RunInfo};
    use sweeplab::render::GpuScene;
    use sweeplab::techniques::ipsvi::{IpsviSettings, SyncStrategy};
    struct Quiet;
    impl SyncObserver for Quiet {
        fn round(&mut self, _: &SyncReport, _: Eta) -> Result<(), ExperimentError> {
            Ok(())
        }
    }
    let ctx = validated_context();
    let mut scene = sweeplab::techniques::default_scene(&[]).unwrap();
    (scene.render.width, scene.render.height) = (12, 12);
    let gpu = GpuScene::upload(&ctx, &scene).unwrap();
    let base = IpsviSettings { cache_size: 16, ..scene.settings.get::<IpsviSettings>().into_owned() };
    let plan = |min_run: Duration, workloads: &[Workload]| SyncPlan {
        width: 12,
        height: 12,
        strategies: vec![SyncStrategy::BarrierGlobal],
        line_widths: vec![1, 2],
        workloads: workloads.to_vec(),
        line_timestamps: true,
        protocol: Protocol::new(1, 6, 6, 3).unwrap(),
        precision: Default::default(),
        time_budget: None,
        min_run,
    };
    let warm_up_frames = |report: &SyncReport, w: Workload| {
        report.workloads.iter().find(|r| r.workload == w).map(|r| r.warm_up_frames).unwrap()
    };
    let both = [Workload::Empty, Workload::Sweep];
    let long = sync::run(&ctx, &gpu, &base, &plan(Duration::ZERO, &both), RunInfo::collect(&ctx), &mut Quiet).unwrap();
    let per_workload = long.configurations.len() / 2;
    for w in both {
        // The frame that compiles, then one that tells the frames are long.
        assert_eq!(warm_up_frames(&long, w), 2, "one set of shaders per workload");
        assert_eq!(long.rounds_of(w), 6);
    }
    assert!(long.configurations.iter().all(|c| c.frames == 6 && c.frames_per_run == 1), "{:?}", long.configurations);
    // Short frames: every configuration warms up and counts its frames per run.
    let short_plan = plan(Duration::from_secs(1), &[Workload::Empty]);
    let short = sync::run(&ctx, &gpu, &base, &short_plan, RunInfo::collect(&ctx), &mut Quiet).unwrap();
    assert_eq!(warm_up_frames(&short, Workload::Empty), 2 * per_workload, "two frames each");
    assert!(short.configurations.iter().all(|c| c.frames_per_run > 1), "short frames are averaged");
    drop(gpu);
    common::assert_validation_clean(&ctx);
}
