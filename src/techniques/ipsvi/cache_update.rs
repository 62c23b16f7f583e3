//! How the illumination cache is fed (`ipsvi.cache_update`) and, when view
//! samples feed it, how the many samples of a line that write one texel are
//! resolved (`ipsvi.cache_write`), what a write stores (`ipsvi.write_value`)
//! which samples take part in writes (`ipsvi.write_rule`) and which
//! invocation computes and stores a write (`ipsvi.write_pass`).
//! docs/ipsvi.md compares the modes.

use crate::scene::suggest::nearest;
use std::str::FromStr;

/// Who writes the light leaving line i into the cache that line i+1 reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CacheUpdate {
    /// The paper's mechanism (section 4.3, Listing 4.1): each view sample
    /// composites itself over the light it received and writes the outgoing
    /// light into its cache texel. The line barrier protects a dependency from
    /// view ray to view ray; plain early ray termination loses features (figure 5).
    ViewSamples,
    /// Every cache texel advances its own light ray to the block's sweep plane:
    /// race-free and independent of the view rays (the comparison mode).
    LightRays,
}

/// Which of the view samples of one line block that end in the same texel is stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CacheWrite {
    /// The paper's plain store: whichever sample stores last wins (a race by design).
    Racy,
    /// Deterministic: the sample farthest along the light ray wins, ties by
    /// pixel. A claim march (medium only) one dispatch ahead finds the winner
    /// with a 64-bit atomicMax; the shading pass stores only the winner.
    Farthest,
    /// Deterministic like `Farthest`, but the sample closest to the light wins:
    /// with piecewise integration a later sample farther along marches back to
    /// it exactly, where a farther write would over-attenuate a nearer reader.
    Nearest,
}

/// What a view sample's write stores (view samples with piecewise integration).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WriteValue {
    /// The paper's: the light the sample received, read bilinearly from the
    /// four texels around its position and carried to it.
    Sample,
    /// The light on the written texel's own ray at the sample's depth, carried
    /// there along that ray from the texel's state: no lateral filtering, so
    /// the light is not blurred again by every line that writes the texel
    /// (engine.vti 512x512: RMSE 7.3e-3 against 1.44e-2; docs/ipsvi.md).
    TexelRay,
}

/// Which view samples take part in the runs that end in a cache write.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WriteRule {
    /// Only samples with non-zero opacity read the cache and form runs; a
    /// texel an empty stretch of a view ray crosses keeps its older state.
    NonEmpty,
    /// The paper's (Listing 4.1): every sample, empty ones included, takes part
    /// in runs, and every run end stores. An empty run passes the light on
    /// unchanged but moves the texel's depth to the current line, so the next
    /// line's piecewise march is about one line long.
    EverySample,
}

/// Which invocation computes and stores a view-sample write (texel-ray writes
/// with piecewise integration, where the stored value is a function of the
/// texel's state and its writer's line plane alone).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WritePass {
    /// `Texel` where the writes allow it (texel-ray writes, piecewise
    /// integration, claimed resolution, every run marching), else `Sample`.
    Auto,
    /// The paper's: the run's writing sample, in its own pixel's invocation,
    /// at the end of the run inside the view march.
    Sample,
    /// The view samples' runs name the texels (the claim march of the block,
    /// one dispatch ahead, as for `cache_write = "farthest"`); one invocation
    /// per texel of the block's region then marches and stores each named
    /// texel. Same texels, same values, same image; the sample loop keeps
    /// no store code, and the marches of neighbouring lanes are neighbouring
    /// texels' rays.
    Texel,
}

impl WritePass {
    pub const ALL: [WritePass; 3] = [WritePass::Auto, WritePass::Sample, WritePass::Texel];
    /// The two passes a frame can run (`Auto` resolves to one of them).
    pub const RUN: [WritePass; 2] = [WritePass::Sample, WritePass::Texel];
    pub fn name(self) -> &'static str {
        match self {
            WritePass::Auto => "auto",
            WritePass::Sample => "sample",
            WritePass::Texel => "texel",
        }
    }
}

impl FromStr for WritePass {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        parse_name(s, &WritePass::ALL, WritePass::name)
    }
}

impl WriteRule {
    pub const ALL: [WriteRule; 2] = [WriteRule::NonEmpty, WriteRule::EverySample];
    pub fn name(self) -> &'static str {
        match self {
            WriteRule::NonEmpty => "non-empty",
            WriteRule::EverySample => "every-sample",
        }
    }
}

impl FromStr for WriteRule {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        parse_name(s, &WriteRule::ALL, WriteRule::name)
    }
}

impl WriteValue {
    pub const ALL: [WriteValue; 2] = [WriteValue::TexelRay, WriteValue::Sample];
    pub fn name(self) -> &'static str {
        match self {
            WriteValue::Sample => "sample",
            WriteValue::TexelRay => "texel-ray",
        }
    }
}

impl FromStr for WriteValue {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        parse_name(s, &WriteValue::ALL, WriteValue::name)
    }
}

impl CacheUpdate {
    pub const ALL: [CacheUpdate; 2] = [CacheUpdate::ViewSamples, CacheUpdate::LightRays];
    pub fn name(self) -> &'static str {
        match self {
            CacheUpdate::ViewSamples => "view-samples",
            CacheUpdate::LightRays => "light-rays",
        }
    }
}

impl CacheWrite {
    pub const ALL: [CacheWrite; 3] = [CacheWrite::Racy, CacheWrite::Farthest, CacheWrite::Nearest];
    pub fn name(self) -> &'static str {
        match self {
            CacheWrite::Racy => "racy",
            CacheWrite::Farthest => "farthest",
            CacheWrite::Nearest => "nearest",
        }
    }

    /// Whether a claim march picks one writer per texel (deterministic).
    pub fn claims(self) -> bool {
        self != CacheWrite::Racy
    }
}

/// `s` as one of `all` by name; else an error with the nearest name.
pub(super) fn parse_name<T: Copy>(s: &str, all: &[T], name: impl Fn(T) -> &'static str) -> Result<T, String> {
    all.iter().copied().find(|t| name(*t) == s).ok_or_else(|| {
        let names: Vec<&str> = all.iter().map(|t| name(*t)).collect();
        let near = nearest(s, names.iter().copied()).map(|n| format!(" (did you mean `{n}`?)")).unwrap_or_default();
        format!("is {s:?}{near}, not one of {}", names.join(", "))
    })
}

impl FromStr for CacheUpdate {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        parse_name(s, &CacheUpdate::ALL, CacheUpdate::name)
    }
}

impl FromStr for CacheWrite {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        parse_name(s, &CacheWrite::ALL, CacheWrite::name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_typos_get_a_suggestion() {
        for m in CacheUpdate::ALL {
            assert_eq!(m.name().parse::<CacheUpdate>().unwrap(), m);
        }
        for w in CacheWrite::ALL {
            assert_eq!(w.name().parse::<CacheWrite>().unwrap(), w);
        }
        for w in WriteValue::ALL {
            assert_eq!(w.name().parse::<WriteValue>().unwrap(), w);
        }
        for w in WriteRule::ALL {
            assert_eq!(w.name().parse::<WriteRule>().unwrap(), w);
        }
        for w in WritePass::ALL {
            assert_eq!(w.name().parse::<WritePass>().unwrap(), w);
        }
        assert!("texels".parse::<WritePass>().unwrap_err().contains("`texel`"));
        assert!("every-samples".parse::<WriteRule>().unwrap_err().contains("`every-sample`"));
        assert!("texel_ray".parse::<WriteValue>().unwrap_err().contains("`texel-ray`"));
        let e = "view-sample".parse::<CacheUpdate>().unwrap_err();
        assert!(e.contains("did you mean `view-samples`"), "{e}");
        assert!("farthes".parse::<CacheWrite>().unwrap_err().contains("`farthest`"));
    }
}
