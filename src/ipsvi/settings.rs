//! IPSVI parameters from the scene file's `[ipsvi]` table (or `--set ipsvi.key=value`).

use super::sync_strategy::SyncStrategy;
use crate::render::RenderError;
use crate::scene::Scene;

#[derive(Clone, Debug, PartialEq)]
pub struct IpsviSettings {
    /// Lines per dispatch, 1..=32; the first block of a sweep is always one line.
    pub line_width: u32,
    /// The cache is cache_size x cache_size texels.
    pub cache_size: u32,
    /// Piecewise integration from each sample toward the cache front (section 4.4).
    pub piecewise: bool,
    /// When view rays stop (section 5.1).
    pub early_termination: EarlyTermination,
    /// Share of light scattered in the forward cone (equation 2's albedo), 0..=1.
    pub albedo: f32,
    /// Half-angle of the forward scattering cone, degrees.
    pub cone_angle_deg: f32,
    /// Width in pixels over which the four zones of a point light are blended.
    pub zone_blend_px: f32,
    /// Step along light rays (cache updates and piecewise integration), voxels.
    pub light_step_voxels: f32,
    /// Full-resolution pixels per pre-pass pixel, per axis (exit-points only).
    pub ert_scale: u32,
    /// How consecutive line blocks are synchronized (`racy` only for cost studies).
    pub sync: SyncStrategy,
    /// Study baseline, not an illumination result: every sweep is one dispatch
    /// over all its lines (the same shader and pixels with no sweep to sync).
    pub single_dispatch_baseline: bool,
}

/// When the view rays of the main pass stop.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EarlyTermination {
    /// March every ray to its exit.
    Off,
    /// Stop once the transmittance is below 1e-4. Exact here: view rays never
    /// feed the cache (docs/ipsvi.md), so nothing behind the stop is needed.
    Plain,
    /// The paper's section 5.1: a low-resolution pre-pass (first-opaque and
    /// last-structure distances) and an exit-point sweep toward the light give
    /// l_max; a ray stops once it is opaque *and* past l_max.
    ExitPoints,
}

impl EarlyTermination {
    pub fn name(self) -> &'static str {
        match self {
            EarlyTermination::Off => "off",
            EarlyTermination::Plain => "plain",
            EarlyTermination::ExitPoints => "exit-points",
        }
    }
}

impl Default for IpsviSettings {
    fn default() -> Self {
        IpsviSettings {
            line_width: 1,
            cache_size: 256,
            piecewise: true,
            early_termination: EarlyTermination::Plain,
            albedo: 0.0,
            cone_angle_deg: 15.0,
            zone_blend_px: 2.0,
            light_step_voxels: 0.5,
            ert_scale: 4,
            sync: SyncStrategy::BarrierGlobal,
            single_dispatch_baseline: false,
        }
    }
}

const KEYS: [&str; 10] = [
    "line_width",
    "cache_size",
    "piecewise",
    "early_termination",
    "albedo",
    "cone_angle",
    "zone_blend",
    "light_step",
    "ert_scale",
    "sync",
];

impl IpsviSettings {
    /// The ranges `from_scene` enforces, for settings built in code (benchmarks).
    pub fn check(&self) -> Result<(), RenderError> {
        whole(self.line_width as f64, 1, 32, "line_width")?;
        whole(self.cache_size as f64, 16, 4096, "cache_size")?;
        within(self.albedo as f64, 0.0, 1.0, "albedo")?;
        within(self.light_step_voxels as f64, 0.01, 16.0, "light_step")?;
        whole(self.ert_scale as f64, 1, 16, "ert_scale")?;
        Ok(())
    }

    pub fn from_scene(scene: &Scene) -> Result<IpsviSettings, RenderError> {
        let mut s = IpsviSettings::default();
        let Some(value) = scene.techniques.get("ipsvi") else {
            return Ok(s);
        };
        let table = value.as_table().ok_or_else(|| bad("[ipsvi] must be a table"))?;
        for (key, v) in table {
            let number = || {
                v.as_float()
                    .or_else(|| v.as_integer().map(|i| i as f64))
                    .ok_or_else(|| bad(&format!("ipsvi.{key} must be a number")))
            };
            let boolean = || v.as_bool().ok_or_else(|| bad(&format!("ipsvi.{key} must be true or false")));
            match key.as_str() {
                "line_width" => s.line_width = whole(number()?, 1, 32, key)?,
                "cache_size" => s.cache_size = whole(number()?, 16, 4096, key)?,
                "piecewise" => s.piecewise = boolean()?,
                "early_termination" => {
                    s.early_termination = match (v.as_bool(), v.as_str()) {
                        (Some(true), _) | (_, Some("plain")) => EarlyTermination::Plain,
                        (Some(false), _) | (_, Some("off")) => EarlyTermination::Off,
                        (_, Some("exit-points")) => EarlyTermination::ExitPoints,
                        _ => return Err(bad("ipsvi.early_termination must be \"off\", \"plain\" or \"exit-points\"")),
                    }
                }
                "ert_scale" => s.ert_scale = whole(number()?, 1, 16, key)?,
                "sync" => {
                    let name = v.as_str().ok_or_else(|| bad("ipsvi.sync must be a strategy name"))?;
                    s.sync = name.parse().map_err(|e: String| bad(&format!("ipsvi.sync: {e}")))?;
                }
                "albedo" => s.albedo = within(number()?, 0.0, 1.0, key)?,
                "cone_angle" => s.cone_angle_deg = within(number()?, 0.0, 80.0, key)?,
                "zone_blend" => s.zone_blend_px = within(number()?, 0.0, 64.0, key)?,
                "light_step" => s.light_step_voxels = within(number()?, 0.01, 16.0, key)?,
                other => return Err(bad(&format!("unknown key ipsvi.{other}; known: {}", KEYS.join(", ")))),
            }
        }
        Ok(s)
    }
}

fn bad(message: &str) -> RenderError {
    RenderError::Invalid(message.to_string())
}

fn whole(v: f64, lo: u32, hi: u32, key: &str) -> Result<u32, RenderError> {
    if v.fract() != 0.0 || v < lo as f64 || v > hi as f64 {
        return Err(bad(&format!("ipsvi.{key} = {v}: must be a whole number in {lo}..={hi}")));
    }
    Ok(v as u32)
}

fn within(v: f64, lo: f32, hi: f32, key: &str) -> Result<f32, RenderError> {
    if !v.is_finite() || v < lo as f64 || v > hi as f64 {
        return Err(bad(&format!("ipsvi.{key} = {v}: must be in {lo}..={hi}")));
    }
    Ok(v as f32)
}
