//! The default IPSVI image of the main job's scene (tests/scenes/slab-under-sphere.toml,
//! what `tools/run.sh` renders) has no stripes and no grain against its ground
//! truth, at 128x128 and 256x256: `sweeplab::metrics::error_structure`, stated
//! against the reference's peak. The ground truth marches at twice the scene's
//! reference steps (0.125 / 0.25 voxel), which keeps the test to seconds; its own
//! stripe and grain figures against the scene's ground truth are far below
//! the bounds (`CHEAP_REFERENCE` below: column stripes 3.8e-5 and 2.5e-5 of
//! the peak at 128 and 256, grain 4.2e-4 and 3.9e-4; at four times the steps,
//! grain 1.4e-3 and 1.3e-3, too near the bound's margin to keep; 2026-12-06).
//!
//! The bounds hold for the image as it is and fail on the images before issue 45
//! (`the_bounds_fail_on_the_images_before_issue_45`, ignored to keep the suite
//! short: it renders the old defaults, named by their settings).
use crate::common;

use common::*;
use std::path::Path;
use sweeplab::metrics::{error_structure, ErrorStructure};
use sweeplab::render::VolumeTexels;
use sweeplab::techniques::comparison::{compare_with_reference, comparison_scene, ReferenceSource};
use sweeplab::techniques::{load_scene, Technique};

/// Column stripes, relative to the reference's peak: the error's column means
/// may depart from their running mean by at most this (RMS over the columns).
/// Measured 1.12e-3 at 128 and 1.25e-3 at 256 (rows 4.7e-4 and 3.1e-4); the
/// image before issue 45 drew 6.39e-3 at 256, where `read_fronts = "auto"`
/// took the blended fronts on the 0.79 px texels (1.45e-3 at 128, per-texel
/// fronts there already).
const MAX_COLUMN_STRIPES: f64 = 3e-3;
/// Grain: the error's departure from its 3x3 mean (RMS over the pixels),
/// relative to the peak. Measured 5.46e-3 at 128 and 5.68e-3 at 256 (the
/// jittered samples on the sphere's lit surface); before issue 45, 1.46e-2 and
/// 2.09e-2: the slab's band, as narrow as the sphere's own, left a film a
/// third of a voxel deep on the sphere that one view sample in a step hit or
/// missed pixel by pixel.
const MAX_GRAIN: f64 = 8e-3;

/// Twice the scene's reference steps.
const CHEAP_REFERENCE: [&str; 2] = ["reference.step=0.125", "reference.shadow_step=0.25"];

fn structure(size: u32, extra: &[String]) -> ErrorStructure {
    let scene_file = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes/slab-under-sphere.toml");
    let mut overrides = vec![format!("render.width={size}"), format!("render.height={size}")];
    overrides.extend(CHEAP_REFERENCE.map(String::from));
    overrides.extend_from_slice(extra);
    // As `sweeplab compare` does: the reference of the model IPSVI approximates.
    let scene = comparison_scene(&load_scene(&scene_file, &overrides).unwrap(), Technique::Ipsvi);
    let ctx = validated_context();
    let c =
        compare_with_reference(&ctx, &scene, Technique::Ipsvi, ReferenceSource::Gpu, VolumeTexels::Native, 8192, None)
            .unwrap();
    assert_validation_clean(&ctx);
    let s = error_structure(&c.image, &c.reference_image).unwrap();
    eprintln!(
        "{size}x{size} {extra:?}: column stripes {:.2e}, row stripes {:.2e}, grain {:.2e} (of the peak {:.3}); {:.2} dB",
        s.column_stripes / s.peak,
        s.row_stripes / s.peak,
        s.grain / s.peak,
        s.peak,
        c.psnr
    );
    s
}

fn clean(s: &ErrorStructure) -> bool {
    s.column_stripes <= MAX_COLUMN_STRIPES * s.peak && s.grain <= MAX_GRAIN * s.peak
}

#[test]
fn the_main_jobs_default_ipsvi_image_has_no_stripes_and_no_grain() {
    for size in [128, 256] {
        let s = structure(size, &[]);
        assert!(clean(&s), "{size}x{size}: {s:?}");
        // Stripes are a pattern along columns: rows show none.
        assert!(s.row_stripes <= MAX_COLUMN_STRIPES * s.peak, "{size}x{size}: {s:?}");
    }
}

/// The defaults before issue 45, named: the slab's band as narrow as the
/// sphere's own (the "slab-sphere" preset then) and, at 256, the paper's blended
/// fronts that `read_fronts = "auto"` took on texels above half a pixel.
#[test]
#[ignore = "demonstration: the bounds fail on the old defaults (about a minute on lavapipe)"]
fn the_bounds_fail_on_the_images_before_issue_45() {
    let old_band = "transfer={points=[[0.0,0.8,0.8,0.8,0.0],[0.34196,0.8,0.8,0.8,0.0],[0.46196,0.8,0.8,0.8,0.5],\
                    [0.52196,0.8,0.8,0.8,0.5],[0.56196,1.0,0.6,0.3,0.0],[0.62,1.0,0.6,0.3,0.0],[1.0,1.0,0.6,0.3,0.95]]}";
    let grainy = structure(128, &[old_band.to_string()]);
    assert!(grainy.grain > MAX_GRAIN * grainy.peak, "{grainy:?}");
    let striped = structure(256, &[old_band.to_string(), "ipsvi.read_fronts=blended".to_string()]);
    assert!(striped.column_stripes > MAX_COLUMN_STRIPES * striped.peak, "{striped:?}");
    assert!(striped.grain > MAX_GRAIN * striped.peak, "{striped:?}");
}
