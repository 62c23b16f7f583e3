//! How piecewise integration (section 4.4) reads the depths of the four cache
//! texels a sample's light is filtered from (`ipsvi.read_fronts`).

use super::cache_update::parse_name;
use std::str::FromStr;

/// Where the march from a sample back to the cache starts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReadFronts {
    /// `PerTexel` where the cache texel at the lit box's centre is narrower
    /// than [`PER_TEXEL_BELOW_PX`] pixels, else `Blended`.
    Auto,
    /// The paper's: the four values blended and carried over one march from
    /// the blended depth (one bilinear lookup of the `res` image).
    Blended,
    /// The four texels grouped by the cache plane their fronts lie on (within
    /// a voxel, or a light step if longer), each value carried to the sample
    /// from its group's blended depth, then blended: one march as long as the
    /// longest stretch, each step counted for each texel as far as its
    /// stretch reaches. All four on one plane: `Blended`, step for step.
    PerTexel,
}

/// Texels narrower than this (pixels, at the lit box's centre) take per-texel
/// fronts under `Auto`. Below a pixel some texel columns hold no pixel's view
/// ray, so a line's samples reach only some of the texels around the next
/// line's samples: a read blends texels written at this line with texels
/// written many lines back, and the blended depth fits none of them. Where
/// every fourth or fifth column of texels is such a one, the blended fronts
/// draw stripes along the sweep (tests/scenes/slab-under-sphere.toml at
/// 256x256, 0.79 px: 30.85 dB blended against 35.71 dB per texel, before the
/// preset's film was widened; docs/ipsvi.md, "Default images"). Measured
/// below half a pixel too (docs/ipsvi.md, "Piecewise fronts"): on a 48x48 slab
/// and sphere, a point light inside the volume, every-sample RMSE 1.91e-2
/// blended against 1.21e-2 per texel at 0.16 px, and 1.70e-2 against 1.68e-2
/// at 0.84 px. Above a pixel every texel column holds a ray and blended fronts
/// are as near for less time: on engine.vti at 512x512 (2.30 px) 4.03e-3
/// against 3.87e-3 for 1.30x (1.16-1.53) the frame's time.
pub const PER_TEXEL_BELOW_PX: f32 = 1.0;

impl ReadFronts {
    pub const ALL: [ReadFronts; 3] = [ReadFronts::Auto, ReadFronts::Blended, ReadFronts::PerTexel];

    pub fn name(self) -> &'static str {
        match self {
            ReadFronts::Auto => "auto",
            ReadFronts::Blended => "blended",
            ReadFronts::PerTexel => "per-texel",
        }
    }

    /// Whether reads take per-texel fronts, given the cache texel's width in
    /// pixels at the lit box's centre (None: no light), asked only for `Auto`.
    pub fn per_texel(self, texel_px: impl FnOnce() -> Option<f32>) -> bool {
        match self {
            ReadFronts::Auto => texel_px().is_some_and(|px| px < PER_TEXEL_BELOW_PX),
            ReadFronts::Blended => false,
            ReadFronts::PerTexel => true,
        }
    }
}

impl FromStr for ReadFronts {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        parse_name(s, &ReadFronts::ALL, ReadFronts::name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn auto_takes_per_texel_fronts_only_on_texels_finer_than_the_threshold() {
        for f in ReadFronts::ALL {
            assert_eq!(f.name().parse::<ReadFronts>().unwrap(), f);
        }
        assert!("per_texel".parse::<ReadFronts>().unwrap_err().contains("`per-texel`"));
        assert!(ReadFronts::Auto.per_texel(|| Some(0.16)));
        assert!(!ReadFronts::Auto.per_texel(|| Some(PER_TEXEL_BELOW_PX)));
        assert!(ReadFronts::Auto.per_texel(|| Some(0.79)));
        assert!(!ReadFronts::Auto.per_texel(|| Some(1.15)));
        assert!(!ReadFronts::Auto.per_texel(|| None));
        let unasked = || -> Option<f32> { panic!("only auto needs the texel's width") };
        assert!(ReadFronts::PerTexel.per_texel(unasked) && !ReadFronts::Blended.per_texel(unasked));
    }
}
