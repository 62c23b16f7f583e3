//! Light volume parameters from the scene file's `[lightvolume]` table (or
//! `--set lightvolume.key=value`).

use crate::scene::settings_controls::check_declared_ranges;
use crate::scene::settings_table::{SettingsError, SettingsTable};
use serde::Deserialize;

/// Section 5's cost estimates deciding between a selective and an entire update.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CostEstimate {
    /// Selective when at most half of the lights changed.
    Share,
    /// Selective when it needs fewer propagation passes than an entire update;
    /// on a tie, the share decides.
    Passes,
    /// Always selective (benchmarks; a re-base still forces an entire update).
    Selective,
    /// Always entire, like a renderer without selective updates.
    Entire,
}

impl CostEstimate {
    pub fn name(self) -> &'static str {
        match self {
            CostEstimate::Share => "share",
            CostEstimate::Passes => "passes",
            CostEstimate::Selective => "selective",
            CostEstimate::Entire => "entire",
        }
    }
}

/// The file's key names are those of the fields; defaults below.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LightVolumeSettings {
    /// Data voxels per illumination voxel along each axis: 1, 2 or 4.
    pub scale: u32,
    /// Coherence-based propagation (the lights of a group share its passes) or
    /// sequential (one pass per light and face, the paper's baseline).
    pub coherent: bool,
    /// Compensated (two-float) summation into the illumination volume, so that
    /// subtracting a light cancels its addition to about 1e-14 of the largest
    /// value instead of 6e-8 (one more RGBA32F volume).
    pub compensated: bool,
    pub cost_estimate: CostEstimate,
    /// Incremental mode: at most this many propagation passes per frame (0: all).
    pub max_passes_per_frame: u32,
    /// Most lights one pass carries (a larger group is split): the slice buffers
    /// hold this many layers.
    pub pass_lights: u32,
    /// Re-base (entire update) once the bound on the rounding error that
    /// selective updates have accumulated exceeds this share of the weakest
    /// light's peak contribution.
    pub rebase_tolerance: f64,
    /// Length of the medium integration's sub-steps between slices, in
    /// illumination voxels (so a coarser volume takes as many sub-steps per
    /// slice as a fine one): longer is faster and misses thin opaque shells.
    pub substep: f32,
    /// The paper's propagation: the medium between slices sampled once per
    /// voxel along the axis and shared by every light of the pass (scaled by
    /// each light's path length), instead of along each light's direction.
    pub shared_medium: bool,
    /// Coloured propagation (the paper's l_i = (1 - alpha) l_{i-1} + alpha c):
    /// per-channel transmittance, the medium passing its own colour on;
    /// off: one transmittance for all channels, optical model (i).
    pub chromatic: bool,
    /// RACY: leaves out the barrier between the slices of a pass, so that
    /// synchronization validation can be shown to catch it (the volume is wrong).
    pub racy: bool,
}

impl Default for LightVolumeSettings {
    fn default() -> Self {
        // Half resolution: the paper's trade of memory and propagation time
        // against shadow sharpness.
        LightVolumeSettings {
            scale: 2,
            coherent: true,
            compensated: true,
            cost_estimate: CostEstimate::Passes,
            max_passes_per_frame: 0,
            // One pass per group for any scene (a scene holds at most 64
            // lights): the slice buffers grow only to the lights a group has.
            pass_lights: 64,
            rebase_tolerance: 1e-6,
            substep: 0.25,
            // The paper's propagation: the pass shares the medium's sampling.
            shared_medium: true,
            chromatic: true,
            racy: false,
        }
    }
}

impl LightVolumeSettings {
    /// The sub-step in data voxels, as the shader takes it.
    pub fn substep_data_voxels(&self) -> f32 {
        self.substep * self.scale as f32
    }
}

impl SettingsTable for LightVolumeSettings {
    const TABLE: &'static str = "lightvolume";

    /// Every key's range is its declaration's (controls.rs).
    fn validate(&self) -> Result<(), SettingsError> {
        check_declared_ranges(self)
    }
}
