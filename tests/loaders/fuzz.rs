//! Fuzzing the volume loaders as a property test that runs in CI: every file of
//! the checked-in corpus (tests/fuzz/volumes, one file per format and storage
//! variant, written by tests/loaders/writers.rs) mutated at random must load
//! into a consistent volume or fail with an error naming the file, in bounded
//! time, never panic. A longer run (docs/volume-formats.md):
//! `PROPTEST_CASES=100000 cargo test --release --test suite loaders::fuzz`.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use proptest::prelude::*;
use proptest::test_runner::{Config, FileFailurePersistence};
use sweeplab::scene::loaders::load_volume;
use sweeplab::scene::{Volume, VoxelData};

use super::malformed::variants;
use super::synthetic::synthetic;
use super::Scratch;

use crate::mutation::{mutated, mutations, Mutation};

const CORPUS_TYPES: [&str; 2] = ["uint16", "float32"];
/// Generous: a seed file loads in well under a millisecond; only a loader that
/// allocates or loops for what a mutated header claims gets near this.
const CASE_TIME_LIMIT: Duration = Duration::from_secs(2);

fn corpus_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz/volumes")
}

/// (header, data file) of every seed, relative to the corpus folder.
fn seeds() -> Vec<(PathBuf, Option<PathBuf>)> {
    let dir = corpus_dir();
    let scratch = Scratch::new("fuzz_seed_names");
    let mut all = Vec::new();
    for type_name in CORPUS_TYPES {
        let written = scratch.path().join(type_name);
        std::fs::create_dir_all(&written).unwrap();
        for (header, data) in variants(&written, &synthetic(type_name, 70)) {
            let relative = |p: &Path| Path::new(type_name).join(p.strip_prefix(&written).unwrap());
            all.push((relative(&header), data.as_deref().map(relative)));
        }
    }
    assert!(dir.is_dir(), "fuzz corpus {} missing", dir.display());
    all
}

/// The checked-in corpus is what the writers write today, and every seed loads.
/// `SWEEPLAB_WRITE_FUZZ_CORPUS=1` rewrites it after a writer changes.
#[test]
fn fuzz_corpus_is_current_and_loads() {
    let scratch = Scratch::new("fuzz_corpus");
    let rewrite = std::env::var_os("SWEEPLAB_WRITE_FUZZ_CORPUS").is_some();
    for type_name in CORPUS_TYPES {
        let written = scratch.path().join(type_name);
        std::fs::create_dir_all(&written).unwrap();
        for (header, data) in variants(&written, &synthetic(type_name, 70)) {
            for file in std::iter::once(&header).chain(data.as_ref()) {
                let checked_in = corpus_dir().join(type_name).join(file.strip_prefix(&written).unwrap());
                let bytes = std::fs::read(file).unwrap();
                if rewrite {
                    std::fs::create_dir_all(checked_in.parent().unwrap()).unwrap();
                    std::fs::write(&checked_in, &bytes).unwrap();
                }
                let stored = std::fs::read(&checked_in).unwrap_or_else(|e| panic!("{}: {e}", checked_in.display()));
                assert!(stored == bytes, "{} differs from the writer's output", checked_in.display());
            }
            let seed = corpus_dir().join(type_name).join(header.strip_prefix(&written).unwrap());
            load_volume(&seed).unwrap_or_else(|e| panic!("seed {}: {e}", seed.display()));
        }
    }
}

/// What a loaded volume must satisfy whatever the file said.
fn check_consistent(volume: &Volume, file: &str) {
    let d = volume.dims;
    assert!(d.x >= 1 && d.y >= 1 && d.z >= 1, "{file}: empty dims {d}");
    assert_eq!(volume.data.len(), volume.voxel_count(), "{file}: {d} but {} voxels", volume.data.len());
    let s = volume.spacing;
    assert!(s.is_finite() && s.min_element() > 0.0, "{file}: spacing {s}");
    let (lo, hi) = volume.value_range;
    assert!(lo.is_finite() && hi.is_finite() && lo <= hi, "{file}: value range {lo}..{hi}");
    if let VoxelData::F32(values) = &volume.data {
        assert!(values.iter().all(|v| (0.0..=1.0).contains(v)), "{file}: normalized value outside 0..=1");
    }
}

fn one_case(seed: &(PathBuf, Option<PathBuf>), mutate_data: bool, ms: &[Mutation], case: &Path) {
    let (header, data) = seed;
    let _ = std::fs::remove_dir_all(case);
    for file in std::iter::once(header).chain(data.as_ref()) {
        let target = case.join(file);
        std::fs::create_dir_all(target.parent().unwrap()).unwrap();
        let original = std::fs::read(corpus_dir().join(file)).unwrap();
        let is_target = if mutate_data && data.is_some() { Some(file) == data.as_ref() } else { file == header };
        std::fs::write(&target, if is_target { mutated(&original, ms) } else { original }).unwrap();
    }
    let path = case.join(header);
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    let start = Instant::now();
    match load_volume(&path) {
        Ok(volume) => check_consistent(&volume, &name),
        Err(error) => assert!(error.to_string().contains(&name), "the error does not name {name}: {error}"),
    }
    assert!(start.elapsed() < CASE_TIME_LIMIT, "{name}: {:?} for {ms:?}", start.elapsed());
}

#[test]
fn mutated_volume_files_load_consistently_or_fail_naming_the_file() {
    let seeds = seeds();
    let scratch = Scratch::new("fuzz_cases");
    let case = scratch.path().to_path_buf();
    let config = Config {
        // CI's share; PROPTEST_CASES raises it for a longer run.
        cases: std::env::var("PROPTEST_CASES").ok().and_then(|n| n.parse().ok()).unwrap_or(3000),
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct("tests/fuzz/volumes.proptest-regressions"))),
        ..Config::default()
    };
    proptest!(config, |(index in 0..seeds.len(), mutate_data in any::<bool>(), ms in mutations())| {
        one_case(&seeds[index], mutate_data, &ms, &case);
    });
}
