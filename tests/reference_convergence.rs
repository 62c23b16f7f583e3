//! The ground truth converged on the example scenes: each synthetic example's
//! reference, at the steps its file gives (or the defaults), is within a stated
//! bound of the same reference at a quarter of both steps. A scene whose
//! default is not converged (thin opaque bands sampled at a quarter voxel band
//! the image) states finer steps in its file.
use crate::common;

use common::*;
use std::path::Path;
use sweeplab::metrics::compare;
use sweeplab::render::{GpuScene, VolumeTexels};
use sweeplab::scene::scene_spec::VolumeSource;
use sweeplab::techniques::load_scene;
use sweeplab::techniques::{render, Technique};
use sweeplab::vk::Profiler;

const SIZE: u32 = 32;
/// Relative RMSE (to the brightest value) against the quarter-step reference.
const CONVERGED: f64 = 0.01;

#[test]
fn the_reference_of_every_synthetic_example_is_converged_at_its_steps() {
    let ctx = validated_context();
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes");
    let mut paths: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).collect();
    paths.retain(|p| p.extension().is_some_and(|e| e == "toml"));
    paths.sort();
    let mut checked = 0;
    let mut failures = Vec::new();
    for path in paths {
        let spec = sweeplab::techniques::parse_scene_file(&path, &[]).unwrap();
        if !matches!(spec.volume, VolumeSource::Synthetic { .. }) {
            continue;
        }
        let scene = load_scene(&path, &[]).unwrap();
        let mut fine = scene.clone();
        fine.reference.step_voxels /= 4.0;
        fine.reference.shadow_step_voxels /= 4.0;
        let mut images = Vec::new();
        for s in [&scene, &fine] {
            let gpu = GpuScene::upload_with(&ctx, s, VolumeTexels::Float32).unwrap();
            let mut profiler = Profiler::new(&ctx, 64).unwrap();
            images.push(render(&gpu, Technique::Reference, SIZE, SIZE, &mut profiler).unwrap().image);
        }
        let peak = images[1].max_value() as f64;
        let error = compare(&images[0], &images[1]).unwrap().rmse / peak;
        println!(
            "{}: steps {} / {} voxel: relative rmse {error:.2e} against a quarter of both",
            path.file_name().unwrap().to_string_lossy(),
            scene.reference.step_voxels,
            scene.reference.shadow_step_voxels
        );
        if error > CONVERGED {
            failures.push(format!("{}: {error:.2e}", path.display()));
        }
        checked += 1;
    }
    assert!(failures.is_empty(), "not converged: {failures:?}");
    assert!(checked >= 5, "{checked} synthetic examples");
    assert_validation_clean(&ctx);
}
