//! The [lightvolume] keys declared once: doc, kind, range and value of each, from which
//! the viewer's panel and the range checks are built (`crate::scene::settings_controls`).

use super::{CostEstimate, LightVolumeSettings};
use crate::scene::settings_controls::{Current, DeclaredSettings, Key, Kind};

impl DeclaredSettings for LightVolumeSettings {
    fn keys() -> Vec<Key<Self>> {
        use Current::{Bool, Name, Number};
        use Kind::{Choice, Numbers, Real, Toggle, Whole};
        let control = Key::<Self>::new;
        let names = |all: &[&'static str]| all.to_vec();
        vec![
            control("scale", "data voxels per illumination voxel", Numbers(&[1, 2, 4]), |s| Number(s.scale as f64)),
            control(
                "coherent",
                "lights propagated in coherence-based groups (the paper's); false: one pass per light",
                Toggle,
                |s| Bool(s.coherent),
            ),
            control("compensated", "compensated summation of the lights' contributions", Toggle, |s| {
                Bool(s.compensated)
            }),
            control(
                "cost_estimate",
                "how a changed light's selective update is chosen over an entire one",
                Choice(names(
                    &[CostEstimate::Share, CostEstimate::Passes, CostEstimate::Selective, CostEstimate::Entire]
                        .map(|c| c.name()),
                )),
                |s| Name(s.cost_estimate.name()),
            ),
            // 0: every pass in one frame.
            control(
                "max_passes_per_frame",
                "propagation passes a frame may run (0: all)",
                Whole { lo: 0, hi: 1_000_000 },
                |s| Number(s.max_passes_per_frame as f64),
            ),
            control("pass_lights", "lights one group pass carries", Whole { lo: 1, hi: 64 }, |s| {
                Number(s.pass_lights as f64)
            }),
            control(
                "rebase_tolerance",
                "drift of the summed volume that triggers an entire update",
                Real { lo: f64::MIN_POSITIVE, hi: f64::INFINITY },
                |s| Number(s.rebase_tolerance),
            ),
            control("substep", "illumination voxels per propagation substep", Real { lo: 0.05, hi: 4.0 }, |s| {
                Number(s.substep as f64)
            }),
            control(
                "shared_medium",
                "the medium sampled once per pass (the paper's); false: along each light",
                Toggle,
                |s| Bool(s.shared_medium),
            ),
            control(
                "chromatic",
                "the medium's colour attenuates per channel (the paper's); false: model (i)",
                Toggle,
                |s| Bool(s.chromatic),
            ),
            control("racy", "the barriers between slices left out (a hazard on purpose, for the study)", Toggle, |s| {
                Bool(s.racy)
            }),
        ]
    }
}
