//! The scenes that need no scene file: the embedded default scene (no arguments)
//! and the scene around a volume file (`--volume FILE`). Both are TOML documents
//! that go through the scene-file parser, so `--set` overrides work the same way.

use std::path::Path;

use toml::{Table, Value};

use super::scene_file::{parse_scene_str, parse_scene_table, SceneError};
use super::scene_spec::SceneSpec;
use super::technique_settings::TableCatalogue;
use super::Scene;

/// Origin named in errors about the default scene.
pub const DEFAULT_SCENE_ORIGIN: &str = "<default scene>";

/// The default scene: the known-shadow scene of the main job (a sphere over a
/// slab, lit from above, tests/scenes/slab-under-sphere.toml), so that the
/// first render shows a shadow.
pub const DEFAULT_SCENE_TOML: &str = include_str!("../../tests/scenes/slab-under-sphere.toml");

/// Reads [`DEFAULT_SCENE_TOML`] with `overrides` applied, without building it.
pub fn default_scene_spec(catalogue: &dyn TableCatalogue, overrides: &[String]) -> Result<SceneSpec, SceneError> {
    parse_scene_str(catalogue, DEFAULT_SCENE_TOML, Path::new(""), DEFAULT_SCENE_ORIGIN, overrides)
}

pub fn default_scene(catalogue: &dyn TableCatalogue, overrides: &[String]) -> Result<Scene, SceneError> {
    default_scene_spec(catalogue, overrides)?.build()
}

/// The scene around a volume file, without its `[volume]` table. No transfer
/// function is given, so it comes from the volume's histogram; no camera
/// distance, so the camera frames the volume's box.
/// The light comes from the upper right of the default camera (azimuth 30,
/// elevation 20), square to its view, so that the shadows it casts show
/// (light from the camera's side hides them behind what casts them).
const VOLUME_FILE_SCENE_TOML: &str = r#"
[[lights]]
type = "directional"
direction = [-0.6, -0.52, 0.56]
"#;

/// Reads the scene for `--volume FILE` (`path` as given, relative to the current
/// folder) with `overrides` applied, without loading the volume.
pub fn volume_file_scene_spec(
    catalogue: &dyn TableCatalogue,
    path: &Path,
    overrides: &[String],
) -> Result<SceneSpec, SceneError> {
    let origin = format!("--volume {}", path.display());
    let file = path.to_str().ok_or_else(|| SceneError::Invalid {
        origin: origin.clone(),
        key: "volume.file".into(),
        problem: "is not valid UTF-8".into(),
    })?;
    let mut doc: Table = VOLUME_FILE_SCENE_TOML
        .parse()
        .map_err(|e: toml::de::Error| SceneError::Syntax { origin: origin.clone(), message: e.to_string() })?;
    let mut volume = Table::new();
    volume.insert("file".into(), Value::String(file.to_string()));
    doc.insert("volume".into(), Value::Table(volume));
    parse_scene_table(catalogue, doc, Path::new(""), &origin, overrides)
}

/// The scene for `--volume FILE`: the file's volume, a transfer function from
/// its histogram, a camera framing what it shows, one directional light from
/// the upper right.
pub fn scene_for_volume_file(
    catalogue: &dyn TableCatalogue,
    path: &Path,
    overrides: &[String],
) -> Result<Scene, SceneError> {
    volume_file_scene_spec(catalogue, path, overrides)?.build()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::scene_spec::{TransferSpec, VolumeSource};
    use crate::scene::synthetic::SyntheticKind;
    use crate::scene::technique_settings::NoTechniqueTables;
    use crate::scene::LightKind;

    #[test]
    fn default_scene_is_the_known_shadow_scene() {
        let scene = default_scene(&NoTechniqueTables, &[]).expect("the embedded default scene is valid");
        assert_eq!(scene.volume.name, "slab-under-sphere");
        assert_eq!(scene.volume.dims, glam::UVec3::splat(64));
        assert_eq!(scene.lights.len(), 1);
        assert!(matches!(scene.lights[0].kind, LightKind::Directional { .. }));
        assert_eq!(Some(scene.transfer), crate::scene::presets::preset("slab-sphere"));
    }

    #[test]
    fn default_scene_takes_overrides() {
        let spec =
            default_scene_spec(&NoTechniqueTables, &["volume.size=16".into(), "render.width=64".into()]).unwrap();
        assert_eq!(spec.volume, VolumeSource::Synthetic { kind: SyntheticKind::SlabUnderSphere, size: 16, seed: 1 });
        assert_eq!(spec.render.width, 64);
        let e = default_scene_spec(&NoTechniqueTables, &["volume.size=0".into()]).unwrap_err().to_string();
        assert!(e.contains(DEFAULT_SCENE_ORIGIN) && e.contains("volume.size"), "{e}");
    }

    #[test]
    fn volume_file_scene_uses_the_path_as_given_and_an_automatic_transfer() {
        let spec = volume_file_scene_spec(&NoTechniqueTables, Path::new("some/dir/ct.nrrd"), &[]).unwrap();
        assert_eq!(spec.volume, VolumeSource::File("some/dir/ct.nrrd".into()));
        assert_eq!(spec.transfer, TransferSpec::FromHistogram);
        assert_eq!(spec.lights.len(), 1);
        let spec =
            volume_file_scene_spec(&NoTechniqueTables, Path::new("ct.nrrd"), &["transfer.preset=ct-bone".into()])
                .unwrap();
        assert!(matches!(spec.transfer, TransferSpec::Given(_)));
    }
}
