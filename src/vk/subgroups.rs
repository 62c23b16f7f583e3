//! What a device's compute shaders can do across a subgroup
//! (`VkPhysicalDeviceSubgroupProperties`, and the size range of
//! `VkPhysicalDeviceVulkan13Properties`), asked once by the renderers that use
//! subgroup operations.

use super::Context;
use ash::vk;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SubgroupSupport {
    /// The subgroup size the device reports.
    pub size: u32,
    /// The smallest subgroup a compute dispatch may get (shaders of SPIR-V
    /// 1.6 may run at any size from it to the largest).
    pub min_size: u32,
    /// Subgroup operations are available in compute shaders.
    pub compute: bool,
    /// `subgroupShuffle`, `subgroupShuffleXor`.
    pub shuffle: bool,
    /// `subgroupShuffleUp`, `subgroupShuffleDown`.
    pub shuffle_relative: bool,
}

impl SubgroupSupport {
    pub fn of(ctx: &Context) -> SubgroupSupport {
        let mut subgroup = vk::PhysicalDeviceSubgroupProperties::default();
        let mut v13 = vk::PhysicalDeviceVulkan13Properties::default();
        let mut props = vk::PhysicalDeviceProperties2::default().push_next(&mut subgroup).push_next(&mut v13);
        // SAFETY: the physical device belongs to this instance; the chained structs live on the stack.
        unsafe { ctx.instance.get_physical_device_properties2(ctx.physical_device, &mut props) };
        let ops = subgroup.supported_operations;
        SubgroupSupport {
            size: subgroup.subgroup_size,
            // Vulkan 1.3 devices report the range; 0 would mean the fixed size.
            min_size: if v13.min_subgroup_size > 0 { v13.min_subgroup_size } else { subgroup.subgroup_size },
            compute: subgroup.supported_stages.contains(vk::ShaderStageFlags::COMPUTE),
            shuffle: ops.contains(vk::SubgroupFeatureFlags::SHUFFLE),
            shuffle_relative: ops.contains(vk::SubgroupFeatureFlags::SHUFFLE_RELATIVE),
        }
    }

    /// What is missing for shuffles within a subgroup in compute shaders, if anything.
    pub fn missing_shuffles(&self) -> Option<&'static str> {
        match (self.compute, self.shuffle, self.shuffle_relative) {
            (false, _, _) => Some("subgroup operations in compute shaders"),
            (_, false, _) => Some("subgroup shuffles (VK_SUBGROUP_FEATURE_SHUFFLE_BIT)"),
            (_, _, false) => Some("relative subgroup shuffles (VK_SUBGROUP_FEATURE_SHUFFLE_RELATIVE_BIT)"),
            _ => None,
        }
    }
}
