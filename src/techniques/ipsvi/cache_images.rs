//! The illumination cache's images and claim keys of one IPSVI renderer.

use super::cache_update::CacheUpdate;
use super::settings::IpsviSettings;
use crate::render::{GpuScene, RenderError};
use crate::vk::{Buffer, Image};
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

/// The ping-pong pair: illumination (E / scale, transmittance) and the position
/// image (which sweep plane each light ray's front sits on, or with view
/// samples the depth its value was computed at); with view samples a second
/// pair that the samples of a block write (value, block stamp | depth), and
/// the claim keys of `cache_write = "farthest"`. What a mode does not use is
/// 1x1 (bound, never read). Merged sweeps stack one cache per sweep in rows
/// (`slots`); keys likewise. With `packed_store` each pair is one rgba32ui
/// image (`history`, `packed_samples`) and the four unpacked ones are 1x1.
pub struct Cache {
    pub light: [Arc<Image>; 2],
    pub front: [Arc<Image>; 2],
    pub samples: [Arc<Image>; 2],
    pub stamps: [Arc<Image>; 2],
    pub history: [Arc<Image>; 2],
    pub packed_samples: [Arc<Image>; 2],
    pub claim_keys: Buffer,
}

impl Cache {
    pub fn new(gpu: &GpuScene, settings: &IpsviSettings, claims: bool, slots: u32) -> Result<Cache, RenderError> {
        let size = settings.cache_size;
        let view_samples = settings.cache_update == CacheUpdate::ViewSamples;
        let sized = |name: &str, format, n: u32| {
            gpu.frame_images.storage_2d(gpu.ctx, name, format, (n, n * slots), vk::ImageUsageFlags::empty())
        };
        let packed = settings.packed_store;
        let unpacked_size = if packed { 1 } else { size };
        let image = |name: &str, format| sized(name, format, unpacked_size);
        let sample_size = if view_samples && !packed { size } else { 1 };
        let sample = |name: &str, format| sized(name, format, sample_size);
        let history_size = if packed { size } else { 1 };
        let history = |name: &str| sized(name, vk::Format::R32G32B32A32_UINT, history_size);
        let packed_sample_size = if packed && view_samples { size } else { 1 };
        let packed_sample = |name: &str| sized(name, vk::Format::R32G32B32A32_UINT, packed_sample_size);
        // Two halves (this block's claims, the next block's) of N x N 64-bit keys.
        let key_bytes = if claims { 2 * 8 * u64::from(size) * u64::from(size) * u64::from(slots) } else { 16 };
        let usage = vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_DST;
        Ok(Cache {
            light: [
                image("ipsvi cache a", vk::Format::R16G16B16A16_SFLOAT)?,
                image("ipsvi cache b", vk::Format::R16G16B16A16_SFLOAT)?,
            ],
            front: [image("ipsvi front a", vk::Format::R16_UINT)?, image("ipsvi front b", vk::Format::R16_UINT)?],
            samples: [
                sample("ipsvi cache samples a", vk::Format::R16G16B16A16_SFLOAT)?,
                sample("ipsvi cache samples b", vk::Format::R16G16B16A16_SFLOAT)?,
            ],
            stamps: [
                sample("ipsvi cache stamps a", vk::Format::R32_UINT)?,
                sample("ipsvi cache stamps b", vk::Format::R32_UINT)?,
            ],
            history: [history("ipsvi history a")?, history("ipsvi history b")?],
            packed_samples: [packed_sample("ipsvi packed samples a")?, packed_sample("ipsvi packed samples b")?],
            claim_keys: Buffer::new(gpu.ctx, "ipsvi claim keys", key_bytes, usage, MemoryLocation::GpuOnly)?,
        })
    }

    pub fn images(&self) -> [&Image; 12] {
        [
            &self.light[0],
            &self.light[1],
            &self.front[0],
            &self.front[1],
            &self.samples[0],
            &self.samples[1],
            &self.stamps[0],
            &self.stamps[1],
            &self.history[0],
            &self.history[1],
            &self.packed_samples[0],
            &self.packed_samples[1],
        ]
    }
}
