//! Events for split barriers: `vkCmdSetEvent2` after the producer,
//! `vkCmdWaitEvents2` before the consumer, both with the same dependency.

use super::context::Context;
use super::error::{VkError, VkResultExt};
use super::memory::GpuMemory;
use ash::vk;
use std::sync::Arc;

/// `count` device-only events, each set and waited at most once per submission.
pub struct EventPool {
    pub events: Vec<vk::Event>,
    memory: Arc<GpuMemory>,
}

impl EventPool {
    pub fn new(ctx: &Context, count: usize) -> Result<EventPool, VkError> {
        let mut pool = EventPool { events: Vec::with_capacity(count), memory: ctx.memory.clone() };
        let info = vk::EventCreateInfo::default().flags(vk::EventCreateFlags::DEVICE_ONLY);
        for _ in 0..count {
            // SAFETY: valid device and create info; the pool destroys what it created.
            pool.events.push(unsafe { ctx.device.create_event(&info, None) }.call("vkCreateEvent")?);
        }
        Ok(pool)
    }
}

impl Drop for EventPool {
    fn drop(&mut self) {
        for &e in &self.events {
            // SAFETY: dropped after the submissions using the events completed.
            unsafe { self.memory.device.destroy_event(e, None) };
        }
    }
}
