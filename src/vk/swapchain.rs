//! A swapchain on a [`Surface`]: an sRGB format the frame can be blitted into
//! (and copied out of, for screenshots), the present mode asked for, the
//! images, and one "ready to present" semaphore per image. Presentation
//! engines hold an image's semaphore until the image is acquired again, so
//! the semaphore belongs to the image, not to a frame in flight.

use super::context::Context;
use super::error::{VkError, VkResultExt};
use super::surface::Surface;
use ash::vk;

/// The present modes a user can ask for, by name.
pub const PRESENT_MODES: [(&str, vk::PresentModeKHR); 4] = [
    ("fifo", vk::PresentModeKHR::FIFO),
    ("mailbox", vk::PresentModeKHR::MAILBOX),
    ("immediate", vk::PresentModeKHR::IMMEDIATE),
    ("fifo-relaxed", vk::PresentModeKHR::FIFO_RELAXED),
];

pub fn present_mode_name(mode: vk::PresentModeKHR) -> String {
    PRESENT_MODES.iter().find(|(_, m)| *m == mode).map(|(n, _)| n.to_string()).unwrap_or(format!("{mode:?}"))
}

pub struct Swapchain<'c> {
    ctx: &'c Context,
    pub loader: ash::khr::swapchain::Device,
    pub raw: vk::SwapchainKHR,
    pub format: vk::Format,
    pub extent: vk::Extent2D,
    pub present_mode: vk::PresentModeKHR,
    pub images: Vec<vk::Image>,
    /// Colour-attachment views of the images (the viewer's panel draws into them).
    pub views: Vec<vk::ImageView>,
    /// Signalled by the frame that wrote image i, waited on by its present.
    pub ready_to_present: Vec<vk::Semaphore>,
}

/// Surface formats whose blit from RGBA32F converts linear to sRGB.
const SRGB_FORMATS: [vk::Format; 2] = [vk::Format::B8G8R8A8_SRGB, vk::Format::R8G8B8A8_SRGB];

impl<'c> Swapchain<'c> {
    /// A swapchain of `wanted` size (clamped to what the surface allows),
    /// replacing `old` if given (which the caller destroys afterwards).
    pub fn new(
        surface: &Surface<'c>,
        wanted: vk::Extent2D,
        present_mode: vk::PresentModeKHR,
        old: Option<&Swapchain>,
    ) -> Result<Swapchain<'c>, VkError> {
        let ctx = surface.ctx;
        let caps = surface.capabilities()?;
        let modes = surface.present_modes()?;
        if !modes.contains(&present_mode) {
            let names: Vec<String> = modes.iter().map(|&m| present_mode_name(m)).collect();
            return Err(VkError::Presentation(format!(
                "present mode {} is not available on this surface; available: {}",
                present_mode_name(present_mode),
                names.join(", ")
            )));
        }
        let formats = surface.formats()?;
        let blit_dst = vk::FormatFeatureFlags::BLIT_DST | vk::FormatFeatureFlags::TRANSFER_SRC;
        let format = SRGB_FORMATS
            .into_iter()
            .flat_map(|f| formats.iter().filter(move |s| s.format == f))
            .find(|s| s.color_space == vk::ColorSpaceKHR::SRGB_NONLINEAR && ctx.format_supports(s.format, blit_dst))
            .ok_or_else(|| {
                VkError::Presentation(format!(
                    "no sRGB surface format that can be blitted into; the surface offers {:?}",
                    formats.iter().map(|f| f.format).collect::<Vec<_>>()
                ))
            })?;
        let usage = vk::ImageUsageFlags::TRANSFER_DST
            | vk::ImageUsageFlags::TRANSFER_SRC
            | vk::ImageUsageFlags::COLOR_ATTACHMENT;
        if !caps.supported_usage_flags.contains(usage) {
            return Err(VkError::Presentation(format!(
                "swapchain images cannot be transfer source and destination (supported: {:?})",
                caps.supported_usage_flags
            )));
        }
        let extent = if caps.current_extent.width != u32::MAX {
            caps.current_extent
        } else {
            vk::Extent2D {
                width: wanted.width.clamp(caps.min_image_extent.width, caps.max_image_extent.width),
                height: wanted.height.clamp(caps.min_image_extent.height, caps.max_image_extent.height),
            }
        };
        let mut image_count = caps.min_image_count + 1;
        if caps.max_image_count > 0 {
            image_count = image_count.min(caps.max_image_count);
        }
        let info = vk::SwapchainCreateInfoKHR::default()
            .surface(surface.raw)
            .min_image_count(image_count)
            .image_format(format.format)
            .image_color_space(format.color_space)
            .image_extent(extent)
            .image_array_layers(1)
            .image_usage(usage)
            .image_sharing_mode(vk::SharingMode::EXCLUSIVE)
            .pre_transform(caps.current_transform)
            .composite_alpha(vk::CompositeAlphaFlagsKHR::OPAQUE)
            .present_mode(present_mode)
            .clipped(true)
            .old_swapchain(old.map_or(vk::SwapchainKHR::null(), |o| o.raw));
        let loader = ash::khr::swapchain::Device::new(&ctx.instance, &ctx.device);
        // SAFETY: the surface is valid and supported by this device's queue
        // (checked in Surface::new); `old` is retired by this call.
        let raw = unsafe { loader.create_swapchain(&info, None) }.call("vkCreateSwapchainKHR")?;
        let mut swapchain = Swapchain {
            ctx,
            loader,
            raw,
            format: format.format,
            extent,
            present_mode,
            images: Vec::new(),
            views: Vec::new(),
            ready_to_present: Vec::new(),
        };
        // SAFETY: raw was just created.
        swapchain.images = unsafe { swapchain.loader.get_swapchain_images(raw) }.call("vkGetSwapchainImagesKHR")?;
        for (i, &image) in swapchain.images.clone().iter().enumerate() {
            ctx.set_name(image, &format!("swapchain image {i}"));
            let view_info = vk::ImageViewCreateInfo::default()
                .image(image)
                .view_type(vk::ImageViewType::TYPE_2D)
                .format(swapchain.format)
                .subresource_range(super::resources::color_range());
            // SAFETY: the image belongs to this swapchain; the view goes before it (Drop).
            let view = unsafe { ctx.device.create_image_view(&view_info, None) }.call("vkCreateImageView")?;
            swapchain.views.push(view);
            // SAFETY: valid device.
            let s = unsafe { ctx.device.create_semaphore(&vk::SemaphoreCreateInfo::default(), None) }
                .call("vkCreateSemaphore")?;
            ctx.set_name(s, &format!("ready to present {i}"));
            swapchain.ready_to_present.push(s);
        }
        Ok(swapchain)
    }

    /// The next image to draw into; `signal` is signalled once it may be written.
    /// `Ok(None)`: the swapchain is out of date (recreate it).
    pub fn acquire(&self, signal: vk::Semaphore) -> Result<Option<(u32, bool)>, VkError> {
        // SAFETY: the semaphore is unsignalled with no pending operation (its
        // last wait belongs to a frame whose fence the caller waited for).
        match unsafe { self.loader.acquire_next_image(self.raw, u64::MAX, signal, vk::Fence::null()) } {
            Ok((index, suboptimal)) => Ok(Some((index, suboptimal))),
            Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => Ok(None),
            Err(result) => Err(VkError::Call { call: "vkAcquireNextImageKHR", result }),
        }
    }

    /// Presents image `index` once its semaphore is signalled. Returns whether
    /// the swapchain should be recreated (out of date or suboptimal).
    pub fn present(&self, index: u32) -> Result<bool, VkError> {
        let waits = [self.ready_to_present[index as usize]];
        let swapchains = [self.raw];
        let indices = [index];
        let info =
            vk::PresentInfoKHR::default().wait_semaphores(&waits).swapchains(&swapchains).image_indices(&indices);
        // SAFETY: the image was acquired and the submission that signals its
        // semaphore was made; the queue is used from this thread only.
        match unsafe { self.loader.queue_present(self.ctx.queue, &info) } {
            Ok(suboptimal) => Ok(suboptimal),
            Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => Ok(true),
            Err(result) => Err(VkError::Call { call: "vkQueuePresentKHR", result }),
        }
    }
}

impl Drop for Swapchain<'_> {
    fn drop(&mut self) {
        // SAFETY: the owner waited for the frames that used the images and for
        // the queue (presents included) before dropping the swapchain.
        unsafe {
            for &v in &self.views {
                self.ctx.device.destroy_image_view(v, None);
            }
            for &s in &self.ready_to_present {
                self.ctx.device.destroy_semaphore(s, None);
            }
            self.loader.destroy_swapchain(self.raw, None);
        }
    }
}
