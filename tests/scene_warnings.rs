//! A render that would be meaningless says why (all-transparent
//! transfer function, constant volume under the automatic one, NaN/Inf voxels
//! in the file, a light that sends nothing), and a frame with non-finite pixels
//! is an error naming the technique and the count, never a written image.
use crate::common;

use common::cli::{sweeplab, temp_dir};
use common::*;
use glam::Vec3;
use std::path::{Path, PathBuf};
use std::process::Output;
use sweeplab::render::{GpuScene, RenderError, VolumeTexels};
use sweeplab::scene::loaders::load_volume;
use sweeplab::scene::synthetic::noise;
use sweeplab::techniques::{render, Technique};
use sweeplab::vk::Profiler;

/// A 4^3 float NRRD, raw little-endian, with `values` (64 of them).
fn write_float_nrrd(dir: &Path, name: &str, values: &[f32]) -> PathBuf {
    let mut bytes = b"NRRD0004\ntype: float\ndimension: 3\nsizes: 4 4 4\nencoding: raw\nendian: little\n\n".to_vec();
    for v in values {
        bytes.extend_from_slice(&v.to_le_bytes());
    }
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

fn render_volume_file(path: &Path, dir: &Path) -> Output {
    let png = dir.join("out.png");
    sweeplab(&[
        "render",
        "--volume",
        path.to_str().unwrap(),
        "--size",
        "16x16",
        "--technique",
        "dvr",
        "--out",
        png.to_str().unwrap(),
    ])
}

#[test]
fn nan_and_inf_voxels_are_counted_by_the_loader_and_warned_about() {
    let dir = temp_dir("nan");
    let mut values: Vec<f32> = (0..64).map(|i| i as f32).collect();
    values[3] = f32::NAN;
    values[10] = f32::INFINITY;
    values[20] = f32::NEG_INFINITY;
    let path = write_float_nrrd(&dir, "nan.nrrd", &values);
    assert_eq!(load_volume(&path).unwrap().non_finite_voxels, 3);
    let o = render_volume_file(&path, &dir);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("warning: 3 of 64 voxels in the file are NaN or infinite"), "{err}");
}

#[test]
fn a_constant_volume_under_the_automatic_transfer_function_is_warned_about() {
    let dir = temp_dir("constant");
    let path = write_float_nrrd(&dir, "constant.nrrd", &[7.0; 64]);
    let o = render_volume_file(&path, &dir);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("warning: the volume is constant"), "{err}");
    // An ordinary volume: no warning at all.
    let path = write_float_nrrd(&dir, "ramp.nrrd", &(0..64).map(|i| i as f32).collect::<Vec<_>>());
    let o = render_volume_file(&path, &dir);
    assert!(!String::from_utf8_lossy(&o.stderr).contains("warning:"), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn an_all_transparent_transfer_function_is_warned_about() {
    let dir = temp_dir("transparent");
    let scene = dir.join("clear.toml");
    std::fs::write(
        &scene,
        "[volume]\nsynthetic = \"noise\"\nsize = 8\n[transfer]\npoints = [[0.0, 1, 1, 1, 0], [1.0, 1, 1, 1, 0]]\n",
    )
    .unwrap();
    let png = dir.join("out.png");
    let o = sweeplab(&[
        "render",
        "--scene",
        scene.to_str().unwrap(),
        "--size",
        "16x16",
        "--technique",
        "dvr",
        "--out",
        png.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("warning: the transfer function is fully transparent"), "{err}");
}

#[test]
fn a_frame_with_non_finite_pixels_is_an_error_naming_technique_and_count() {
    // An infinite light: Blinn-Phong's inf * 0 on unlit sides gives NaN.
    let scene = scene_with(noise(8, 3), vec![directional(Vec3::new(-1.0, -1.0, -0.5), f32::INFINITY)], 8, 8);
    let ctx = validated_context();
    {
        let gpu = GpuScene::upload_with(&ctx, &scene, VolumeTexels::Float32).unwrap();
        let mut profiler = Profiler::new(&ctx, 4096).unwrap();
        let e = render(&gpu, Technique::Phong, 8, 8, &mut profiler).err().expect("refused");
        match &e {
            RenderError::NonFinite { technique, bad, total } => {
                assert_eq!((*technique, *total), ("phong", 64));
                assert!(*bad > 0 && *bad <= 64);
            }
            other => panic!("{other}"),
        }
        assert!(e.to_string().contains("phong rendered") && e.to_string().contains("of 64 pixels"), "{e}");
        // The same scene without lights in the shading is finite: DVR renders.
        assert!(render(&gpu, Technique::Dvr, 8, 8, &mut profiler).is_ok());
    }
    assert_validation_clean(&ctx);
}
