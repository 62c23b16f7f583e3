//! `tools/gpu_check.sh` end to end on lavapipe at tiny sizes, so that the
//! one command for a GPU machine cannot rot: every part runs and passes, the
//! report (JSON and Markdown) lists each with its exit status and time, and a
//! failing part is recorded while the parts after it still run.

use crate::common;

use common::cli::{small_cornell_box, GPU_CHECK_BENCH_SIZE, GPU_CHECK_IPSVI_ARGS};
use std::path::{Path, PathBuf};
use std::process::Command;

/// The folder the suite's own processes keep Mesa's shader cache in (as
/// `mesa_shader_cache/` under it), if that can be told.
fn suite_cache_home() -> Option<PathBuf> {
    std::env::var_os("XDG_CACHE_HOME")
        .filter(|v| !v.is_empty())
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").filter(|v| !v.is_empty()).map(|h| PathBuf::from(h).join(".cache")))
}

/// Mesa's shader cache where the suite's own processes keep it. Mesa puts its
/// `mesa_shader_cache/` folder into MESA_SHADER_CACHE_DIR as it does into
/// XDG_CACHE_HOME, so the variable names the cache's parent.
fn mesa_shader_cache() -> Option<(&'static str, PathBuf)> {
    suite_cache_home().map(|home| ("MESA_SHADER_CACHE_DIR", home))
}

/// The script in a bundle's layout (`tools/gpu_check_prepare.sh`): `tools/`
/// with `data/engine.vti` beside it, away from the checkout, so that the
/// data sets it reads are the ones beside it.
fn bundle(out: &Path) -> PathBuf {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let bundle = out.with_extension("bundle");
    let _ = std::fs::remove_dir_all(&bundle);
    std::fs::create_dir_all(bundle.join("tools")).unwrap();
    std::fs::create_dir_all(bundle.join("data")).unwrap();
    std::fs::copy(root.join("tools/gpu_check.sh"), bundle.join("tools/gpu_check.sh")).unwrap();
    std::os::unix::fs::symlink(root.join("data/engine.vti"), bundle.join("data/engine.vti")).unwrap();
    bundle
}

fn run_check(out: &Path, techniques: &str, benches: bool) -> (bool, serde_json::Value) {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let scene = small_cornell_box(&out.with_extension("scene"));
    let bundle = bundle(out);
    let status = Command::new("bash")
        .arg(bundle.join("tools/gpu_check.sh"))
        .arg(out)
        .env("GPU_CHECK_BIN", env!("CARGO_BIN_EXE_sweeplab"))
        .env("GPU_CHECK_SCENE", &scene)
        .env("GPU_CHECK_HALF_ANGLE_SCENE", root.join("tests/scenes/slab-under-sphere.toml"))
        // The script keeps its caches with its report (XDG_CACHE_HOME); lavapipe's
        // compiled shaders stay with the rest of the suite's, as a rerun would find them.
        .envs(mesa_shader_cache())
        .env("GPU_CHECK_SIZE", "16")
        .env("GPU_CHECK_BENCH_SIZE", GPU_CHECK_BENCH_SIZE)
        .env("GPU_CHECK_TECHNIQUES", techniques)
        .env("GPU_CHECK_AO_SET", "ao.clusters=16")
        .env("GPU_CHECK_SYNC_ARGS", "--quick --repeat 6 --max-rounds 6 --max-minutes 0.2 --line-widths 1,4")
        .env("GPU_CHECK_IPSVI_ARGS", GPU_CHECK_IPSVI_ARGS)
        .env(
            "GPU_CHECK_MODES_ARGS",
            "--one-at-a-time --line-widths 1 --cache-sizes 16 --half-angle-slices --repeat 1 --kernels serial",
        )
        .env(
            "GPU_CHECK_TABLE1_ARGS",
            "--data-sets engine.vti --sizes 8 --kernels serial,segmented --segments 0,16,16/4 --repeat 1",
        )
        .env(
            "GPU_CHECK_LIGHTS_ARGS",
            "--size 16x16 --scales 4 --light-counts 2 --scaling-counts 1 --error-scales 4 --incremental-passes 1 \
             --repeat 1",
        )
        .env("GPU_CHECK_BENCHES", if benches { "1" } else { "0" })
        .env_remove("SWEEPLAB_VALIDATE")
        .env_remove("SWEEPLAB_DATA")
        .status()
        .expect("run tools/gpu_check.sh");
    let report = std::fs::read_to_string(out.join("report.json")).expect("report.json written");
    let report: serde_json::Value =
        serde_json::from_str(&report).unwrap_or_else(|e| panic!("report.json: {e}\n{report}"));
    let md = std::fs::read_to_string(out.join("report.md")).expect("report.md written");
    let data = format!("data sets from {}/data;", bundle.display());
    assert!(md.contains(&data), "the data sets beside the script: {md}");
    let _ = std::fs::remove_dir_all(&bundle);
    (status.success(), report)
}

/// How many files a folder and its subfolders hold (0 where it does not exist).
fn files_in(dir: &Path) -> usize {
    std::fs::read_dir(dir)
        .map(|entries| entries.flatten().map(|e| if e.path().is_dir() { files_in(&e.path()) } else { 1 }).sum())
        .unwrap_or(0)
}

fn parts_of(report: &serde_json::Value) -> Vec<(String, i64, String)> {
    report["parts"]
        .as_array()
        .expect("parts")
        .iter()
        .map(|p| {
            let name = p["name"].as_str().unwrap().to_string();
            (name, p["rc"].as_i64().unwrap(), p["validation"].as_str().unwrap().to_string())
        })
        .collect()
}

#[test]
fn the_gpu_check_runs_every_part_on_lavapipe_and_records_a_failing_one() {
    let out = std::env::temp_dir().join(format!("sweeplab-gpu-check-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let all = "dvr,phong,reference,ipsvi,half-angle,lightvolume,ao";
    // Where Mesa would put a cache of the parts' own (MESA_SHADER_CACHE_DIR
    // naming the cache itself instead of its parent).
    let nested_cache = suite_cache_home().unwrap_or_default().join("mesa_shader_cache/mesa_shader_cache");
    let nested_before = files_in(&nested_cache);
    let (ok, report) = run_check(&out, all, true);
    let parts = parts_of(&report);
    let names: Vec<&str> = parts.iter().map(|p| p.0.as_str()).collect();
    let mut expected = vec!["devices".to_string()];
    expected.extend(all.split(',').map(|t| format!("compare-{t}")));
    expected.extend(
        ["bench-table1", "bench-sync", "bench-ipsvi-breakdown", "bench-ipsvi-modes", "bench-lights"].map(String::from),
    );
    assert_eq!(names, expected);
    for (name, rc, validation) in &parts {
        assert_eq!(*rc, 0, "{name} failed: {report:#}");
        if name.starts_with("compare-") {
            assert_eq!(validation, "clean", "{name} ran with validation on");
        }
    }
    assert!(ok, "the script exits 0 when every part passed");
    assert_eq!(report["failed_parts"], 0);
    // The parts' compiled shaders went where the suite's own are, not into a
    // cache of their own inside it.
    assert_eq!(files_in(&nested_cache), nested_before, "the parts kept a shader cache of their own");
    // The build it ran: the binary's version and commit.
    let build = format!("sweeplab {} at {}", env!("CARGO_PKG_VERSION"), env!("SWEEPLAB_GIT_COMMIT"));
    assert_eq!(report["build"], build.as_str(), "{report:#}");
    // The layer's version beside the driver's API version, for every reader of the report.
    let layer = report["validation_layer"].as_str().unwrap_or_default();
    assert!(layer.starts_with("VK_LAYER_KHRONOS_validation 1."), "{report:#}");
    let validated = report["validated_device"].as_str().unwrap_or_default();
    assert!(validated.contains("Vulkan 1.") && validated.contains("validation on (layer 1."), "{report:#}");
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.contains("- validation layer: VK_LAYER_KHRONOS_validation 1."), "{md}");
    assert!(md.contains(&format!("- build: {build}\n")), "{md}");
    assert!(out.join("compare/ipsvi.json").exists() && out.join("bench-sync").is_dir());
    assert!(out.join("bench-ipsvi-modes/ipsvi.json").exists(), "the error against time per mode");
    // The ground truth is rendered once per model: phong, reference and ao reuse dvr's
    // (single scattering, one colour), ipsvi's model and the light volume's colour differ.
    let compared = |t: &str| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(out.join(format!("compare/{t}.json"))).unwrap()).unwrap()
    };
    for (t, cached) in [("dvr", false), ("phong", true), ("reference", true), ("ao", true), ("ipsvi", false)] {
        assert_eq!(compared(t)["reference_cached"], cached, "{t}: {}", compared(t));
    }
    assert_eq!(compared("lightvolume")["reference_cached"], false, "chromatic: its own ground truth");
    // The reference rendered afresh equals the one dvr's run stored.
    assert_eq!(compared("reference")["rmse"], 0.0, "{}", compared("reference"));
    let markdown = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(markdown.contains("| compare-ao | 0 |"), "{markdown}");
    // Table 1 beside the paper's figures (none at 8x8), both kernels, the segmented one at each
    // count asked (16/4: 16 segments, 4 texel lanes), each against the fastest at its line width.
    assert!(
        markdown.contains("engine.vti 8x8 lw=4 segmented x8:")
            && markdown.contains("engine.vti 8x8 lw=4 segmented x16, texels x2:")
            && markdown.contains("engine.vti 8x8 lw=4 segmented x16, texels x4:")
            && markdown.contains("(the paper has no figure at this size and line width for CT Engine")
            && markdown.contains("; the fastest kernel here (lowest median)")
            && markdown.contains("x the time of ")
            && markdown.contains("x the serial kernel's"),
        "{markdown}"
    );

    // A part that fails is recorded, and the check goes on.
    let failing = out.join("failing");
    let (ok, report) = run_check(&failing, "no-such-technique,dvr", false);
    let parts = parts_of(&report);
    assert!(!ok, "the script's exit status says a part failed");
    assert_eq!(report["failed_parts"], 1);
    assert_ne!(parts[1].1, 0, "{:?}", parts[1]);
    assert_eq!(parts[2], ("compare-dvr".to_string(), 0, "clean".to_string()));
    assert_eq!(parts.len(), 3);
    std::fs::remove_dir_all(&out).ok();
    std::fs::remove_dir_all(out.with_extension("scene")).ok();
    std::fs::remove_dir_all(failing.with_extension("scene")).ok();
}

/// A bundle whose `sweeplab` answers at once, except `bench`, which sleeps past any limit the
/// test sets: what a lent machine's call does when the check outlasts its time.
fn slow_bench_bundle(stage: &Path) {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let bundle = stage.join("gpu-check");
    for dir in ["tools", "bin", "data"] {
        std::fs::create_dir_all(bundle.join(dir)).unwrap();
    }
    std::fs::copy(root.join("tools/gpu_check.sh"), bundle.join("tools/gpu_check.sh")).unwrap();
    // `devices` prints no device line: the report still has to be JSON.
    let fake = "#!/bin/sh\n[ \"$1\" = bench ] && exec sleep 60\nexit 0\n";
    std::fs::write(bundle.join("bin/sweeplab"), fake).unwrap();
    let status = Command::new("chmod").arg("+x").arg(bundle.join("bin/sweeplab")).status().unwrap();
    assert!(status.success());
    let status = Command::new("tar")
        .arg("-czf")
        .arg(stage.join("gpu-check.tar.gz"))
        .arg("-C")
        .arg(stage)
        .arg("gpu-check")
        .status();
    assert!(status.unwrap().success());
}

#[test]
fn a_lent_machine_gets_back_the_parts_before_the_time_limit_and_the_report() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let base = std::env::temp_dir().join(format!("sweeplab-gpu-check-limit-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&base);
    let (stage, results, unpacked) = (base.join("stage"), base.join("results"), base.join("unpacked"));
    slow_bench_bundle(&stage);
    let limit = 5;
    let started = std::time::Instant::now();
    let run = Command::new("bash")
        .arg(root.join("tools/gpu_check_on_device.sh"))
        .arg(&results)
        .current_dir(&root)
        .env("GPU_CHECK_STAGE", &stage)
        .env("GPU_CHECK_MAX_SECONDS", limit.to_string())
        .env("GPU_CHECK_TECHNIQUES", "dvr,ipsvi")
        .output()
        .expect("run tools/gpu_check_on_device.sh");
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(!run.status.success(), "a part cut at the limit fails the check: {stdout}");
    // `bench` sleeps 60 s: the limit ended it (TERM, KILL 10 s later at the latest).
    assert!(started.elapsed().as_secs() < 40, "the limit did not hold: {:?}", started.elapsed());
    std::fs::create_dir_all(&unpacked).unwrap();
    let status =
        Command::new("tar").arg("-xzf").arg(results.join("gpu-check-out.tar.gz")).arg("-C").arg(&unpacked).status();
    assert!(status.unwrap().success(), "the results came back packed: {stdout}");
    let out = unpacked.join("gpu-check-out");
    let report = std::fs::read_to_string(out.join("report.json")).expect("the report, written after the cut");
    let report: serde_json::Value =
        serde_json::from_str(&report).unwrap_or_else(|e| panic!("report.json: {e}\n{report}"));
    assert_eq!(report["max_seconds"], limit, "{report:#}");
    assert_eq!(report["build"], "unknown", "the fake binary names no version: {report:#}");
    let outcomes: Vec<(String, String)> = report["parts"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| (p["name"].as_str().unwrap().to_string(), p["outcome"].as_str().unwrap().to_string()))
        .collect();
    let names: Vec<&str> = outcomes.iter().map(|o| o.0.as_str()).collect();
    assert_eq!(
        names,
        [
            "devices",
            "compare-dvr",
            "compare-ipsvi",
            "bench-table1",
            "bench-sync",
            "bench-ipsvi-breakdown",
            "bench-ipsvi-modes",
            "bench-lights"
        ],
        "Table 1 first among the benches"
    );
    // Everything before the first bench passed, that bench was cut, the rest skipped.
    let expected = |name: &str| match name {
        "bench-table1" => "cut at the time limit",
        n if n.starts_with("bench-") => "skipped",
        _ => "passed",
    };
    for (name, outcome) in &outcomes {
        assert_eq!(outcome, expected(name), "{name}: {report:#}");
    }
    assert_eq!(report["failed_parts"], 5);
    assert_eq!(report["cut_or_skipped_parts"], 5);
    let log = std::fs::read_to_string(out.join("logs/bench-table1.log")).unwrap();
    assert!(log.contains("GPU_CHECK_MAX_SECONDS=5) ended it"), "{log}");
    // The summary on standard output names the cut part.
    assert!(stdout.contains("| bench-table1 | 124 | cut at the time limit |"), "{stdout}");
    assert!(out.join("machine.txt").exists());
    std::fs::remove_dir_all(&base).ok();
}
