//! The [half_angle] keys declared once: kind, range and value of each, from which
//! the viewer's panel is built (`crate::scene::settings_controls`).

use super::HalfAngleSettings;
use crate::scene::settings_controls::{Control, Current, DeclaredSettings, Kind};

impl DeclaredSettings for HalfAngleSettings {
    fn controls() -> Vec<Control> {
        use Current::Number;
        use Kind::{Real, Whole};
        let control = Control::of::<Self>;
        vec![
            // Unset: the scene's render.step, shown as such.
            control("slice_step", Real { lo: 0.01, hi: 16.0 }, |s| {
                Number(s.settings.get::<HalfAngleSettings>().slice_step_voxels(s) as f64)
            }),
            control("light_buffer_size", Whole { lo: 16, hi: 4096 }, |s| {
                Number(s.settings.get::<HalfAngleSettings>().light_buffer_size as f64)
            }),
        ]
    }
}
