//! Every device limit the engine relies on, checked before GPU work
//! (src/vk/limits.rs, src/render/device_fit.rs): the error names the limit, the
//! device's value and the setting to change; each technique's needs against
//! the Vulkan spec's guaranteed minimum limits and typical desktop limits say
//! which techniques and sizes each can run.
use crate::common;

use common::*;
use glam::{UVec3, Vec3};
use sweeplab::render::device_fit;
use sweeplab::render::GpuScene;
use sweeplab::scene::synthetic::three_spheres;
use sweeplab::scene::{Scene, Volume, VoxelData};
use sweeplab::techniques::{render, Technique};
use sweeplab::vk::commands::submit_and_wait;
use sweeplab::vk::limits::{DeviceLimits, DESKTOP, SPEC_MINIMUM};
use sweeplab::vk::Profiler;

fn long_volume(length: u32) -> Volume {
    let dims = UVec3::new(length, 2, 2);
    Volume {
        name: format!("long-{length}"),
        dims,
        spacing: Vec3::ONE,
        data: VoxelData::U8(vec![100; (dims.x * dims.y * dims.z) as usize]),
        value_range: (0.0, 255.0),
        non_finite_voxels: 0,
        interpolation: Default::default(),
    }
}

fn scene(volume: Volume) -> Scene {
    scene_with(volume, vec![directional(Vec3::new(0.3, -1.0, 0.2), 1.0)], 64, 64)
}

/// Which (technique, image size) of a 64^3 volume each table row can run, and
/// which volume lengths: printed as the table docs/native-gpu.md quotes, and
/// checked where the limits decide it.
#[test]
fn each_technique_against_the_spec_minimum_and_desktop_limits() {
    let spheres = scene(three_spheres(64));
    let rows: Vec<(&str, DeviceLimits)> =
        std::iter::once(("Vulkan spec minimum", SPEC_MINIMUM)).chain(DESKTOP).collect();
    for (device, limits) in &rows {
        let mut line = format!("{device}:");
        for technique in Technique::named() {
            let largest = [256u32, 512, 1024, 2048, 4096, 8192]
                .into_iter()
                .filter(|&s| device_fit::check(limits, device, &*technique, &spheres, s, s).is_ok())
                .max();
            line += &format!(" {} up to {}", technique.name(), largest.map_or("none".into(), |s| format!("{s}^2")));
        }
        let longest = [256u32, 2048, 4096, 8192, 16384]
            .into_iter()
            .filter(|&n| {
                limits.check(device, &device_fit::needs(&*Technique::Dvr, &scene(long_volume(n)), 64, 64)).is_ok()
            })
            .max();
        println!("{line}; volumes up to {longest:?} voxels long");
    }
    // The spec minimum's 3D images are 256 long: a 257-long volume is refused
    // by name; every desktop row takes the 64^3 scene at 1024^2 everywhere.
    let e = device_fit::check(&SPEC_MINIMUM, "spec minimum", &*Technique::Dvr, &scene(long_volume(257)), 64, 64)
        .unwrap_err()
        .to_string();
    assert!(e.contains("maxImageDimension3D = 257") && e.contains("has 256") && e.contains("resample"), "{e}");
    for (device, limits) in DESKTOP {
        for technique in Technique::named() {
            device_fit::check(&limits, device, &*technique, &spheres, 1024, 1024)
                .unwrap_or_else(|e| panic!("{device}: {} at 1024^2: {e}", technique.name()));
        }
    }
    // RADV's and ANV's 2048 refuse a 4096-long volume that NVIDIA's driver takes.
    let long = scene(long_volume(4096));
    let fits = |l: &DeviceLimits| l.check("d", &device_fit::needs(&*Technique::Dvr, &long, 64, 64)).is_ok();
    assert!(fits(&DESKTOP[0].1) && !fits(&DESKTOP[1].1) && !fits(&DESKTOP[2].1));
}

/// On this device: a volume one voxel longer than its `maxImageDimension3D` is
/// refused at upload, before any GPU work, naming limit, value and setting.
#[test]
fn a_volume_over_the_device_limit_is_refused_before_upload() {
    let ctx = validated_context();
    let limit = ctx.limits.max_image_dimension3_d;
    let s = scene(long_volume(limit + 1));
    let e = GpuScene::upload(&ctx, &s).err().expect("a volume over the limit must be refused").to_string();
    assert!(e.contains("maxImageDimension3D") && e.contains(&format!("has {limit}")) && e.contains("resample"), "{e}");
    assert_validation_clean(&ctx);
}

/// A dispatch over `maxComputeWorkGroupCount` (here lowered on the context to
/// stand for a smaller device) is not recorded and its submission refused;
/// the frame check refuses an image too wide for the 8x8 passes first.
#[test]
fn dispatches_over_the_work_group_count_are_refused_before_submission() {
    let mut ctx = validated_context();
    ctx.limits.max_compute_work_group_count = [4, 4, 4];
    let e = submit_and_wait(&ctx, "too_many_groups", |rec| {
        rec.begin_label("wide pass");
        rec.dispatch(5, 1, 1);
        rec.end_label();
        Ok(())
    })
    .expect_err("over the limit")
    .to_string();
    assert!(e.contains("maxComputeWorkGroupCount[0] = 5") && e.contains("has 4") && e.contains("wide pass"), "{e}");
    let s = scene(three_spheres(16));
    let gpu = GpuScene::upload(&ctx, &s).unwrap();
    let mut profiler = Profiler::new(&ctx, 64).unwrap();
    let e = render(&gpu, Technique::Dvr, 64, 64, &mut profiler).err().expect("too wide").to_string();
    assert!(e.contains("maxComputeWorkGroupCount[0] = 8") && e.contains("--size"), "{e}");
    render(&gpu, Technique::Dvr, 32, 32, &mut profiler).unwrap();
    assert_validation_clean(&ctx);
}
