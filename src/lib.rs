//! sweeplab: volume illumination on raw Vulkan with explicit synchronization.
//!
//! Layers, bottom up: [`vk`] (thin layer over ash), [`scene`] (volumes, loaders,
//! transfer functions, camera, lights, scene files), [`render`] (what all GPU
//! techniques share, and the [`render::RenderTechnique`] trait), one module per
//! technique ([`dvr`] baselines, [`reference`] ground truth, [`ipsvi`],
//! [`half_angle`], [`lightvolume`], [`ao`]), [`metrics`], and above them the
//! catalogue [`techniques`] that lists them and owns their scene-file tables.
//! Each technique's settings type sits in its module; the scene stores them
//! without knowing their types ([`scene::TechniqueSettings`]).

pub mod ao;
pub mod bench;
pub mod dvr;
pub mod half_angle;
pub mod ipsvi;
pub mod lightvolume;
pub mod linear_image;
pub mod metrics;
pub mod output_paths;
pub mod plural;
pub mod reference;
pub mod render;
pub mod scene;
pub mod techniques;
pub mod viewer;
pub mod vk;

/// SPIR-V of every `glsl/*.comp`, compiled by build.rs.
pub mod shaders {
    include!(concat!(env!("OUT_DIR"), "/shaders.rs"));
}
