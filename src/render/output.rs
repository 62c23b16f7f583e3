//! The RGBA32F storage image a technique writes its frame into, and its readback
//! into a [`LinearImage`].

use super::error::RenderError;
use crate::linear_image::LinearImage;
use crate::vk::barriers::{Access, Barrier};
use crate::vk::{Buffer, Context, Image, Recorder};
use ash::vk;
use gpu_allocator::MemoryLocation;

pub struct OutputImage {
    pub image: Image,
    pub width: u32,
    pub height: u32,
}

impl OutputImage {
    pub fn new(ctx: &Context, name: &str, width: u32, height: u32) -> Result<OutputImage, RenderError> {
        let image = Image::storage_2d(
            ctx,
            name,
            vk::Format::R32G32B32A32_SFLOAT,
            width,
            height,
            vk::ImageUsageFlags::TRANSFER_SRC | vk::ImageUsageFlags::TRANSFER_DST,
        )?;
        Ok(OutputImage { image, width, height })
    }

    /// Before the first write of a frame: old contents are discarded.
    pub fn prepare_for_compute_write(&self, rec: &mut Recorder) {
        rec.barrier(&Barrier::image(
            "output_discard_to_compute_write",
            &self.image,
            rec.discard_after,
            Access::COMPUTE_WRITE,
            vk::ImageLayout::UNDEFINED,
            vk::ImageLayout::GENERAL,
        ));
    }

    /// Like `prepare_for_compute_write` for an image that shaders also bind for
    /// reading (one side of a ping-pong pair).
    pub fn prepare_for_compute_read_write(&self, rec: &mut Recorder) {
        rec.discard_for_compute("pingpong_discard_to_compute_access", &[&self.image]);
    }

    /// Host-visible buffer big enough for the image.
    pub fn readback_buffer(&self, ctx: &Context) -> Result<Buffer, RenderError> {
        let size = self.width as u64 * self.height as u64 * 16;
        Ok(Buffer::staging(ctx, "output readback", size, vk::BufferUsageFlags::TRANSFER_DST, MemoryLocation::GpuToCpu)?)
    }

    /// Copies the finished frame (written by compute shaders) into `readback`.
    pub fn record_readback(&self, rec: &mut Recorder, readback: &Buffer) {
        rec.readback_image(
            &self.image,
            readback,
            "output_compute_write_to_readback_copy",
            "readback_copy_to_host_read",
        );
    }

    pub fn read(&self, readback: &Buffer) -> Result<LinearImage, RenderError> {
        let texels: Vec<[f32; 4]> = readback.read(self.width as usize * self.height as usize)?;
        Ok(LinearImage {
            width: self.width,
            height: self.height,
            pixels: texels.into_iter().map(|t| [t[0], t[1], t[2]]).collect(),
        })
    }
}
