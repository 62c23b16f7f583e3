//! The present pass: the technique's linear frame, uploaded into an RGBA32F
//! image, blitted into the swapchain image (the blit converts linear to the
//! sRGB format), optionally copied out for a screenshot, and handed to the
//! presentation engine. Each barrier is named for what it protects.

use crate::vk::barriers::{Access, Barrier};
use crate::vk::resources::color_layers;
use crate::vk::{Buffer, Image, Profiler, Recorder, VkError};
use ash::vk;

/// Blits read and write in the BLIT stage (not COPY).
const BLIT_READ: Access = Access { stage: vk::PipelineStageFlags2::BLIT, access: vk::AccessFlags2::TRANSFER_READ };
const BLIT_WRITE: Access = Access { stage: vk::PipelineStageFlags2::BLIT, access: vk::AccessFlags2::TRANSFER_WRITE };
/// The stage the "image acquired" semaphore is waited in: the barrier that
/// takes the swapchain image starts from it, so the two chain.
pub const ACQUIRE_WAIT_STAGE: vk::PipelineStageFlags2 = vk::PipelineStageFlags2::BLIT;
/// Presentation waits on a semaphore; the signal covers all earlier work.
const TO_PRESENT: Access = Access::NONE;

pub struct PresentTarget {
    pub image: vk::Image,
    pub extent: vk::Extent2D,
}

/// Records the pass under the profiler scope `present_blit`.
pub fn record(
    rec: &mut Recorder,
    profiler: &mut Profiler,
    linear: &Image,
    staging: &Buffer,
    target: &PresentTarget,
    screenshot: Option<&Buffer>,
) -> Result<(), VkError> {
    let scope = profiler.begin(rec, "present_blit")?;
    let (dst_layout, src_layout) = (vk::ImageLayout::TRANSFER_DST_OPTIMAL, vk::ImageLayout::TRANSFER_SRC_OPTIMAL);
    // The slot's previous frame read this image; its fence was waited.
    rec.barrier(&Barrier::image(
        "frame_upload_discard_to_copy_write",
        linear,
        Access::NONE,
        Access::TRANSFER_WRITE,
        vk::ImageLayout::UNDEFINED,
        dst_layout,
    ));
    rec.copy_buffer_to_image(staging, linear);
    rec.barrier(&Barrier::image(
        "frame_upload_write_to_blit_read",
        linear,
        Access::TRANSFER_WRITE,
        BLIT_READ,
        dst_layout,
        src_layout,
    ));
    // Starts from the acquire semaphore's wait stage, so the layout change
    // happens after the presentation engine let go of the image.
    rec.barrier(&Barrier::raw_image(
        "swapchain_acquired_to_blit_write",
        target.image,
        Access { stage: ACQUIRE_WAIT_STAGE, access: vk::AccessFlags2::NONE },
        BLIT_WRITE,
        vk::ImageLayout::UNDEFINED,
        dst_layout,
    ));
    let e = linear.extent();
    let src_end = vk::Offset3D { x: e.width as i32, y: e.height as i32, z: 1 };
    let dst_end = vk::Offset3D { x: target.extent.width as i32, y: target.extent.height as i32, z: 1 };
    let region = vk::ImageBlit::default()
        .src_subresource(color_layers())
        .src_offsets([vk::Offset3D::default(), src_end])
        .dst_subresource(color_layers())
        .dst_offsets([vk::Offset3D::default(), dst_end]);
    // SAFETY: both images are in the layouts named (the barriers above), were
    // created with TRANSFER usage, and their formats support BLIT_SRC/BLIT_DST
    // (RGBA32F on every Vulkan device; the swapchain format was checked).
    unsafe {
        rec.device().cmd_blit_image(
            rec.cb,
            linear.raw,
            src_layout,
            target.image,
            dst_layout,
            &[region],
            vk::Filter::NEAREST,
        )
    };
    let present = vk::ImageLayout::PRESENT_SRC_KHR;
    match screenshot {
        Some(buffer) => {
            rec.barrier(&Barrier::raw_image(
                "swapchain_blit_write_to_screenshot_copy",
                target.image,
                BLIT_WRITE,
                Access::TRANSFER_READ,
                dst_layout,
                src_layout,
            ));
            let copy = vk::BufferImageCopy::default().image_subresource(color_layers()).image_extent(vk::Extent3D {
                width: target.extent.width,
                height: target.extent.height,
                depth: 1,
            });
            // SAFETY: the image is in TRANSFER_SRC_OPTIMAL (barrier above) and the
            // buffer holds width * height * 4 bytes (the caller sized it).
            unsafe { rec.device().cmd_copy_image_to_buffer(rec.cb, target.image, src_layout, buffer.raw, &[copy]) };
            rec.barrier(&Barrier::raw_image(
                "screenshot_copy_to_present",
                target.image,
                Access::TRANSFER_READ,
                TO_PRESENT,
                src_layout,
                present,
            ));
            rec.barrier(&Barrier::memory("screenshot_copy_to_host_read", Access::TRANSFER_WRITE, Access::HOST_READ));
        }
        None => rec.barrier(&Barrier::raw_image(
            "swapchain_blit_write_to_present",
            target.image,
            BLIT_WRITE,
            TO_PRESENT,
            dst_layout,
            present,
        )),
    }
    profiler.end(rec, scope)?;
    Ok(())
}
