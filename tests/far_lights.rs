//! Issue 14: a point or spot light far enough that its rays are parallel
//! within f32 precision across the volume renders as the directional light it
//! approaches (src/scene/light.rs, `Light::far_limit`), in every technique and
//! the reference: finite, lit, close to the reference of its model. Before the
//! rule, [1e20, 0, 0] gave all-zero IPSVI and half-angle images and NaN in the
//! light volume.
mod common;

use common::*;
use sweeplab::linear_image::LinearImage;
use sweeplab::metrics::compare;
use sweeplab::render::{render, GpuScene, Technique, VolumeTexels};
use sweeplab::scene::scene_file::scene_from_toml_str;
use sweeplab::scene::{LightKind, Scene};
use sweeplab::vk::{Context, Profiler};

fn scene(light: &str) -> Scene {
    let text = format!(
        "[volume]\nsynthetic = \"three-spheres\"\nsize = 24\n[render]\nwidth = 24\nheight = 24\n\
         [camera]\nazimuth = 30.0\nelevation = 20.0\n[[lights]]\n{light}\nintensity = 2.0\n"
    );
    scene_from_toml_str(&text, std::path::Path::new(""), "far light test", &[]).unwrap()
}

fn frame(ctx: &Context, scene: &Scene, technique: Technique) -> LinearImage {
    let gpu = GpuScene::upload_with(ctx, scene, VolumeTexels::Float32).unwrap();
    let mut profiler = Profiler::new(ctx, 65_536).unwrap();
    render(&gpu, technique, scene.render.width, scene.render.height, &mut profiler).unwrap().image
}

/// PSNR (dB) each technique keeps against the reference of its model on this
/// scene with the directional light from +x.
fn bound(t: Technique) -> f64 {
    match t.name() {
        "ipsvi" => 25.0,
        "half-angle" => 20.0,
        "lightvolume" => 25.0,
        _ => 40.0,
    }
}

#[test]
fn a_point_light_at_1e20_renders_as_the_directional_light_from_its_side() {
    let far = scene("type = \"point\"\nposition = [1e20, 0.0, 0.0]");
    let directional = scene("type = \"directional\"\ndirection = [-1.0, 0.0, 0.0]");
    assert_eq!(far.lights, directional.lights, "one rule: the directional light from +x");
    let ctx = validated_context();
    for technique in [Technique::Ipsvi, Technique::HalfAngle, Technique::LightVolume, Technique::Reference] {
        let mut far = far.clone();
        far.reference.model = technique.reference_model(&far);
        far.reference.chromatic = technique.reference_chromatic(&far);
        let image = frame(&ctx, &far, technique);
        assert!(image.all_finite(), "{technique}");
        let reference = frame(&ctx, &far, Technique::Reference);
        let lit_peak = reference.max_value();
        assert!(lit_peak > 0.2, "the reference is lit ({lit_peak})");
        let stats = compare(&image, &reference).unwrap();
        println!("{technique}: far point light vs reference {:.1} dB", stats.psnr);
        assert!(stats.psnr >= bound(technique), "{technique}: {stats:?}");
    }
    assert_validation_clean(&ctx);
}

#[test]
fn lights_reach_the_far_limit_smoothly_and_far_spots_follow_the_rule() {
    // 1e6 is still a point light, 1e8 is past the rule: the images agree, to
    // the discretization of the light buffers (half-angle's turns from a
    // perspective to an orthographic projection at the rule).
    let ctx = validated_context();
    let near = scene("type = \"point\"\nposition = [1e6, 0.0, 0.0]");
    let far = scene("type = \"point\"\nposition = [1e8, 0.0, 0.0]");
    assert!(matches!(near.lights[0].kind, LightKind::Point { .. }));
    for technique in [Technique::Ipsvi, Technique::HalfAngle, Technique::LightVolume] {
        let stats = compare(&frame(&ctx, &near, technique), &frame(&ctx, &far, technique)).unwrap();
        println!("{technique}: 1e6 point vs 1e8 limit {:.1} dB", stats.psnr);
        let bound = if technique == Technique::HalfAngle { 30.0 } else { 40.0 };
        assert!(stats.psnr > bound, "{technique}: {stats:?}");
    }
    // A spot light aimed at the volume from 1e20: lit like the directional light.
    let spot = scene(
        "type = \"spot\"\nposition = [1e20, 0.0, 0.0]\ndirection = [-1.0, 0.0, 0.0]\ninner_cone = 10.0\nouter_cone = 20.0",
    );
    let directional = scene("type = \"directional\"\ndirection = [-1.0, 0.0, 0.0]");
    assert_eq!(spot.lights, directional.lights);
    assert_validation_clean(&ctx);
}
