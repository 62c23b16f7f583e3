//! Host mirrors of the shader-side `FrameParams` (a std140 storage buffer) and `Light` records
//! (glsl/frame.glsl, glsl/lights.glsl); `assert_gpu_layout!` checks them against
//! the offsets reflected from the SPIR-V.

use crate::render::early_termination::EARLY_TERMINATION_TRANSMITTANCE;
use crate::scene::{Falloff, Light, LightKind, Scene};
use bytemuck::{Pod, Zeroable};

#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct FrameParams {
    pub cam_origin: [f32; 3],
    /// 1: parallel rays from the image plane.
    pub orthographic: u32,
    /// w unused.
    pub cam_forward: [f32; 4],
    pub cam_right: [f32; 4],
    pub cam_up: [f32; 4],
    pub box_half: [f32; 3],
    /// World units per voxel.
    pub voxel_length: f32,
    pub dims: [f32; 3],
    /// Texels of the transfer LUT.
    pub lut_size: f32,
    pub background: [f32; 3],
    /// Emission scale of the medium.
    pub emission: f32,
    /// Voxels.
    pub view_step: f32,
    /// Voxels.
    pub shadow_step: f32,
    /// Where the ground truth's view rays stop.
    pub min_transmittance: f32,
    pub light_count: u32,
    pub ambient: f32,
    pub diffuse: f32,
    pub specular: f32,
    pub shininess: f32,
    /// Width, height.
    pub image_size: [u32; 2],
    /// 1: each pixel's view samples start at its own phase (`render.jitter`).
    pub jitter: u32,
    pub frame_unused: u32,
}

crate::assert_gpu_layout!(
    FrameParams,
    crate::shaders::raycast::layout::FRAME_PARAMS,
    [
        cam_origin,
        orthographic,
        cam_forward,
        cam_right,
        cam_up,
        box_half,
        voxel_length,
        dims,
        lut_size,
        background,
        emission,
        view_step,
        shadow_step,
        min_transmittance,
        light_count,
        ambient,
        diffuse,
        specular,
        shininess,
        image_size,
        jitter,
        frame_unused,
    ]
);

#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuLight {
    pub pos_type: [f32; 4],
    pub spot_dir: [f32; 4],
    pub radiance: [f32; 4],
    pub params: [f32; 4],
}

crate::assert_gpu_layout!(GpuLight, crate::shaders::raycast::layout::LIGHT, [pos_type, spot_dir, radiance, params]);
crate::assert_gpu_layout!(
    GpuLight,
    crate::shaders::lightvolume_slice::layout::LIGHT,
    [pos_type, spot_dir, radiance, params]
);

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
            min_transmittance: EARLY_TERMINATION_TRANSMITTANCE as f32,
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
        cam_origin: b.origin.to_array(),
        orthographic: b.orthographic as u32,
        cam_forward: b.forward.extend(0.0).to_array(),
        cam_right: b.right.extend(0.0).to_array(),
        cam_up: b.up.extend(0.0).to_array(),
        box_half: bx.half_extent.to_array(),
        voxel_length: bx.voxel_length,
        dims: d.to_array(),
        lut_size: lut_size as f32,
        background: bg.to_array(),
        emission: scene.render.emission,
        view_step: steps.view_step_voxels,
        shadow_step: steps.shadow_step_voxels,
        min_transmittance: steps.min_transmittance,
        light_count: scene.lights.len() as u32,
        ambient: scene.phong.ambient,
        diffuse: scene.phong.diffuse,
        specular: scene.phong.specular,
        shininess: scene.phong.shininess,
        image_size: [width, height],
        jitter: scene.render.jitter as u32,
        frame_unused: 0,
    }
}

pub fn gpu_lights(scene: &Scene) -> Vec<GpuLight> {
    scene.rendered_lights().iter().map(gpu_light).collect()
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
