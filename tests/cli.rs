//! The `sweeplab` binary as a user runs it: outputs, reports, and clear errors
//! with a non-zero exit for bad input (never a panic).

use crate::common;

use common::cli::*;
use std::process::Command;

#[test]
fn render_writes_png_profile_and_trace_validation_clean() {
    let dir = temp_dir("render");
    let (png, json, trace) = (dir.join("r.png"), dir.join("p.json"), dir.join("t.json"));
    let o = sweeplab(&[
        "render",
        "--size",
        "48x40",
        "--technique",
        "phong",
        "--out",
        png.to_str().unwrap(),
        "--profile-json",
        json.to_str().unwrap(),
        "--trace",
        trace.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("validation: clean"), "{}", stderr(&o));
    let img = image::open(&png).unwrap();
    assert_eq!((img.width(), img.height()), (48, 40));
    let p: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    for key in ["device", "gpu_ms_total", "gpu_memory_bytes", "passes"] {
        assert!(p.get(key).is_some(), "profile JSON lacks {key}: {p}");
    }
    let pass = &p["passes"][0];
    assert_eq!(pass["name"], "phong");
    assert!(pass["gpu_ms"].as_f64().unwrap() > 0.0 && pass["count"] == 1);
    assert!(p["gpu_memory_bytes"].as_u64().unwrap() > 0);
    let t: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&trace).unwrap()).unwrap();
    assert_eq!(t["traceEvents"][0]["ph"], "X");
}

/// Linear RGB of a PNG that `sweeplab` wrote (sRGB, 8 bits).
fn linear_pixels(path: &std::path::Path) -> Vec<f64> {
    let srgb = |c: u8| {
        let c = c as f64 / 255.0;
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    };
    image::open(path).unwrap().to_rgb8().into_raw().into_iter().map(srgb).collect()
}

#[test]
fn compare_reports_error_and_time_as_json() {
    let dir = temp_dir("compare");
    let compare = |technique: &str| {
        let (json, out, reference) =
            (dir.join(format!("{technique}.json")), dir.join(format!("{technique}.png")), dir.join("reference.png"));
        let heat = dir.join("h.png");
        let o = sweeplab(&[
            "compare",
            "--technique",
            technique,
            "--size",
            "32x32",
            "--json",
            json.to_str().unwrap(),
            "--heatmap",
            heat.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--reference-out",
            reference.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(image::open(&heat).is_ok());
        let c: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        (c, linear_pixels(&out), linear_pixels(&reference))
    };
    let (c, dvr, reference) = compare("dvr");
    for key in ["technique", "rmse", "max_abs", "psnr", "gpu_ms", "reference_gpu_ms"] {
        assert!(c.get(key).is_some(), "compare JSON lacks {key}: {c}");
    }
    assert_eq!(c["technique"], "dvr");
    // The reported error is the error between the two images it wrote, up to
    // their 8-bit sRGB rounding (measured: 0.071472 reported, 0.071476 from the PNGs).
    let rmse = c["rmse"].as_f64().unwrap();
    let from_pngs = (dvr.iter().zip(&reference).map(|(a, b)| (a - b) * (a - b)).sum::<f64>() / dvr.len() as f64).sqrt();
    println!("rmse reported {rmse}, from the PNGs {from_pngs}");
    assert!(
        (rmse - from_pngs).abs() <= 0.01 * from_pngs,
        "reported rmse {rmse}, between the written images {from_pngs}"
    );
    // Unshaded DVR is measurably not the lit ground truth (measured 0.071 at a
    // peak of 0.77); and the ground truth compared with itself is exact.
    let peak = reference.iter().cloned().fold(0.0, f64::max);
    assert!(rmse > 0.02 * peak, "unshaded DVR cannot equal the lit reference: rmse {rmse}, peak {peak}");
    let (itself, _, _) = compare("reference");
    assert_eq!(itself["rmse"].as_f64(), Some(0.0), "the ground truth against itself: {itself}");
    assert_eq!(itself["psnr"], "inf");
}

/// `compare` of an IPSVI frame prints its line shape and writes it in the
/// JSON, naming the kernel as it ran: here 8 segments per pixel, so each of
/// the 16 pixels of a line is 8 invocations (the rest are the texel pass's).
#[test]
fn compare_reports_the_ipsvi_line_shape() {
    let dir = temp_dir("compare-shape");
    let json = dir.join("ipsvi.json");
    let kernel = r#"ipsvi.line_kernel="segmented""#;
    let args = ["compare", "--technique", "ipsvi", "--size", "16x16", "--set", kernel, "--set", "ipsvi.segments=8"];
    let o = sweeplab(&[&args[..], &["--json", json.to_str().unwrap()]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    let line =
        stdout.lines().find(|l| l.starts_with("line shape (segmented x8): ")).unwrap_or_else(|| panic!("{stdout}"));
    let c: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let shape = &c["line_shape"];
    assert_eq!(shape["kernel"], "segmented x8", "{c}");
    let median = shape["invocations_median"].as_u64().unwrap();
    assert!(median >= 16 * 8, "16 pixels x 8 segments at least: {shape}");
    assert!(line.contains(&format!("invocations per dispatch median {median} ")), "{line}");
    assert!(shape["chain_median"].as_u64().is_some_and(|c| c > 0), "{shape}");
}

#[test]
fn devices_lists_timestamp_properties() {
    let o = sweeplab(&["devices", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let d: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let first = &d[0];
    for key in ["name", "api_version", "driver_name", "timestamp_period_ns", "timestamp_valid_bits"] {
        assert!(first.get(key).is_some(), "{key} missing: {first}");
    }
}

#[test]
fn bad_input_gives_clear_errors_not_panics() {
    let dir = temp_dir("errors");
    let missing = dir.join("missing-scene.toml");
    assert_user_error(&sweeplab(&["render", "--scene", missing.to_str().unwrap()]), "missing-scene.toml");
    let garbage = dir.join("garbage.vti");
    std::fs::write(&garbage, b"<VTKFile type=\"ImageData\"><ImageData WholeExtent=\"0 1").unwrap();
    assert_user_error(&sweeplab(&["render", "--volume", garbage.to_str().unwrap()]), "garbage.vti");
    let unknown = dir.join("volume.xyz");
    std::fs::write(&unknown, b"x").unwrap();
    assert_user_error(&sweeplab(&["render", "--volume", unknown.to_str().unwrap()]), "volume.xyz");
    assert_user_error(&sweeplab(&["render", "--size", "12"]), "--size");
    assert_user_error(&sweeplab(&["render", "--size", "0x5"]), "--size");
    assert_user_error(&sweeplab(&["render", "--technique", "raytrace"]), "raytrace");
    assert_user_error(&sweeplab(&["render", "--set", "camera.azimut=3"]), "azimut");
    assert_user_error(&sweeplab(&["render", "--set", "novalue"]), "novalue");
    assert_user_error(
        &sweeplab(&["render", "--set", "ipsvi.line_width=99", "--technique", "ipsvi", "--size", "8x8"]),
        "line_width",
    );
    assert_user_error(&sweeplab(&["render", "--device", "no-such-gpu"]), "no-such-gpu");
    let out = dir.join("bench");
    let out = out.to_str().unwrap();
    assert_user_error(&sweeplab(&["bench", "ipsvi", "--sizes", "0", "--out-dir", out]), "empty");
    assert_user_error(
        &sweeplab(&["bench", "ipsvi", "--sizes", "8", "--line-widths", "99", "--repeat", "1", "--out-dir", out]),
        "line_width",
    );
    assert_user_error(&sweeplab(&["bench", "sync", "--strategies", "fences", "--out-dir", out]), "fences");
    let unwritable = dir.join("no-such-dir").join("out.png");
    assert_user_error(&sweeplab(&["render", "--size", "8x8", "--out", unwritable.to_str().unwrap()]), "out.png");
}

#[test]
fn bench_lights_writes_table1_scaling_memory_and_error_rows_validation_clean() {
    let dir = temp_dir("bench-lights");
    let out = dir.join("lights");
    #[rustfmt::skip]
    let o = sweeplab(&[
        "bench", "lights", "--scales", "4", "--light-counts", "2", "--scaling-counts", "1,2",
        "--error-scales", "4", "--repeat", "1", "--size", "16x16", "--out-dir", out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("validation: clean"), "{}", stderr(&o));
    for file in ["lights.csv", "lights.md", "lights_scaling.png", "lights_table1_4.png", "lights_error_vs_time.png"] {
        assert!(out.join(file).is_file(), "{file} missing");
    }
    let rows = bench_rows(&out.join("lights.json"));
    assert_names_its_run(&out.join("lights.csv"), &out.join("lights.md"));
    assert_every_output_names_its_run(&out);
    let part = |p: &str| rows.iter().filter(|r| r["part"] == p).collect::<Vec<_>>();
    let table1 = part("table1");
    assert_eq!(table1.len(), 2, "ours and the paper's DR*1/4 2-light row: {table1:?}");
    assert_eq!(table1[1]["coherent_ms"], 18.0);
    for key in ["sequential_ms", "coherent_ms", "state_change_ms", "toggle_ms", "state_change_over_toggle"] {
        assert!(table1[0][key].as_f64().is_some_and(|v| v > 0.0), "{key}: {}", table1[0]);
    }
    let kinds: Vec<(&str, &str)> =
        part("update").iter().map(|r| (r["update"].as_str().unwrap(), r["kind"].as_str().unwrap())).collect();
    assert_eq!(
        kinds,
        [
            ("entire-sequential", "Entire"),
            ("entire-coherent", "Entire"),
            ("state-change", "Selective"),
            ("toggle", "Selective")
        ]
    );
    assert_eq!(part("scaling").len(), 4, "two light counts, coherent and sequential");
    assert!(part("scaling_fit").iter().any(|r| r["propagation"] == "sequential" && r["ms_per_added_light"].is_f64()));
    assert!(part("memory").iter().all(|r| r["illumination_bytes"].as_u64().is_some_and(|b| b > 0)));
    let incremental = part("incremental");
    assert_eq!(incremental.len(), 2, "one and two passes a frame");
    assert!(incremental[0]["frames"].as_u64() > incremental[1]["frames"].as_u64(), "{incremental:?}");
    let inside = part("inside");
    assert_eq!(inside.len(), 2, "a point light at the centre and outside: {inside:?}");
    assert_eq!((inside[0]["passes"].as_u64(), inside[1]["passes"].as_u64()), (Some(6), Some(2)), "{inside:?}");
    let error = part("error");
    assert_eq!(error.len(), 4, "DVR and the light volume at scale 4: default, per-light, per-light grey");
    for (technique, chromatic) in
        [("lightvolume", true), ("lightvolume-per-light", true), ("lightvolume-per-light-grey", false)]
    {
        assert!(error.iter().any(|r| r["technique"] == technique && r["chromatic"] == chromatic), "{error:?}");
    }
    assert!(error.iter().all(|r| r["rmse"].as_f64().is_some_and(f64::is_finite)));
    let markdown = std::fs::read_to_string(out.join("lights.md")).unwrap();
    assert!(markdown.contains("paper (GTX 670)") && markdown.contains("ms_per_added_light"));
}

#[test]
fn bench_lights_rejects_bad_parameters_clearly() {
    let out = temp_dir("bench-lights-errors");
    let out = out.to_str().unwrap();
    assert_user_error(&sweeplab(&["bench", "lights", "--scales", "3", "--out-dir", out]), "--scales");
    assert_user_error(&sweeplab(&["bench", "lights", "--light-counts", "0", "--out-dir", out]), "--light-counts");
    assert_user_error(&sweeplab(&["bench", "lights", "--light-counts", "17", "--out-dir", out]), "--light-counts");
    assert_user_error(
        &sweeplab(&["bench", "lights", "--incremental-passes", "0", "--out-dir", out]),
        "--incremental-passes",
    );
    assert_user_error(&sweeplab(&["bench", "lights", "--scaling-counts", "0", "--out-dir", out]), "--scaling-counts");
    assert_user_error(&sweeplab(&["bench", "lights", "--scaling-scale", "8", "--out-dir", out]), "--scaling-scale");
    assert_user_error(&sweeplab(&["bench", "lights", "--error-scales", "1,5", "--out-dir", out]), "--error-scales");
    assert_user_error(&sweeplab(&["bench", "lights", "--repeat", "0", "--out-dir", out]), "--repeat");
    assert_user_error(&sweeplab(&["bench", "lights", "--scales", "x", "--out-dir", out]), "--scales");
}

/// Every bench measures at least one timed run: `--repeat 0` is an error
/// before any GPU work (it used to be raised silently to 1), and no output is written.
#[test]
fn every_bench_refuses_zero_repeats() {
    let dir = temp_dir("bench-repeat-zero");
    for bench in ["ipsvi", "table1", "lights", "stability"] {
        let out = dir.join(bench);
        let o = sweeplab(&["bench", bench, "--repeat", "0", "--out-dir", out.to_str().unwrap()]);
        assert_user_error(&o, "--repeat");
        assert!(stderr(&o).contains("use 1 or more"), "{bench}: {}", stderr(&o));
        assert!(!out.exists(), "{bench} wrote {} before refusing", out.display());
    }
}

/// Bad outputs and list values are refused before the GPU is opened (the
/// `device:` line is printed when it is).
#[test]
fn outputs_and_list_values_are_checked_before_any_gpu_work() {
    let dir = temp_dir("checked-first");
    let jpg = dir.join("r.jpg");
    let missing = dir.join("no-such-folder").join("h.png");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["render", "--out", jpg.to_str().unwrap()], "PNG"),
        (vec!["compare", "--technique", "dvr", "--heatmap", missing.to_str().unwrap()], "does not exist"),
        (vec!["bench", "ipsvi", "--line-widths", "1,0", "--out-dir", dir.to_str().unwrap()], "line_width = 0"),
        (vec!["bench", "ipsvi", "--sizes", "0", "--out-dir", dir.to_str().unwrap()], "--sizes"),
        (vec!["bench", "ipsvi", "--half-angle-slices", "100", "--out-dir", dir.to_str().unwrap()], "slice_step = 100"),
        (vec!["bench", "sync", "--line-widths", "1,64", "--out-dir", dir.to_str().unwrap()], "line_width = 64"),
        (vec!["bench", "table1", "--sizes", "20000", "--out-dir", dir.to_str().unwrap()], "--sizes"),
    ];
    for (args, mention) in cases {
        let o = sweeplab(&args);
        assert_user_error(&o, mention);
        assert!(!stderr(&o).contains("device:"), "{args:?}: opened the GPU before refusing: {}", stderr(&o));
        // One cause, printed once.
        assert_eq!(stderr(&o).matches("error:").count(), 1, "{}", stderr(&o));
    }
}

/// A bench never overwrites another run's results: a second run into the
/// same folder is refused unless `--force`, which removes the files the first
/// wrote and this one does not (a strategy left out), and nothing else.
#[test]
fn bench_output_folders_are_refused_when_full_and_forced_hold_no_stale_files() {
    let dir = temp_dir("stale");
    let run = |strategies: &str, force: bool| {
        #[rustfmt::skip]
        let mut args = vec![
            "bench", "sync", "--size", "8x8", "--line-widths", "1,2", "--workloads", "sweep",
            // A small light cache: what is tested is the folder, not the sweep's cost.
            "--set", "ipsvi.cache_size=16",
            "--strategies", strategies, "--repeat", "6", "--max-rounds", "6", "--out-dir", dir.to_str().unwrap(),
        ];
        if force {
            args.push("--force");
        }
        sweeplab(&args)
    };
    let o = run("barrier-global,events,secondary", false);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains(&format!("writing into {}", dir.display())), "{}", stderr(&o));
    assert!(dir.join("trace_sweep_events.json").exists() && !dir.join("PARTIAL").exists());
    // Every strategy's traced frame has per-line timestamps (secondary's from a secondary
    // recorded for the timestamped frame): gaps that are numbers, not 0 or NaN.
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("sync.json")).unwrap()).unwrap();
    let trace = |s: &str| report["traces"].as_array().unwrap().iter().find(|r| r["strategy"] == s).unwrap().clone();
    for strategy in ["barrier-global", "secondary"] {
        let lines = &trace(strategy)["line_median_us"];
        assert!(lines.as_f64().is_some_and(|v| v > 0.0), "{strategy}: {}", trace(strategy));
    }
    assert!(dir.join("trace_sweep_secondary.json").exists());
    // Refused before any GPU work, the first run's files untouched.
    let first = std::fs::read_to_string(dir.join("sync.json")).unwrap();
    let o = run("barrier-global", false);
    assert_user_error(&o, "--force");
    assert!(!stderr(&o).contains("device:"), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(dir.join("sync.json")).unwrap(), first);
    std::fs::write(dir.join("mine.txt"), "a user's file").unwrap();
    let o = run("barrier-global", true);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!dir.join("trace_sweep_events.json").exists(), "a stale file of the first run is left");
    assert!(!dir.join("trace_sweep_secondary.json").exists(), "a stale file of the first run is left");
    assert!(dir.join("trace_sweep_barrier-global.json").exists() && dir.join("sync.csv").exists());
    assert!(dir.join("mine.txt").exists(), "a file the bench did not write was removed");
}

/// Without `--out-dir`, each run writes a new folder under the bench's own
/// (named by the run's date and time) and says which.
#[test]
fn without_out_dir_every_bench_run_writes_a_new_folder() {
    let dir = temp_dir("new-folders");
    let run = || {
        let args = ["bench", "stability", "--cases", "baseline", "--techniques", "dvr", "--size", "8"];
        let o = Command::new(env!("CARGO_BIN_EXE_sweeplab")).args(args).current_dir(&dir).output().unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
        let err = stderr(&o);
        let line = err.lines().find_map(|l| l.strip_prefix("writing into ")).unwrap_or_else(|| panic!("{err}"));
        let folder = dir.join(line.split(" (").next().unwrap());
        assert!(folder.join("stability.json").is_file(), "{}", folder.display());
        assert!(!folder.join("PARTIAL").exists());
        folder
    };
    let (first, second) = (run(), run());
    assert_ne!(first, second, "the second run wrote over the first");
    assert_eq!(first.parent(), Some(dir.join("bench-stability").as_path()));
    assert_eq!(second.parent(), first.parent());
}

/// A run stopped while it measures (Ctrl-C) keeps the rounds it measured,
/// named as partial: the PARTIAL marker, and the report's own header.
#[test]
fn a_stopped_bench_keeps_what_it_measured_named_as_partial() {
    let dir = temp_dir("stopped").join("sync");
    #[rustfmt::skip]
    let mut child = Command::new(env!("CARGO_BIN_EXE_sweeplab"))
        .args([
            "bench", "sync", "--size", "8x8", "--line-widths", "1,2", "--workloads", "empty",
            "--strategies", "barrier-global", "--repeat", "6", "--max-rounds", "100000", "--target-ci", "1e-9",
            "--target-ci-us", "0", "--out-dir", dir.to_str().unwrap(),
        ])
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let stderr = child.stderr.take().unwrap();
    let mut seen = String::new();
    for line in std::io::BufRead::lines(std::io::BufReader::new(stderr)) {
        let line = line.unwrap();
        seen += &line;
        seen.push('\n');
        if line.contains("round 2 done") {
            break;
        }
    }
    // Ctrl-C: SIGINT to the process, which has no handler for it.
    let stopped = Command::new("kill").args(["-INT", &child.id().to_string()]).status().unwrap();
    assert!(stopped.success());
    let status = child.wait().unwrap();
    assert!(!status.success(), "{seen}");
    let marker = std::fs::read_to_string(dir.join("PARTIAL")).unwrap_or_else(|e| panic!("{e}: {seen}"));
    assert!(marker.contains("has not finished") && marker.contains("bench sync"), "{marker}");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("sync.json")).unwrap()).unwrap();
    assert_eq!(report["complete"], false);
    assert!(report["workloads"][0]["rounds"].as_u64().is_some_and(|r| r >= 2), "{}", report["workloads"][0]);
    let md = std::fs::read_to_string(dir.join("sync.md")).unwrap();
    assert!(md.contains("Partial: rounds so far"), "{md}");
}

/// `bench ipsvi --breakdown`: six steps per cache-update mode (eleven for view
/// samples, whose write path is split, under each write rule and write pass), each with its
/// time, share and time per line. Run without validation: step b is the sweep
/// with no barriers, which synchronization validation reports by design.
#[test]
fn bench_ipsvi_breakdown_writes_every_step_of_both_modes() {
    let dir = temp_dir("bench-breakdown");
    let out = dir.join("breakdown");
    let o = Command::new(env!("CARGO_BIN_EXE_sweeplab"))
        .args(["bench", "ipsvi", "--breakdown", "--sizes", "16", "--repeat", "1", "--out-dir", out.to_str().unwrap()])
        // A small light cache: the steps and their rows do not depend on its size.
        .args(["--set", "ipsvi.cache_size=16"])
        // The serial kernel's modes (the segmented kernel's: tests/bench_breakdown_line_widths.rs).
        .args(["--kernels", "serial"])
        .env_remove("SWEEPLAB_VALIDATE")
        .output()
        .expect("run sweeplab");
    assert!(o.status.success(), "{}", stderr(&o));
    for file in ["ipsvi_breakdown.csv", "ipsvi_breakdown.md", "ipsvi_breakdown.png"] {
        assert!(out.join(file).is_file(), "{file} missing");
    }
    let rows = bench_rows(&out.join("ipsvi_breakdown.json"));
    assert_names_its_run(&out.join("ipsvi_breakdown.csv"), &out.join("ipsvi_breakdown.md"));
    assert_every_output_names_its_run(&out);
    // View samples split the write path (e1-e5) under both write rules.
    let modes = [
        ("view-samples", "non-empty", "sample", 11),
        ("view-samples", "non-empty", "texel", 11),
        ("view-samples", "every-sample", "sample", 11),
        ("view-samples", "every-sample", "texel", 11),
        ("light-rays", "", "", 6),
    ];
    assert_eq!(rows.len(), modes.iter().map(|m| m.3).sum::<usize>(), "no other rows");
    for (mode, rule, pass, count) in modes {
        let steps: Vec<&serde_json::Value> = rows
            .iter()
            .filter(|r| r["cache_update"] == mode && r["write_rule"].as_str().unwrap_or("") == rule)
            .filter(|r| r["write_pass"].as_str().unwrap_or("") == pass)
            .collect();
        assert_eq!(steps.len(), count, "{mode} {rule} {pass}: a to f: {steps:?}");
        assert!(steps[0]["step"].as_str().unwrap().starts_with("a:"));
        assert!(steps[count - 1]["step"].as_str().unwrap().starts_with("f:"));
        assert_eq!(steps[count - 1]["step_share"].as_f64().map(|s| s.is_finite()), Some(true));
        assert!(steps.iter().all(|r| r["gpu_ms"].as_f64().is_some_and(|v| v > 0.0)), "{mode} {pass}: {steps:?}");
        // Step b has no barriers between blocks; step c adds one per block.
        assert!(steps[2]["barriers"].as_u64() > steps[1]["barriers"].as_u64(), "{mode} {pass}: {steps:?}");
    }
}

/// `bench stability`: its lists are checked before any GPU work,
/// with a "did you mean"; a small table writes every report, each cell with
/// its status, and a meaningless or stiff case shows as warned, not ok.
#[test]
fn bench_stability_checks_its_lists_first_and_writes_the_table() {
    let dir = temp_dir("bench-stability");
    let out = dir.join("stability");
    let out = out.to_str().unwrap();
    for (args, mention) in [
        (vec!["--cases", "baseline,stif"], "did you mean stiff?"),
        (vec!["--techniques", "dvr,half_angle"], "did you mean half-angle?"),
        (vec!["--size", "0"], "--size"),
    ] {
        let o = sweeplab(&[&["bench", "stability", "--out-dir", out][..], &args].concat());
        assert_user_error(&o, mention);
        assert!(!stderr(&o).contains("device:"), "{args:?}: opened the GPU before refusing: {}", stderr(&o));
        assert_eq!(stderr(&o).matches("error:").count(), 1, "{}", stderr(&o));
    }
    #[rustfmt::skip]
    let o = sweeplab(&[
        "bench", "stability", "--cases", "baseline,opaque,transparent", "--techniques", "dvr,lightvolume",
        "--size", "8", "--out-dir", out,
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_every_output_names_its_run(std::path::Path::new(out));
    assert!(stderr(&o).contains("validation: clean"), "{}", stderr(&o));
    for file in ["stability.csv", "stability.md", "stability.png", "stability_convergence.csv"] {
        assert!(dir.join("stability").join(file).is_file(), "{file} missing");
    }
    let rows = bench_rows(&dir.join("stability").join("stability.json"));
    assert_names_its_run(&dir.join("stability").join("stability.csv"), &dir.join("stability").join("stability.md"));
    let status = |case: &str, t: &str| {
        let row = rows.iter().find(|r| r["case"] == case && r["technique"] == t).unwrap();
        row["status"].as_str().unwrap().to_string()
    };
    assert_eq!(rows.len(), 6, "3 cases x 2 techniques");
    assert_eq!(status("baseline", "dvr"), "ok");
    assert_eq!(status("opaque", "dvr"), "ok", "DVR marches the model exactly, opaque or not");
    assert_eq!(status("opaque", "lightvolume"), "warned", "the light grid cannot resolve it, and says so");
    assert_eq!(status("transparent", "lightvolume"), "warned", "an empty image comes with its warning");
    let orders = bench_rows(&dir.join("stability").join("stability_convergence.json"));
    let dvr = orders.iter().find(|r| r["technique"] == "dvr").unwrap();
    assert!(dvr["overall_order"].as_f64().is_some_and(|o| o > 1.5), "DVR's midpoint rule is second order: {dvr}");
}

/// `--set` names what is wrong: an unknown table or key with a "did you mean",
/// a bad value as a bad value; a technique that cannot hold a scene to its
/// bound says so on stderr.
#[test]
fn set_errors_name_the_cause_and_technique_warnings_are_printed() {
    let o = sweeplab(&["render", "--set", "camra.azimuth=3", "--size", "4x4"]);
    assert_user_error(&o, "did you mean [camera]?");
    let o = sweeplab(&["render", "--set", "render.step=abc", "--size", "4x4"]);
    assert_user_error(&o, "\"abc\"");
    assert!(!stderr(&o).contains("known"), "a bad value is not an unknown key: {}", stderr(&o));
    let dir = temp_dir("technique-warnings");
    let scene = dir.join("opaque.toml");
    std::fs::write(
        &scene,
        "[volume]\nsynthetic = \"noise\"\nsize = 8\n[transfer]\npoints = [[0.0, 1, 1, 1, 1], [1.0, 1, 1, 1, 1]]\n\
         [[lights]]\ntype = \"directional\"\ndirection = [-1.0, -1.0, -0.5]\n",
    )
    .unwrap();
    let png = dir.join("o.png");
    let (scene, png) = (scene.to_str().unwrap(), png.to_str().unwrap());
    let o = sweeplab(&["render", "--scene", scene, "--technique", "lightvolume", "--size", "8x8", "--out", png]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("warning: lightvolume: the transfer function gives the volume an optical depth"));
    let o = sweeplab(&["render", "--scene", scene, "--technique", "dvr", "--size", "8x8", "--out", png]);
    assert!(!stderr(&o).contains("warning:"), "DVR renders it exactly: {}", stderr(&o));
}

/// Messages in the user's terms: what was given, what is accepted, and the
/// nearest right thing, each before any GPU work.
#[test]
fn messages_say_what_is_accepted_and_suggest_the_right_thing() {
    let dir = temp_dir("messages");
    let folder_out = format!("{}/", dir.join("some-dir").display());
    std::fs::create_dir_all(dir.join("some-dir")).unwrap();
    std::fs::write(dir.join("engine.vti"), b"x").unwrap();
    let typo = dir.join("engin.vti");
    let nowhere = dir.join("no-such-folder").join("engine.vti");
    let cases: Vec<(Vec<&str>, Vec<&str>)> = vec![
        (vec!["render", "--size", "-64x64"], vec!["--size", "1..=16384"]),
        (
            vec!["render", "--technique", "ipsvi", "--set", "ipsvi.line_width=four"],
            vec!["ipsvi.line_width", "a whole number in 1..=32", "\"four\""],
        ),
        (vec!["render", "--set", "camera.azimuth=abc"], vec!["camera.azimuth", "expected a number"]),
        (vec!["render", "--technique", "IPSVI"], vec!["did you mean ipsvi?"]),
        (vec!["render", "--volume", typo.to_str().unwrap()], vec!["no such file", "did you mean", "engine.vti"]),
        (vec!["render", "--volume", nowhere.to_str().unwrap()], vec!["does not exist", "SWEEPLAB_DATA"]),
        (vec!["render", "--out", &folder_out], vec!["expects a file, got a directory"]),
        (vec!["bench", "ipsvi", "--sizes", "64x64"], vec!["side lengths", "`64` for 64x64"]),
    ];
    for (args, mentions) in cases {
        let o = sweeplab(&args);
        for mention in &mentions {
            assert_user_error(&o, mention);
        }
        let err = stderr(&o);
        assert!(!err.contains("device:"), "{args:?}: opened the GPU before refusing: {err}");
        for rust_type in ["u32", "f32", "unexpected argument"] {
            assert!(!err.contains(rust_type), "{args:?}: {err}");
        }
    }
    // A missing volume names its path once.
    let err = stderr(&sweeplab(&["render", "--volume", typo.to_str().unwrap()]));
    assert_eq!(err.matches("engin.vti").count(), 1, "{err}");
    // `render -h` lists every technique, `ao` included.
    let help = String::from_utf8_lossy(&sweeplab(&["render", "-h"]).stdout).into_owned();
    assert!(help.contains("lightvolume | ao"), "{help}");
}

/// A bench that stops before its first row leaves no empty output folder.
#[test]
fn a_bench_that_fails_early_leaves_no_empty_folder() {
    let out = temp_dir("no-empty").join("bench-out");
    let o =
        sweeplab(&["bench", "ipsvi", "--sizes", "8", "--device", "no-such-gpu", "--out-dir", out.to_str().unwrap()]);
    assert_user_error(&o, "no-such-gpu");
    assert!(!out.exists(), "an empty output folder was left behind");
}

/// The AO preprocessing says where it came from: computed and cached, then
/// loaded from that cache file.
#[test]
fn ao_says_whether_it_loaded_or_computed_its_preprocessing() {
    let dir = temp_dir("ao-cache");
    let cache = format!("ao.cache_dir={}", dir.join("cache").display());
    let png = dir.join("ao.png");
    let run = || {
        let o = sweeplab(&[
            "render",
            "--technique",
            "ao",
            "--size",
            "8x8",
            "--set",
            "ao.radius=1",
            "--set",
            "ao.clusters=4",
            "--set",
            &cache,
            "--out",
            png.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        stderr(&o)
    };
    let first = run();
    let stored =
        first.lines().find(|l| l.contains("computed preprocessing, cached at ")).unwrap_or_else(|| panic!("{first}"));
    let path = stored.rsplit("cached at ").next().unwrap().trim();
    assert!(std::path::Path::new(path).is_file(), "{first}");
    let second = run();
    assert!(second.contains(&format!("loaded preprocessing from cache {path}")), "{second}");
}

/// Without arguments `render` shows the point of the project: IPSVI with the
/// sphere's shadow, and the per-line row of its profile.
#[test]
fn render_without_arguments_runs_ipsvi_with_its_per_line_profile() {
    let dir = temp_dir("render-default");
    let png = dir.join("r.png");
    let o = sweeplab(&["render", "--size", "48x48", "--out", png.to_str().unwrap()]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.contains("ipsvi_line") && out.contains("ipsvi: 48x48"), "{out}");
    // --no-detail leaves the per-line row out.
    let o = sweeplab(&["render", "--size", "48x48", "--no-detail", "--out", png.to_str().unwrap()]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success() && !out.contains("ipsvi_line"), "{out}");
}

/// A setting of a technique that does not run is named, with the technique
/// that would read it; the same setting for the technique that runs is not.
#[test]
fn a_setting_of_a_technique_that_does_not_run_is_a_warning() {
    let dir = temp_dir("unused-setting");
    let png = dir.join("r.png");
    let run = |technique: &str| {
        let o = sweeplab(&[
            "render",
            "--size",
            "16x16",
            "--technique",
            technique,
            "--set",
            "ipsvi.sync=events",
            "--out",
            png.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        stderr(&o)
    };
    let err = run("dvr");
    assert!(err.contains("warning: the [ipsvi] settings are read only by technique ipsvi, not by dvr"), "{err}");
    assert!(!run("ipsvi").contains("[ipsvi] settings"));
}
