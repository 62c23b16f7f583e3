//! Where a technique that holds light on a grid (IPSVI's cache, half-angle's
//! light buffer, the light volume) cannot keep its stated bound against the
//! reference of its model: a named warning each, which the command line prints
//! and the stability table counts as a warning, not a pass (never a
//! silent wrong image). The thresholds are where the table's cells left their
//! bounds on lavapipe (docs/stability.md).

use crate::scene::{Scene, TransferLut};

/// Optical depth per voxel above which light falls by 95 % within one voxel:
/// far finer than the light grids resolve (their cells and light steps are
/// 0.5 to 2 voxels). Measured: IPSVI, half-angle and the light volume keep
/// their bounds up to 2.3 (three-spheres, soft edges) and leave them at 6.9
/// to 13.8 (opacity 0.999 to 1) by 15 to 30 dB.
pub const STIFF_OPTICAL_DEPTH: f32 = 3.0;

/// Optical depth per voxel at the volume's faces above which a face voxel is
/// dense: the box cuts the medium there with a hard edge the light grids blur
/// across (measured: opacity 0.5 or a transfer-function step over the faces
/// cost 2 to 16 dB below the bounds).
pub const DENSE_FACE_OPTICAL_DEPTH: f32 = 0.3;

/// Share of the face voxels that must be dense before the cut matters: a
/// medium the box cuts over much of its faces, not a few voxels of an object
/// touching them. Measured: engine.toml 0.001 % (up to 0.36), noise.toml 5 %,
/// the Cornell box's walls 87 %, the table's dense 16^3 noise up to 100 %;
/// the table's isolated +inf voxels on the faces (1 %) stay within the bounds.
pub const DENSE_FACE_SHARE: f64 = 0.1;

/// Half-angle slicing below this many slices through the volume leaves its
/// bound (measured: 7 slices at step 4 on 16^3 gave 21 dB, 4 slices through
/// one voxel 18 dB, 55 slices 42 dB).
pub const MIN_HALF_ANGLE_SLICES: u32 = 16;

/// The largest optical depth per voxel the transfer function gives a value of
/// the volume (as the lookup table every renderer reads holds it).
pub fn steepest_optical_depth(scene: &Scene) -> f32 {
    let (lo, hi) = scene.volume.normalized_range();
    let lut = scene.transfer.bake(TransferLut::DEFAULT_SIZE);
    let n = lut.texels.len() as f32;
    // Texels whose filtering reaches a value in [lo, hi].
    let first = ((lo * n - 1.5).floor().max(0.0)) as usize;
    let last = ((hi * n + 0.5).ceil() as usize).min(lut.texels.len() - 1);
    lut.texels[first.min(last)..=last].iter().map(|t| t[3]).fold(0.0, f32::max)
}

/// The voxels on the volume's faces: the largest optical depth per voxel among
/// them, and the share denser than [`DENSE_FACE_OPTICAL_DEPTH`].
pub fn face_optical_depth(scene: &Scene) -> (f32, f64) {
    let v = &scene.volume;
    let lut = scene.transfer.bake(TransferLut::DEFAULT_SIZE);
    let d = v.dims;
    let (mut most, mut dense, mut count) = (0.0f32, 0u64, 0u64);
    let mut visit = |x: u32, y: u32, z: u32| {
        let sigma = lut.sample(v.voxel(x, y, z) as f64)[3] as f32;
        most = most.max(sigma);
        dense += (sigma > DENSE_FACE_OPTICAL_DEPTH) as u64;
        count += 1;
    };
    for a in 0..d.x {
        for b in 0..d.y {
            visit(a, b, 0);
            visit(a, b, d.z - 1);
        }
        for c in 0..d.z {
            visit(a, 0, c);
            visit(a, d.y - 1, c);
        }
    }
    for b in 0..d.y {
        for c in 0..d.z {
            visit(0, b, c);
            visit(d.x - 1, b, c);
        }
    }
    (most, dense as f64 / count.max(1) as f64)
}

/// What stops a technique from resolving light that falls within a voxel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StiffLimit {
    /// Its light grid (half-angle's light buffer, the light volume's cells).
    LightGrid,
    /// Its view step: the light is exact along each sample's light ray, but a
    /// view sample stands for a step over which the light changes (IPSVI; the
    /// reference alike, at its own step). Measured at equal view steps IPSVI
    /// keeps its bound on the table's stiff cases (docs/stability.md).
    ViewStep,
}

/// A stiff medium, or a dense one cut by the volume's faces: light falls
/// faster, or more abruptly, than `technique` resolves.
pub fn stiff_medium(scene: &Scene, technique: &str, limit: StiffLimit) -> Option<String> {
    let opacity = |sigma: f32| 1.0 - (-sigma).exp();
    let sigma = steepest_optical_depth(scene);
    if sigma > STIFF_OPTICAL_DEPTH {
        let why = match limit {
            StiffLimit::LightGrid => {
                format!("faster than {technique}'s light grid resolves, so its image may be far from the reference")
            }
            StiffLimit::ViewStep => format!(
                "within one view step (render.step = {} voxel): its image, as the reference's, depends on the step \
                 until render.step is well below 1/{sigma:.1} = {:.3} voxel, so it may be far from a reference at \
                 another reference.step",
                scene.render.step_voxels,
                1.0 / sigma
            ),
        };
        return Some(format!(
            "{technique}: the transfer function gives the volume an optical depth of up to {sigma:.2} per voxel \
             (opacity {:.3}): light falls by more than 95 % within one voxel, {why} (docs/stability.md)",
            opacity(sigma)
        ));
    }
    let (face, share) = face_optical_depth(scene);
    (share > DENSE_FACE_SHARE).then(|| {
        format!(
            "{technique}: {:.0} % of the volume's faces hold a dense medium (optical depth up to {face:.2} per voxel, \
             opacity {:.3}): the box cuts it with a hard edge that {technique}'s light grid blurs, so its image may \
             be far from the reference (docs/stability.md)",
            share * 100.0,
            opacity(face)
        )
    })
}

/// The camera inside the volume's box, where `technique` marches from the eye.
pub fn camera_inside(scene: &Scene, technique: &str) -> Option<String> {
    let half = scene.volume_box().half_extent;
    let eye = scene.camera.eye;
    (eye.abs().cmplt(half).all()).then(|| {
        format!(
            "{technique}: the camera at {eye} is inside the volume (half extent {half}): its light reaches samples \
             beside the eye coarsely, so its image may be far from the reference (docs/stability.md)"
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::scene_file::scene_from_toml_str;
    use crate::scene::technique_settings::NoTechniqueTables;

    fn scene(tf: &str, camera: &str) -> Scene {
        let text = format!("[volume]\nsynthetic = \"noise\"\nsize = 8\n[transfer]\n{tf}\n{camera}");
        scene_from_toml_str(&NoTechniqueTables, &text, std::path::Path::new(""), "test", &[]).unwrap()
    }

    #[test]
    fn a_stiff_medium_is_named_and_an_ordinary_one_is_not() {
        let ramp = scene("preset = \"grayscale-ramp\"", "");
        assert!((steepest_optical_depth(&ramp) - 0.105).abs() < 0.01, "{}", steepest_optical_depth(&ramp));
        assert_eq!(stiff_medium(&ramp, "ipsvi", StiffLimit::ViewStep), None);
        let opaque = scene("points = [[0.0, 1, 1, 1, 1], [1.0, 1, 1, 1, 1]]", "");
        let w = stiff_medium(&opaque, "ipsvi", StiffLimit::ViewStep).unwrap();
        assert!(w.contains("ipsvi") && w.contains("13.8") && w.contains("optical depth"), "{w}");
        assert!(w.contains("render.step = 0.5") && w.contains("0.072 voxel"), "{w}");
        let w = stiff_medium(&opaque, "half-angle", StiffLimit::LightGrid).unwrap();
        assert!(w.contains("half-angle's light grid"), "{w}");
        // Opacity 0.5 everywhere: not stiff, but the faces cut it.
        let half = scene("points = [[0.0, 1, 1, 1, 0.5], [1.0, 1, 1, 1, 0.5]]", "");
        assert!(stiff_medium(&half, "lightvolume", StiffLimit::LightGrid)
            .unwrap()
            .contains("faces hold a dense medium"));
        // Opaque only above every value of the volume: not stiff where it is.
        let mut outside = scene("points = [[0.0, 1, 1, 1, 0], [0.6, 1, 1, 1, 0], [0.7, 1, 1, 1, 1]]", "");
        let count = outside.volume.voxel_count();
        outside.volume.data = crate::scene::VoxelData::F32((0..count).map(|i| 0.2 + 0.3 * (i % 2) as f32).collect());
        assert_eq!(stiff_medium(&outside, "ipsvi", StiffLimit::ViewStep), None);
        outside.volume.data = crate::scene::VoxelData::F32((0..count).map(|i| 0.2 + 0.5 * (i % 2) as f32).collect());
        assert!(
            stiff_medium(&outside, "ipsvi", StiffLimit::ViewStep).is_some_and(|w| w.contains("13.8")),
            "0.7 reaches the opaque end"
        );
    }

    #[test]
    fn a_camera_inside_the_box_is_named() {
        let orbit = scene("preset = \"grayscale-ramp\"", "");
        assert_eq!(camera_inside(&orbit, "half-angle"), None);
        let inside = scene(
            "preset = \"grayscale-ramp\"",
            "[camera]\neye = [0.05, 0.1, 0.2]\ntarget = [0.0, 0.0, -1.0]\nup = [0.0, 1.0, 0.0]",
        );
        assert!(camera_inside(&inside, "half-angle").unwrap().contains("inside the volume"));
    }
}
