//! The last finished frame's command pool, fence and timeline semaphore, kept
//! until the next frame has finished instead of destroyed at once.
//!
//! Why: the Khronos validation layer retires submissions on a thread of its
//! own, and wakes a fence's waiter before it drops its own references to the
//! submission's command buffers. A command buffer the application frees in
//! between dies on the layer's thread, which (in 1.3.239, Debian 12's) erases
//! the buffer's debug labels from a map without the lock under which the
//! application thread's next `vkCmdBeginDebugUtilsLabelEXT` writes to it
//! (locked upstream in 1.3.243: "layers: Fix debug label race conditions").
//! The heap corrupts: `malloc(): unaligned fastbin chunk detected`, or a
//! SIGSEGV in the layer's label code (docs/testing.md, "The validation
//! layer's retire thread"). The layer retires one queue's submissions in
//! order, so once a later submission's fence has been waited on, the earlier
//! submission's references are gone and its objects die on our thread.

use ash::vk;
use std::sync::Mutex;

/// What one `submit_and_wait` frame leaves behind once its fence signalled.
pub struct FinishedFrame {
    pub pool: vk::CommandPool,
    pub fence: vk::Fence,
    pub timeline: Option<vk::Semaphore>,
}

/// Holds at most one [`FinishedFrame`]: the newest.
pub struct FinishedFrameKeeper {
    device: ash::Device,
    kept: Mutex<Option<FinishedFrame>>,
}

impl FinishedFrameKeeper {
    pub fn new(device: &ash::Device) -> FinishedFrameKeeper {
        FinishedFrameKeeper { device: device.clone(), kept: Mutex::new(None) }
    }

    /// Keeps `frame` (its fence waited on) and destroys the one kept before:
    /// that frame's submission came earlier on the queue, so the layer has
    /// retired it completely before it signalled `frame`'s fence.
    pub fn keep(&self, frame: FinishedFrame) {
        let older = self.kept.lock().unwrap_or_else(|p| p.into_inner()).replace(frame);
        if let Some(older) = older {
            self.destroy(older);
        }
    }

    /// The kept frame's pool, if any (for tests of the keeping).
    pub fn kept_pool(&self) -> Option<vk::CommandPool> {
        self.kept.lock().unwrap_or_else(|p| p.into_inner()).as_ref().map(|f| f.pool)
    }

    /// Destroys the kept frame (context drop, after the device is idle).
    pub fn clear(&self) {
        if let Some(frame) = self.kept.lock().unwrap_or_else(|p| p.into_inner()).take() {
            self.destroy(frame);
        }
    }

    fn destroy(&self, frame: FinishedFrame) {
        // SAFETY: the frame's fence was waited on, so its command buffers,
        // fence and semaphore are no longer in use by the device.
        unsafe {
            self.device.destroy_command_pool(frame.pool, None);
            self.device.destroy_fence(frame.fence, None);
            if let Some(t) = frame.timeline {
                self.device.destroy_semaphore(t, None);
            }
        }
    }
}
