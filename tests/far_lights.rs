//! A point or spot light far enough that its rays are parallel
//! within f32 precision across the volume renders as the directional light it
//! approaches (src/scene/light.rs, `Light::far_limit`), in every technique and
//! the reference: finite, lit, close to the reference of its model. Before the
//! rule, [1e20, 0, 0] gave all-zero IPSVI and half-angle images and NaN in the
//! light volume.
use crate::common;

use common::*;
use glam::Vec3;
use sweeplab::linear_image::LinearImage;
use sweeplab::metrics::compare;
use sweeplab::reference::cpu::{render_cpu, CpuRenderKind};
use sweeplab::render::{GpuScene, VolumeTexels};
use sweeplab::scene::{Falloff, Light, LightKind, Scene};
use sweeplab::techniques::ipsvi::IpsviSettings;
use sweeplab::techniques::scene_from_toml_str;
use sweeplab::techniques::{render, Technique};
use sweeplab::vk::{Context, Profiler};

/// The camera at the distance the bounds below were measured at (the bounding
/// sphere of the box framed with 5 % margin, the automatic framing then): the
/// framing of what shows puts the spheres over more of the image.
fn scene(light: &str) -> Scene {
    let text = format!(
        "[volume]\nsynthetic = \"three-spheres\"\nsize = 24\n[render]\nwidth = 24\nheight = 24\n\
         [camera]\nazimuth = 30.0\nelevation = 20.0\ndistance = 3.5137\n[[lights]]\n{light}\nintensity = 2.0\n"
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

#[test]
fn a_scene_built_in_code_with_a_point_light_at_1e20_gets_the_directional_image_in_every_technique() {
    // Built from the scene types, not a file: the far-light rule must not
    // depend on the TOML path (Scene::rendered_lights applies it where the
    // GPU records, light-space planes and the CPU reference are made).
    let point = Light {
        kind: LightKind::Point { position: Vec3::new(1e20, 0.0, 0.0) },
        color: Vec3::ONE,
        intensity: 2.0,
        falloff: Falloff::None,
    };
    let far = scene_with(sphere_volume(16, 6.0), vec![point], 16, 16);
    let mut directional = far.clone();
    directional.lights = vec![common::directional(Vec3::NEG_X, 2.0)];
    assert_eq!(far.rendered_lights(), directional.lights);
    // Bit for bit: -0 == 0, but IPSVI's cache lays its texels out by the sign
    // of z (and 1/-0 is -inf), so a far light with -0 components gave another
    // image than the directional light on a coarse cache (1e-3 at 64 texels).
    assert_eq!(format!("{:?}", far.rendered_lights()), format!("{:?}", directional.lights));
    let ctx = validated_context();
    let coarse = |s: &Scene| {
        let mut s = s.clone();
        s.settings.get_mut::<IpsviSettings>().cache_size = 64;
        s
    };
    let ipsvi_coarse =
        compare(&frame(&ctx, &coarse(&far), Technique::Ipsvi), &frame(&ctx, &coarse(&directional), Technique::Ipsvi));
    assert_eq!(
        ipsvi_coarse.unwrap().max_abs,
        0.0,
        "ipsvi at 64 texels: the far point light differs from the directional one"
    );
    for technique in Technique::all() {
        let (a, b) = (frame(&ctx, &far, technique), frame(&ctx, &directional, technique));
        let stats = compare(&a, &b).unwrap();
        assert!(b.max_value() > 0.05, "{technique}: the directional image is lit");
        // The same inputs on the GPU, bit for bit: the same image.
        assert_eq!(stats.max_abs, 0.0, "{technique}: the far point light differs from the directional one: {stats:?}");
        for kind in [CpuRenderKind::Reference(technique.reference_model(&far)), CpuRenderKind::Phong] {
            let (a, b) = (render_cpu(&far, kind, 8, 8).unwrap(), render_cpu(&directional, kind, 8, 8).unwrap());
            assert_eq!(compare(&a, &b).unwrap().max_abs, 0.0, "CPU {kind:?}");
        }
    }
    assert_validation_clean(&ctx);
}
