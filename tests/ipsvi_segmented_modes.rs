//! The segmented line kernel in the modes a user can select beyond those
//! `ipsvi_segmented.rs` runs on every light placement, and on the other test
//! volumes: the same claims and stops as the serial kernel, the same image
//! up to the order of compositing, no farther from the ground truth
//! (`matches_serial_in`). What it cannot run is refused by name
//! (`ipsvi_segmented::what_cannot_be_segmented_is_refused_by_name...` and
//! `line_kernel`'s unit tests); the sync strategies are `sync_strategies.rs`'.
use crate::common;
use crate::ipsvi_segmented::{light_placements, matches_serial_in, settings, slab_scene, SIZE};
use crate::ipsvi_visible_box::visible_sphere;

use common::*;
use glam::Vec3;
use sweeplab::scene::Scene;
use sweeplab::techniques::ipsvi::{CacheUpdate, CacheWrite, IpsviSettings, LineKernel, ReadFronts};
use sweeplab::techniques::scene_from_toml_str;

/// lavapipe's whole subgroup in the default rounds, and more rounds than a
/// ray has segments of samples: each split of each mode is a pipeline that
/// lavapipe compiles, most of this file's time.
const MODE_SPLITS: [(u32, u32); 2] = [(8, 4), (2, 64)];

fn placement(name: &str) -> Vec<(&'static str, Scene)> {
    light_placements().into_iter().filter(|(what, _)| *what == name).collect()
}

/// The cache read (blended fronts, the paper's, and per texel), forward-cone
/// scattering, light rays without piecewise integration, the claims'
/// nearest rule, wide line blocks, and two lights swept one after the other
/// or merged step by step.
#[test]
fn segmented_matches_serial_in_every_other_selectable_mode() {
    let base = settings(LineKernel::Auto, 0, 4);
    let (from_above, inside) = (placement("directional"), placement("point inside the volume"));
    let on =
        |scenes: &[(&str, Scene)], mode: &str, s: IpsviSettings| matches_serial_in(&MODE_SPLITS, &[(mode, s)], scenes);
    on(&from_above, "blended fronts", IpsviSettings { read_fronts: ReadFronts::Blended, ..base.clone() });
    on(&from_above, "per-texel fronts", IpsviSettings { read_fronts: ReadFronts::PerTexel, ..base.clone() });
    let cone = IpsviSettings { cache_update: CacheUpdate::LightRays, albedo: 0.5, ..base.clone() };
    on(&from_above, "forward-cone scattering (light rays)", cone);
    let rays = IpsviSettings { cache_update: CacheUpdate::LightRays, piecewise: false, ..base.clone() };
    on(&from_above, "light rays without piecewise integration", rays);
    on(&inside, "nearest claims", IpsviSettings { cache_write: CacheWrite::Nearest, ..base.clone() });
    on(&inside, "line blocks of 8", IpsviSettings { line_width: 8, ..base.clone() });
    let two_lights = [(
        "a directional light and a point light inside",
        slab_scene(vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0), point(Vec3::new(0.15, 0.35, 0.1))]),
    )];
    on(&two_lights, "sweeps one after the other", IpsviSettings { merge_sweeps: false, ..base.clone() });
    on(&two_lights, "merged sweeps", IpsviSettings { merge_sweeps: true, ..base });
}

/// The volumes of the other IPSVI tests: the sphere whose inside alone is
/// visible, with the cache fitted to it; the selective-light-updates paper's
/// three spheres under a point light; the Cornell box under its spot light.
#[test]
fn segmented_matches_serial_on_the_other_test_volumes() {
    let base = settings(LineKernel::Auto, 0, 4);
    let sphere = visible_sphere(directional(Vec3::new(0.3, -1.0, 0.2), 2.0), SIZE);
    let fitted = IpsviSettings { fit_to_visible: true, ..base.clone() };
    matches_serial_in(&MODE_SPLITS, &[("fitted to the visible cells", fitted)], &[("visible sphere", sphere)]);
    let text = format!(
        "[volume]\nsynthetic = \"three-spheres\"\nsize = 24\n[render]\nwidth = {SIZE}\nheight = {SIZE}\n\
         [camera]\nazimuth = 30.0\nelevation = 20.0\n[[lights]]\ntype = \"point\"\nposition = [0.0, 0.6, 0.3]\n"
    );
    let spheres = scene_from_toml_str(&text, std::path::Path::new(""), "three spheres", &[]).unwrap();
    let cornell = cornell_box_scene(32, SIZE, "");
    let scenes = [("three spheres, point light", spheres), ("Cornell box, spot light", cornell)];
    matches_serial_in(&MODE_SPLITS, &[("every-sample", base)], &scenes);
}
