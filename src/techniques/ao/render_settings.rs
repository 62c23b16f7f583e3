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

/// Range checks of the rendering keys; the error names `ao.key = value` and
/// the allowed range.
pub fn validate_render_keys(isovalue: f32, phase_g: f32, glow_max: f32, glow_range: [f32; 2]) -> Result<(), AoError> {
    let out =
        |key: &str, value: String, allowed: &str| AoError::Invalid(format!("ao.{key} = {value}: allowed {allowed}"));
    if !(0.0..=1.0).contains(&isovalue) {
        return Err(out("isovalue", isovalue.to_string(), "0..=1 (normalized intensity)"));
    }
    if !(-MAX_PHASE_G..=MAX_PHASE_G).contains(&phase_g) {
        return Err(out("phase_g", phase_g.to_string(), &format!("-{MAX_PHASE_G}..={MAX_PHASE_G}")));
    }
    if !(1.0..=MAX_GLOW).contains(&glow_max) {
        return Err(out("glow_max", glow_max.to_string(), &format!("1..={MAX_GLOW} (h_max)")));
    }
    let [lo, hi] = glow_range;
    if !((0.0..=1.0).contains(&lo) && (0.0..=1.0).contains(&hi) && lo <= hi) {
        return Err(out("glow_range", format!("[{lo}, {hi}]"), "[low, high] with 0 <= low <= high <= 1"));
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
    fn out_of_range_render_keys_name_key_and_range() {
        let ok = (DEFAULT_ISOVALUE, DEFAULT_PHASE_G, DEFAULT_GLOW_MAX, DEFAULT_GLOW_RANGE);
        validate_render_keys(ok.0, ok.1, ok.2, ok.3).unwrap();
        for (args, needle) in [
            ((1.5, 0.5, 4.0, [0.9, 1.0]), "ao.isovalue = 1.5"),
            ((0.5, 1.0, 4.0, [0.9, 1.0]), "ao.phase_g = 1"),
            ((0.5, 0.5, 0.5, [0.9, 1.0]), "ao.glow_max = 0.5"),
            ((0.5, 0.5, 4.0, [0.9, 0.1]), "ao.glow_range = [0.9, 0.1]"),
            ((f32::NAN, 0.5, 4.0, [0.9, 1.0]), "ao.isovalue = NaN"),
        ] {
            let e = validate_render_keys(args.0, args.1, args.2, args.3).unwrap_err().to_string();
            assert!(e.contains(needle) && e.contains("allowed"), "{e}");
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
