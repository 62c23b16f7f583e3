//! What the CPU renderer refuses to march: scene values that would loop forever,
//! index out of bounds, or turn every pixel into NaN. Each error names the
//! offending setting and value.

use glam::Vec3;

use super::cpu::CpuRenderKind;
use crate::scene::{Light, LightKind, Projection, Scene, VoxelData};

#[derive(Debug, thiserror::Error)]
pub enum CpuRenderError {
    #[error("volume {name}: {problem}")]
    Volume { name: String, problem: String },
    #[error("transfer function control point {index}: {problem}")]
    Transfer { index: usize, problem: String },
    #[error("{setting} must be a finite number above 0, got {value}")]
    Step { setting: &'static str, value: f32 },
    #[error("{setting} must be finite, got {value}")]
    NotFinite { setting: &'static str, value: String },
    #[error("light {index}: {problem}")]
    Light { index: usize, problem: String },
    #[error("reference.chromatic = true needs reference.model = \"single-scattering\", got {model:?}")]
    ChromaticModel { model: crate::scene::OpticalModel },
    #[error("pixel ({x}, {y}) is outside the {width}x{height} image")]
    PixelOutOfRange { x: u32, y: u32, width: u32, height: u32 },
    #[error("{0}")]
    Unsupported(String),
}

pub fn check_scene(scene: &Scene, kind: CpuRenderKind) -> Result<(), CpuRenderError> {
    check_volume(scene)?;
    check_transfer(scene)?;
    check_settings(scene, kind)?;
    for (index, light) in scene.lights.iter().enumerate() {
        check_light(index, light)?;
    }
    Ok(())
}

fn check_volume(scene: &Scene) -> Result<(), CpuRenderError> {
    let v = &scene.volume;
    let problem = |problem: String| CpuRenderError::Volume { name: v.name.clone(), problem };
    if v.dims.min_element() == 0 {
        return Err(problem(format!("dimensions {} contain a zero", v.dims)));
    }
    if v.data.len() != v.voxel_count() {
        return Err(problem(format!(
            "holds {} voxels but its dimensions {} need {}",
            v.data.len(),
            v.dims,
            v.voxel_count()
        )));
    }
    if !v.spacing.is_finite() || v.spacing.min_element() <= 0.0 {
        return Err(problem(format!("spacing {} must be finite and above 0", v.spacing)));
    }
    if let VoxelData::F32(values) = &v.data {
        if let Some(i) = values.iter().position(|x| !x.is_finite()) {
            return Err(problem(format!("voxel {i} is {}", values[i])));
        }
    }
    Ok(())
}

fn check_transfer(scene: &Scene) -> Result<(), CpuRenderError> {
    for (index, point) in scene.transfer.points.iter().enumerate() {
        if !point.value.is_finite() || point.rgba.iter().any(|c| !c.is_finite()) {
            return Err(CpuRenderError::Transfer {
                index,
                problem: format!("value {} and rgba {:?} must be finite", point.value, point.rgba),
            });
        }
    }
    Ok(())
}

fn positive_step(setting: &'static str, value: f32) -> Result<(), CpuRenderError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(CpuRenderError::Step { setting, value })
    }
}

fn finite(setting: &'static str, values: &[f32]) -> Result<(), CpuRenderError> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(CpuRenderError::NotFinite { setting, value: format!("{values:?}") })
    }
}

fn check_settings(scene: &Scene, kind: CpuRenderKind) -> Result<(), CpuRenderError> {
    let cam = &scene.camera;
    finite("camera.eye", &cam.eye.to_array())?;
    finite("camera.target", &cam.target.to_array())?;
    finite("camera.up", &cam.up.to_array())?;
    let projection = match cam.projection {
        Projection::Perspective { fov_y_deg } => fov_y_deg,
        Projection::Orthographic { height } => height,
    };
    finite("camera projection", &[projection])?;
    finite("render.background", &scene.render.background.to_array())?;
    match kind {
        CpuRenderKind::Dvr => positive_step("render.step_voxels", scene.render.step_voxels),
        CpuRenderKind::Phong => {
            positive_step("render.step_voxels", scene.render.step_voxels)?;
            let p = &scene.phong;
            finite("phong (ambient, diffuse, specular, shininess)", &[p.ambient, p.diffuse, p.specular, p.shininess])
        }
        CpuRenderKind::Reference(model) => {
            let r = &scene.reference;
            if r.chromatic && model != crate::scene::OpticalModel::SingleScattering {
                return Err(CpuRenderError::ChromaticModel { model });
            }
            positive_step("reference.step_voxels", r.step_voxels)?;
            positive_step("reference.shadow_step_voxels", r.shadow_step_voxels)?;
            finite("reference.min_transmittance", &[r.min_transmittance])?;
            finite("render.emission", &[scene.render.emission])
        }
    }
}

fn check_light(index: usize, light: &Light) -> Result<(), CpuRenderError> {
    let vectors: Vec<Vec3> = match light.kind {
        LightKind::Directional { direction } => vec![direction],
        LightKind::Point { position } => vec![position],
        LightKind::Spot { position, direction, inner_cone_deg, outer_cone_deg } => {
            vec![position, direction, Vec3::new(inner_cone_deg, outer_cone_deg, 0.0)]
        }
    };
    let all_finite = vectors.iter().all(|v| v.is_finite()) && light.color.is_finite() && light.intensity.is_finite();
    if all_finite {
        Ok(())
    } else {
        Err(CpuRenderError::Light { index, problem: format!("every value must be finite: {light:?}") })
    }
}
