//! The illumination volume: RGBA32F 3D storage images holding the coloured,
//! HDR light arriving at each voxel (summed over lights, weighted by their group
//! factors), at 1, 1/2 or 1/4 of the data resolution. With compensated sums the
//! light is `high + low` (the low words in a second volume); otherwise `low` is
//! a one-voxel placeholder the shader never touches. Only this technique
//! allocates them. The volume stays in GENERAL layout from the first clear on,
//! so selective updates can add to what earlier frames left.

use crate::render::{FrameImages, RenderError};
use crate::vk::resources::ImageDesc;
use crate::vk::{Buffer, Context, Image, Recorder, VkError};
use ash::vk;
use glam::UVec3;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

const FORMAT: vk::Format = vk::Format::R32G32B32A32_SFLOAT;

pub struct IlluminationVolume {
    pub image: Arc<Image>,
    pub low: Arc<Image>,
    pub compensated: bool,
    pub size: UVec3,
}

/// The volume read back: per voxel (x fastest) the high words, and the low words
/// where the sums are compensated.
pub struct IlluminationReadback {
    pub high: Vec<[f32; 4]>,
    pub low: Option<Vec<[f32; 4]>>,
}

impl IlluminationReadback {
    /// Voxel i's light, channel c, as the exact value of its two-float sum.
    pub fn value(&self, i: usize, c: usize) -> f64 {
        self.high[i][c] as f64 + self.low.as_ref().map_or(0.0, |l| l[i][c] as f64)
    }
}

fn volume_image(ctx: &Context, images: &FrameImages, name: &str, size: UVec3) -> Result<Arc<Image>, VkError> {
    images.image(
        ctx,
        name,
        ImageDesc {
            image_type: vk::ImageType::TYPE_3D,
            format: FORMAT,
            extent: vk::Extent3D { width: size.x, height: size.y, depth: size.z },
            usage: vk::ImageUsageFlags::STORAGE | vk::ImageUsageFlags::TRANSFER_DST | vk::ImageUsageFlags::TRANSFER_SRC,
        },
    )
}

impl IlluminationVolume {
    /// Voxels per axis for data of `dims` at `scale` data voxels per illumination
    /// voxel (rounded up, so the grid covers the whole box).
    pub fn size_for(dims: UVec3, scale: u32) -> UVec3 {
        let s = scale.max(1);
        UVec3::new(dims.x.div_ceil(s), dims.y.div_ceil(s), dims.z.div_ceil(s)).max(UVec3::ONE)
    }

    /// Its images from `images` (kept across the viewer's scenes; the first
    /// update of a new renderer clears them).
    pub fn new(
        ctx: &Context,
        images: &FrameImages,
        dims: UVec3,
        scale: u32,
        compensated: bool,
    ) -> Result<IlluminationVolume, RenderError> {
        if !ctx.format_supports(FORMAT, vk::FormatFeatureFlags::STORAGE_IMAGE) {
            return Err(VkError::NoFormat {
                kind: "illumination volume",
                candidates: "R32G32B32A32_SFLOAT".into(),
                usage: "3D storage image",
            }
            .into());
        }
        let size = Self::size_for(dims, scale);
        let image = volume_image(ctx, images, "lightvolume illumination", size)?;
        let low = if compensated {
            volume_image(ctx, images, "lightvolume illumination low words", size)?
        } else {
            volume_image(ctx, images, "lightvolume illumination low placeholder", UVec3::ONE)?
        };
        Ok(IlluminationVolume { image, low, compensated, size })
    }

    /// Zeroes the volume before an entire update adds into it.
    pub fn record_clear(&self, rec: &mut Recorder) {
        rec.clear_for_compute(
            &self.image,
            [0.0; 4],
            "illumination_discard_to_clear",
            "illumination_clear_to_propagation",
        );
        rec.clear_for_compute(
            &self.low,
            [0.0; 4],
            "illumination_low_discard_to_clear",
            "illumination_low_clear_to_propagation",
        );
    }

    /// Voxels of the volume (of each of its two images when compensated).
    pub fn voxel_count(&self) -> usize {
        (self.size.x * self.size.y * self.size.z) as usize
    }

    pub fn readback_buffers(&self, ctx: &Context) -> Result<[Buffer; 2], RenderError> {
        let bytes = self.voxel_count() as u64 * 16;
        let low_bytes = if self.compensated { bytes } else { 16 };
        let buffer = |name, bytes| {
            Buffer::staging(ctx, name, bytes, vk::BufferUsageFlags::TRANSFER_DST, MemoryLocation::GpuToCpu)
        };
        Ok([buffer("illumination readback", bytes)?, buffer("illumination low readback", low_bytes)?])
    }

    /// After the ray cast: copies the volume into `readback` (x fastest, then y,
    /// z), leaving it in GENERAL for the next update.
    pub fn record_readback(&self, rec: &mut Recorder, readback: &[Buffer; 2]) {
        rec.readback_image_for_reuse(
            &self.image,
            &readback[0],
            [
                "illumination_write_to_readback_copy",
                "illumination_readback_copy_to_next_update",
                "illumination_readback_copy_to_host_read",
            ],
        );
        if self.compensated {
            rec.readback_image_for_reuse(
                &self.low,
                &readback[1],
                [
                    "illumination_low_write_to_readback_copy",
                    "illumination_low_readback_copy_to_next_update",
                    "illumination_low_readback_copy_to_host_read",
                ],
            );
        }
    }

    pub fn read(&self, readback: &[Buffer; 2]) -> Result<IlluminationReadback, RenderError> {
        let n = self.voxel_count();
        Ok(IlluminationReadback {
            high: readback[0].read(n)?,
            low: if self.compensated { Some(readback[1].read(n)?) } else { None },
        })
    }
}
