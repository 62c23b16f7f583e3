//! The techniques a user can name, and one entry point that renders any of them
//! into a [`LinearImage`] with its GPU profile.

use super::error::RenderError;
use super::gpu_scene::GpuScene;
use crate::linear_image::LinearImage;
use crate::vk::{ProfileReport, Profiler};
use std::fmt;
use std::str::FromStr;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Technique {
    /// Unshaded emission-absorption ray casting (one dispatch).
    Dvr,
    /// Gradient Blinn-Phong ray casting, no shadows (one dispatch).
    Phong,
    /// Ground truth on the GPU: brute-force shadow rays per sample.
    Reference,
    /// Image plane sweep volume illumination: one dispatch and barrier per line.
    Ipsvi,
    /// Half-angle slicing: one dispatch and barrier per slice.
    HalfAngle,
    /// Light volume: slice-by-slice propagation in coherence-based groups, one
    /// secondary command buffer per group, then a ray cast.
    LightVolume,
}

impl Technique {
    pub const ALL: [Technique; 6] = [
        Technique::Dvr,
        Technique::Phong,
        Technique::Reference,
        Technique::Ipsvi,
        Technique::HalfAngle,
        Technique::LightVolume,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Technique::Dvr => "dvr",
            Technique::Phong => "phong",
            Technique::Reference => "reference",
            Technique::Ipsvi => "ipsvi",
            Technique::HalfAngle => "half-angle",
            Technique::LightVolume => "lightvolume",
        }
    }

    /// The ground-truth model this technique approximates (docs/optical-model.md):
    /// IPSVI carries emission along its light rays (model ii); the light volume and
    /// half-angle slicing carry transmittance alone (model i); the baselines are
    /// compared with the model the scene names.
    pub fn reference_model(self, scene: &crate::scene::Scene) -> crate::scene::OpticalModel {
        match self {
            Technique::Ipsvi => crate::scene::OpticalModel::EmissiveScattering,
            Technique::LightVolume | Technique::HalfAngle => crate::scene::OpticalModel::SingleScattering,
            _ => scene.reference.model,
        }
    }
}

impl Technique {
    /// Whether the ground truth this technique is compared with uses coloured
    /// extinction along shadow rays: the light volume's `chromatic` setting;
    /// IPSVI and half-angle slicing carry one transmittance; the baselines
    /// follow the scene's `reference.chromatic`.
    pub fn reference_chromatic(self, scene: &crate::scene::Scene) -> Result<bool, RenderError> {
        Ok(match self {
            Technique::LightVolume => crate::lightvolume::LightVolumeSettings::from_scene(scene)?.chromatic,
            Technique::Ipsvi | Technique::HalfAngle => false,
            _ => scene.reference.chromatic,
        })
    }
}

impl fmt::Display for Technique {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Technique {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Technique::ALL
            .into_iter()
            .find(|t| t.name() == s)
            .ok_or_else(|| format!("unknown technique {s:?}; known: {}", Technique::ALL.map(|t| t.name()).join(", ")))
    }
}

pub struct RenderOutput {
    pub technique: Technique,
    pub image: LinearImage,
    pub profile: ProfileReport,
    /// Compute dispatches and pipeline barriers recorded for the frame.
    pub dispatches: u32,
    pub barriers: u32,
}

/// What a technique module returns before the profile is resolved.
pub struct FrameResult {
    pub image: LinearImage,
    pub dispatches: u32,
    pub barriers: u32,
}

/// Renders one frame of `technique` at `width` x `height`.
pub fn render(
    gpu: &GpuScene,
    technique: Technique,
    width: u32,
    height: u32,
    profiler: &mut Profiler,
) -> Result<RenderOutput, RenderError> {
    if width == 0 || height == 0 {
        return Err(RenderError::Invalid(format!("image size {width}x{height} is empty")));
    }
    gpu.ctx.memory.reset_peak();
    profiler.reset();
    let frame = match technique {
        Technique::Dvr => crate::dvr::render(gpu, crate::dvr::Shading::Unshaded, width, height, profiler)?,
        Technique::Phong => crate::dvr::render(gpu, crate::dvr::Shading::BlinnPhong, width, height, profiler)?,
        Technique::Reference => crate::reference::gpu::render(gpu, width, height, profiler)?,
        Technique::Ipsvi => crate::ipsvi::render(gpu, width, height, profiler)?,
        Technique::HalfAngle => crate::half_angle::render(gpu, width, height, profiler)?,
        Technique::LightVolume => crate::lightvolume::render(gpu, width, height, profiler)?,
    };
    let profile = profiler.resolve(gpu.ctx.memory.device_local_peak())?;
    Ok(RenderOutput { technique, image: frame.image, profile, dispatches: frame.dispatches, barriers: frame.barriers })
}
