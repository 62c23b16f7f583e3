//! Light volume parameters from the scene file's `[lightvolume]` table (or
//! `--set lightvolume.key=value`).

use crate::render::RenderError;
use crate::scene::Scene;

/// Section 5's cost estimates deciding between a selective and an entire update.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
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

#[derive(Clone, Debug, PartialEq)]
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
            pass_lights: 16,
            rebase_tolerance: 1e-6,
            substep: 0.25,
            // The paper's propagation: the pass shares the medium's sampling.
            shared_medium: true,
            chromatic: true,
            racy: false,
        }
    }
}

const KNOWN: &str = "scale (1, 2 or 4), coherent, compensated (true or false), cost_estimate (\"share\", \
                     \"passes\", \"selective\" or \"entire\"), max_passes_per_frame (0 = all), pass_lights (1..=64), rebase_tolerance (> 0), substep (0.05..=4 illumination voxels), shared_medium, chromatic, racy (true or false)";

impl LightVolumeSettings {
    /// The sub-step in data voxels, as the shader takes it.
    pub fn substep_data_voxels(&self) -> f32 {
        self.substep * self.scale as f32
    }

    /// Reads `[lightvolume]`; a missing table gives the defaults, unknown keys
    /// and out-of-range values are errors.
    pub fn from_scene(scene: &Scene) -> Result<Self, RenderError> {
        let mut s = LightVolumeSettings::default();
        let Some(table) = scene.techniques.get("lightvolume") else { return Ok(s) };
        let table = table.as_table().ok_or_else(|| RenderError::Invalid("[lightvolume] must be a table".into()))?;
        for (key, v) in table {
            let float = v.as_float().or_else(|| v.as_integer().map(|i| i as f64));
            match (key.as_str(), v.as_integer(), v.as_bool(), v.as_str()) {
                ("scale", Some(x), _, _) if matches!(x, 1 | 2 | 4) => s.scale = x as u32,
                ("coherent", _, Some(b), _) => s.coherent = b,
                ("compensated", _, Some(b), _) => s.compensated = b,
                ("racy", _, Some(b), _) => s.racy = b,
                ("shared_medium", _, Some(b), _) => s.shared_medium = b,
                ("chromatic", _, Some(b), _) => s.chromatic = b,
                ("substep", _, _, _) if float.is_some_and(|f| (0.05..=4.0).contains(&f)) => {
                    s.substep = float.unwrap_or_default() as f32
                }
                ("cost_estimate", _, _, Some("share")) => s.cost_estimate = CostEstimate::Share,
                ("cost_estimate", _, _, Some("passes")) => s.cost_estimate = CostEstimate::Passes,
                ("cost_estimate", _, _, Some("selective")) => s.cost_estimate = CostEstimate::Selective,
                ("cost_estimate", _, _, Some("entire")) => s.cost_estimate = CostEstimate::Entire,
                ("max_passes_per_frame", Some(x), _, _) if (0..=1_000_000).contains(&x) => {
                    s.max_passes_per_frame = x as u32
                }
                ("pass_lights", Some(x), _, _) if (1..=64).contains(&x) => s.pass_lights = x as u32,
                ("rebase_tolerance", _, _, _) if float.is_some_and(|f| f.is_finite() && f > 0.0) => {
                    s.rebase_tolerance = float.unwrap_or_default()
                }
                _ => return Err(RenderError::Invalid(format!("lightvolume.{key} = {v}: the known keys are {KNOWN}"))),
            }
        }
        Ok(s)
    }
}
