//! The scene as the viewer edits it: where it came from, the `--set` edits so
//! far (reparsed with the same checks and suggestions as the command line),
//! and the camera the mouse moved. The volume is loaded once and kept.

use super::error::ViewerError;
use crate::scene::scene_spec::SceneSpec;
use crate::scene::{Camera, Light, Scene};
use crate::techniques;
use std::path::PathBuf;

#[derive(Clone, Debug)]
pub enum SceneSource {
    /// The embedded default scene.
    Default,
    /// A TOML scene file.
    File(PathBuf),
    /// A volume file with the default transfer function, camera and light.
    Volume(PathBuf),
}

/// What an edit changed: only the lights (a session that follows lights goes
/// on), or anything else (the scene is uploaded again).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Change {
    Lights,
    Scene,
}

pub struct LiveScene {
    source: SceneSource,
    edits: Vec<String>,
    camera: Option<Camera>,
    lights: Option<Vec<Light>>,
    pub scene: Scene,
}

impl LiveScene {
    pub fn load(source: SceneSource, overrides: &[String]) -> Result<LiveScene, ViewerError> {
        let scene = spec(&source, overrides)?.build()?;
        Ok(LiveScene { source, edits: overrides.to_vec(), camera: None, lights: None, scene })
    }

    /// Applies `KEY=VALUE` as `--set` would.
    pub fn set(&mut self, edit: &str) -> Result<Change, ViewerError> {
        let mut edits = self.edits.clone();
        edits.push(edit.to_string());
        let spec = spec(&self.source, &edits)?;
        let mut scene = spec.build_with_volume(self.scene.volume.clone());
        if let Some(c) = self.camera {
            scene.camera = c;
        }
        if let Some(l) = &self.lights {
            if !edit.trim_start().starts_with("lights") {
                scene.lights = l.clone();
            }
        }
        self.edits = edits;
        self.scene = scene;
        if edit.trim_start().starts_with("lights") {
            // The edit started from the file's lights: the panel's edits are gone.
            self.lights = None;
        }
        let key = edit.split('=').next().unwrap_or("").trim();
        Ok(if key == "lights" || key.starts_with("lights.") { Change::Lights } else { Change::Scene })
    }

    /// The panel edited the lights (kept over later `set` edits of other keys).
    pub fn set_lights(&mut self, lights: Vec<Light>) {
        self.scene.lights = lights.clone();
        self.lights = Some(lights);
    }

    /// The mouse moved the camera.
    pub fn set_camera(&mut self, camera: Camera) {
        self.camera = Some(camera);
        self.scene.camera = camera;
    }
}

fn spec(source: &SceneSource, overrides: &[String]) -> Result<SceneSpec, ViewerError> {
    Ok(match source {
        SceneSource::Default => techniques::default_scene_spec(overrides)?,
        SceneSource::File(path) => techniques::parse_scene_file(path, overrides)?,
        SceneSource::Volume(path) => techniques::volume_file_scene_spec(path, overrides)?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn live() -> LiveScene {
        let small = ["volume.size=8".to_string()];
        LiveScene::load(SceneSource::Default, &small).unwrap()
    }

    #[test]
    fn light_edits_are_told_apart_from_scene_edits_and_typos_get_suggestions() {
        let mut l = live();
        assert_eq!(l.set("lights.0.intensity=2").unwrap(), Change::Lights);
        assert_eq!(l.scene.lights[0].intensity, 2.0);
        assert_eq!(l.set("camera.azimuth=75").unwrap(), Change::Scene);
        assert_eq!(l.scene.lights[0].intensity, 2.0, "earlier edits stay");
        let e = l.set("camera.azimth=3").unwrap_err().to_string();
        assert!(e.contains("azimuth"), "{e}");
        assert_eq!(l.scene.lights[0].intensity, 2.0, "a failed edit changes nothing");
    }

    #[test]
    fn panel_lights_and_mouse_camera_survive_other_edits_until_a_lights_edit() {
        let mut l = live();
        let mut lights = l.scene.lights.clone();
        lights[0].intensity = 7.0;
        lights.push(lights[0]);
        l.set_lights(lights);
        let mut camera = l.scene.camera;
        camera.eye.x += 1.0;
        l.set_camera(camera);
        l.set("render.emission=0.5").unwrap();
        assert_eq!((l.scene.lights.len(), l.scene.lights[0].intensity), (2, 7.0));
        assert_eq!(l.scene.camera, camera);
        l.set("lights.0.intensity=3").unwrap();
        assert_eq!((l.scene.lights.len(), l.scene.lights[0].intensity), (1, 3.0));
    }
}
