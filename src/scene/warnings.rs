//! Scenes that load and render but whose image would be meaningless: the
//! library returns these, the command line prints them (never a
//! silent black image).

use super::{Scene, TransferFunction, TransferLut};

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
    #[error(
        "transfer function point {index} (value {value}, alpha {alpha}) is a peak narrower than the lookup table's \
         texel spacing (1/{lut_size}): the baked table gives it at most alpha {seen:.3}, so no sample sees it; widen it"
    )]
    TransferPeakMissed { index: usize, value: f32, alpha: f32, seen: f32, lut_size: usize },
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
    warnings.extend(missed_peaks(&scene.transfer, TransferLut::DEFAULT_SIZE));
    for (index, light) in scene.rendered_lights().iter().enumerate() {
        if light.radiance().max_element() <= 0.0 {
            warnings.push(SceneWarning::DarkLight { index });
        }
    }
    warnings
}

/// Control points whose opacity the baked lookup table of `lut_size` texels
/// loses: every renderer reads the table, filtered linearly between texel
/// centres, so near a point's value it sees at most the larger alpha of the
/// two centres around it. A point shown at less than half its alpha (a spike
/// between two centres) is missed by every sample.
fn missed_peaks(tf: &TransferFunction, lut_size: usize) -> Vec<SceneWarning> {
    let n = lut_size.max(2);
    let centre = |i: usize| (i as f32 + 0.5) / n as f32;
    tf.points
        .iter()
        .enumerate()
        .filter_map(|(index, p)| {
            let below = ((p.value * n as f32 - 0.5).floor().max(0.0) as usize).min(n - 1);
            let seen = [below, (below + 1).min(n - 1)].iter().map(|&i| tf.eval(centre(i))[3]).fold(0.0, f32::max);
            (seen < 0.5 * p.rgba[3]).then_some(SceneWarning::TransferPeakMissed {
                index,
                value: p.value,
                alpha: p.rgba[3],
                seen,
                lut_size: n,
            })
        })
        .collect()
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
    use crate::scene::technique_settings::NoTechniqueTables;
    use crate::scene::VoxelData;

    fn scene(extra: &str) -> Scene {
        let text = format!("[volume]\nsynthetic = \"noise\"\nsize = 8\n{extra}");
        scene_from_toml_str(&NoTechniqueTables, &text, std::path::Path::new(""), "test", &[]).unwrap()
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
    fn a_peak_between_two_lut_texels_is_named_and_a_step_or_a_ramp_is_not() {
        let tf = |points: &[(f32, f32)]| TransferFunction {
            points: points
                .iter()
                .map(|&(value, a)| crate::scene::ControlPoint { value, rgba: [1.0, 1.0, 1.0, a] })
                .collect(),
        };
        // Centres of 1024 texels around 0.6: 0.59912 and 0.60010.
        let needle = tf(&[(0.0, 0.3), (0.5992, 0.3), (0.5996, 1.0), (0.6, 0.3), (1.0, 0.3)]);
        let w = missed_peaks(&needle, 1024);
        assert!(matches!(w[..], [SceneWarning::TransferPeakMissed { index: 2, .. }]), "{w:?}");
        assert!(w[0].to_string().contains("point 2 (value 0.5996, alpha 1)"), "{}", w[0]);
        // Wide enough to reach a texel centre: seen.
        let wide = tf(&[(0.0, 0.3), (0.5985, 0.3), (0.5996, 1.0), (0.6015, 0.3), (1.0, 0.3)]);
        assert_eq!(missed_peaks(&wide, 1024), vec![]);
        let step = tf(&[(0.0, 0.0), (0.5, 0.0), (0.5, 0.6), (1.0, 0.6)]);
        assert_eq!(missed_peaks(&step, 1024), vec![]);
        let ramp = tf(&[(0.0, 0.0), (0.3, 0.9), (1.0, 0.1)]);
        assert_eq!(missed_peaks(&ramp, 1024), vec![]);
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
