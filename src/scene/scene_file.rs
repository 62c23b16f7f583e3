//! Scene files: a TOML document, edited by `--set` overrides, checked, and built
//! into a [`Scene`].
//!
//! Every key has a default except the volume, so `[volume]\nsynthetic = "noise"`
//! is a complete scene. Misspelt keys are errors (`deny_unknown_fields`); tables
//! other than the scene sections below are technique parameters, passed through
//! verbatim into [`Scene::techniques`].
//!
//! ```toml
//! [volume]     # exactly one of:
//! file = "ct.nrrd"         # relative to the scene file's folder
//! data_file = "engine.vti" # relative to the data folder ($SWEEPLAB_DATA)
//! synthetic = "shepp-logan" # three-spheres | cornell-box | slab-under-sphere | single-voxel | noise
//! size = 64                 # synthetic only, 1..=512
//! seed = 1                  # noise only
//!
//! [transfer]   # at most one of (default: the synthetic volume's own preset, else auto):
//! preset = "ct-bone"        # see presets::PRESET_NAMES
//! auto = true               # from the volume's histogram
//! points = [[0.0, 0, 0, 0, 0], [1.0, 1, 1, 1, 0.5]]  # [value, r, g, b, alpha per voxel], sorted
//!
//! [camera]
//! projection = "perspective" # or "orthographic"
//! fov_y = 30.0               # perspective only, degrees, (0, 180)
//! ortho_height = 1.2         # orthographic only; default: frames the volume
//! azimuth = 30.0             # orbit: degrees about +y from +z
//! elevation = 20.0           # orbit: degrees up from the xz plane, [-90, 90]
//! distance = 2.5             # orbit: default frames the volume
//! target = [0.0, 0.0, 0.0]
//! # look-at instead of orbit: eye = [x, y, z], up = [0, 1, 0] (not with azimuth/elevation/distance)
//!
//! [[lights]]   # default: one directional light from upper-left-front; `lights = []` for none
//! type = "directional"       # point | spot
//! direction = [1.0, -1.0, -1.0] # directional and spot: where the light travels
//! position = [-1.0, 1.0, 1.0]   # point and spot
//! color = [1.0, 1.0, 1.0]
//! intensity = 1.0
//! inner_cone = 20.0          # spot: half-angles in degrees, 0 <= inner < outer <= 180
//! outer_cone = 30.0
//! falloff = "none"           # point and spot: or "inverse-square"
//!
//! [render]
//! width = 512                # 1..=16384
//! height = 512
//! step = 0.5                 # voxels
//! background = [0.0, 0.0, 0.0]
//! emission = 0.1
//!
//! [reference]
//! model = "single-scattering" # or "emissive-scattering"
//! step = 0.25
//! shadow_step = 0.5
//! min_transmittance = 1e-4   # [0, 1)
//! chromatic = false          # coloured extinction along shadow rays
//!
//! [phong]
//! ambient = 0.2
//! diffuse = 0.8
//! specular = 0.3
//! shininess = 32.0
//!
//! [ipsvi]      # any other table: technique parameters, free-form
//! ```

use std::path::{Path, PathBuf};

use toml::{Table, Value};

use super::loaders::LoadError;
use super::overrides::{apply_overrides, OverrideError};
use super::scene_schema::{check_scene, SceneTables, DEFAULT_LIGHT_DIRECTION};
use super::scene_spec::SceneSpec;
use super::Scene;

/// Why a scene could not be read or built. Every variant names where the scene
/// came from (`origin`: the scene file's path, `<default scene>`, `--volume FILE`).
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    #[error("cannot read scene file {path}: {source}")]
    Read { path: PathBuf, source: std::io::Error },
    #[error("{origin}: not valid TOML: {message}")]
    Syntax { origin: String, message: String },
    #[error("{origin}: {source}")]
    Override { origin: String, source: OverrideError },
    /// A key of the wrong type, an unknown key or enum name.
    #[error("{origin}: `{key}`: {message}")]
    Schema { origin: String, key: String, message: String },
    /// A value of the right type but out of range, or contradicting another key.
    #[error("{origin}: `{key}` {problem}")]
    Invalid { origin: String, key: String, problem: String },
    #[error("{origin}: cannot load volume {path}: {source}")]
    Volume { origin: String, path: PathBuf, source: Box<LoadError> },
}

/// Reads, checks and builds (loading the volume) the scene file at `path`.
pub fn load_scene(path: &Path, overrides: &[String]) -> Result<Scene, SceneError> {
    parse_scene_file(path, overrides)?.build()
}

/// Reads and checks the scene file at `path` without loading its volume.
pub fn parse_scene_file(path: &Path, overrides: &[String]) -> Result<SceneSpec, SceneError> {
    let text = std::fs::read_to_string(path).map_err(|source| SceneError::Read { path: path.to_path_buf(), source })?;
    let base_dir = path.parent().unwrap_or(Path::new(""));
    parse_scene_str(&text, base_dir, &path.display().to_string(), overrides)
}

/// Checks and builds a scene given as TOML text; relative volume paths are taken
/// from `base_dir`; `origin` names the text in errors.
pub fn scene_from_toml_str(
    text: &str,
    base_dir: &Path,
    origin: &str,
    overrides: &[String],
) -> Result<Scene, SceneError> {
    parse_scene_str(text, base_dir, origin, overrides)?.build()
}

pub fn parse_scene_str(
    text: &str,
    base_dir: &Path,
    origin: &str,
    overrides: &[String],
) -> Result<SceneSpec, SceneError> {
    let doc: Table = text.parse().map_err(|e: toml::de::Error| SceneError::Syntax {
        origin: origin.to_string(),
        message: e.to_string().trim_end().to_string(),
    })?;
    parse_scene_table(doc, base_dir, origin, overrides)
}

/// The scene sections, for telling a misspelt one from a technique table.
const SECTIONS: [&str; 7] = ["volume", "transfer", "camera", "lights", "render", "reference", "phong"];

/// Applies `overrides` to `doc` and checks it. A missing `lights` array gets the
/// default light first, so `--set lights.0.intensity=2` applies to it. Tables
/// other than the scene sections go to [`SceneSpec::techniques`].
pub fn parse_scene_table(
    mut doc: Table,
    base_dir: &Path,
    origin: &str,
    overrides: &[String],
) -> Result<SceneSpec, SceneError> {
    if !doc.contains_key("lights") {
        doc.insert("lights".into(), Value::Array(vec![Value::Table(default_light_table())]));
    }
    apply_overrides(&mut doc, overrides)
        .map_err(|source| SceneError::Override { origin: origin.to_string(), source })?;

    let invalid =
        |key: &str, problem: String| SceneError::Invalid { origin: origin.to_string(), key: key.to_string(), problem };
    let mut tables = SceneTables::default();
    let mut techniques = Table::new();
    for (key, value) in doc {
        let slot = match key.as_str() {
            "volume" => &mut tables.volume,
            "transfer" => &mut tables.transfer,
            "camera" => &mut tables.camera,
            "lights" => &mut tables.lights,
            "render" => &mut tables.render,
            "reference" => &mut tables.reference,
            "phong" => &mut tables.phong,
            _ if !value.is_table() => {
                return Err(invalid(&key, "is not a scene setting (settings belong in tables such as [render])".into()))
            }
            _ => {
                if let Some(near) = SECTIONS.iter().find(|s| edit_distance(s, &key) <= 2) {
                    return Err(invalid(&key, format!("is not a known table; did you mean [{near}]?")));
                }
                techniques.insert(key, value);
                continue;
            }
        };
        *slot = Some(value);
    }
    check_scene(origin, base_dir, tables, techniques)
}

/// `{ type = "directional", direction = DEFAULT_LIGHT_DIRECTION }`
fn default_light_table() -> Table {
    let mut t = Table::new();
    t.insert("type".into(), Value::String("directional".into()));
    t.insert(
        "direction".into(),
        Value::Array(DEFAULT_LIGHT_DIRECTION.iter().map(|&x| Value::Float(x as f64)).collect()),
    );
    t
}

/// Levenshtein distance, to tell a misspelt section from a technique table.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let substitution = diagonal + usize::from(ca != cb);
            diagonal = row[j + 1];
            row[j + 1] = substitution.min(row[j] + 1).min(row[j + 1] + 1);
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scene_errors_can_cross_threads() {
        // The binary wraps them in anyhow, which needs Send + Sync + 'static.
        fn assert_send_sync<T: Send + Sync + 'static>() {}
        assert_send_sync::<SceneError>();
    }

    #[test]
    fn edit_distance_counts_single_character_edits() {
        assert_eq!(edit_distance("camera", "camera"), 0);
        assert_eq!(edit_distance("camera", "camra"), 1);
        assert_eq!(edit_distance("lights", "light"), 1);
        assert_eq!(edit_distance("render", "rendre"), 2);
        assert_eq!(edit_distance("ipsvi", "phong"), 5);
        assert_eq!(edit_distance("", "ao"), 2);
    }
}
