//! Scenes that load and render but whose image would be meaningless: the
//! library returns these, the command line prints them (issue 14: never a
//! silent black image).

use super::Scene;

#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SceneWarning {
    #[error(
        "the transfer function is fully transparent over the volume's values (normalized {lo} to {hi}): the image \
         shows only the background"
    )]
    AllTransparent { lo: f32, hi: f32 },
    #[error(
        "the volume is constant (every voxel {value} normalized) and the transfer function gives that value no \
         opacity (the automatic one always does so): the image shows only the background"
    )]
    ConstantVolume { value: f32 },
    #[error(
        "{count} of {total} voxels in the file are NaN or infinite; they render as value 0 (NaN, -inf) or 1 (+inf)"
    )]
    NonFiniteVoxels { count: u64, total: u64 },
    #[error(
        "light {index} sends no light: its colour x intensity (x its falloff at the volume, for a far light) is zero"
    )]
    DarkLight { index: usize },
}

/// Everything about `scene` that makes its image meaningless, or empty.
pub fn scene_warnings(scene: &Scene) -> Vec<SceneWarning> {
    let mut warnings = Vec::new();
    let volume = &scene.volume;
    if volume.non_finite_voxels > 0 {
        warnings.push(SceneWarning::NonFiniteVoxels {
            count: volume.non_finite_voxels,
            total: volume.voxel_count() as u64,
        });
    }
    if volume.voxel_count() > 0 {
        let (lo, hi) = volume.normalized_range();
        if max_opacity(scene, lo, hi) <= 0.0 {
            warnings.push(if lo == hi {
                SceneWarning::ConstantVolume { value: lo }
            } else {
                SceneWarning::AllTransparent { lo, hi }
            });
        }
    }
    for (index, light) in scene.lights.iter().enumerate() {
        if light.radiance().max_element() <= 0.0 {
            warnings.push(SceneWarning::DarkLight { index });
        }
    }
    warnings
}

/// The largest opacity the transfer function gives a value in [lo, hi]: it is
/// piecewise linear, so its ends and the control points between are enough.
/// Trilinear filtering never leaves [lo, hi].
fn max_opacity(scene: &Scene, lo: f32, hi: f32) -> f32 {
    let tf = &scene.transfer;
    let inner = tf.points.iter().filter(|p| p.value > lo && p.value < hi).map(|p| p.rgba[3]);
    inner.chain([tf.eval(lo)[3], tf.eval(hi)[3]]).fold(0.0, f32::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::scene_file::scene_from_toml_str;
    use crate::scene::VoxelData;

    fn scene(extra: &str) -> Scene {
        let text = format!("[volume]\nsynthetic = \"noise\"\nsize = 8\n{extra}");
        scene_from_toml_str(&text, std::path::Path::new(""), "test", &[]).unwrap()
    }

    #[test]
    fn an_ordinary_scene_has_no_warning() {
        assert_eq!(scene_warnings(&scene("")), vec![]);
    }

    #[test]
    fn an_all_transparent_transfer_function_is_named() {
        let mut s = scene("");
        for p in &mut s.transfer.points {
            p.rgba[3] = 0.0;
        }
        let w = scene_warnings(&s);
        assert!(matches!(w[..], [SceneWarning::AllTransparent { .. }]), "{w:?}");
        assert!(w[0].to_string().contains("fully transparent"));
    }

    #[test]
    fn a_transfer_function_opaque_only_outside_the_values_is_transparent_over_them() {
        let mut s = scene("");
        s.volume.data = VoxelData::F32((0..s.volume.voxel_count()).map(|i| 0.2 + 0.1 * (i % 2) as f32).collect());
        s.transfer = crate::scene::TransferFunction::new(vec![
            crate::scene::ControlPoint { value: 0.35, rgba: [1.0, 1.0, 1.0, 0.0] },
            crate::scene::ControlPoint { value: 0.5, rgba: [1.0, 1.0, 1.0, 1.0] },
        ])
        .unwrap();
        assert!(matches!(scene_warnings(&s)[..], [SceneWarning::AllTransparent { .. }]));
        s.transfer.points[0].value = 0.25;
        assert_eq!(scene_warnings(&s), vec![], "a ramp starting inside the values shows them");
    }

    #[test]
    fn a_constant_volume_under_the_automatic_transfer_function_is_named() {
        let mut s = scene("");
        // The loaders map a constant file to 0.
        s.volume.data = VoxelData::F32(vec![0.0; s.volume.voxel_count()]);
        s.transfer = crate::scene::presets::transfer_from_histogram(&s.volume);
        let w = scene_warnings(&s);
        assert!(matches!(w[..], [SceneWarning::ConstantVolume { value }] if value == 0.0), "{w:?}");
    }

    #[test]
    fn non_finite_voxels_and_dark_lights_are_counted() {
        let mut s = scene("[[lights]]\ntype = \"point\"\nposition = [2.0, 0.0, 0.0]\nintensity = 0.0\n");
        s.volume.non_finite_voxels = 3;
        let w = scene_warnings(&s);
        assert!(w.contains(&SceneWarning::NonFiniteVoxels { count: 3, total: 512 }), "{w:?}");
        assert!(w.iter().any(|w| matches!(w, SceneWarning::DarkLight { index: 0 })), "{w:?}");
        assert!(w[0].to_string().contains("3 of 512 voxels"), "{}", w[0]);
    }
}
