//! Host mirrors of the shader-side `Frame` uniform block and `Light` records
//! (glsl/frame.glsl, glsl/lights.glsl): all vec4s, so std140 and std430 agree.

use crate::scene::{Falloff, Light, LightKind, Scene};
use bytemuck::{Pod, Zeroable};

#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct FrameParams {
    pub cam_origin: [f32; 4],
    pub cam_forward: [f32; 4],
    pub cam_right: [f32; 4],
    pub cam_up: [f32; 4],
    pub box_half: [f32; 4],
    pub dims: [f32; 4],
    pub background: [f32; 4],
    pub march: [f32; 4],
    pub phong: [f32; 4],
    pub image_size: [u32; 4],
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuLight {
    pub pos_type: [f32; 4],
    pub spot_dir: [f32; 4],
    pub radiance: [f32; 4],
    pub params: [f32; 4],
}

/// Which step sizes a pass marches with.
#[derive(Clone, Copy, Debug)]
pub struct MarchSteps {
    pub view_step_voxels: f32,
    pub shadow_step_voxels: f32,
    pub min_transmittance: f32,
}

impl MarchSteps {
    pub fn render(scene: &Scene) -> Self {
        MarchSteps {
            view_step_voxels: scene.render.step_voxels,
            shadow_step_voxels: scene.reference.shadow_step_voxels,
            min_transmittance: 1e-4,
        }
    }

    pub fn reference(scene: &Scene) -> Self {
        MarchSteps {
            view_step_voxels: scene.reference.step_voxels,
            shadow_step_voxels: scene.reference.shadow_step_voxels,
            min_transmittance: scene.reference.min_transmittance,
        }
    }
}

pub fn frame_params(scene: &Scene, width: u32, height: u32, lut_size: usize, steps: MarchSteps) -> FrameParams {
    let b = scene.camera.basis(width, height);
    let bx = scene.volume_box();
    let d = scene.volume.dims.as_vec3();
    let bg = scene.render.background;
    FrameParams {
        cam_origin: [b.origin.x, b.origin.y, b.origin.z, if b.orthographic { 1.0 } else { 0.0 }],
        cam_forward: b.forward.extend(0.0).to_array(),
        cam_right: b.right.extend(0.0).to_array(),
        cam_up: b.up.extend(0.0).to_array(),
        box_half: bx.half_extent.extend(bx.voxel_length).to_array(),
        dims: [d.x, d.y, d.z, lut_size as f32],
        background: [bg.x, bg.y, bg.z, scene.render.emission],
        march: [steps.view_step_voxels, steps.shadow_step_voxels, steps.min_transmittance, scene.lights.len() as f32],
        phong: [scene.phong.ambient, scene.phong.diffuse, scene.phong.specular, scene.phong.shininess],
        image_size: [width, height, 0, 0],
    }
}

pub fn gpu_lights(scene: &Scene) -> Vec<GpuLight> {
    scene.lights.iter().map(gpu_light).collect()
}

/// One light as the shaders read it (glsl/lights.glsl).
pub fn gpu_light(l: &Light) -> GpuLight {
    let rad = l.radiance();
    let falloff = if l.falloff == Falloff::InverseSquare { 1.0 } else { 0.0 };
    match l.kind {
        LightKind::Directional { direction } => GpuLight {
            pos_type: direction.normalize_or(glam::Vec3::NEG_Y).extend(0.0).to_array(),
            spot_dir: [0.0, 0.0, 0.0, 1.0],
            radiance: rad.extend(0.0).to_array(),
            params: [falloff, 0.0, 0.0, 0.0],
        },
        LightKind::Point { position } => GpuLight {
            pos_type: position.extend(1.0).to_array(),
            spot_dir: [0.0, 0.0, 0.0, 1.0],
            radiance: rad.extend(0.0).to_array(),
            params: [falloff, 0.0, 0.0, 0.0],
        },
        LightKind::Spot { position, direction, inner_cone_deg, outer_cone_deg } => GpuLight {
            pos_type: position.extend(2.0).to_array(),
            spot_dir: direction.normalize_or(glam::Vec3::NEG_Y).extend(inner_cone_deg.to_radians().cos()).to_array(),
            radiance: rad.extend(outer_cone_deg.to_radians().cos()).to_array(),
            params: [falloff, 0.0, 0.0, 0.0],
        },
    }
}
