//! The images a technique's frame writes (output, view-chunk state, slice and
//! cache images), kept from frame to frame where frames follow one another on
//! one device (the viewer): asked for by the same name with the same size and
//! format, the image of the last frame comes back; with another size (a
//! resize) or format (a setting) it is created anew and replaces the old one.
//! Everywhere else (`render`, benches) each frame creates its own, as before.
//!
//! A kept image may still be in use by the frame before (the viewer has two in
//! flight, and its blit reads the output): the recorder of a frame on kept
//! images discards them after any earlier access
//! ([`crate::vk::Recorder::discard_after`], set by [`FrameImages::discard_after`]).

use super::error::RenderError;
use super::output::OutputImage;
use crate::vk::barriers::Access;
use crate::vk::resources::ImageDesc;
use crate::vk::{Context, Image, VkError};
use ash::vk;
use std::collections::HashMap;
use std::sync::{Arc, Mutex};

/// Where a frame's images come from: its own, or kept across frames.
#[derive(Default)]
pub struct FrameImages {
    /// `None`: each frame creates its own.
    kept: Option<Mutex<Kept>>,
}

#[derive(Default)]
struct Kept {
    images: HashMap<String, Arc<Image>>,
    outputs: HashMap<String, Arc<OutputImage>>,
}

impl FrameImages {
    /// Each frame creates its own images (headless rendering).
    pub fn each_frame_anew() -> Arc<FrameImages> {
        Arc::new(FrameImages::default())
    }

    /// Images kept from frame to frame.
    pub fn kept() -> Arc<FrameImages> {
        Arc::new(FrameImages { kept: Some(Mutex::default()) })
    }

    /// What a frame's recorder waits for before it discards an image (see
    /// the module's comment): any earlier access where images are kept.
    pub fn discard_after(&self) -> Access {
        if self.kept.is_some() {
            Access::ANY
        } else {
            Access::NONE
        }
    }

    /// Lets go of every kept image (another technique, with other images, is
    /// chosen); frames and sessions that hold one keep it until they end.
    pub fn release_all(&self) {
        if let Some(kept) = &self.kept {
            *kept.lock().unwrap_or_else(|e| e.into_inner()) = Kept::default();
        }
    }

    /// The image `name` of `desc`: last frame's where it had that description.
    pub fn image(&self, ctx: &Context, name: &str, desc: ImageDesc) -> Result<Arc<Image>, VkError> {
        let Some(kept) = &self.kept else {
            return Ok(Arc::new(Image::new(ctx, name, desc)?));
        };
        let mut kept = kept.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(image) = kept.images.get(name).filter(|i| same(&i.desc, &desc)) {
            return Ok(image.clone());
        }
        let image = Arc::new(Image::new(ctx, name, desc)?);
        kept.images.insert(name.to_string(), image.clone());
        Ok(image)
    }

    /// A 2D storage image (`Image::storage_2d`), kept as [`FrameImages::image`] says.
    pub fn storage_2d(
        &self,
        ctx: &Context,
        name: &str,
        format: vk::Format,
        (width, height): (u32, u32),
        extra: vk::ImageUsageFlags,
    ) -> Result<Arc<Image>, VkError> {
        let desc = ImageDesc {
            image_type: vk::ImageType::TYPE_2D,
            format,
            extent: vk::Extent3D { width, height, depth: 1 },
            usage: vk::ImageUsageFlags::STORAGE | extra,
        };
        self.image(ctx, name, desc)
    }

    /// The RGBA32F output image `name` of `width` x `height`.
    pub fn output(&self, ctx: &Context, name: &str, width: u32, height: u32) -> Result<Arc<OutputImage>, RenderError> {
        let Some(kept) = &self.kept else {
            return Ok(Arc::new(OutputImage::new(ctx, name, width, height)?));
        };
        let mut kept = kept.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(output) = kept.outputs.get(name).filter(|o| (o.width, o.height) == (width, height)) {
            return Ok(output.clone());
        }
        let output = Arc::new(OutputImage::new(ctx, name, width, height)?);
        kept.outputs.insert(name.to_string(), output.clone());
        Ok(output)
    }
}

fn same(a: &ImageDesc, b: &ImageDesc) -> bool {
    (a.image_type, a.format, a.extent, a.usage) == (b.image_type, b.format, b.extent, b.usage)
}
