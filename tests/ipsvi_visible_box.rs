//! IPSVI's cache fitted to the visible cells (`fit_to_visible`) and the cache
//! texel's width in pixels: tolerances kept, exact where all is visible, why
//! view samples lose on a cache finer than their spacing, and the width that
//! `render`, `compare` and `bench ipsvi` print, and the cache sized from it.
use crate::common;
use crate::ipsvi_view_samples::{
    ipsvi, reference, relative_rmse, view_samples, DIRECTIONAL_TOLERANCE, FED_CACHE, POINT_TOLERANCE, SIZE,
};

use common::*;
use glam::Vec3;
use sweeplab::render::{GpuScene, VolumeTexels};
use sweeplab::scene::{ControlPoint, Light, LightKind, Scene, TransferFunction, VolumeFilter};
use sweeplab::techniques::ipsvi::cache_plane::{auto_cache_size, texel_pixels, AUTO_CACHE_MIN, AUTO_TEXEL_PX};
use sweeplab::techniques::ipsvi::{CacheUpdate, CacheWrite, IpsviSettings, ReadFronts, SyncStrategy, WriteRule};
/// A sphere of radius 7 voxels in a 32^3 box, only its inside visible (the
/// values below 0.3 have no extinction), under `light`, side x side pixels.
pub(crate) fn visible_sphere(light: Light, side: u32) -> Scene {
    let mut scene = scene_with(sphere_volume(32, 7.0), vec![light], side, side);
    reference_settings(&mut scene);
    scene.transfer = TransferFunction {
        points: vec![
            ControlPoint { value: 0.0, rgba: [0.0, 0.0, 0.0, 0.0] },
            ControlPoint { value: 0.3, rgba: [0.9, 0.6, 0.3, 0.0] },
            ControlPoint { value: 1.0, rgba: [0.9, 0.8, 0.7, 0.6] },
        ],
    };
    scene
}

/// `fit_to_visible`: a sphere of radius 7 voxels in a 32^3 box, lit by a
/// directional and a point light. Fitted to the box of the cells the transfer
/// function can show, every mode stays within its stated tolerance; light rays
/// (both lights) and view samples (directional light, both write rules) come
/// nearer the ground truth than with the volume box; with the point light,
/// view samples do not (every-sample 0.0037 -> 0.0047, printed: the cache is
/// then finer than the view samples can feed, see the next test). Where every
/// value is visible that box is the volume's and the image the same bit for bit.
#[test]
fn the_cache_fitted_to_the_visible_cells_keeps_its_tolerance_and_is_exact_where_all_is_visible() {
    let ctx = validated_context();
    let lights = [directional(Vec3::new(0.3, -1.0, 0.2), 2.0), point(Vec3::new(1.6, 0.4, 0.3))];
    let modes = [
        IpsviSettings { write_rule: WriteRule::NonEmpty, ..view_samples(FED_CACHE, CacheWrite::Farthest) },
        IpsviSettings { write_rule: WriteRule::EverySample, ..view_samples(FED_CACHE, CacheWrite::Farthest) },
        IpsviSettings { cache_update: CacheUpdate::LightRays, ..view_samples(FED_CACHE, CacheWrite::Farthest) },
    ];
    for light in lights {
        let scene = visible_sphere(light, SIZE);
        let gpu = GpuScene::upload_with(&ctx, &scene, VolumeTexels::Float32).unwrap();
        let truth = reference(&ctx, &gpu);
        for volume_box in &modes {
            let fitted = IpsviSettings { fit_to_visible: true, ..volume_box.clone() };
            let (a, b) = (
                ipsvi(&ctx, &gpu, volume_box, SyncStrategy::BarrierGlobal),
                ipsvi(&ctx, &gpu, &fitted, SyncStrategy::BarrierGlobal),
            );
            let (ea, eb) = (relative_rmse(&a, &truth), relative_rmse(&b, &truth));
            let what = format!("{:?}, {:?} {:?}", light.kind, volume_box.cache_update, volume_box.write_rule);
            println!("{what}: relative RMSE volume box {ea:.5}, visible box {eb:.5}");
            assert!(a != b, "{what}: the fitted cache should change the image");
            // Measured: directional 0.0053 -> 0.0048 (non-empty), 0.0040 -> 0.0028 (every-sample),
            // 0.0040 -> 0.0013 (light rays); point 0.0051 -> 0.0051, 0.0037 -> 0.0047 (every-sample
            // farther: finer texels than the view samples feed, next test), 0.0037 -> 0.0009 (light rays).
            let directional = matches!(light.kind, LightKind::Directional { .. });
            let tolerance = if directional { DIRECTIONAL_TOLERANCE } else { POINT_TOLERANCE };
            assert!(eb <= tolerance, "{what}: {eb:.5} past the stated tolerance {tolerance}");
            if directional || volume_box.cache_update == CacheUpdate::LightRays {
                assert!(eb < ea, "{what}: the visible box {eb:.5} is not nearer the truth than the volume box {ea:.5}");
            }
        }
        // Every value visible: the lit box is the volume box.
        let mut all = scene.clone();
        all.transfer = TransferFunction {
            points: vec![
                ControlPoint { value: 0.0, rgba: [0.5, 0.5, 0.5, 0.02] },
                ControlPoint { value: 1.0, rgba: [0.9, 0.8, 0.7, 0.6] },
            ],
        };
        let gpu = GpuScene::upload_with(&ctx, &all, VolumeTexels::Float32).unwrap();
        for volume_box in &modes {
            let fitted = IpsviSettings { fit_to_visible: true, ..volume_box.clone() };
            let (a, b) = (
                ipsvi(&ctx, &gpu, volume_box, SyncStrategy::BarrierGlobal),
                ipsvi(&ctx, &gpu, &fitted, SyncStrategy::BarrierGlobal),
            );
            assert!(
                a == b,
                "{:?} {:?}: the volume box, fitted, must give the same image",
                light.kind,
                volume_box.cache_update
            );
        }
    }
    assert_validation_clean(&ctx);
}

/// Why the visible box takes view samples (under a point light) farther from
/// the truth on this sphere although it takes light rays nearer: it makes the
/// cache's texels finer (about half as wide here), and a view-sample cache has
/// an optimum texel size near the view samples' own spacing (about a pixel's
/// footprint): finer texels are written by fewer samples each and lag behind
/// the sweep, while light rays advance every texel and only gain. Shown without
/// the visible box: the volume box's cache at twice the resolution errs the
/// same way, and the visible box's error is nearer the volume box's at the same
/// texel size than at the same texel count.
#[test]
fn the_visible_box_errs_for_view_samples_only_by_refining_the_cache_past_their_spacing() {
    use sweeplab::render::light_space::LightSpacePlane;
    use sweeplab::scene::transfer::TransferLut;
    use sweeplab::techniques::ipsvi::lit_box::lit_box;

    let ctx = validated_context();
    let light = point(Vec3::new(1.6, 0.4, 0.3));
    let scene = visible_sphere(light, SIZE);
    // The volume box's cache size whose texel is nearest the visible box's at FED_CACHE.
    let bx = scene.volume_box();
    let lit = lit_box(&scene.volume, &scene.transfer.bake(TransferLut::DEFAULT_SIZE), &bx);
    let radius = bx.half_extent.length();
    let texel = |corners: &[Vec3; 8], size: u32| LightSpacePlane::fit_to(&light.kind, corners, radius, size).texel;
    let (volume_texel, fitted_texel) = (texel(&bx.corners(), FED_CACHE), texel(&lit.corners(), FED_CACHE));
    assert!(
        fitted_texel < 0.7 * volume_texel,
        "the visible box should refine the cache: {fitted_texel} {volume_texel}"
    );
    let off = |size: u32| (texel(&bx.corners(), size) / fitted_texel - 1.0).abs();
    let same_texel = (FED_CACHE..8 * FED_CACHE).min_by(|&a, &b| off(a).total_cmp(&off(b))).unwrap();
    assert!(off(same_texel) < 0.05, "cache {same_texel}: texel {} off the visible box's", off(same_texel));

    // Both filters (docs/filtering.md): the mechanism is the cache's, not the sampler's.
    for filter in VolumeFilter::ALL {
        let mut scene = scene.clone();
        scene.render.filter = filter;
        let gpu = GpuScene::upload_with(&ctx, &scene, VolumeTexels::Float32).unwrap();
        let truth = reference(&ctx, &gpu);
        // Blended fronts: the mechanism below is theirs. Per-texel fronts, which
        // `read_fronts = "auto"` takes on texels under a pixel, keep a fine
        // texel from lagging (checked after the loop).
        let every = IpsviSettings {
            write_rule: WriteRule::EverySample,
            read_fronts: ReadFronts::Blended,
            ..view_samples(FED_CACHE, CacheWrite::Farthest)
        };
        let error = |s: &IpsviSettings| relative_rmse(&ipsvi(&ctx, &gpu, s, SyncStrategy::BarrierGlobal), &truth);
        let with = |cache_size: u32, fit_to_visible: bool, s: &IpsviSettings| {
            error(&IpsviSettings { cache_size, fit_to_visible, ..s.clone() })
        };
        let volume = with(FED_CACHE, false, &every);
        let (fitted, volume_finer) = (with(FED_CACHE, true, &every), with(2 * FED_CACHE, false, &every));
        let volume_same_texel = with(same_texel, false, &every);
        println!(
            "{filter:?}, every-sample: volume box {volume:.5} (cache {FED_CACHE}), {volume_finer:.5} (cache {}), \
             {volume_same_texel:.5} (cache {same_texel}, the visible box's texel); visible box {fitted:.5} (cache {FED_CACHE})",
            2 * FED_CACHE
        );
        // Measured (exact filter): 0.00370, 0.00485, 0.00502 (cache 104); 0.00465.
        assert!(fitted > volume, "the visible box at {FED_CACHE} no longer errs for view samples: update the docs");
        assert!(volume_finer > volume, "finer texels, volume box: {volume_finer:.5} not farther than {volume:.5}");
        assert!(
            (fitted - volume_same_texel).abs() < (fitted - volume).abs(),
            "the visible box {fitted:.5} is not nearer the volume box at its texel size ({volume_same_texel:.5}) \
             than at its texel count ({volume:.5})"
        );
        // Light rays advance every texel: finer is nearer (0.0037 -> 0.0010 measured).
        let rays = IpsviSettings { cache_update: CacheUpdate::LightRays, ..every.clone() };
        let (coarse, fine) = (with(FED_CACHE, false, &rays), with(2 * FED_CACHE, false, &rays));
        assert!(fine < coarse, "light rays, finer cache: {fine:.5} not nearer than {coarse:.5}");
        // The default fronts on these sub-pixel texels are per texel: there the
        // visible box takes view samples nearer too (measured, exact filter:
        // 0.00206 against 0.00370).
        let auto = IpsviSettings { read_fronts: ReadFronts::Auto, ..every.clone() };
        let (auto_volume, auto_fitted) = (with(FED_CACHE, false, &auto), with(FED_CACHE, true, &auto));
        println!("{filter:?}, every-sample, auto fronts: volume box {auto_volume:.5}, visible box {auto_fitted:.5}");
        assert!(
            auto_fitted < auto_volume,
            "auto fronts: the visible box {auto_fitted:.5} not nearer than {auto_volume:.5}"
        );
    }
    assert_validation_clean(&ctx);
}

/// The cache texel's width in pixels that `render`, `compare` and `bench ipsvi`
/// report: half as wide for twice the texels, twice as wide for twice the
/// pixels, narrower with the visible box, none without a light.
#[test]
fn the_printed_texel_width_follows_the_cache_the_image_and_the_box() {
    for light in [directional(Vec3::new(0.3, -1.0, 0.2), 2.0), point(Vec3::new(1.6, 0.4, 0.3))] {
        let mut scene = visible_sphere(light, 64);
        // square()'s texel is side / (size - 2).
        let s = IpsviSettings { cache_size: 66, ..IpsviSettings::default() };
        let width = |s: &IpsviSettings, side: u32| texel_pixels(&scene, s, side, side);
        let base = width(&s, 64).unwrap();
        let finer = width(&IpsviSettings { cache_size: 130, ..s.clone() }, 64).unwrap();
        assert!((finer / base - 0.5).abs() < 1e-4, "{:?}: {base} {finer}", light.kind);
        let fitted = width(&IpsviSettings { fit_to_visible: true, ..s.clone() }, 64).unwrap();
        assert!(fitted < 0.7 * base, "{:?}: visible box {fitted} against {base}", light.kind);
        let more_pixels = width(&s, 128).unwrap();
        assert!((more_pixels / base - 2.0).abs() < 1e-3, "{:?}: {base} {more_pixels}", light.kind);
        scene.lights.clear();
        assert_eq!(texel_pixels(&scene, &s, 64, 64), None);
    }
}

/// The texel width of a `size`-texel cache in a `side` x `side` image.
fn auto_px(scene: &Scene, size: u32, side: u32) -> f32 {
    let s = IpsviSettings { cache_size: size, ..IpsviSettings::default() };
    texel_pixels(scene, &s, side, side).expect("the scene has a light")
}

/// `cache_size = 0` (the default): 256 texels where their texel fits in
/// 1.5 px, else the smallest multiple of 16 that fits, at most the image's
/// longer side; a size set is kept.
#[test]
fn auto_cache_is_the_smallest_multiple_of_16_whose_texel_fits_and_no_larger_than_the_image() {
    let mut scene = sweeplab::techniques::default_scene(&["volume.size=8".to_string()]).unwrap();
    let auto = IpsviSettings::default();
    assert_eq!(auto.cache_size, 0, "the default is sized per image");
    let mut grown = 0;
    for side in [64, 256, 512, 1024, 2048] {
        let size = auto_cache_size(&scene, &auto, side, side);
        assert_eq!(auto.sized_for(&scene, side, side).cache_size, size);
        if auto_px(&scene, AUTO_CACHE_MIN, side) <= AUTO_TEXEL_PX {
            assert_eq!(size, AUTO_CACHE_MIN, "{side}: 256 texels fit");
            continue;
        }
        grown += 1;
        assert!(size.is_multiple_of(16) && size < side.max(AUTO_CACHE_MIN), "{side}: {size}");
        assert!(auto_px(&scene, size, side) <= AUTO_TEXEL_PX, "{side}: {size} texels too wide");
        assert!(auto_px(&scene, size - 16, side) > AUTO_TEXEL_PX, "{side}: {size} is not the smallest");
    }
    assert!(grown >= 2, "the sides grow the cache {grown} times");
    // A size the scene sets is kept.
    let set = IpsviSettings { cache_size: 64, ..auto.clone() };
    assert_eq!(set.sized_for(&scene, 2048, 2048).cache_size, 64);
    // Zoomed in, a texel would need more texels than the image has pixels.
    scene.camera.projection = sweeplab::scene::Projection::Perspective { fov_y_deg: 2.0 };
    assert!(auto_px(&scene, 512, 512) > AUTO_TEXEL_PX);
    assert_eq!(auto_cache_size(&scene, &auto, 512, 500), 512);
    assert_eq!(auto_cache_size(&scene, &auto, 100, 100), AUTO_CACHE_MIN);
}
