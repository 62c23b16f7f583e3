//! AO preprocessing parameters from the scene file's `[ao]` table.
//!
//! ```toml
//! [ao]
//! radius = 8          # sphere radius r, in units of d_min (voxels)
//! bits = 8            # 2^b intensity bins per local histogram
//! packed_dim = 64     # dimension of the packed histograms the VQ trains on
//! clusters = 2048     # codebook size n_c
//! metric = "l2"       # "l2", "l1" or "lmax"
//! training = { rule = "random", count = 16384, seed = 1 }
//! # training = { rule = "gradient", eps = 0.05, count = 16384, seed = 1 }
//! backend = "gpu"     # "gpu" or "cpu"; default: gpu when a Vulkan device is given
//! ```
//!
//! `clusters` accepts 2..=2048: the paper works with 256..=2048; smaller
//! codebooks are allowed for tests and for the error-against-n_c curve (the
//! paper's figure 6 goes down to 256, our bench goes lower).

use serde::Deserialize;

use super::error::AoError;
use super::render_settings::{
    validate_glow_range, AoMode, DEFAULT_GLOW_MAX, DEFAULT_GLOW_RANGE, DEFAULT_ISOVALUE, DEFAULT_PHASE_G,
};
use crate::scene::settings_controls::check_declared_ranges;
use crate::scene::settings_table::{check_keys, read_table, SettingsError, SettingsTable};
use crate::scene::Scene;

/// Distance between histograms during vector quantization (paper figure 6).
#[derive(Deserialize, Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[serde(rename_all = "lowercase")]
pub enum Metric {
    L2,
    L1,
    Lmax,
}

impl Metric {
    pub const ALL: [Metric; 3] = [Metric::L2, Metric::L1, Metric::Lmax];

    pub fn name(self) -> &'static str {
        match self {
            Metric::L2 => "l2",
            Metric::L1 => "l1",
            Metric::Lmax => "lmax",
        }
    }
}

/// Where the per-voxel work (local histograms, packing, assignment) runs. The
/// CPU is the reference; the GPU sweep gives the same histograms to f32
/// rounding (docs/ao.md).
#[derive(Deserialize, Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[serde(rename_all = "lowercase")]
pub enum Backend {
    Gpu,
    Cpu,
}

impl Backend {
    pub fn name(self) -> &'static str {
        match self {
            Backend::Gpu => "gpu",
            Backend::Cpu => "cpu",
        }
    }
}

/// Which voxels make up the training set TS (section 3.2). Each voxel
/// contributes two vectors, its forward and its backward histogram.
#[derive(Deserialize, Clone, Copy, Debug, PartialEq)]
#[serde(tag = "rule", rename_all = "lowercase", deny_unknown_fields)]
pub enum TrainingSet {
    /// `count` voxels drawn uniformly without replacement (all voxels when the
    /// volume has fewer).
    Random {
        #[serde(default = "default_training_count")]
        count: u32,
        #[serde(default = "default_training_seed")]
        seed: u64,
    },
    /// The voxels with |grad f| > `eps` (normalized intensity per d_min), the
    /// paper's choice for colour bleeding on surfaces; a seeded uniform
    /// subsample of `count` of them when there are more.
    Gradient {
        eps: f32,
        #[serde(default = "default_training_count")]
        count: u32,
        #[serde(default = "default_training_seed")]
        seed: u64,
    },
}

fn default_training_count() -> u32 {
    16_384
}

fn default_training_seed() -> u64 {
    1
}

impl TrainingSet {
    pub fn count(&self) -> u32 {
        match *self {
            TrainingSet::Random { count, .. } | TrainingSet::Gradient { count, .. } => count,
        }
    }
}

#[derive(Deserialize, Clone, Debug, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct AoSettings {
    /// Sphere radius r in units of d_min (the smallest voxel spacing).
    pub radius: u32,
    /// Intensity bits b: local histograms have 2^b bins.
    pub bits: u32,
    /// Dimension of the packed histograms (section 3.2's histogram packing).
    pub packed_dim: u32,
    /// Codebook size n_c.
    pub clusters: u32,
    pub metric: Metric,
    pub training: TrainingSet,
    /// Most Lloyd iterations per codebook size during LBG.
    pub lbg_iterations: u32,
    /// Lloyd iterations stop once the relative distortion change is below this.
    pub lbg_threshold: f64,
    /// Load and store the result in the disk cache.
    pub cache: bool,
    /// Cache directory; default [`super::cache::default_cache_dir`].
    pub cache_dir: Option<String>,
    /// Rendering (not part of the cache key): the shading of technique `ao`
    /// and its parameters ([`super::render_settings`]).
    pub mode: AoMode,
    pub isovalue: f32,
    pub phase_g: f32,
    pub glow_max: f32,
    pub glow_range: [f32; 2],
    /// Where the per-voxel work runs; `None`: the GPU when the caller gives a
    /// Vulkan context, else the CPU ([`Self::backend_for`]).
    pub backend: Option<Backend>,
}

impl Default for AoSettings {
    fn default() -> Self {
        // The paper's real-world setting (2048 codewords, packed dimension 64)
        // at a radius that suits the 64^3 test scenes.
        AoSettings {
            radius: 8,
            bits: 8,
            packed_dim: 64,
            clusters: 2048,
            metric: Metric::L2,
            training: TrainingSet::Random { count: default_training_count(), seed: default_training_seed() },
            lbg_iterations: 20,
            lbg_threshold: 1e-3,
            cache: true,
            cache_dir: None,
            mode: AoMode::default(),
            isovalue: DEFAULT_ISOVALUE,
            phase_g: DEFAULT_PHASE_G,
            glow_max: DEFAULT_GLOW_MAX,
            glow_range: DEFAULT_GLOW_RANGE,
            backend: None,
        }
    }
}

const TRAINING_KEYS: [&str; 4] = ["rule", "count", "seed", "eps"];

pub const MAX_RADIUS: u32 = 64;
pub const MAX_BITS: u32 = 12;
pub const MAX_CLUSTERS: u32 = 2048;

impl AoSettings {
    /// The scene's `[ao]` settings (read and checked with the scene file;
    /// checked again here for settings changed in code).
    pub fn from_scene(scene: &Scene) -> Result<Self, AoError> {
        let settings = scene.settings.get::<AoSettings>().into_owned();
        settings.validate()?;
        Ok(settings)
    }

    /// Parses and validates an `[ao]` table as the scene file reads it; a
    /// misspelt key is an error that suggests the nearest known one.
    pub fn from_toml(value: &toml::Value) -> Result<Self, AoError> {
        read_table(value.clone()).map_err(|e| AoError::Invalid(e.to_string()))
    }

    /// Every value in its range; the error names `ao.key = value` and the
    /// range. The numeric keys' ranges are their declarations' (controls.rs);
    /// checked here: what one key's range depends on another's value, the
    /// training set's inline table, the cache folder and the glow range.
    pub fn validate(&self) -> Result<(), AoError> {
        fn out(key: &str, value: impl std::fmt::Display, allowed: &str) -> AoError {
            AoError::Invalid(format!("ao.{key} = {value}: allowed {allowed}"))
        }
        check_declared_ranges(self).map_err(|e| AoError::Invalid(e.to_string()))?;
        let bins = 1u32 << self.bits;
        if !(2..=bins).contains(&self.packed_dim) {
            return Err(out(
                "packed_dim",
                self.packed_dim,
                &format!("2..={bins} (at most 2^bits with bits = {})", self.bits),
            ));
        }
        let count = self.training.count();
        if count < 1 {
            return Err(out("training.count", count, "at least 1 voxel"));
        }
        if let TrainingSet::Gradient { eps, .. } = self.training {
            if !(eps.is_finite() && eps >= 0.0) {
                return Err(out("training.eps", eps, ">= 0 (normalized intensity per voxel)"));
            }
        }
        if self.cache_dir.as_deref() == Some("") {
            return Err(out("cache_dir", "\"\"", "a directory path (leave it out for the default)"));
        }
        validate_glow_range(self.glow_range)
    }

    /// The backend that runs with (`has_gpu`) or without a Vulkan context: the
    /// setting, else the GPU when there is one. `backend = "gpu"` without a
    /// context is an error, never a silent fall-back.
    pub fn backend_for(&self, has_gpu: bool) -> Result<Backend, AoError> {
        match (self.backend, has_gpu) {
            (Some(Backend::Gpu), false) => Err(AoError::Invalid(
                "ao.backend = \"gpu\" needs a Vulkan device, and none was given: \
                 use ao.backend = \"cpu\" or run with a device"
                    .into(),
            )),
            (Some(backend), _) => Ok(backend),
            (None, true) => Ok(Backend::Gpu),
            (None, false) => Ok(Backend::Cpu),
        }
    }

    /// Number of histogram bins, 2^bits.
    pub fn bins(&self) -> usize {
        1 << self.bits
    }
}

impl SettingsTable for AoSettings {
    const TABLE: &'static str = "ao";

    fn validate(&self) -> Result<(), SettingsError> {
        AoSettings::validate(self).map_err(|e| SettingsError::Technique(e.to_string()))
    }

    /// `training` is an inline table of its own keys.
    fn check_nested_keys(entries: &toml::Table) -> Result<(), SettingsError> {
        match entries.get("training").and_then(|t| t.as_table()) {
            Some(training) => check_keys("ao.training", training, &TRAINING_KEYS),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<AoSettings, AoError> {
        let value: toml::Value = toml::from_str(text).unwrap();
        AoSettings::from_toml(&value)
    }

    #[test]
    fn an_empty_table_gives_the_defaults_and_they_are_valid() {
        assert_eq!(parse("").unwrap(), AoSettings::default());
        AoSettings::default().validate().unwrap();
    }

    #[test]
    fn every_key_is_read() {
        let s = parse(
            "radius = 4\nbits = 6\npacked_dim = 16\nclusters = 64\nmetric = \"lmax\"\nlbg_iterations = 7\n\
             lbg_threshold = 0.01\ncache = false\ncache_dir = \"/tmp/x\"\n\
             training = { rule = \"gradient\", eps = 0.1, count = 100, seed = 9 }",
        )
        .unwrap();
        assert_eq!((s.radius, s.bits, s.packed_dim, s.clusters), (4, 6, 16, 64));
        assert_eq!(s.metric, Metric::Lmax);
        assert_eq!(s.training, TrainingSet::Gradient { eps: 0.1, count: 100, seed: 9 });
        assert_eq!((s.lbg_iterations, s.lbg_threshold, s.cache), (7, 0.01, false));
        assert_eq!(s.cache_dir.as_deref(), Some("/tmp/x"));
        let r = parse("training = { rule = \"random\", count = 5 }").unwrap();
        assert_eq!(r.training, TrainingSet::Random { count: 5, seed: 1 });
    }

    #[test]
    fn a_misspelt_key_suggests_the_right_one() {
        let e = parse("radus = 4").unwrap_err().to_string();
        assert!(e.contains("ao.radus") && e.contains("did you mean `radius`?"), "{e}");
        let e = parse("training = { rule = \"random\", cuont = 4 }").unwrap_err().to_string();
        assert!(e.contains("ao.training.cuont") && e.contains("did you mean `count`?"), "{e}");
    }

    #[test]
    fn out_of_range_values_name_key_value_and_range() {
        for (text, needle) in [
            ("radius = 0", "ao.radius = 0: must be a whole number in 1..=64"),
            ("bits = 13", "ao.bits = 13: must be a whole number in 1..=12"),
            ("bits = 4\npacked_dim = 32", "ao.packed_dim = 32: allowed 2..=16"),
            ("clusters = 4096", "ao.clusters = 4096: must be a whole number in 2..=2048"),
            ("lbg_iterations = 0", "ao.lbg_iterations = 0: must be a whole number in 1..=1000"),
            ("lbg_threshold = 1.5", "ao.lbg_threshold = 1.5: must be in 0..=0.999999"),
            ("isovalue = 1.5", "ao.isovalue = 1.5: must be in 0..=1"),
            ("isovalue = nan", "ao.isovalue = NaN: must be in 0..=1"),
            ("phase_g = 1.0", "ao.phase_g = 1: must be in -0.99..=0.99"),
            ("glow_max = 0.5", "ao.glow_max = 0.5: must be in 1..=64"),
            ("glow_range = [0.9, 0.1]", "ao.glow_range = [0.9, 0.1]: allowed"),
            ("training = { rule = \"gradient\", eps = -1.0 }", "ao.training.eps = -1"),
            ("training = { rule = \"random\", count = 0 }", "ao.training.count = 0"),
        ] {
            let e = parse(text).unwrap_err().to_string();
            assert!(e.contains(needle), "{text}: {e}");
        }
    }

    #[test]
    fn the_backend_defaults_to_the_gpu_when_there_is_one() {
        let s = parse("").unwrap();
        assert_eq!((s.backend_for(true).unwrap(), s.backend_for(false).unwrap()), (Backend::Gpu, Backend::Cpu));
        let s = parse("backend = \"cpu\"").unwrap();
        assert_eq!((s.backend_for(true).unwrap(), s.backend_for(false).unwrap()), (Backend::Cpu, Backend::Cpu));
        let s = parse("backend = \"gpu\"").unwrap();
        assert_eq!(s.backend_for(true).unwrap(), Backend::Gpu);
        let e = s.backend_for(false).unwrap_err().to_string();
        assert!(e.contains("ao.backend = \"gpu\"") && e.contains("\"cpu\""), "{e}");
        let e = parse("backend = \"vulkan\"").unwrap_err().to_string();
        assert!(e.contains("gpu") && e.contains("cpu"), "{e}");
        let e = parse("backnd = \"cpu\"").unwrap_err().to_string();
        assert!(e.contains("did you mean `backend`?"), "{e}");
    }

    #[test]
    fn unknown_metric_and_rule_are_errors() {
        let e = parse("metric = \"l3\"").unwrap_err().to_string();
        assert!(e.contains("l2") && e.contains("lmax"), "{e}");
        let e = parse("training = { rule = \"edges\" }").unwrap_err().to_string();
        assert!(e.contains("random") && e.contains("gradient"), "{e}");
        assert!(parse("training = { rule = \"gradient\" }").unwrap_err().to_string().contains("eps"));
    }
}
