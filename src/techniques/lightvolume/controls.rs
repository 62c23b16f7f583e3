//! The [lightvolume] keys declared once: kind, range and value of each, from which
//! the viewer's panel is built (`crate::scene::settings_controls`).

use super::{CostEstimate, LightVolumeSettings};
use crate::scene::settings_controls::{Control, Current, DeclaredSettings, Kind};

impl DeclaredSettings for LightVolumeSettings {
    fn controls() -> Vec<Control> {
        use Current::{Bool, Name, Number};
        use Kind::{Choice, Numbers, Real, Toggle, Whole};
        let control = Control::of::<Self>;
        let names = |all: &[&'static str]| all.to_vec();
        vec![
            control("scale", Numbers(&[1, 2, 4]), |s| Number(s.settings.get::<LightVolumeSettings>().scale as f64)),
            control("coherent", Toggle, |s| Bool(s.settings.get::<LightVolumeSettings>().coherent)),
            control("compensated", Toggle, |s| Bool(s.settings.get::<LightVolumeSettings>().compensated)),
            control(
                "cost_estimate",
                Choice(names(
                    &[CostEstimate::Share, CostEstimate::Passes, CostEstimate::Selective, CostEstimate::Entire]
                        .map(|c| c.name()),
                )),
                |s| Name(s.settings.get::<LightVolumeSettings>().cost_estimate.name()),
            ),
            control("max_passes_per_frame", Whole { lo: 0, hi: 1_000_000 }, |s| {
                Number(s.settings.get::<LightVolumeSettings>().max_passes_per_frame as f64)
            }),
            control("pass_lights", Whole { lo: 1, hi: 64 }, |s| {
                Number(s.settings.get::<LightVolumeSettings>().pass_lights as f64)
            }),
            control("rebase_tolerance", Real { lo: f64::MIN_POSITIVE, hi: f64::INFINITY }, |s| {
                Number(s.settings.get::<LightVolumeSettings>().rebase_tolerance)
            }),
            control("substep", Real { lo: 0.05, hi: 4.0 }, |s| {
                Number(s.settings.get::<LightVolumeSettings>().substep as f64)
            }),
            control("shared_medium", Toggle, |s| Bool(s.settings.get::<LightVolumeSettings>().shared_medium)),
            control("chromatic", Toggle, |s| Bool(s.settings.get::<LightVolumeSettings>().chromatic)),
            control("racy", Toggle, |s| Bool(s.settings.get::<LightVolumeSettings>().racy)),
        ]
    }
}
