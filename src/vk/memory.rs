//! All device memory goes through gpu-allocator; this wrapper counts what the
//! renderers hold so reports can state `gpu_memory_bytes` honestly.

use super::error::VkError;
use ash::vk;
use gpu_allocator::vulkan::{Allocation, AllocationCreateDesc, AllocationScheme, Allocator, AllocatorCreateDesc};
use gpu_allocator::MemoryLocation;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

pub struct GpuMemory {
    pub(crate) device: ash::Device,
    allocator: Mutex<Option<Allocator>>,
    /// Bytes of the renderers' resources alive now (staging and readback buffers,
    /// which exist only around a transfer, are not counted).
    device_local_bytes: AtomicU64,
    device_local_peak: AtomicU64,
}

impl GpuMemory {
    pub fn new(
        instance: &ash::Instance,
        device: &ash::Device,
        physical_device: vk::PhysicalDevice,
    ) -> Result<Self, VkError> {
        let allocator = Allocator::new(&AllocatorCreateDesc {
            instance: instance.clone(),
            device: device.clone(),
            physical_device,
            debug_settings: Default::default(),
            buffer_device_address: false,
            allocation_sizes: Default::default(),
        })
        .map_err(|e| VkError::Allocation { name: "allocator".into(), message: e.to_string() })?;
        Ok(GpuMemory {
            device: device.clone(),
            allocator: Mutex::new(Some(allocator)),
            device_local_bytes: AtomicU64::new(0),
            device_local_peak: AtomicU64::new(0),
        })
    }

    pub fn allocate(
        &self,
        name: &str,
        requirements: vk::MemoryRequirements,
        location: MemoryLocation,
        linear: bool,
        tracked: bool,
    ) -> Result<Allocation, VkError> {
        let mut guard = self
            .allocator
            .lock()
            .map_err(|_| VkError::Allocation { name: name.into(), message: "allocator lock poisoned".into() })?;
        let allocator = guard
            .as_mut()
            .ok_or_else(|| VkError::Allocation { name: name.into(), message: "allocator already destroyed".into() })?;
        let allocation = allocator
            .allocate(&AllocationCreateDesc {
                name,
                requirements,
                location,
                linear,
                allocation_scheme: AllocationScheme::GpuAllocatorManaged,
            })
            .map_err(|e| VkError::Allocation { name: name.into(), message: e.to_string() })?;
        if tracked {
            let now = self.device_local_bytes.fetch_add(requirements.size, Ordering::Relaxed) + requirements.size;
            self.device_local_peak.fetch_max(now, Ordering::Relaxed);
        }
        Ok(allocation)
    }

    pub fn free(&self, allocation: Allocation, tracked: bool) {
        if tracked {
            self.device_local_bytes.fetch_sub(allocation.size(), Ordering::Relaxed);
        }
        if let Ok(mut guard) = self.allocator.lock() {
            if let Some(allocator) = guard.as_mut() {
                // A failed free leaks the block; nothing more useful can be done in Drop.
                let _ = allocator.free(allocation);
            }
        }
    }

    /// Bytes held by live (tracked) resources now.
    pub fn device_local_bytes(&self) -> u64 {
        self.device_local_bytes.load(Ordering::Relaxed)
    }

    /// Highest tracked byte count since creation or the last reset.
    pub fn device_local_peak(&self) -> u64 {
        self.device_local_peak.load(Ordering::Relaxed)
    }

    pub fn reset_peak(&self) {
        self.device_local_peak.store(self.device_local_bytes(), Ordering::Relaxed);
    }

    /// Drops the allocator; called by the context before it destroys the device.
    pub(crate) fn destroy_allocator(&self) {
        if let Ok(mut guard) = self.allocator.lock() {
            guard.take();
        }
    }
}
