//! The scene readers of `crate::scene` with the techniques' tables: what
//! every front end (CLI, viewer, tests) calls to read a scene.

use std::path::Path;

use super::tables::CATALOGUE;
use crate::scene::default_scene as defaults;
use crate::scene::scene_file::{self as file, SceneError};
use crate::scene::scene_spec::SceneSpec;
use crate::scene::Scene;

/// Reads, checks and builds (loading the volume) the scene file at `path`.
pub fn load_scene(path: &Path, overrides: &[String]) -> Result<Scene, SceneError> {
    file::load_scene(&CATALOGUE, path, overrides)
}

/// Reads and checks the scene file at `path` without loading its volume.
pub fn parse_scene_file(path: &Path, overrides: &[String]) -> Result<SceneSpec, SceneError> {
    file::parse_scene_file(&CATALOGUE, path, overrides)
}

/// Checks and builds a scene given as TOML text (see [`file::scene_from_toml_str`]).
pub fn scene_from_toml_str(
    text: &str,
    base_dir: &Path,
    origin: &str,
    overrides: &[String],
) -> Result<Scene, SceneError> {
    file::scene_from_toml_str(&CATALOGUE, text, base_dir, origin, overrides)
}

/// Reads and checks a scene given as TOML text without building it.
pub fn parse_scene_str(
    text: &str,
    base_dir: &Path,
    origin: &str,
    overrides: &[String],
) -> Result<SceneSpec, SceneError> {
    file::parse_scene_str(&CATALOGUE, text, base_dir, origin, overrides)
}

/// The embedded default scene (see [`defaults::default_scene`]).
pub fn default_scene(overrides: &[String]) -> Result<Scene, SceneError> {
    defaults::default_scene(&CATALOGUE, overrides)
}

pub fn default_scene_spec(overrides: &[String]) -> Result<SceneSpec, SceneError> {
    defaults::default_scene_spec(&CATALOGUE, overrides)
}

/// The scene around a volume file (see [`defaults::scene_for_volume_file`]).
pub fn scene_for_volume_file(path: &Path, overrides: &[String]) -> Result<Scene, SceneError> {
    defaults::scene_for_volume_file(&CATALOGUE, path, overrides)
}

pub fn volume_file_scene_spec(path: &Path, overrides: &[String]) -> Result<SceneSpec, SceneError> {
    defaults::volume_file_scene_spec(&CATALOGUE, path, overrides)
}
