//! What a frame of a technique needs of the device's limits
//! ([`crate::vk::limits`]), from the scene and the image size alone, checked
//! before any GPU work: the volume image, the output image and its 8x8
//! dispatch, every image and buffer the technique lists as its resources
//! ([`RenderTechnique::resources`]) and the frame's parameters. Dispatches
//! whose size depends on planning (IPSVI's 1-D line blocks) are checked as they
//! are recorded: [`crate::vk::Recorder::check_limits`] refuses the submission.

use super::frame_params::FrameParams;
use super::technique::RenderTechnique;
use crate::scene::Scene;
use crate::vk::limits::{DeviceLimits, Limit, LimitExceeded, Need};

const IMAGE_SIZE: &str = "the image size (--size, render.width / render.height)";

pub fn needs(technique: &dyn RenderTechnique, scene: &Scene, width: u32, height: u32) -> Vec<Need> {
    let dims = scene.volume.dims;
    let mut out = vec![
        Need::new(
            Limit::ImageDimension3D,
            dims.max_element() as u64,
            format!("volume {} ({}x{}x{})", scene.volume.name, dims.x, dims.y, dims.z),
            "the volume's size (resample it, or pick a smaller synthetic size)",
        ),
        Need::new(Limit::ImageDimension2D, width.max(height) as u64, "the output image", IMAGE_SIZE),
        Need::new(Limit::WorkGroupCount(0), width.div_ceil(8) as u64, "an image pass (8x8 groups)", IMAGE_SIZE),
        Need::new(Limit::WorkGroupCount(1), height.div_ceil(8) as u64, "an image pass (8x8 groups)", IMAGE_SIZE),
        Need::new(Limit::StorageBufferRange, std::mem::size_of::<FrameParams>() as u64, "the frame parameters", "none"),
    ];
    let setting = format!("{}'s size settings", technique.name());
    for r in technique.resources(scene, width, height) {
        match r.image {
            Some((extent, _)) if extent[2] > 1 => out.push(Need::new(
                Limit::ImageDimension3D,
                extent.into_iter().max().unwrap_or(0) as u64,
                &r.name,
                &setting,
            )),
            Some((extent, _)) => out.push(Need::new(
                Limit::ImageDimension2D,
                extent[0].max(extent[1]) as u64,
                &r.name,
                format!("{setting} or {IMAGE_SIZE}"),
            )),
            // Buffers are bound whole, as storage buffers.
            None => out.push(Need::new(Limit::StorageBufferRange, r.bytes, &r.name, &setting)),
        }
    }
    out
}

/// `needs` against `limits` of the device `device`.
pub fn check(
    limits: &DeviceLimits,
    device: &str,
    technique: &dyn RenderTechnique,
    scene: &Scene,
    width: u32,
    height: u32,
) -> Result<(), LimitExceeded> {
    limits.check(device, &needs(technique, scene, width, height))
}
