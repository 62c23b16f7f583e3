//! The rendering keys of the `[ao]` table (sections 4.2-4.4): which shading
//! the technique `ao` renders, and the parameters each shading reads. They do
//! not change the preprocessing, so they are not part of its cache key.
//!
//! ```toml
//! [ao]
//! mode = "dvr"              # "isosurface", "dvr", "phase", "glow"
//! isovalue = 0.5            # isosurface: normalized intensity of the surface
//! phase_g = 0.5             # phase: Henyey-Greenstein anisotropy, -0.99..=0.99
//! glow_max = 4.0            # glow: h_max, 1..=64
//! glow_range = [0.9, 1.0]   # glow: intensities that glow with h_max (h = 1 elsewhere)
//! ```

use serde::Deserialize;

use super::error::AoError;

/// The shading of technique `ao`.
#[derive(Deserialize, Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[serde(rename_all = "lowercase")]
pub enum AoMode {
    /// First hit of `isovalue`, Blinn-Phong with the ambient term of
    /// equation 6: (1 - O_env) * Col_iso.
    Isosurface,
    /// Direct volume rendering with colour bleeding (section 4.3): hue between
    /// tau_rgb and E_env by O_env, luminance min(1 - O_env, Lambert) plus
    /// specular.
    #[default]
    Dvr,
    /// `dvr` plus the Henyey-Greenstein phase function applied to the
    /// environment of both hemispheres (section 4.1, the subsurface look of
    /// figure 7).
    Phase,
    /// `dvr` plus volumetric glow (section 4.4): E_env weighted by h(j), and
    /// otherwise transparent samples take the environment's glow as opacity.
    Glow,
}

impl AoMode {
    pub const ALL: [AoMode; 4] = [AoMode::Isosurface, AoMode::Dvr, AoMode::Phase, AoMode::Glow];

    pub fn name(self) -> &'static str {
        match self {
            AoMode::Isosurface => "isosurface",
            AoMode::Dvr => "dvr",
            AoMode::Phase => "phase",
            AoMode::Glow => "glow",
        }
    }

    /// The shader's `MODE` specialization constant (glsl/ao_render.comp).
    pub fn shader_value(self) -> u32 {
        self as u32
    }

    /// Whether the environment lookup carries the glow table.
    pub fn has_glow(self) -> bool {
        self == AoMode::Glow
    }
}

pub const DEFAULT_ISOVALUE: f32 = 0.5;
pub const DEFAULT_PHASE_G: f32 = 0.5;
pub const DEFAULT_GLOW_MAX: f32 = 4.0;
pub const DEFAULT_GLOW_RANGE: [f32; 2] = [0.9, 1.0];
pub const MAX_PHASE_G: f32 = 0.99;
pub const MAX_GLOW: f32 = 64.0;

/// The glow range's check (the other rendering keys' ranges are declared in
/// controls.rs and checked from there); the error names `ao.glow_range` and
/// what it must be.
pub fn validate_glow_range(glow_range: [f32; 2]) -> Result<(), AoError> {
    let [lo, hi] = glow_range;
    if !((0.0..=1.0).contains(&lo) && (0.0..=1.0).contains(&hi) && lo <= hi) {
        return Err(AoError::Invalid(format!(
            "ao.glow_range = [{lo}, {hi}]: allowed [low, high] with 0 <= low <= high <= 1"
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_mode_has_its_own_name_and_shader_value() {
        for (i, m) in AoMode::ALL.iter().enumerate() {
            assert_eq!(m.shader_value(), i as u32);
            assert_eq!(AoMode::ALL.iter().filter(|n| n.name() == m.name()).count(), 1);
        }
        assert_eq!(AoMode::default(), AoMode::Dvr);
    }

    #[test]
    fn a_glow_range_out_of_order_or_out_of_0_1_is_refused_by_name() {
        validate_glow_range(DEFAULT_GLOW_RANGE).unwrap();
        for range in [[0.9, 0.1], [-0.1, 0.5], [0.5, 1.5], [f32::NAN, 1.0]] {
            let e = validate_glow_range(range).unwrap_err().to_string();
            assert!(e.contains("ao.glow_range = [") && e.contains("allowed"), "{e}");
        }
    }
}

#[cfg(test)]
mod table_tests {
    use crate::techniques::ao::AoSettings;

    fn parse(text: &str) -> Result<AoSettings, crate::techniques::ao::AoError> {
        AoSettings::from_toml(&toml::from_str::<toml::Value>(text).unwrap())
    }

    #[test]
    fn the_render_keys_are_read_typed_and_checked() {
        let s =
            parse("mode = \"glow\"\nisovalue = 0.25\nphase_g = -0.3\nglow_max = 8.0\nglow_range = [0.5, 0.7]").unwrap();
        assert_eq!(
            (s.mode, s.isovalue, s.phase_g, s.glow_max, s.glow_range),
            (super::AoMode::Glow, 0.25, -0.3, 8.0, [0.5, 0.7])
        );
        let e = parse("mode = \"dvrr\"").unwrap_err().to_string();
        assert!(e.contains("isosurface") && e.contains("glow"), "{e}");
        let e = parse("mdoe = \"dvr\"").unwrap_err().to_string();
        assert!(e.contains("did you mean `mode`?"), "{e}");
        let e = parse("glow_max = 100.0").unwrap_err().to_string();
        assert!(e.contains("ao.glow_max = 100"), "{e}");
    }
}
