//! `bench sync` at tiny sizes: the protocol's rounds (shuffled, recorded,
//! per workload), the equal-work baseline and its A/A control, hazards of the
//! racy arms counted while every other message fails the run, metadata in
//! every output, `sweeplab report` over two devices, and the dispatch probe.
mod common;

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
    let o = bench(&dir, &[]);
    // With validation on (sweeplab() sets it): the racy arms' hazards are
    // expected and counted, anything else would fail the run.
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("validation: clean"), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    for line in ["empty workload (6 rounds", "sweep workload (6 rounds", "barrier-global: ", "events: "] {
        assert!(stdout.contains(line), "verdict lacks {line:?}: {stdout}");
    }
    assert!(!stdout.contains("per boundary over no barriers; per-line gaps: -"), "{stdout}");
    let report = json(&dir.join("sync.json"));
    assert_eq!(report["complete"], true);
    assert_every_output_names_its_run(&dir);
    let configs = report["configurations"].as_array().unwrap();
    // 2 workloads x (baseline, A/A control, 3 strategies) x 2 line widths, and
    // per workload 4 arms with per-line timestamps at line width 1.
    assert_eq!(configs.len(), 2 * 5 * 2 + 2 * 4, "{configs:?}");
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
                assert!(r["sync_us"].is_null(), "{r}");
            } else {
                assert_eq!(r["sync_us"]["n"], 6, "{r}");
            }
        }
    }
    // A strategy's per-line-timestamp frames synchronize after every other
    // block only (racy by design), and pair the two kinds of boundary in the
    // frame: about half the plain frame's barriers, and an in-frame estimate.
    for workload in ["empty", "sweep"] {
        let find = |arm: &str, stamped: bool| {
            configs
                .iter()
                .find(|c| {
                    c["workload"] == workload
                        && c["arm"] == arm
                        && c["line_width"] == 1
                        && c["line_timestamps"] == stamped
                })
                .unwrap_or_else(|| panic!("no {arm} {stamped} in {workload}"))
        };
        let base = find("no-barriers", false);
        let per_block = |c: &Value| c["barriers"].as_u64().unwrap() - base["barriers"].as_u64().unwrap();
        // `secondary` records its timestamped sweeps into a secondary per frame
        // (a recording replayed every frame cannot hold one frame's queries).
        for strategy in ["barrier-global", "secondary"] {
            let (plain, halved) = (find(strategy, false), find(strategy, true));
            // One barrier after every line record of the frame (blocks, and claim-only records).
            let every = per_block(plain);
            assert!(every >= plain["blocks"].as_u64().unwrap(), "{plain}");
            assert_eq!(per_block(halved), every.div_ceil(2), "after records 0, 2, 4, ...: {halved}");
            assert_eq!(halved["racy"], true, "{halved}");
            let row = strategies.iter().find(|r| r["workload"] == workload && r["strategy"] == strategy).unwrap();
            assert_eq!(row["line_gaps"]["in_frame_sync_us"]["n"], 6, "{row}");
            assert!(row["line_gaps"]["perturbation_ms"].is_null(), "only the baseline's frames measure it: {row}");
        }
    }
    // Non-racy strategies render barrier-global's image.
    for c in configs.iter().filter(|c| c["racy"] == false && c["workload"] == "sweep") {
        assert_eq!(c["rmse_vs_barrier_global"], 0.0, "{c}");
    }
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

/// Where the fewest rounds of every configuration would run past the time
/// budget, a workload measures fewer configurations (interior line widths,
/// then the A/A control) and says what it left out, instead of overrunning.
#[test]
fn a_budget_too_short_for_every_configuration_leaves_some_out_and_says_so() {
    let dir = temp_dir("sync-budget");
    let run = |minutes: &str, line_widths: &str| {
        let mut args = vec!["bench", "sync", "--size", "12x12", "--strategies", "barrier-global"];
        args.extend(["--repeat", "6", "--max-rounds", "6", "--seed", "7", "--workloads", "sweep"]);
        args.extend(["--line-widths", line_widths, "--max-minutes", minutes, "--out-dir", dir.to_str().unwrap()]);
        args.push("--force");
        sweeplab(&args)
    };
    // 0.06 s for set-up, warm-up and six rounds: nothing fits, so the least
    // that gives a slope stays (the narrowest and widest line widths, no control).
    let o = run("0.001", "1,2,4");
    assert!(o.status.success(), "{}", stderr(&o));
    let warning = "warning: sweep workload: line width(s) 2 and the A/A control left out to fit the time budget";
    assert!(stderr(&o).contains(warning), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("  line width(s) 2 and the A/A control left out"), "the verdict says it: {stdout}");
    let report = json(&dir.join("sync.json"));
    let sweep = &report["workloads"][0];
    assert_eq!(sweep["line_widths"], serde_json::json!([1, 4]), "{sweep}");
    assert_eq!(sweep["left_out"]["line_widths"], serde_json::json!([2]), "{sweep}");
    assert_eq!(sweep["left_out"]["control"], true);
    assert_eq!(sweep["rounds"], 6, "the fewest rounds still run");
    let configs = report["configurations"].as_array().unwrap();
    assert!(configs.iter().all(|c| c["line_width"] != 2 && c["strategy"] != "no-barriers-again"), "{configs:?}");
    // no-barriers and barrier-global at 1 and 4, and both with per-line timestamps.
    assert_eq!(configs.len(), 2 * 2 + 2, "{configs:?}");
    assert!(configs.iter().all(|c| c["frames"] == 6), "{configs:?}");
    let rows = report["strategies"].as_array().unwrap();
    assert!(rows.iter().all(|r| r["strategy"] != "no-barriers-again"), "no row for what was not measured: {rows:?}");
    let barrier = rows.iter().find(|r| r["strategy"] == "barrier-global").unwrap();
    assert_eq!(barrier["sync_us"]["n"], 6, "{barrier}");
    let md = std::fs::read_to_string(dir.join("sync.md")).unwrap();
    assert!(md.contains("The sweep workload measured line widths [1, 4]: line width(s) 2 and the A/A control"), "{md}");
    // Cut short by its budget, the run is named partial.
    let marker = std::fs::read_to_string(dir.join("PARTIAL")).unwrap();
    assert!(marker.contains("measured less than planned: sweep workload: line width(s) 2"), "{marker}");
    assert!(stderr(&o).contains("partial: sweep workload"), "{}", stderr(&o));
    assert_every_output_names_its_run(&dir);
    // A budget that holds every configuration leaves nothing out.
    let o = run("10", "1,2,4");
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stderr(&o).contains("left out"), "{}", stderr(&o));
    let report = json(&dir.join("sync.json"));
    assert!(report["workloads"][0]["left_out"].is_null(), "{}", report["workloads"][0]);
    assert_eq!(report["configurations"].as_array().unwrap().len(), 3 * 3 + 2);
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
    // Every slope is read with its verdict beside it, so a negative one is never taken as a cost.
    let header = md.lines().find(|l| l.contains("| boundary_us")).expect("the table's header");
    assert!(header.contains("boundary_verdict"), "no boundary_verdict column: {header}");
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
    use sweeplab::ipsvi::{IpsviSettings, SyncStrategy};
    use sweeplab::render::GpuScene;
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
    let base = scene.settings.get::<IpsviSettings>();
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
    let long = sync::run(&ctx, &gpu, &base, &plan(Duration::ZERO, &Workload::ALL), RunInfo::collect(&ctx), &mut Quiet)
        .unwrap();
    let per_workload = long.configurations.len() / 2;
    for w in Workload::ALL {
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
