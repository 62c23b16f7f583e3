//! The device limits the engine relies on, checked before any GPU work: what a
//! frame needs ([`Need`], listed per technique by `render::device_fit`) against
//! what a device reports, with an error that names the limit, the device's
//! value and the setting to change. Two tables let a test say which
//! techniques and sizes a device can run without one: the Vulkan spec's
//! guaranteed minimum limits and typical desktop limits.

use ash::vk;

/// The limits the engine's resources and dispatches touch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DeviceLimits {
    pub max_image_dimension_2d: u32,
    pub max_image_dimension_3d: u32,
    pub max_compute_work_group_count: [u32; 3],
    pub max_compute_work_group_invocations: u32,
    pub max_compute_shared_memory_size: u32,
    pub max_storage_buffer_range: u32,
    pub max_uniform_buffer_range: u32,
    pub max_push_constants_size: u32,
}

/// One limit, by its name in `VkPhysicalDeviceLimits`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Limit {
    ImageDimension2D,
    ImageDimension3D,
    /// `maxComputeWorkGroupCount[axis]`.
    WorkGroupCount(usize),
    WorkGroupInvocations,
    SharedMemory,
    StorageBufferRange,
    UniformBufferRange,
    PushConstants,
}

impl Limit {
    pub fn name(self) -> String {
        match self {
            Limit::ImageDimension2D => "maxImageDimension2D".into(),
            Limit::ImageDimension3D => "maxImageDimension3D".into(),
            Limit::WorkGroupCount(a) => format!("maxComputeWorkGroupCount[{a}]"),
            Limit::WorkGroupInvocations => "maxComputeWorkGroupInvocations".into(),
            Limit::SharedMemory => "maxComputeSharedMemorySize".into(),
            Limit::StorageBufferRange => "maxStorageBufferRange".into(),
            Limit::UniformBufferRange => "maxUniformBufferRange".into(),
            Limit::PushConstants => "maxPushConstantsSize".into(),
        }
    }
}

/// What one resource or dispatch needs of one limit, and what to change
/// where the device has less.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Need {
    pub limit: Limit,
    pub value: u64,
    /// What needs it (`volume engine`, `ipsvi cache`, a pass name).
    pub what: String,
    /// The setting that makes it smaller (`--size`, `ipsvi.cache_size`).
    pub setting: String,
}

impl Need {
    pub fn new(limit: Limit, value: u64, what: impl Into<String>, setting: impl Into<String>) -> Need {
        Need { limit, value, what: what.into(), setting: setting.into() }
    }
}

#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "{what} needs {limit} = {needed}, but {device} has {available}; lower {setting}",
    limit = need.limit.name(),
    needed = need.value,
    what = need.what,
    setting = need.setting
)]
pub struct LimitExceeded {
    pub device: String,
    pub need: Need,
    pub available: u64,
}

impl DeviceLimits {
    pub fn from_vk(l: &vk::PhysicalDeviceLimits) -> DeviceLimits {
        DeviceLimits {
            max_image_dimension_2d: l.max_image_dimension2_d,
            max_image_dimension_3d: l.max_image_dimension3_d,
            max_compute_work_group_count: l.max_compute_work_group_count,
            max_compute_work_group_invocations: l.max_compute_work_group_invocations,
            max_compute_shared_memory_size: l.max_compute_shared_memory_size,
            max_storage_buffer_range: l.max_storage_buffer_range,
            max_uniform_buffer_range: l.max_uniform_buffer_range,
            max_push_constants_size: l.max_push_constants_size,
        }
    }

    pub fn value(&self, limit: Limit) -> u64 {
        (match limit {
            Limit::ImageDimension2D => self.max_image_dimension_2d,
            Limit::ImageDimension3D => self.max_image_dimension_3d,
            Limit::WorkGroupCount(a) => self.max_compute_work_group_count[a.min(2)],
            Limit::WorkGroupInvocations => self.max_compute_work_group_invocations,
            Limit::SharedMemory => self.max_compute_shared_memory_size,
            Limit::StorageBufferRange => self.max_storage_buffer_range,
            Limit::UniformBufferRange => self.max_uniform_buffer_range,
            Limit::PushConstants => self.max_push_constants_size,
        }) as u64
    }

    /// The first of `needs` over these limits, as an error naming `device`.
    pub fn check(&self, device: &str, needs: &[Need]) -> Result<(), LimitExceeded> {
        match needs.iter().find(|n| n.value > self.value(n.limit)) {
            Some(n) => {
                Err(LimitExceeded { device: device.to_string(), need: n.clone(), available: self.value(n.limit) })
            }
            None => Ok(()),
        }
    }
}

/// The limits every Vulkan 1.3 device guarantees (the specification's table
/// "Required Limits", section "Limit Requirements").
pub const SPEC_MINIMUM: DeviceLimits = DeviceLimits {
    max_image_dimension_2d: 4096,
    max_image_dimension_3d: 256,
    max_compute_work_group_count: [65535; 3],
    max_compute_work_group_invocations: 128,
    max_compute_shared_memory_size: 16384,
    max_storage_buffer_range: 1 << 27,
    max_uniform_buffer_range: 16384,
    max_push_constants_size: 128,
};

/// Typical desktop limits, one row per vendor's current driver, as
/// vulkan.gpuinfo.org lists them per limit
/// (`https://vulkan.gpuinfo.org/displaydevicelimit.php?name=<limit>`, the
/// value most reports of that vendor's desktop GPUs give) and as the open
/// drivers set them (Mesa `src/amd/vulkan/radv_physical_device.c`:
/// `maxImageDimension3D = (1 << 11)`, `maxComputeWorkGroupCount = {65535,
/// 65535, 65535}`, `maxStorageBufferRange = UINT32_MAX`;
/// `src/intel/vulkan/anv_physical_device.c`). The Intel row is an integrated
/// or Arc GPU on ANV. RADV and ANV both cap 3D images at 2048 per side, the
/// tightest of the three; only NVIDIA's driver allows 16384.
pub const DESKTOP: [(&str, DeviceLimits); 3] = [
    (
        "NVIDIA GeForce RTX 40x0 (proprietary driver)",
        DeviceLimits {
            max_image_dimension_2d: 32768,
            max_image_dimension_3d: 16384,
            max_compute_work_group_count: [2147483647, 65535, 65535],
            max_compute_work_group_invocations: 1024,
            max_compute_shared_memory_size: 49152,
            max_storage_buffer_range: u32::MAX,
            max_uniform_buffer_range: 65536,
            max_push_constants_size: 256,
        },
    ),
    (
        "AMD Radeon RX 7900 (RADV)",
        DeviceLimits {
            max_image_dimension_2d: 16384,
            max_image_dimension_3d: 2048,
            max_compute_work_group_count: [65535; 3],
            max_compute_work_group_invocations: 1024,
            max_compute_shared_memory_size: 65536,
            max_storage_buffer_range: u32::MAX,
            max_uniform_buffer_range: u32::MAX,
            max_push_constants_size: 256,
        },
    ),
    (
        "Intel UHD / Arc (ANV)",
        DeviceLimits {
            max_image_dimension_2d: 16384,
            max_image_dimension_3d: 2048,
            max_compute_work_group_count: [65535; 3],
            max_compute_work_group_invocations: 1024,
            max_compute_shared_memory_size: 65536,
            max_storage_buffer_range: 1 << 30,
            max_uniform_buffer_range: 1 << 30,
            max_push_constants_size: 256,
        },
    ),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_error_names_limit_device_value_and_setting() {
        let need = Need::new(Limit::ImageDimension3D, 4096, "volume engine", "the volume's size (resample it)");
        let e = SPEC_MINIMUM.check("spec minimum", &[need]).unwrap_err().to_string();
        for word in ["maxImageDimension3D = 4096", "spec minimum has 256", "volume engine", "resample"] {
            assert!(e.contains(word), "{e}");
        }
        assert!(DESKTOP[0].1.check("nvidia", &[Need::new(Limit::ImageDimension3D, 4096, "v", "s")]).is_ok());
    }
}
