//! The CPU reference against closed forms and physical expectations
//! (docs/optical-model.md). Scenes are built inline from the scene types.

use glam::{UVec3, Vec3};
use sweeplab::reference::{
    render_cpu, render_pixel_cpu, CpuRenderError, CpuRenderKind, EARLY_TERMINATION_TRANSMITTANCE,
};
use sweeplab::scene::*;

const SINGLE: CpuRenderKind = CpuRenderKind::Reference(OpticalModel::SingleScattering);
const EMISSIVE: CpuRenderKind = CpuRenderKind::Reference(OpticalModel::EmissiveScattering);

fn volume_from(n: u32, mut value: impl FnMut(u32, u32, u32) -> u8) -> Volume {
    let mut data = Vec::with_capacity((n * n * n) as usize);
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                data.push(value(x, y, z));
            }
        }
    }
    Volume {
        name: "inline".into(),
        dims: UVec3::splat(n),
        spacing: Vec3::ONE,
        data: VoxelData::U8(data),
        value_range: (0.0, 255.0),
        non_finite_voxels: 0,
        interpolation: Default::default(),
    }
}

fn constant_volume(n: u32) -> Volume {
    volume_from(n, |_, _, _| 255)
}

/// The same colour and opacity for every scalar: a homogeneous medium.
fn constant_transfer(rgb: [f32; 3], alpha: f32) -> TransferFunction {
    TransferFunction { points: vec![ControlPoint { value: 0.0, rgba: [rgb[0], rgb[1], rgb[2], alpha] }] }
}

/// Orthographic camera on the +z axis looking down -z; every ray crosses the
/// unit box through its full depth (L = 1) when `height` < 1.
fn looking_down_z(height: f32) -> Camera {
    Camera {
        eye: Vec3::new(0.0, 0.0, 2.0),
        target: Vec3::ZERO,
        up: Vec3::Y,
        projection: Projection::Orthographic { height },
    }
}

fn directional(direction: Vec3, color: Vec3, intensity: f32) -> Light {
    Light { kind: LightKind::Directional { direction }, color, intensity, falloff: Falloff::None }
}

fn tiny_scene(volume: Volume, transfer: TransferFunction, lights: Vec<Light>) -> Scene {
    Scene {
        volume,
        transfer,
        camera: looking_down_z(0.5),
        lights,
        render: RenderSettings {
            width: 8,
            height: 8,
            step_voxels: 0.5,
            background: Vec3::new(0.1, 0.2, 0.3),
            emission: 0.0,
            // Closed forms are written for midpoint samples.
            jitter: false,
            filter: VolumeFilter::Exact,
        },
        reference: ReferenceSettings {
            model: OpticalModel::SingleScattering,
            step_voxels: 0.5,
            shadow_step_voxels: 0.5,
            min_transmittance: 0.0,
            chromatic: false,
        },
        phong: PhongSettings { ambient: 0.2, diffuse: 0.6, specular: 0.3, shininess: 16.0 },
        settings: TechniqueSettings::default(),
        technique_tables: Vec::new(),
    }
}

/// Optical depth per voxel as the renderers read it (the baked LUT's sigma).
fn sigma_of(scene: &Scene) -> f64 {
    scene.transfer.bake(TransferLut::DEFAULT_SIZE).texels[0][3] as f64
}

fn world_ray_origin(scene: &Scene, x: u32, y: u32, w: u32, h: u32) -> [f64; 3] {
    let (nx, ny) = RayBasis::ndc(x, y, w, h);
    scene.camera.basis(w, h).ray_f64(nx as f64, ny as f64).0
}

fn dv(v: Vec3) -> [f64; 3] {
    v.as_dvec3().to_array()
}

fn assert_close(got: [f64; 3], want: [f64; 3], tol: f64, what: &str) {
    for c in 0..3 {
        assert!(
            (got[c] - want[c]).abs() <= tol,
            "{what}: channel {c}: got {}, want {} (tolerance {tol})",
            got[c],
            want[c]
        );
    }
}

// ---------------------------------------------------------------- DVR, Phong

/// Homogeneous medium, L = 1 world = 8 voxels: the opacity-corrected midpoint
/// rule is exact for any step, `C = rgb (1 - e^-tau) + bg e^-tau`.
#[test]
fn dvr_of_a_homogeneous_box_is_the_closed_form() {
    let rgb = [0.8, 0.4, 0.2];
    let mut scene = tiny_scene(constant_volume(8), constant_transfer(rgb, 0.1), vec![]);
    let tau = sigma_of(&scene) * 8.0;
    assert!((-tau).exp() > EARLY_TERMINATION_TRANSMITTANCE);
    let bg = dv(scene.render.background);
    let want: [f64; 3] = std::array::from_fn(|c| rgb[c] as f64 * (1.0 - (-tau).exp()) + bg[c] * (-tau).exp());
    for step in [0.5, 0.3, 1.0, 2.5, 20.0] {
        scene.render.step_voxels = step;
        for (x, y) in [(0, 0), (3, 5), (7, 7)] {
            let got = render_pixel_cpu(&scene, CpuRenderKind::Dvr, 8, 8, x, y).unwrap();
            assert_close(got, want, 1e-13, &format!("step {step} pixel ({x}, {y})"));
        }
        let image = render_cpu(&scene, CpuRenderKind::Dvr, 8, 8).unwrap();
        for p in &image.pixels {
            let p = p.map(|c| c as f64);
            assert_close(p, want, 1e-6, &format!("step {step} image"));
        }
    }
}

/// Stopping at T < t_min changes a pixel by at most t_min * max(S, background).
#[test]
fn dvr_early_termination_error_is_bounded_by_t_min() {
    let rgb = [0.8, 0.4, 0.2];
    let scene = tiny_scene(constant_volume(8), constant_transfer(rgb, 0.9), vec![]);
    let tau = sigma_of(&scene) * 8.0;
    let bg = dv(scene.render.background);
    let exact: [f64; 3] = std::array::from_fn(|c| rgb[c] as f64 * (1.0 - (-tau).exp()) + bg[c] * (-tau).exp());
    let got = render_pixel_cpu(&scene, CpuRenderKind::Dvr, 8, 8, 4, 4).unwrap();
    let bound = EARLY_TERMINATION_TRANSMITTANCE * 0.8;
    let err: f64 = (0..3).map(|c| (got[c] - exact[c]).abs()).fold(0.0, f64::max);
    assert!(err <= bound, "error {err} above {bound}");
    // The ray did stop early (the final transmittance e^-18 is far below t_min,
    // and a ray that ran to the end would match to rounding).
    assert!(err > 1e-9, "error {err}: the ray did not terminate early");
}

#[test]
fn phong_without_lights_or_gradient_is_flat_shading() {
    let rgb = [0.8, 0.4, 0.2];
    let light = directional(Vec3::new(0.3, -1.0, -0.2), Vec3::ONE, 3.0);
    for lights in [vec![], vec![light]] {
        let scene = tiny_scene(constant_volume(8), constant_transfer(rgb, 0.1), lights);
        let tau = sigma_of(&scene) * 8.0;
        let bg = dv(scene.render.background);
        let flat = scene.phong.ambient as f64 + scene.phong.diffuse as f64;
        let want: [f64; 3] =
            std::array::from_fn(|c| rgb[c] as f64 * flat * (1.0 - (-tau).exp()) + bg[c] * (-tau).exp());
        let got = render_pixel_cpu(&scene, CpuRenderKind::Phong, 8, 8, 2, 6).unwrap();
        assert_close(got, want, 1e-13, "flat phong");
    }
}

/// A scalar ramp along z has its normal along z everywhere; with the light at
/// 60 degrees from the view axis, N.L = cos 60 and N.H = cos 30.
#[test]
fn phong_on_a_ramp_is_blinn_phong_of_the_ramp_normal() {
    let rgb = [0.8, 0.4, 0.2];
    let n = 16;
    let ramp = |rising: bool| {
        let mut v = volume_from(n, |_, _, _| 0);
        let data = (0..n * n * n)
            .map(|i| {
                let z = (i / (n * n)) as f32 / (n - 1) as f32;
                if rising {
                    0.25 + 0.5 * z
                } else {
                    0.75 - 0.5 * z
                }
            })
            .collect();
        v.data = VoxelData::F32(data);
        v
    };
    let theta = 60f64.to_radians();
    let travel = Vec3::new(-theta.sin() as f32, 0.0, -theta.cos() as f32);
    let radiance = [1.5, 1.0, 0.5];
    let light = directional(travel, Vec3::from_array(radiance), 1.0);
    // The flip toward the viewer makes both ramp directions shade alike.
    for rising in [true, false] {
        let scene = tiny_scene(ramp(rising), constant_transfer(rgb, 0.1), vec![light]);
        let ph = &scene.phong;
        let (a, d, s) = (ph.ambient as f64, ph.diffuse as f64, ph.specular as f64);
        let highlight = (theta / 2.0).cos().powf(ph.shininess as f64);
        let tau = sigma_of(&scene) * n as f64;
        let bg = dv(scene.render.background);
        let want: [f64; 3] = std::array::from_fn(|c| {
            let rgb = rgb[c] as f64;
            // The f32 light direction is normalized in f64: N.L is cos 60 to ~1e-8.
            let source = rgb * a + radiance[c] as f64 * (rgb * d * theta.cos() + s * highlight);
            source * (1.0 - (-tau).exp()) + bg[c] * (-tau).exp()
        });
        let got = render_pixel_cpu(&scene, CpuRenderKind::Phong, 8, 8, 3, 4).unwrap();
        assert_close(got, want, 1e-6, &format!("rising {rising}"));
    }
}

// ------------------------------------------------------ reference, analytic

/// Light travels down (-y), the camera looks along -z: every sample of a view
/// ray sits at the same depth d below the lit face, so
/// `C = rgb (e + R e^{-kd} [+ e rgb (1 - e^{-kd})]) (1 - e^{-kL}) + bg e^{-kL}`,
/// exactly for any step (homogeneous medium), for model (i) [and (ii)].
#[test]
fn reference_at_a_known_depth_below_a_lit_face_is_the_closed_form() {
    let rgb = [0.9, 0.7, 0.5];
    let radiance = [1.0, 0.8, 0.6];
    let n = 16;
    let light = directional(Vec3::NEG_Y, Vec3::from_array(radiance), 2.0);
    let mut scene = tiny_scene(constant_volume(n), constant_transfer(rgb, 0.15), vec![light]);
    scene.camera = looking_down_z(1.0);
    scene.render.emission = 0.25;
    let e = 0.25f64;
    let vl = 1.0 / n as f64;
    let kappa = sigma_of(&scene) / vl;
    let view_t = (-kappa).exp();
    let bg = dv(scene.render.background);
    for (kind, step) in [(SINGLE, 0.5), (SINGLE, 1.7), (EMISSIVE, 0.5), (EMISSIVE, 0.9)] {
        scene.reference.step_voxels = step;
        scene.reference.shadow_step_voxels = step;
        for (x, y) in [(0, 0), (4, 3), (7, 7)] {
            let depth = 0.5 - world_ray_origin(&scene, x, y, 8, 8)[1];
            let tl = (-kappa * depth).exp();
            let want: [f64; 3] = std::array::from_fn(|c| {
                let rgb = rgb[c] as f64;
                let mut light_in = e + 2.0 * radiance[c] as f64 * tl;
                if kind == EMISSIVE {
                    light_in += e * rgb * (1.0 - tl);
                }
                rgb * light_in * (1.0 - view_t) + bg[c] * view_t
            });
            let got = render_pixel_cpu(&scene, kind, 8, 8, x, y).unwrap();
            assert_close(got, want, 1e-12, &format!("{kind:?} step {step} ({x}, {y})"));
        }
    }
}

/// Light travels along the view ray (toward the eye): the source varies along
/// the ray, `S(u) = rgb (e + R e^{-ku})`. Continuous:
/// `C = rgb e (1 - e^{-kL}) + rgb R (1 - e^{-2kL}) / 2 + bg e^{-kL}`.
/// The midpoint rule keeps the emission part exact and scales the scattering
/// part by exactly `1 / cosh(k h / 2)` (geometric sums), so its error is at most
/// `(k h)^2 / 8` of it and shrinks about fourfold when the step halves.
#[test]
fn reference_along_the_light_converges_quadratically_to_the_integral() {
    let rgb = [0.9, 0.7, 0.5];
    let n = 8;
    let light = directional(Vec3::NEG_Z, Vec3::ONE, 1.5);
    let mut scene = tiny_scene(constant_volume(n), constant_transfer(rgb, 0.5), vec![light]);
    scene.render.emission = 0.2;
    let (e, big_r) = (scene.render.emission as f64, 1.5f64);
    let vl = 1.0 / n as f64;
    let kappa = sigma_of(&scene) / vl;
    let bg = dv(scene.render.background);
    let view_t = (-kappa).exp();
    let scatter: [f64; 3] = std::array::from_fn(|c| rgb[c] as f64 * big_r * (1.0 - (-2.0 * kappa).exp()) / 2.0);
    let continuous: [f64; 3] =
        std::array::from_fn(|c| rgb[c] as f64 * e * (1.0 - view_t) + scatter[c] + bg[c] * view_t);
    let mut errors = vec![];
    for step in [1.0, 0.5, 0.25] {
        scene.reference.step_voxels = step;
        let got = render_pixel_cpu(&scene, SINGLE, 8, 8, 3, 3).unwrap();
        let h = step as f64 * vl;
        let shrink = 1.0 / (kappa * h / 2.0).cosh();
        let discrete: [f64; 3] = std::array::from_fn(|c| continuous[c] - scatter[c] * (1.0 - shrink));
        assert_close(got, discrete, 1e-12, &format!("discrete sum, step {step}"));
        let bound = (kappa * h).powi(2) / 8.0;
        let err = (got[0] - continuous[0]).abs();
        assert!(err <= scatter[0] * bound, "step {step}: {err} > {bound}");
        errors.push(err);
    }
    for pair in errors.windows(2) {
        assert!(pair[1] < pair[0] / 3.5, "halving the step: {pair:?}");
    }
}

// ----------------------------------------------------- sphere over a slab

/// 24^3: a slab (scalar 128, alpha ~0.08) in the bottom third and a dense ball
/// (scalar 255, alpha 0.5, radius 5 voxels) above its centre.
fn sphere_over_slab(with_sphere: bool) -> (Volume, TransferFunction) {
    let n = 24;
    let centre = Vec3::new(11.5, 16.0, 11.5);
    let volume = volume_from(n, |x, y, z| {
        let d = Vec3::new(x as f32, y as f32, z as f32).distance(centre);
        if with_sphere && d <= 5.0 {
            255
        } else if y < 8 {
            128
        } else {
            0
        }
    });
    let grey = |a: f32, v: f32| ControlPoint { value: v, rgba: [0.9, 0.9, 0.9, a] };
    let transfer = TransferFunction { points: vec![grey(0.0, 0.0), grey(0.08, 0.5), grey(0.5, 1.0)] };
    (volume, transfer)
}

fn slab_scene(with_sphere: bool, lights: Vec<Light>) -> Scene {
    let (volume, transfer) = sphere_over_slab(with_sphere);
    let mut scene = tiny_scene(volume, transfer, lights);
    scene.camera = looking_down_z(1.0);
    scene.render.background = Vec3::ZERO;
    scene
}

/// Row 19 of 24 looks through the slab 3.5 voxels below its top; column 11 passes
/// under the ball, column 21 (x = 0.4) well beside its shadow.
const SLAB_ROW: u32 = 19;
const UNDER_BALL: u32 = 11;
const BESIDE: u32 = 21;

#[test]
fn a_ball_over_a_slab_lit_from_above_shadows_the_slab_below_it() {
    let light = directional(Vec3::NEG_Y, Vec3::ONE, 1.0);
    let lit = |with_sphere: bool, x: u32| {
        let scene = slab_scene(with_sphere, vec![light]);
        render_pixel_cpu(&scene, SINGLE, 24, 24, x, SLAB_ROW).unwrap()[0]
    };
    // Without the ball both columns see the same slab under the same light.
    let (open_under, open_beside) = (lit(false, UNDER_BALL), lit(false, BESIDE));
    assert!(open_beside > 0.1);
    assert!((open_under - open_beside).abs() < 1e-12 * open_beside);
    // With it, the middle third of the view ray under the ball is in a shadow of
    // transmittance ~0.5^10; that third carries ~30% of the lit column's light.
    let (under, beside) = (lit(true, UNDER_BALL), lit(true, BESIDE));
    assert!((beside - open_beside).abs() < 1e-6 * open_beside);
    assert!(under < 0.8 * beside, "under {under}, beside {beside}");
}

fn three_lights() -> Vec<Light> {
    vec![
        directional(Vec3::new(0.2, -1.0, -0.1), Vec3::new(1.0, 0.9, 0.8), 1.0),
        Light {
            kind: LightKind::Point { position: Vec3::new(-0.6, 0.3, 0.4) },
            color: Vec3::new(0.5, 0.6, 1.0),
            intensity: 0.4,
            falloff: Falloff::InverseSquare,
        },
        Light {
            kind: LightKind::Spot {
                position: Vec3::new(0.0, 0.9, 0.0),
                direction: Vec3::NEG_Y,
                inner_cone_deg: 10.0,
                outer_cone_deg: 25.0,
            },
            color: Vec3::ONE,
            intensity: 2.0,
            falloff: Falloff::None,
        },
    ]
}

#[test]
fn emissive_model_without_emission_is_single_scattering_bit_for_bit() {
    let scene = slab_scene(true, three_lights());
    let single = render_cpu(&scene, SINGLE, 16, 16).unwrap();
    let emissive = render_cpu(&scene, EMISSIVE, 16, 16).unwrap();
    assert!(single.max_value() > 0.0);
    assert_eq!(single, emissive);
    for (x, y) in [(5, 12), (8, 8)] {
        let a = render_pixel_cpu(&scene, SINGLE, 16, 16, x, y).unwrap();
        let b = render_pixel_cpu(&scene, EMISSIVE, 16, 16, x, y).unwrap();
        assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits));
    }
}

/// In model (ii) the light reaching a sample also carries the emission of what
/// lies toward the light: the slab under the emitting ball gains more than the
/// slab beside it, and nothing gets darker.
#[test]
fn emissive_model_brightens_the_shadow_of_an_emitting_occluder() {
    let light = directional(Vec3::NEG_Y, Vec3::ONE, 1.0);
    let mut scene = slab_scene(true, vec![light]);
    scene.render.emission = 0.3;
    let at = |kind, x| render_pixel_cpu(&scene, kind, 24, 24, x, SLAB_ROW).unwrap()[0];
    let gain_under = at(EMISSIVE, UNDER_BALL) - at(SINGLE, UNDER_BALL);
    let gain_beside = at(EMISSIVE, BESIDE) - at(SINGLE, BESIDE);
    assert!(gain_beside > 0.0);
    assert!(gain_under > gain_beside, "{gain_under} vs {gain_beside}");
    let single = render_cpu(&scene, SINGLE, 12, 12).unwrap();
    let emissive = render_cpu(&scene, EMISSIVE, 12, 12).unwrap();
    for (a, b) in single.pixels.iter().zip(&emissive.pixels) {
        assert!((0..3).all(|c| b[c] >= a[c]), "{a:?} -> {b:?}");
    }
}

// ------------------------------------------------------------ robustness

#[test]
fn point_light_inside_the_volume_gives_finite_light() {
    let light = Light {
        kind: LightKind::Point { position: Vec3::new(0.0, -0.3, 0.0) },
        color: Vec3::ONE,
        intensity: 1.0,
        falloff: Falloff::InverseSquare,
    };
    let scene = slab_scene(true, vec![light]);
    for kind in [SINGLE, EMISSIVE, CpuRenderKind::Phong] {
        let image = render_cpu(&scene, kind, 16, 16).unwrap();
        assert!(image.all_finite(), "{kind:?}");
        assert!(image.max_value() > 0.0, "{kind:?}");
    }
}

/// Model (i) with no emission and no background is linear in the light
/// intensity. Pixels in f64 agree to a few roundings; the f32 image to the two
/// f32 roundings of the values compared.
#[test]
fn light_intensity_scales_the_image_linearly() {
    let scene_with = |intensity: f32| {
        let mut lights = three_lights();
        for l in &mut lights {
            l.intensity = intensity;
        }
        slab_scene(true, lights)
    };
    let unit = scene_with(1.0);
    let unit_image = render_cpu(&unit, SINGLE, 12, 12).unwrap();
    let unit_pixel = render_pixel_cpu(&unit, SINGLE, 12, 12, 6, 9).unwrap();
    assert!(unit_pixel[0] > 0.0);
    for k in [1e-6f32, 1e6] {
        let scene = scene_with(k);
        let k = k as f64;
        let pixel = render_pixel_cpu(&scene, SINGLE, 12, 12, 6, 9).unwrap();
        for c in 0..3 {
            let want = k * unit_pixel[c];
            assert!((pixel[c] - want).abs() <= 1e-13 * want, "{k}: {pixel:?}");
        }
        let image = render_cpu(&scene, SINGLE, 12, 12).unwrap();
        assert!(image.all_finite());
        for (a, b) in image.pixels.iter().zip(&unit_image.pixels) {
            for c in 0..3 {
                let want = k * b[c] as f64;
                let tol = f32::EPSILON as f64 * 1.001 * want;
                assert!((a[c] as f64 - want).abs() <= tol, "{k}: {a:?} vs {b:?}");
            }
        }
    }
}

#[test]
fn grazing_and_axis_parallel_directional_lights_are_finite_and_continuous() {
    let render = |direction: Vec3| {
        let scene = slab_scene(true, vec![directional(direction, Vec3::ONE, 1.0)]);
        let image = render_cpu(&scene, SINGLE, 12, 12).unwrap();
        assert!(image.all_finite(), "{direction}");
        image
    };
    let parallel = render(Vec3::X);
    let grazing = render(Vec3::new(1.0, -1e-7, 0.0));
    let upward_grazing = render(Vec3::new(1.0, 1e-7, 1e-7));
    assert!(parallel.max_value() > 0.0);
    // Shadow rays tilted by 1e-7 over at most ~1.7 world units move by < 1e-6
    // world, a hundred-thousandth of a voxel.
    for other in [&grazing, &upward_grazing] {
        for (a, b) in parallel.pixels.iter().zip(&other.pixels) {
            assert!((0..3).all(|c| (a[c] - b[c]).abs() < 1e-5), "{a:?} {b:?}");
        }
    }
}

#[test]
fn near_opaque_medium_stays_finite() {
    let light = directional(Vec3::new(0.3, -1.0, 0.2), Vec3::ONE, 1.0);
    let mut scene =
        tiny_scene(constant_volume(16), constant_transfer([0.9, 0.7, 0.5], transfer::MAX_ALPHA), vec![light]);
    scene.render.emission = 0.1;
    for kind in [CpuRenderKind::Dvr, CpuRenderKind::Phong, SINGLE, EMISSIVE] {
        let image = render_cpu(&scene, kind, 8, 8).unwrap();
        assert!(image.all_finite(), "{kind:?}");
        // Nothing can exceed the brightest source term (rgb <= 1, emission +
        // light <= 1.1, plus El <= 0.1 for model (ii); Phong <= 1.1).
        assert!(image.max_value() <= 1.2, "{kind:?}");
    }
}

// --------------------------------------------------------------- plumbing

#[test]
fn rays_that_miss_the_box_see_the_background() {
    let mut scene = tiny_scene(constant_volume(8), constant_transfer([1.0; 3], 0.5), vec![]);
    scene.camera.eye = Vec3::new(3.0, 0.0, 0.0);
    scene.camera.target = Vec3::new(3.0, 0.0, -1.0);
    for kind in [CpuRenderKind::Dvr, CpuRenderKind::Phong, SINGLE, EMISSIVE] {
        let image = render_cpu(&scene, kind, 5, 4).unwrap();
        assert!(image.pixels.iter().all(|p| *p == [0.1, 0.2, 0.3]));
    }
}

#[test]
fn image_is_the_pixels_in_row_order_and_deterministic() {
    let mut scene = slab_scene(true, three_lights());
    scene.camera = Camera::orbit(Vec3::ZERO, 2.5, 30.0, 20.0, Projection::Perspective { fov_y_deg: 35.0 });
    let (w, h) = (13, 7);
    let image = render_cpu(&scene, SINGLE, w, h).unwrap();
    assert_eq!((image.width, image.height), (w, h));
    assert_eq!(image, render_cpu(&scene, SINGLE, w, h).unwrap());
    for (x, y) in [(0, 0), (12, 0), (6, 3), (2, 6), (12, 6)] {
        let p = render_pixel_cpu(&scene, SINGLE, w, h, x, y).unwrap();
        assert_eq!(image.get(x, y), p.map(|c| c as f32), "({x}, {y})");
    }
}

#[test]
fn invalid_settings_are_errors_not_panics() {
    let base = tiny_scene(constant_volume(4), constant_transfer([1.0; 3], 0.5), vec![]);
    let mut zero_step = base.clone();
    zero_step.reference.shadow_step_voxels = 0.0;
    assert!(matches!(
        render_cpu(&zero_step, SINGLE, 4, 4),
        Err(CpuRenderError::Step { setting: "reference.shadow_step_voxels", .. })
    ));
    let mut nan_step = base.clone();
    nan_step.render.step_voxels = f32::NAN;
    assert!(render_cpu(&nan_step, CpuRenderKind::Dvr, 4, 4).is_err());
    let mut bad_light = base.clone();
    bad_light.lights = vec![directional(Vec3::NEG_Y, Vec3::ONE, f32::INFINITY)];
    assert!(matches!(render_cpu(&bad_light, SINGLE, 4, 4), Err(CpuRenderError::Light { index: 0, .. })));
    let mut short = base.clone();
    short.volume.dims = UVec3::new(4, 4, 5);
    assert!(matches!(render_cpu(&short, CpuRenderKind::Dvr, 4, 4), Err(CpuRenderError::Volume { .. })));
    assert!(matches!(
        render_pixel_cpu(&base, CpuRenderKind::Dvr, 4, 4, 4, 0),
        Err(CpuRenderError::PixelOutOfRange { .. })
    ));
}
