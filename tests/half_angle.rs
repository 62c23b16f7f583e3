//! Half-angle slicing against the ground truth of model (i), its per-slice
//! barrier under synchronization validation, and its limits.
use crate::common;

use common::*;
use glam::Vec3;
use sweeplab::linear_image::LinearImage;
use sweeplab::metrics::compare;
use sweeplab::render::{GpuScene, VolumeTexels};
use sweeplab::scene::synthetic::slab_under_sphere;
use sweeplab::scene::{presets, OpticalModel, Scene};
use sweeplab::techniques::half_angle::{slicing, HalfAngleSettings};
use sweeplab::techniques::{render, Technique};
use sweeplab::vk::Profiler;

const SIZE: u32 = 48;

fn slab_scene(direction: Vec3) -> Scene {
    let mut scene = scene_with(slab_under_sphere(32), vec![directional(direction, 2.0)], SIZE, SIZE);
    scene.transfer = presets::preset("slab-sphere").unwrap();
    scene.reference.model = OpticalModel::SingleScattering;
    // A fine ground truth: slices sample the volume on planes, not along the view
    // rays, so a coarse reference's own error on these hard surfaces would dominate.
    scene.reference.step_voxels = 0.125;
    scene.reference.shadow_step_voxels = 0.125;
    scene.render.emission = 0.2;
    scene.settings.set(HalfAngleSettings { slice_step: Some(0.125), light_buffer_size: 256 });
    scene
}

fn relative_rmse(test: &LinearImage, reference: &LinearImage) -> f64 {
    compare(test, reference).unwrap().rmse / reference.max_value() as f64
}

/// Stated tolerance: slices 0.125 voxel apart, light buffer 256, against model (i)
/// with 0.125-voxel view and shadow steps: RMSE within 5% of the peak (and well
/// below unshaded DVR's error, so the shadows must be there).
const RMSE_TOLERANCE: f64 = 0.05;

#[test]
fn half_angle_matches_the_reference_with_the_light_behind_and_in_front_of_the_viewer() {
    let ctx = validated_context();
    for (what, direction) in [
        ("light from behind the viewer", Vec3::new(0.3, -1.0, -0.6)),
        ("light facing the viewer", Vec3::new(-0.3, -1.0, 0.8)),
    ] {
        let scene = slab_scene(direction);
        let sl = slicing(&scene, &scene.settings.get::<HalfAngleSettings>()).unwrap();
        let gpu = GpuScene::upload_with(&ctx, &scene, VolumeTexels::Float32).unwrap();
        let mut profiler = Profiler::new(&ctx, 16).unwrap();
        let out = render(&gpu, Technique::HalfAngle, SIZE, SIZE, &mut profiler).unwrap();
        assert_eq!(out.dispatches, sl.count, "{what}: one dispatch per slice");
        assert!(out.image.all_finite());
        let reference = common::reference_image(&gpu, SIZE, SIZE);
        let rmse = relative_rmse(&out.image, &reference);
        let unshaded = render(&gpu, Technique::Dvr, SIZE, SIZE, &mut profiler).unwrap().image;
        println!(
            "{what}: front to back {}, {} slices, relative rmse {rmse:.4} (unshaded DVR {:.4})",
            sl.front_to_back,
            sl.count,
            relative_rmse(&unshaded, &reference)
        );
        assert!(rmse <= RMSE_TOLERANCE, "{what}: relative rmse {rmse:.4}");
        assert!(rmse < 0.5 * relative_rmse(&unshaded, &reference), "{what}: no better than unshaded DVR");
    }
    assert_validation_clean(&ctx);
}

#[test]
fn half_angle_refuses_what_it_cannot_do() {
    let ctx = validated_context();
    let mut two = slab_scene(Vec3::NEG_Y);
    two.lights.push(directional(Vec3::X, 1.0));
    let gpu = GpuScene::upload(&ctx, &two).unwrap();
    let mut profiler = Profiler::new(&ctx, 16).unwrap();
    assert!(render(&gpu, Technique::HalfAngle, 8, 8, &mut profiler).is_err(), "two lights");
}

#[test]
fn front_to_back_the_last_slice_adds_the_background_on_the_gpu() {
    // Light from behind the viewer: slices go front to back and the eye buffer
    // holds colour and transmittance; the last slice adds background x
    // transmittance (on the host before the frame could record). A bright
    // background makes a missing or doubled term plain.
    let ctx = validated_context();
    let mut scene = slab_scene(Vec3::new(0.3, -1.0, -0.6));
    scene.render.background = Vec3::new(0.6, 0.3, 0.9);
    assert!(slicing(&scene, &scene.settings.get::<HalfAngleSettings>()).unwrap().front_to_back);
    let gpu = GpuScene::upload_with(&ctx, &scene, VolumeTexels::Float32).unwrap();
    let mut profiler = Profiler::new(&ctx, 16).unwrap();
    let out = render(&gpu, Technique::HalfAngle, SIZE, SIZE, &mut profiler).unwrap();
    // The corner's ray misses the volume: the background alone.
    let corner = out.image.pixels[0];
    for c in 0..3 {
        assert!((corner[c] - scene.render.background[c]).abs() < 1e-6, "corner {corner:?}");
    }
    let reference = common::reference_image(&gpu, SIZE, SIZE);
    let rmse = relative_rmse(&out.image, &reference);
    println!("bright background, front to back: relative rmse {rmse:.4}");
    assert!(rmse <= RMSE_TOLERANCE, "relative rmse {rmse:.4}");
    assert_validation_clean(&ctx);
}

/// Each slice updates only the light buffer texels whose rays cross its own or
/// the previous slice's slab inside the box (`LightRegions::Slices`): the
/// image is the one every texel updated every slice gives, bit for bit, with
/// the light behind and in front of the viewer, jittered samples, a point
/// light, a rod whose slices each cross a small part of the buffer, and a
/// medium filling the box.
#[test]
fn the_light_buffer_regions_give_the_whole_buffers_image_bit_for_bit() {
    use sweeplab::techniques::half_angle::{render_with, LightRegions};
    let ctx = validated_context();
    let behind = slab_scene(Vec3::new(0.3, -1.0, -0.6));
    let mut jittered = slab_scene(Vec3::new(-0.3, -1.0, 0.8));
    jittered.render.jitter = true;
    let mut lit_by_point = slab_scene(Vec3::NEG_Y);
    lit_by_point.lights = vec![point(Vec3::new(0.8, 2.5, 0.4))];
    let mut rod = slab_scene(Vec3::new(0.3, -1.0, 0.2));
    rod.volume.spacing = Vec3::new(1.0, 1.0, 12.0);
    // A medium up to the box's faces: every texel the box's shadow covers matters.
    let filled = scene_with(sphere_volume(16, 40.0), vec![directional(Vec3::new(0.3, -1.0, 0.2), 2.0)], SIZE, SIZE);
    for (what, mut scene) in [
        ("light behind", behind),
        ("jittered, light facing", jittered),
        ("point light", lit_by_point),
        ("rod", rod),
        ("filled box", filled),
    ] {
        // Coarse slices and a small buffer: the identity does not depend on them.
        scene.settings.set(HalfAngleSettings { slice_step: Some(0.5), light_buffer_size: 64 });
        let gpu = GpuScene::upload_with(&ctx, &scene, VolumeTexels::Float32).unwrap();
        let mut profiler = Profiler::new(&ctx, 16).unwrap();
        let mut frame = |regions| render_with(&gpu, SIZE, SIZE, &mut profiler, regions).unwrap().image;
        let (slices, whole) = (frame(LightRegions::Slices), frame(LightRegions::Whole));
        assert!(slices.pixels.iter().any(|p| p[0] > 0.0), "{what}: the image is black");
        assert!(slices == whole, "{what}: the regions changed the image");
    }
    assert_validation_clean(&ctx);
}
