//! sweeplab: volume illumination on raw Vulkan with explicit synchronization.
//!
//! Layers, bottom up: [`vk`] (thin layer over ash), [`scene`] (volumes, loaders,
//! transfer functions, camera, lights, scene files), [`render`] (what all GPU
//! techniques share, and the [`render::RenderTechnique`] trait), the ground
//! truth [`reference`], one module per technique under [`techniques`]
//! ([`techniques::dvr`] baselines, [`techniques::ipsvi`],
//! [`techniques::half_angle`], [`techniques::lightvolume`], [`techniques::ao`]),
//! [`metrics`], and the catalogue ([`techniques`] itself) that lists them and
//! owns their scene-file tables.
//! Each technique's settings type sits in its module; the scene stores them
//! without knowing their types ([`scene::TechniqueSettings`]).

pub mod atomic_file;
pub mod bench;
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
