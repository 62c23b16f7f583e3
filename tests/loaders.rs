//! Tests of the volume file loaders (`sweeplab::scene::loaders`): the shared real
//! data sets, synthetic round trips through every format, and broken files.

// A test crate root resolves modules next to itself, so point into tests/loaders/.
#[path = "loaders/fuzz.rs"]
mod fuzz;
#[path = "loaders/malformed.rs"]
mod malformed;
#[path = "loaders/round_trips.rs"]
mod round_trips;
#[path = "loaders/samples.rs"]
mod samples;
#[path = "loaders/synthetic.rs"]
mod synthetic;
#[path = "loaders/writers.rs"]
mod writers;

use std::path::{Path, PathBuf};

use sweeplab::scene::loaders::{data_dir, load_volume, LoadError};
use sweeplab::scene::Volume;

/// Path of a shared data set; fails with a hint when the data folder is missing.
pub fn sample(name: &str) -> PathBuf {
    let dir = data_dir();
    let path = dir.join(name);
    assert!(
        path.is_file(),
        "real data set {name} not found in {}: the repository's data/ holds it \
         (SWEEPLAB_DATA names another folder)",
        dir.display()
    );
    path
}

/// A fresh scratch folder under the target dir, removed when dropped.
pub struct Scratch(PathBuf);

impl Scratch {
    pub fn new(test: &str) -> Scratch {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("loaders").join(test);
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }

    pub fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

pub fn load_ok(path: &Path) -> Volume {
    match load_volume(path) {
        Ok(volume) => volume,
        Err(e) => panic!("{} should load: {e}", path.display()),
    }
}

/// Loading must fail, and the message must name the file.
pub fn load_err(path: &Path) -> LoadError {
    let error = match load_volume(path) {
        Ok(volume) => panic!("{} should not load, but gave {:?} voxels", path.display(), volume.dims),
        Err(e) => e,
    };
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    let message = error.to_string();
    assert!(message.contains(&name), "the error for {name} does not name the file: {message}");
    error
}

/// Writes the first `len` bytes of `source` to `target`.
pub fn truncated_copy(source: &Path, target: &Path, len: usize) {
    let bytes = std::fs::read(source).unwrap();
    std::fs::write(target, &bytes[..len]).unwrap();
}
