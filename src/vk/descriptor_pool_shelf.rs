//! Descriptor pools handed on instead of destroyed: a pipeline's pool is given
//! back when the pipeline is dropped (after the GPU work that used its sets),
//! reset, and taken by the next pipeline that needs a pool of the same shape,
//! so frame after frame of the same passes creates no pool. The shelf keeps
//! at most [`SHELVED`]; the context destroys what is left when it drops.

use super::error::{VkError, VkResultExt};
use ash::vk;
use std::sync::Mutex;

/// Pools kept for reuse (two frames in flight of the largest technique's passes fit).
pub const SHELVED: usize = 64;

/// What a pool holds: its set count and descriptors of each type.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PoolShape {
    pub max_sets: u32,
    pub sizes: Vec<(vk::DescriptorType, u32)>,
}

pub struct PoolShelf {
    device: ash::Device,
    pools: Mutex<Vec<(PoolShape, vk::DescriptorPool)>>,
}

impl PoolShelf {
    pub fn new(device: &ash::Device) -> PoolShelf {
        PoolShelf { device: device.clone(), pools: Mutex::new(Vec::new()) }
    }

    /// A shelved pool of `shape`, reset (no sets allocated).
    pub fn take(&self, shape: &PoolShape) -> Option<vk::DescriptorPool> {
        let mut pools = self.pools.lock().unwrap_or_else(|p| p.into_inner());
        let i = pools.iter().position(|(s, _)| s == shape)?;
        Some(pools.swap_remove(i).1)
    }

    /// Takes `pool` back: reset and shelved, or destroyed when the shelf is full.
    /// The caller guarantees no pending GPU work uses its sets.
    pub fn give_back(&self, shape: PoolShape, pool: vk::DescriptorPool) -> Result<(), VkError> {
        let mut pools = self.pools.lock().unwrap_or_else(|p| p.into_inner());
        if pools.len() >= SHELVED {
            // SAFETY: no pending work uses the pool's sets (the caller's guarantee).
            unsafe { self.device.destroy_descriptor_pool(pool, None) };
            return Ok(());
        }
        // SAFETY: as above; resetting frees every set allocated from it.
        unsafe { self.device.reset_descriptor_pool(pool, vk::DescriptorPoolResetFlags::empty()) }
            .call("vkResetDescriptorPool")?;
        pools.push((shape, pool));
        Ok(())
    }

    /// Destroys every shelved pool (context drop, device idle).
    pub fn clear(&self) {
        let mut pools = self.pools.lock().unwrap_or_else(|p| p.into_inner());
        for (_, pool) in pools.drain(..) {
            // SAFETY: shelved pools have no sets in use.
            unsafe { self.device.destroy_descriptor_pool(pool, None) };
        }
    }
}
