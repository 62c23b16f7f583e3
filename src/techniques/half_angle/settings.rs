//! Half-angle slicing parameters from the scene file's `[half_angle]` table (or
//! `--set half_angle.key=value`).

use crate::scene::settings_controls::check_declared_ranges;
use crate::scene::settings_table::{SettingsError, SettingsTable};
use crate::scene::Scene;
use serde::Deserialize;

#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct HalfAngleSettings {
    /// Distance between slices, in voxels; `None`: the scene's `render.step`.
    pub slice_step: Option<f32>,
    /// The light buffer is N x N.
    pub light_buffer_size: u32,
}

impl Default for HalfAngleSettings {
    fn default() -> Self {
        HalfAngleSettings { slice_step: None, light_buffer_size: 256 }
    }
}

impl HalfAngleSettings {
    /// Distance between slices in voxels.
    pub fn slice_step_voxels(&self, scene: &Scene) -> f32 {
        self.slice_step.unwrap_or(scene.render.step_voxels)
    }
}

/// Slice distances (voxels) half-angle slicing accepts, from either setting.
pub const SLICE_STEP_RANGE: (f32, f32) = (0.01, 16.0);

impl SettingsTable for HalfAngleSettings {
    const TABLE: &'static str = "half_angle";

    fn validate(&self) -> Result<(), SettingsError> {
        check_declared_ranges(self)
    }
}
