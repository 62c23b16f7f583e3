//! A window's Vulkan surface (VK_KHR_surface), made by `ash_window` from raw
//! window handles; it borrows the context so it is destroyed before the instance.

use super::context::Context;
use super::error::{VkError, VkResultExt};
use ash::vk;
use raw_window_handle::{RawDisplayHandle, RawWindowHandle};

pub struct Surface<'c> {
    pub ctx: &'c Context,
    pub loader: ash::khr::surface::Instance,
    pub raw: vk::SurfaceKHR,
}

impl<'c> Surface<'c> {
    /// A surface for the window; fails when the context's queue cannot present to it.
    pub fn new(ctx: &'c Context, display: RawDisplayHandle, window: RawWindowHandle) -> Result<Surface<'c>, VkError> {
        // SAFETY: the handles come from a live window that outlives the surface
        // (the viewer drops the surface first), and the instance was created with
        // the extensions `ash_window::enumerate_required_extensions` named.
        let raw = unsafe { ash_window::create_surface(&ctx.entry, &ctx.instance, display, window, None) }
            .call("vkCreate*SurfaceKHR")?;
        let loader = ash::khr::surface::Instance::new(&ctx.entry, &ctx.instance);
        let surface = Surface { ctx, loader, raw };
        // SAFETY: queue family and surface belong to this physical device / instance.
        let supported =
            unsafe { surface.loader.get_physical_device_surface_support(ctx.physical_device, ctx.queue_family, raw) }
                .call("vkGetPhysicalDeviceSurfaceSupportKHR")?;
        if !supported {
            return Err(VkError::Presentation(format!(
                "queue family {} of {} cannot present to this window",
                ctx.queue_family, ctx.info.name
            )));
        }
        Ok(surface)
    }

    pub fn capabilities(&self) -> Result<vk::SurfaceCapabilitiesKHR, VkError> {
        // SAFETY: a query on a valid surface of this instance.
        unsafe { self.loader.get_physical_device_surface_capabilities(self.ctx.physical_device, self.raw) }
            .call("vkGetPhysicalDeviceSurfaceCapabilitiesKHR")
    }

    pub fn formats(&self) -> Result<Vec<vk::SurfaceFormatKHR>, VkError> {
        // SAFETY: a query on a valid surface of this instance.
        unsafe { self.loader.get_physical_device_surface_formats(self.ctx.physical_device, self.raw) }
            .call("vkGetPhysicalDeviceSurfaceFormatsKHR")
    }

    pub fn present_modes(&self) -> Result<Vec<vk::PresentModeKHR>, VkError> {
        // SAFETY: a query on a valid surface of this instance.
        unsafe { self.loader.get_physical_device_surface_present_modes(self.ctx.physical_device, self.raw) }
            .call("vkGetPhysicalDeviceSurfacePresentModesKHR")
    }
}

impl Drop for Surface<'_> {
    fn drop(&mut self) {
        // SAFETY: the swapchains made from this surface borrow it, so they are gone.
        unsafe { self.loader.destroy_surface(self.raw, None) };
    }
}
