//! The [ao] keys declared once: doc, kind, range and value of each, from which
//! the viewer's panel and the range checks are built (`crate::scene::settings_controls`).

use super::render_settings::{AoMode, MAX_GLOW, MAX_PHASE_G};
use super::settings::{Metric, TrainingSet, MAX_BITS, MAX_CLUSTERS, MAX_RADIUS};
use super::AoSettings;
use crate::scene::settings_controls::{Current, DeclaredSettings, Key, Kind};

impl DeclaredSettings for AoSettings {
    fn keys() -> Vec<Key<Self>> {
        use Current::{Bool, Name, Number, Text};
        use Kind::{Choice, Real, Toggle, Whole};
        let control = Key::<Self>::new;
        let names = |all: &[&'static str]| all.to_vec();
        vec![
            control("radius", "sphere radius, voxels", Whole { lo: 1, hi: MAX_RADIUS }, |s| Number(s.radius as f64)),
            control("bits", "2^bits intensity bins per local histogram", Whole { lo: 1, hi: MAX_BITS }, |s| {
                Number(s.bits as f64)
            }),
            // At most 2^bits: the check refuses more.
            control("packed_dim", "packed histogram size, at most 2^bits", Whole { lo: 2, hi: 4096 }, |s| {
                Number(s.packed_dim as f64)
            }),
            control("clusters", "codebook size n_c (the paper: 256 to 2048)", Whole { lo: 2, hi: MAX_CLUSTERS }, |s| {
                Number(s.clusters as f64)
            }),
            control(
                "metric",
                "histogram distance of the clustering",
                Choice(names(&Metric::ALL.map(|m| m.name()))),
                |s| Name(s.metric.name()),
            ),
            control(
                "training",
                "the voxels the codebook is trained on: random, or gradient (eps = ...)",
                Kind::Text,
                |s| Text(training_toml(&s.training)),
            ),
            control("lbg_iterations", "most iterations of the LBG clustering", Whole { lo: 1, hi: 1000 }, |s| {
                Number(s.lbg_iterations as f64)
            }),
            control(
                "lbg_threshold",
                "relative distortion change that ends the clustering",
                Real { lo: 0.0, hi: 0.999_999 },
                |s| Number(s.lbg_threshold),
            ),
            control("cache", "preprocessing cached on disk, keyed by volume content and parameters", Toggle, |s| {
                Bool(s.cache)
            }),
            control("cache_dir", "where the cache lives (unset: $XDG_CACHE_HOME/sweeplab/ao)", Kind::Text, |s| {
                Text(s.cache_dir.as_ref().map_or(String::new(), |d| format!("{d:?}")))
            }),
            control(
                "mode",
                "what the occlusion shades (phase: Henyey-Greenstein, both hemispheres)",
                Choice(names(&AoMode::ALL.map(|m| m.name()))),
                |s| Name(s.mode.name()),
            ),
            control("isovalue", "isosurface: normalized intensity", Real { lo: 0.0, hi: 1.0 }, |s| {
                Number(s.isovalue as f64)
            }),
            control("phase_g", "phase: anisotropy", Real { lo: -MAX_PHASE_G as f64, hi: MAX_PHASE_G as f64 }, |s| {
                Number(s.phase_g as f64)
            }),
            control("glow_max", "glow: h_max", Real { lo: 1.0, hi: MAX_GLOW as f64 }, |s| Number(s.glow_max as f64)),
            control("glow_range", "glow: intensities that glow with h_max (h = 1 elsewhere)", Kind::Text, |s| {
                let [lo, hi] = s.glow_range;
                Text(format!("[{lo:?}, {hi:?}]"))
            }),
            // Unset: the GPU when there is a device, shown as empty.
            control("backend", "\"gpu\" or \"cpu\" (unset: the GPU when there is a Vulkan device)", Kind::Text, |s| {
                Text(s.backend.map_or(String::new(), |b| format!("{:?}", b.name())))
            }),
        ]
    }
}

/// `ao.training` as the file writes it.
fn training_toml(t: &TrainingSet) -> String {
    match *t {
        TrainingSet::Random { count, seed } => format!("{{ rule = \"random\", count = {count}, seed = {seed} }}"),
        TrainingSet::Gradient { eps, count, seed } => {
            format!("{{ rule = \"gradient\", eps = {eps}, count = {count}, seed = {seed} }}")
        }
    }
}
