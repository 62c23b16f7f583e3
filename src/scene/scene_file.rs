//! Scene files: a TOML document, edited by `--set` overrides, checked, and built
//! into a [`Scene`].
//!
//! Every key has a default except the volume, so `[volume]\nsynthetic = "noise"`
//! is a complete scene. Misspelt keys are errors (`deny_unknown_fields`); besides
//! the scene sections below, the techniques' tables (`[ipsvi]`, `[lightvolume]`,
//! `[half_angle]`, `[ao]`) are read by the [`TableCatalogue`] the reader is
//! given (the techniques' catalogue, `crate::techniques`) into
//! [`Scene::settings`]; any other table is an error naming it.
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
//! [ipsvi]      # and [lightvolume], [half_angle]: each technique's settings
//! line_width = 1             # keys and ranges: the technique's settings type
//! ```

use std::path::{Path, PathBuf};

use toml::{Table, Value};

use super::loaders::LoadError;
use super::overrides::{apply_overrides, OverrideError};
use super::scene_schema::{check_scene, SceneTables, DEFAULT_LIGHT_DIRECTION};
use super::scene_spec::SceneSpec;
use super::settings_table::SettingsError;
use super::suggest::nearest;
use super::technique_settings::TableCatalogue;
use super::{Scene, TechniqueSettings};

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
    /// A technique table with an unknown key or a value out of range.
    /// (Not a `source`: the message already says all of it.)
    #[error("{origin}: {error}")]
    Settings { origin: String, error: SettingsError },
    /// The volume file is there but cannot be loaded: its path once.
    /// (Not a `source`: the message already says all of it.)
    #[error("{origin}: {}", volume_failure(.origin, .path, .error))]
    Volume { origin: String, path: PathBuf, error: Box<LoadError> },
    /// The volume file is not there: its path once, and a likely meant one.
    #[error("{origin}: {}{hint}", missing_volume(.origin, .path))]
    MissingVolume { origin: String, path: PathBuf, hint: String },
}

/// Why the volume at `path` did not load, naming the file once: "cannot load:
/// PROBLEM" where the origin names it already (`--volume FILE`), else "cannot
/// load volume FILE: PROBLEM" (a detached data file is named by the problem).
fn volume_failure(origin: &str, path: &Path, error: &LoadError) -> String {
    let problem = if error.file() == path { error.detail() } else { error.to_string() };
    if origin.ends_with(&path.display().to_string()) {
        format!("cannot load: {problem}")
    } else {
        format!("cannot load volume {}: {problem}", path.display())
    }
}

/// "no such file" where the origin already names the path (`--volume FILE`),
/// else "no volume file FILE".
fn missing_volume(origin: &str, path: &Path) -> String {
    if origin.ends_with(&path.display().to_string()) {
        "no such file".to_string()
    } else {
        format!("no volume file {}", path.display())
    }
}

/// Reads, checks and builds (loading the volume) the scene file at `path`;
/// `catalogue` reads the technique tables.
pub fn load_scene(catalogue: &dyn TableCatalogue, path: &Path, overrides: &[String]) -> Result<Scene, SceneError> {
    parse_scene_file(catalogue, path, overrides)?.build()
}

/// Reads and checks the scene file at `path` without loading its volume.
pub fn parse_scene_file(
    catalogue: &dyn TableCatalogue,
    path: &Path,
    overrides: &[String],
) -> Result<SceneSpec, SceneError> {
    let text = std::fs::read_to_string(path).map_err(|source| SceneError::Read { path: path.to_path_buf(), source })?;
    let base_dir = path.parent().unwrap_or(Path::new(""));
    parse_scene_str(catalogue, &text, base_dir, &path.display().to_string(), overrides)
}

/// Checks and builds a scene given as TOML text; relative volume paths are taken
/// from `base_dir`; `origin` names the text in errors.
pub fn scene_from_toml_str(
    catalogue: &dyn TableCatalogue,
    text: &str,
    base_dir: &Path,
    origin: &str,
    overrides: &[String],
) -> Result<Scene, SceneError> {
    parse_scene_str(catalogue, text, base_dir, origin, overrides)?.build()
}

pub fn parse_scene_str(
    catalogue: &dyn TableCatalogue,
    text: &str,
    base_dir: &Path,
    origin: &str,
    overrides: &[String],
) -> Result<SceneSpec, SceneError> {
    let doc: Table = text.parse().map_err(|e: toml::de::Error| SceneError::Syntax {
        origin: origin.to_string(),
        message: e.to_string().trim_end().to_string(),
    })?;
    parse_scene_table(catalogue, doc, base_dir, origin, overrides)
}

/// The scene sections.
const SECTIONS: [&str; 7] = ["volume", "transfer", "camera", "lights", "render", "reference", "phong"];

/// Applies `overrides` to `doc` and checks it. A missing `lights` array gets the
/// default light first, so `--set lights.0.intensity=2` applies to it. The
/// techniques' tables go to [`SceneSpec::settings`].
pub fn parse_scene_table(
    catalogue: &dyn TableCatalogue,
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
    let mut settings = TechniqueSettings::default();
    let mut technique_tables = Vec::new();
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
                let Some(read) = catalogue.read(&key, value) else {
                    return Err(invalid(&key, unknown_table(catalogue, &key)));
                };
                let table = read.map_err(|error| SceneError::Settings { origin: origin.to_string(), error })?;
                technique_tables.push(table.table());
                settings.insert(table);
                continue;
            }
        };
        *slot = Some(value);
    }
    check_scene(origin, base_dir, tables, settings, technique_tables)
}

/// "is not a known table", with the nearest known one and the list.
fn unknown_table(catalogue: &dyn TableCatalogue, name: &str) -> String {
    let known = SECTIONS.iter().chain(catalogue.tables()).copied();
    let near = nearest(name, known.clone()).map(|n| format!("; did you mean [{n}]?")).unwrap_or_default();
    let list: Vec<String> = known.map(|k| format!("[{k}]")).collect();
    format!("is not a known table{near} (known: {})", list.join(" "))
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scene_errors_can_cross_threads() {
        // The binary wraps them in anyhow, which needs Send + Sync + 'static.
        fn assert_send_sync<T: Send + Sync + 'static>() {}
        assert_send_sync::<SceneError>();
    }
}
