//! The [half_angle] keys declared once: doc, kind, range and value of each, from which
//! the viewer's panel and the range checks are built (`crate::scene::settings_controls`).

use super::settings::SLICE_STEP_RANGE;
use super::HalfAngleSettings;
use crate::scene::settings_controls::{Current, DeclaredSettings, Key, Kind};
use crate::scene::Scene;

impl DeclaredSettings for HalfAngleSettings {
    fn keys() -> Vec<Key<Self>> {
        use Current::{Number, Unset};
        use Kind::{Real, Whole};
        let control = Key::<Self>::new;
        vec![
            control(
                "slice_step",
                "voxels between slices (unset: render.step)",
                Real { lo: SLICE_STEP_RANGE.0 as f64, hi: SLICE_STEP_RANGE.1 as f64 },
                |s| s.slice_step.map_or(Unset, |step| Number(step as f64)),
            ),
            control("light_buffer_size", "light buffer texels per side", Whole { lo: 16, hi: 4096 }, |s| {
                Number(s.light_buffer_size as f64)
            }),
        ]
    }

    /// Unset, the slices are the scene's `render.step` apart: shown as such.
    fn shown_unset(key: &str, scene: &Scene) -> Current {
        match key {
            "slice_step" => Current::Number(scene.render.step_voxels as f64),
            _ => Current::Unset,
        }
    }
}
