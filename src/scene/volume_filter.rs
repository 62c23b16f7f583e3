//! How the GPU filters the volume between texels (`render.filter`,
//! docs/filtering.md). The CPU renderers always filter exactly in f64.

use super::suggest::nearest;
use std::str::FromStr;

/// Environment variable that overrides every scene's `render.filter` (a whole
/// test suite in one mode: `SWEEPLAB_FILTER=gpu-8bit tools/test.sh`).
pub const FILTER_ENV: &str = "SWEEPLAB_FILTER";

#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum VolumeFilter {
    /// The sampler's trilinear filter: exact on lavapipe for r32f volumes.
    #[default]
    Exact,
    /// Trilinear with sub-texel weights rounded to 1/256, as NVIDIA, AMD and
    /// Intel hardware filters every format: lavapipe shows what those give.
    Gpu8Bit,
}

impl VolumeFilter {
    pub const ALL: [VolumeFilter; 2] = [VolumeFilter::Exact, VolumeFilter::Gpu8Bit];

    pub fn name(self) -> &'static str {
        match self {
            VolumeFilter::Exact => "exact",
            VolumeFilter::Gpu8Bit => "gpu-8bit",
        }
    }

    /// The value of volume_fetch.glsl's VOLUME_FILTER constant.
    pub fn shader_constant(self) -> u32 {
        match self {
            VolumeFilter::Exact => 0,
            VolumeFilter::Gpu8Bit => 1,
        }
    }

    /// The largest error of one sub-texel weight: half of 1/256 with rounding
    /// (the emulation); exact filtering has none.
    pub fn weight_error(self) -> f64 {
        match self {
            VolumeFilter::Exact => 0.0,
            VolumeFilter::Gpu8Bit => 1.0 / 512.0,
        }
    }

    /// `SWEEPLAB_FILTER` if set (an error naming the variable for a typo).
    pub fn from_env() -> Result<Option<VolumeFilter>, String> {
        match std::env::var(FILTER_ENV) {
            Ok(v) if !v.trim().is_empty() => v.trim().parse().map(Some).map_err(|e| format!("{FILTER_ENV}: {e}")),
            _ => Ok(None),
        }
    }
}

impl FromStr for VolumeFilter {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        if let Some(f) = VolumeFilter::ALL.into_iter().find(|f| f.name() == s) {
            return Ok(f);
        }
        let names = VolumeFilter::ALL.map(VolumeFilter::name);
        let hint = nearest(s, names).map(|n| format!(" (did you mean `{n}`?)")).unwrap_or_default();
        Err(format!("unknown filter `{s}`, expected `exact` or `gpu-8bit`{hint}"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_typos_get_a_suggestion() {
        for f in VolumeFilter::ALL {
            assert_eq!(f.name().parse::<VolumeFilter>().unwrap(), f);
        }
        let e = "gpu-8-bit".parse::<VolumeFilter>().unwrap_err();
        assert!(e.contains("did you mean `gpu-8bit`"), "{e}");
        let e = "exakt".parse::<VolumeFilter>().unwrap_err();
        assert!(e.contains("did you mean `exact`"), "{e}");
    }
}
