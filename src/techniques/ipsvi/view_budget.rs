//! How long a view ray IPSVI can march. A pixel is shaded inside its line's
//! dispatch, view samples and their piecewise light integration in one
//! invocation, so the march cannot be split across dispatches as DVR's is:
//! llvmpipe ends an invocation after 65,535 loop iterations. The piecewise
//! integration gets what the view samples leave of [`LOOP_BUDGET`]; a step so
//! small that fewer than [`MIN_PIECEWISE_STEPS`] remain per sample is refused.

use crate::render::view_chunks::diagonal_voxels;
use crate::render::view_chunks::LOOP_BUDGET;
use crate::render::RenderError;
use crate::scene::Scene;

/// Fewest piecewise light steps per view sample IPSVI accepts.
pub const MIN_PIECEWISE_STEPS: u64 = 4;

/// Loop iterations of one view sample besides its piecewise steps: the sample
/// itself and the one more iteration llvmpipe counts for the inner loop.
const OVERHEAD_PER_SAMPLE: u64 = 2;

/// llvmpipe's 65,535 less room for the set-up loops before the march.
const HARD_LIMIT: u64 = 65_000;

/// Most view samples a ray can take at `step_voxels`.
pub fn max_view_samples(scene: &Scene, step_voxels: f64) -> u64 {
    (diagonal_voxels(scene) / step_voxels).ceil() as u64 + 1
}

/// The smallest `render.step` (voxels) IPSVI supports on `scene`.
pub fn smallest_step(scene: &Scene) -> f64 {
    let samples = HARD_LIMIT / (MIN_PIECEWISE_STEPS + OVERHEAD_PER_SAMPLE);
    diagonal_voxels(scene) / (samples - 1) as f64
}

/// Piecewise light steps each view sample may take at the scene's
/// `render.step`, or the step refused by name.
pub fn piecewise_steps(scene: &Scene) -> Result<u32, RenderError> {
    let step = scene.render.step_voxels as f64;
    let smallest = smallest_step(scene);
    let samples = if step.is_finite() && step > 0.0 { max_view_samples(scene, step) } else { u64::MAX };
    // The budget IPSVI has always given (LOOP_BUDGET / samples - 1: ordinary
    // steps render as before), capped where the total would pass llvmpipe's.
    let steps =
        (LOOP_BUDGET / samples).saturating_sub(1).min((HARD_LIMIT / samples).saturating_sub(OVERHEAD_PER_SAMPLE));
    if steps < MIN_PIECEWISE_STEPS {
        return Err(RenderError::Invalid(format!(
            "render.step = {:e} voxels is too small for ipsvi on this scene: its view rays and their piecewise \
             light integration run in one invocation, within llvmpipe's loop limit; the smallest step it supports \
             here is {smallest:.3e} voxels",
            scene.render.step_voxels
        )));
    }
    Ok(steps as u32)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::scene_file::scene_from_toml_str;
    use crate::scene::technique_settings::NoTechniqueTables;

    fn scene(step: f32) -> Scene {
        let text = format!("[volume]\nsynthetic = \"noise\"\nsize = 16\n[render]\nstep = {step}\n");
        scene_from_toml_str(&NoTechniqueTables, &text, std::path::Path::new(""), "test", &[]).unwrap()
    }

    #[test]
    fn the_smallest_step_is_accepted_and_below_it_refused() {
        let smallest = smallest_step(&scene(0.5)) as f32;
        let at = piecewise_steps(&scene(smallest * 1.01)).unwrap();
        assert!(at as u64 >= MIN_PIECEWISE_STEPS);
        let e = piecewise_steps(&scene(smallest * 0.5)).unwrap_err().to_string();
        assert!(e.contains("render.step") && e.contains("ipsvi") && e.contains(&format!("{:.3e}", smallest)), "{e}");
    }

    #[test]
    fn the_view_samples_and_their_light_steps_stay_within_the_budget() {
        for step in [0.05f32, 0.1, 0.5, 1.0, 4.0] {
            let s = scene(step);
            let m = piecewise_steps(&s).unwrap() as u64;
            assert!(max_view_samples(&s, step as f64) * (m + OVERHEAD_PER_SAMPLE) <= HARD_LIMIT, "step {step}");
        }
    }
}
