//! Fuzzing the scene files as a property test that runs in CI: every example
//! of tests/scenes (the checked-in corpus) with its text mutated at random, or
//! with `--set` overrides of random keys to extreme values, must give a scene
//! that is consistent or an error naming its origin, never a panic. A longer
//! run: `PROPTEST_CASES=100000 cargo test --release --test suite scene_fuzz::`.

use std::path::{Path, PathBuf};

use proptest::prelude::*;
use proptest::test_runner::{Config, FileFailurePersistence};
use sweeplab::scene::scene_spec::VolumeSource;
use sweeplab::scene::{LightKind, Scene};
use sweeplab::techniques::parse_scene_str;

use crate::mutation::{mutated, mutations, EXTREME_NUMBERS};

fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes")
}

fn corpus() -> Vec<(String, String)> {
    let mut files: Vec<(String, String)> = std::fs::read_dir(scenes_dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .map(|p| (p.file_name().unwrap().to_string_lossy().into_owned(), std::fs::read_to_string(&p).unwrap()))
        .collect();
    files.sort();
    assert!(files.len() >= 5, "tests/scenes holds the corpus");
    files
}

/// Every dotted key of a TOML document (array entries by index), the keys a
/// `--set` can reach.
fn keys(table: &toml::Table, prefix: &str, out: &mut Vec<String>) {
    for (key, value) in table {
        let path = if prefix.is_empty() { key.clone() } else { format!("{prefix}.{key}") };
        out.push(path.clone());
        match value {
            toml::Value::Table(t) => keys(t, &path, out),
            toml::Value::Array(items) => {
                for (i, item) in items.iter().enumerate() {
                    if let toml::Value::Table(t) = item {
                        keys(t, &format!("{path}.{i}"), out);
                    }
                }
            }
            _ => {}
        }
    }
}

/// Values a `--set` may carry: extreme numbers, wrong types, empty and odd
/// strings, arrays of the wrong length, tables where values belong.
fn override_value() -> impl Strategy<Value = String> {
    prop_oneof![
        // In range for many keys, at their edges for others.
        3 => proptest::sample::select(&["0.5", "1", "2", "1e-9", "1e9", "-1e9", "90", "-90", "180", "89.999", "0.001"][..])
            .prop_map(str::to_string),
        2 => proptest::sample::select(&EXTREME_NUMBERS[..]).prop_map(str::to_string),
        1 => proptest::sample::select(&EXTREME_NUMBERS[..]).prop_map(|n| format!("[{n}, 0, 1]")),
        1 => proptest::sample::select(
            &[
                "true",
                "\"\"",
                "[]",
                "[1]",
                "[0, 0, 0]",
                "[1, 2, 3, 4]",
                "{}",
                "{ type = \"point\" }",
                "orthographic",
                "auto",
                "/dev/null",
                "../../etc/passwd",
                "1e-45",
                "[[1, 2], [3]]",
                "[nan, nan, nan]",
                "[inf, 0, 0]",
                "[1e30, 1e30, 1e30]",
            ][..]
        )
        .prop_map(str::to_string),
    ]
}

/// What a scene that was accepted must satisfy.
fn check_consistent(scene: &Scene, what: &str) {
    let c = &scene.camera;
    assert!(c.eye.is_finite() && c.target.is_finite() && c.up.is_finite(), "{what}: camera {c:?}");
    assert!(c.eye != c.target, "{what}: camera at its target");
    let r = &scene.render;
    assert!(r.width >= 1 && r.height >= 1, "{what}: image {}x{}", r.width, r.height);
    assert!(r.step_voxels.is_finite() && r.step_voxels > 0.0, "{what}: step {}", r.step_voxels);
    assert!(r.background.is_finite() && r.emission.is_finite(), "{what}: render {r:?}");
    for light in &scene.lights {
        assert!(light.intensity.is_finite() && light.color.is_finite(), "{what}: light {light:?}");
        let finite = match light.kind {
            LightKind::Directional { direction } => direction.is_finite() && direction.length() > 0.0,
            LightKind::Point { position } => position.is_finite(),
            LightKind::Spot { position, direction, inner_cone_deg, outer_cone_deg } => {
                position.is_finite()
                    && direction.is_finite()
                    && direction.length() > 0.0
                    && inner_cone_deg.is_finite()
                    && outer_cone_deg.is_finite()
            }
        };
        assert!(finite, "{what}: light {light:?}");
    }
    for p in &scene.transfer.points {
        assert!(p.value.is_finite() && p.rgba.iter().all(|c| c.is_finite()), "{what}: transfer point {p:?}");
    }
}

fn one_case(origin: &str, text: &str, overrides: &[String]) {
    let what = format!("{origin} with {overrides:?}");
    let spec = match parse_scene_str(text, &scenes_dir(), origin, overrides) {
        Ok(spec) => spec,
        Err(error) => {
            let message = error.to_string();
            assert!(message.contains(origin) || message.contains("--set"), "{what}: error names neither: {message}");
            return;
        }
    };
    // Build (generate the volume) only where that is cheap: small synthetic volumes.
    if matches!(spec.volume, VolumeSource::Synthetic { size, .. } if size <= 32) {
        match spec.build() {
            Ok(scene) => check_consistent(&scene, &what),
            Err(error) => assert!(error.to_string().contains(origin), "{what}: {error}"),
        }
    }
}

fn config(file: &'static str) -> Config {
    Config {
        // CI's share; PROPTEST_CASES raises it for a longer run.
        cases: std::env::var("PROPTEST_CASES").ok().and_then(|n| n.parse().ok()).unwrap_or(1500),
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(file))),
        ..Config::default()
    }
}

#[test]
fn mutated_scene_text_gives_a_consistent_scene_or_an_error_naming_the_file() {
    let corpus = corpus();
    proptest!(config("tests/fuzz/scene_text.proptest-regressions"), |(index in 0..corpus.len(), ms in mutations())| {
        let (name, text) = &corpus[index];
        let bytes = mutated(text.as_bytes(), &ms);
        // A scene file is UTF-8 text; the file reader refuses anything else before parsing.
        if let Ok(text) = String::from_utf8(bytes) {
            // Small volumes only: a mutated `size` must not make each case generate 512^3 voxels.
            one_case(name, &text.replace("size = 64", "size = 16"), &[]);
        }
    });
}

#[test]
fn random_overrides_give_a_consistent_scene_or_an_error_naming_the_setting() {
    let corpus = corpus();
    let key_lists: Vec<Vec<String>> = corpus
        .iter()
        .map(|(_, text)| {
            let mut out = Vec::new();
            keys(&text.parse::<toml::Table>().unwrap(), "", &mut out);
            out.push("lights.7.intensity".into());
            out.push("ipsvi.no_such_key".into());
            out.push("nonsense".into());
            out
        })
        .collect();
    let case = (0..corpus.len()).prop_flat_map(|index| {
        let n = key_lists[index].len();
        (Just(index), proptest::collection::vec((0..n, override_value()), 1..3))
    });
    proptest!(config("tests/fuzz/scene_overrides.proptest-regressions"), |((index, sets) in case)| {
        let (name, text) = &corpus[index];
        let overrides: Vec<String> = sets.iter().map(|(k, v)| format!("{}={v}", key_lists[index][*k])).collect();
        one_case(name, &text.replace("size = 64", "size = 16"), &overrides);
    });
}
