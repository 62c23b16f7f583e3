//! sweeplab: volume illumination on raw Vulkan with explicit synchronization.
//!
//! Layers, bottom up: [`vk`] (thin layer over ash), [`scene`] (volumes, loaders,
//! transfer functions, camera, lights, scene files), the renderers ([`dvr`]
//! baselines, [`reference`] ground truth), and [`metrics`].

pub mod linear_image;
pub mod metrics;
pub mod reference;
pub mod scene;

/// SPIR-V of every `glsl/*.comp`, compiled by build.rs.
pub mod shaders {
    include!(concat!(env!("OUT_DIR"), "/shaders.rs"));
}
