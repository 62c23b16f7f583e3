//! The present pass: the technique's linear RGBA32F frame, recorded into the
//! same command buffer just before ([`record_handoff`]; or, for a technique
//! that cannot record there, uploaded from the host: [`record_upload`]),
//! blitted into the swapchain image (the blit converts linear to the sRGB
//! format), the control panel drawn over it, optionally copied out for a
//! screenshot, and handed to the presentation engine. Each barrier is named
//! for what it protects; the upload, the blit and the panel have profiler
//! scopes `frame_upload`, `present_blit` and `ui`.

use super::ui::Ui;
use crate::render::recorded_frame::{FRAME_OUTPUT_LAYOUT, FRAME_OUTPUT_WRITE};
use crate::vk::barriers::{Access, Barrier};
use crate::vk::resources::{color_layers, color_range};
use crate::vk::{Buffer, Image, Profiler, Recorder, VkError};
use ash::vk;

/// The layout the blit reads the frame in.
pub const BLIT_SOURCE_LAYOUT: vk::ImageLayout = vk::ImageLayout::TRANSFER_SRC_OPTIMAL;
/// Blits read and write in the BLIT stage (not COPY).
const BLIT_READ: Access = Access { stage: vk::PipelineStageFlags2::BLIT, access: vk::AccessFlags2::TRANSFER_READ };
const BLIT_WRITE: Access = Access { stage: vk::PipelineStageFlags2::BLIT, access: vk::AccessFlags2::TRANSFER_WRITE };
/// The stage the "image acquired" semaphore is waited in: the barrier that
/// takes the swapchain image starts from it, so the two chain.
pub const ACQUIRE_WAIT_STAGE: vk::PipelineStageFlags2 = vk::PipelineStageFlags2::BLIT;
/// The panel blends over the frame: it reads and writes the attachment.
const UI_DRAW: Access = Access {
    stage: vk::PipelineStageFlags2::COLOR_ATTACHMENT_OUTPUT,
    access: vk::AccessFlags2::from_raw(
        vk::AccessFlags2::COLOR_ATTACHMENT_READ.as_raw() | vk::AccessFlags2::COLOR_ATTACHMENT_WRITE.as_raw(),
    ),
};
/// A clear of the swapchain image (a transfer write).
const CLEAR_WRITE: Access = Access { stage: vk::PipelineStageFlags2::CLEAR, access: vk::AccessFlags2::TRANSFER_WRITE };
/// The first writes of the swapchain image: the clear where the image does
/// not fill the window, and the blit.
const CLEAR_OR_BLIT_WRITE: Access = Access {
    stage: vk::PipelineStageFlags2::from_raw(
        vk::PipelineStageFlags2::CLEAR.as_raw() | vk::PipelineStageFlags2::BLIT.as_raw(),
    ),
    access: vk::AccessFlags2::TRANSFER_WRITE,
};
/// Presentation waits on a semaphore; the signal covers all earlier work.
const TO_PRESENT: Access = Access::NONE;

/// Profiler scopes (and debug labels) of the present pass.
pub const UPLOAD_SCOPE: &str = "frame_upload";
pub const BLIT_SCOPE: &str = "present_blit";
pub const UI_SCOPE: &str = "ui";

/// The technique's frame, just recorded into this command buffer, becomes the
/// blit's source: its compute writes made visible to the blit's reads, in the
/// blit's source layout; returns the layout it is in. Without this barrier
/// (`handoff_barrier` false: only to prove it load-bearing) the blit may read
/// the frame before it is written.
pub fn record_handoff(rec: &mut Recorder, output: &Image, handoff_barrier: bool) -> vk::ImageLayout {
    if !handoff_barrier {
        return FRAME_OUTPUT_LAYOUT;
    }
    rec.barrier(&Barrier::image(
        "frame_output_write_to_present_read",
        output,
        FRAME_OUTPUT_WRITE,
        BLIT_READ,
        FRAME_OUTPUT_LAYOUT,
        BLIT_SOURCE_LAYOUT,
    ));
    BLIT_SOURCE_LAYOUT
}

/// A frame rendered by its own submission and read back: `staging` (its
/// pixels) copied into `linear`, which is left like a recorded frame's output
/// after [`record_handoff`], in [`BLIT_SOURCE_LAYOUT`].
pub fn record_upload(
    rec: &mut Recorder,
    profiler: &mut Profiler,
    staging: &Buffer,
    linear: &Image,
) -> Result<(), VkError> {
    let scope = profiler.begin(rec, UPLOAD_SCOPE)?;
    let dst_layout = vk::ImageLayout::TRANSFER_DST_OPTIMAL;
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
        BLIT_SOURCE_LAYOUT,
    ));
    profiler.end(rec, scope)
}

pub struct PresentTarget {
    pub image: vk::Image,
    pub view: vk::ImageView,
    pub extent: vk::Extent2D,
}

/// The blit of the technique's frame into the window.
pub struct Blit<'a> {
    /// The linear frame, readable by the blit in `layout` ([`record_handoff`]
    /// or [`record_upload`] made it so).
    pub source: &'a Image,
    pub layout: vk::ImageLayout,
    /// Where the image starts: right of the panel.
    pub x: u32,
    /// The size it takes there (a preview is stretched to it; where it does
    /// not fill the window, the rest is cleared).
    pub shown: vk::Extent2D,
    /// The filter of a stretching blit ([`stretch_filter`]).
    pub filter: vk::Filter,
}

/// Linear where the device filters RGBA32F images linearly (a stretched
/// preview then looks smooth), else nearest.
pub fn stretch_filter(ctx: &crate::vk::Context) -> vk::Filter {
    // SAFETY: a valid physical device of this instance.
    let properties = unsafe {
        ctx.instance.get_physical_device_format_properties(ctx.physical_device, vk::Format::R32G32B32A32_SFLOAT)
    };
    let linear = vk::FormatFeatureFlags::SAMPLED_IMAGE_FILTER_LINEAR;
    if properties.optimal_tiling_features.contains(linear) {
        vk::Filter::LINEAR
    } else {
        vk::Filter::NEAREST
    }
}

/// The window's background where the image does not reach (egui's dark panel).
const BACKGROUND: [f32; 4] = [0.01, 0.01, 0.01, 1.0];

/// Records the pass: `blit` into the target right of the panel; `ui` draws
/// the panel, whose opaque fill covers the target left of `blit.x`.
pub fn record(
    rec: &mut Recorder,
    profiler: &mut Profiler,
    blit: &Blit,
    target: &PresentTarget,
    screenshot: Option<&Buffer>,
    ui: Option<&mut Ui>,
) -> Result<(), VkError> {
    let scope = profiler.begin(rec, BLIT_SCOPE)?;
    let (dst_layout, src_layout) = (vk::ImageLayout::TRANSFER_DST_OPTIMAL, vk::ImageLayout::TRANSFER_SRC_OPTIMAL);
    // Starts from the acquire semaphore's wait stage, so the layout change
    // happens after the presentation engine let go of the image.
    // Its second scope holds the clear as well as the blit.
    rec.barrier(&Barrier::raw_image(
        "swapchain_acquired_to_blit_write",
        target.image,
        Access { stage: ACQUIRE_WAIT_STAGE, access: vk::AccessFlags2::NONE },
        CLEAR_OR_BLIT_WRITE,
        vk::ImageLayout::UNDEFINED,
        dst_layout,
    ));
    let (right, bottom) = (blit.x + blit.shown.width, blit.shown.height);
    if right < target.extent.width || bottom < target.extent.height {
        // The window is larger than the image (it fits the panel): the rest
        // is background, not what the image held before.
        let clear = vk::ClearColorValue { float32: BACKGROUND };
        // SAFETY: the image is in TRANSFER_DST_OPTIMAL (barrier above) and was
        // created with TRANSFER_DST usage (the blit writes it).
        unsafe { rec.device().cmd_clear_color_image(rec.cb, target.image, dst_layout, &clear, &[color_range()]) };
        rec.barrier(&Barrier::raw_image(
            "swapchain_clear_to_blit_write",
            target.image,
            CLEAR_WRITE,
            BLIT_WRITE,
            dst_layout,
            dst_layout,
        ));
    }
    let e = blit.source.extent();
    let src_end = vk::Offset3D { x: e.width as i32, y: e.height as i32, z: 1 };
    let dst_end =
        vk::Offset3D { x: right.min(target.extent.width) as i32, y: bottom.min(target.extent.height) as i32, z: 1 };
    let region = vk::ImageBlit::default()
        .src_subresource(color_layers())
        .src_offsets([vk::Offset3D::default(), src_end])
        .dst_subresource(color_layers())
        .dst_offsets([vk::Offset3D { x: blit.x as i32, y: 0, z: 0 }, dst_end]);
    // Same size: nearest copies the pixels as they are.
    let stretched = (e.width, e.height) != ((dst_end.x - blit.x as i32) as u32, dst_end.y as u32);
    let filter = if stretched { blit.filter } else { vk::Filter::NEAREST };
    // SAFETY: both images are in the layouts named (the caller's barrier and the
    // one above), were created with TRANSFER usage, and their formats support BLIT_SRC/BLIT_DST
    // (RGBA32F on every Vulkan device; the swapchain format was checked); a
    // linear filter only where the format supports it (`stretch_filter`).
    unsafe {
        rec.device().cmd_blit_image(rec.cb, blit.source.raw, blit.layout, target.image, dst_layout, &[region], filter)
    };
    profiler.end(rec, scope)?;
    let (mut last_write, mut layout) = (BLIT_WRITE, dst_layout);
    if let Some(ui) = ui {
        let attachment = vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL;
        rec.barrier(&Barrier::raw_image(
            "swapchain_blit_write_to_ui_draw",
            target.image,
            BLIT_WRITE,
            UI_DRAW,
            dst_layout,
            attachment,
        ));
        let ui_scope = profiler.begin(rec, UI_SCOPE)?;
        let color = [vk::RenderingAttachmentInfo::default()
            .image_view(target.view)
            .image_layout(attachment)
            .load_op(vk::AttachmentLoadOp::LOAD)
            .store_op(vk::AttachmentStoreOp::STORE)];
        let info = vk::RenderingInfo::default()
            .render_area(vk::Rect2D { offset: vk::Offset2D::default(), extent: target.extent })
            .layer_count(1)
            .color_attachments(&color);
        // SAFETY: the view is of the target image, now in COLOR_ATTACHMENT_OPTIMAL
        // (barrier above); dynamic rendering is enabled on window contexts.
        unsafe { rec.device().cmd_begin_rendering(rec.cb, &info) };
        let drawn = ui.draw(rec.cb, target.extent);
        // SAFETY: paired with the begin above, even when the draw failed.
        unsafe { rec.device().cmd_end_rendering(rec.cb) };
        drawn?;
        profiler.end(rec, ui_scope)?;
        (last_write, layout) = (UI_DRAW, attachment);
    }
    let present = vk::ImageLayout::PRESENT_SRC_KHR;
    match screenshot {
        Some(buffer) => {
            rec.barrier(&Barrier::raw_image(
                "swapchain_frame_write_to_screenshot_copy",
                target.image,
                last_write,
                Access::TRANSFER_READ,
                layout,
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
            "swapchain_frame_write_to_present",
            target.image,
            last_write,
            TO_PRESENT,
            layout,
            present,
        )),
    }
    Ok(())
}
