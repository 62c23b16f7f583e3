//! The illumination volume: an RGBA32F 3D storage image holding the coloured,
//! HDR light arriving at each voxel (summed over lights, weighted by their group
//! factors), at 1, 1/2 or 1/4 of the data resolution. Only this technique
//! allocates it.

use crate::render::RenderError;
use crate::vk::resources::ImageDesc;
use crate::vk::{Buffer, Context, Image, Recorder, VkError};
use ash::vk;
use glam::UVec3;
use gpu_allocator::MemoryLocation;

const FORMAT: vk::Format = vk::Format::R32G32B32A32_SFLOAT;

pub struct IlluminationVolume {
    pub image: Image,
    pub size: UVec3,
}

impl IlluminationVolume {
    /// Voxels per axis for data of `dims` at `scale` data voxels per illumination
    /// voxel (rounded up, so the grid covers the whole box).
    pub fn size_for(dims: UVec3, scale: u32) -> UVec3 {
        let s = scale.max(1);
        UVec3::new(dims.x.div_ceil(s), dims.y.div_ceil(s), dims.z.div_ceil(s)).max(UVec3::ONE)
    }

    pub fn new(ctx: &Context, dims: UVec3, scale: u32) -> Result<IlluminationVolume, RenderError> {
        if !ctx.format_supports(FORMAT, vk::FormatFeatureFlags::STORAGE_IMAGE) {
            return Err(VkError::NoFormat {
                kind: "illumination volume",
                candidates: "R32G32B32A32_SFLOAT".into(),
                usage: "3D storage image",
            }
            .into());
        }
        let size = Self::size_for(dims, scale);
        let image = Image::new(
            ctx,
            "lightvolume illumination",
            ImageDesc {
                image_type: vk::ImageType::TYPE_3D,
                format: FORMAT,
                extent: vk::Extent3D { width: size.x, height: size.y, depth: size.z },
                usage: vk::ImageUsageFlags::STORAGE
                    | vk::ImageUsageFlags::TRANSFER_DST
                    | vk::ImageUsageFlags::TRANSFER_SRC,
            },
        )?;
        Ok(IlluminationVolume { image, size })
    }

    /// Zeroes the volume before the group passes add into it.
    pub fn record_clear(&self, rec: &mut Recorder) {
        rec.clear_for_compute(
            &self.image,
            [0.0; 4],
            "illumination_discard_to_clear",
            "illumination_clear_to_propagation",
        );
    }

    pub fn readback_buffer(&self, ctx: &Context) -> Result<Buffer, RenderError> {
        let bytes = self.size.x as u64 * self.size.y as u64 * self.size.z as u64 * 16;
        Ok(Buffer::staging(
            ctx,
            "illumination readback",
            bytes,
            vk::BufferUsageFlags::TRANSFER_DST,
            MemoryLocation::GpuToCpu,
        )?)
    }

    /// After the ray cast: copies the volume into `readback` (x fastest, then y, z).
    pub fn record_readback(&self, rec: &mut Recorder, readback: &Buffer) {
        rec.readback_image(
            &self.image,
            readback,
            "illumination_compute_access_to_readback_copy",
            "illumination_readback_copy_to_host_read",
        );
    }

    pub fn read(&self, readback: &Buffer) -> Result<Vec<[f32; 4]>, RenderError> {
        Ok(readback.read((self.size.x * self.size.y * self.size.z) as usize)?)
    }
}
