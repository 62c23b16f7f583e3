//! Light volume parameters from the scene file's `[lightvolume]` table (or
//! `--set lightvolume.key=value`).

use crate::render::RenderError;
use crate::scene::Scene;

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LightVolumeSettings {
    /// Data voxels per illumination voxel along each axis: 1, 2 or 4.
    pub scale: u32,
    /// Coherence-based propagation (the lights of a group share its passes) or
    /// sequential (one pass per light and face, the paper's baseline).
    pub coherent: bool,
}

impl Default for LightVolumeSettings {
    fn default() -> Self {
        // Half resolution: the paper's trade of memory and propagation time
        // against shadow sharpness.
        LightVolumeSettings { scale: 2, coherent: true }
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
            match (key.as_str(), v.as_integer(), v.as_bool()) {
                ("scale", Some(x), _) if matches!(x, 1 | 2 | 4) => s.scale = x as u32,
                ("coherent", _, Some(b)) => s.coherent = b,
                _ => {
                    return Err(RenderError::Invalid(format!(
                        "lightvolume.{key} = {v}: the known keys are scale (1, 2 or 4) and coherent (true or false)"
                    )))
                }
            }
        }
        Ok(s)
    }
}
