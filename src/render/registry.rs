//! The techniques a user can name, and one entry point that renders any of them
//! into a [`LinearImage`] with its GPU profile. The one part of `render` above
//! the techniques: it lists them; they know nothing of it.

use super::error::RenderError;
use super::gpu_scene::GpuScene;
use super::technique::RenderTechnique;
use crate::linear_image::LinearImage;
use crate::vk::{ProfileReport, Profiler};
use std::fmt;
use std::ops::Deref;
use std::str::FromStr;

/// A technique by name: a copyable handle on its [`RenderTechnique`].
#[derive(Clone, Copy)]
pub struct Technique(&'static dyn RenderTechnique);

// Named like the variants of the enum this handle replaced, so that call sites
// keep reading `Technique::Ipsvi`.
#[allow(non_upper_case_globals)]
impl Technique {
    pub const Dvr: Technique = Technique(&crate::dvr::Dvr);
    pub const Phong: Technique = Technique(&crate::dvr::Phong);
    pub const Reference: Technique = Technique(&crate::reference::gpu::Reference);
    pub const Ipsvi: Technique = Technique(&crate::ipsvi::Ipsvi);
    pub const HalfAngle: Technique = Technique(&crate::half_angle::HalfAngle);
    pub const LightVolume: Technique = Technique(&crate::lightvolume::LightVolume);

    /// The registry: every technique, in the order help text lists them.
    pub const ALL: [Technique; 6] = [
        Technique::Dvr,
        Technique::Phong,
        Technique::Reference,
        Technique::Ipsvi,
        Technique::HalfAngle,
        Technique::LightVolume,
    ];

    /// `name: summary` of every technique, one per line (for `--technique` help).
    pub fn help() -> String {
        Technique::ALL.map(|t| format!("{}: {}", t.name(), t.summary())).join("\n")
    }
}

impl Deref for Technique {
    type Target = dyn RenderTechnique;
    fn deref(&self) -> &Self::Target {
        self.0
    }
}

impl PartialEq for Technique {
    fn eq(&self, other: &Self) -> bool {
        self.name() == other.name()
    }
}

impl Eq for Technique {}

impl fmt::Debug for Technique {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
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
        Technique::ALL.into_iter().find(|t| t.name() == s).ok_or_else(|| {
            let names = Technique::ALL.map(|t| t.name());
            let near = crate::scene::suggest::nearest(s, names).map(|n| format!(" (did you mean {n}?)"));
            format!("unknown technique {s:?}{}; known: {}", near.unwrap_or_default(), names.join(", "))
        })
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
    let frame = technique.render(gpu, width, height, profiler)?;
    let profile = profiler.resolve(gpu.ctx.memory.device_local_peak())?;
    Ok(RenderOutput { technique, image: frame.image, profile, dispatches: frame.dispatches, barriers: frame.barriers })
}
