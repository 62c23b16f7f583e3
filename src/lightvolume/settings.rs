//! Light volume parameters from the scene file's `[lightvolume]` table (or
//! `--set lightvolume.key=value`).

use crate::render::RenderError;
use crate::scene::Scene;

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LightVolumeSettings {
    /// Data voxels per illumination voxel along each axis: 1, 2 or 4.
    pub scale: u32,
}

impl Default for LightVolumeSettings {
    fn default() -> Self {
        // Half resolution: the paper's trade of memory and propagation time
        // against shadow sharpness.
        LightVolumeSettings { scale: 2 }
    }
}

impl LightVolumeSettings {
    /// Reads `[lightvolume]`; a missing table gives the defaults, unknown keys
    /// and out-of-range values are errors.
    pub fn from_scene(scene: &Scene) -> Result<Self, RenderError> {
        let mut s = LightVolumeSettings::default();
        let Some(table) = scene.techniques.get("lightvolume") else { return Ok(s) };
        let table = table.as_table().ok_or_else(|| RenderError::Invalid("[lightvolume] must be a table".into()))?;
        for (key, v) in table {
            match (key.as_str(), v.as_integer()) {
                ("scale", Some(x)) if matches!(x, 1 | 2 | 4) => s.scale = x as u32,
                _ => {
                    return Err(RenderError::Invalid(format!(
                        "lightvolume.{key} = {v}: the known key is scale (1, 2 or 4)"
                    )))
                }
            }
        }
        Ok(s)
    }
}
