//! What `sweeplab devices` prints, and how `--device` picks one.

use ash::vk;
use serde::Serialize;

#[derive(Clone, Debug, Serialize)]
pub struct DeviceInfo {
    pub index: usize,
    pub name: String,
    pub device_type: String,
    pub api_version: String,
    /// PCI vendor id (0x10DE NVIDIA, 0x1002 AMD, 0x8086 Intel, 0x10005 Mesa).
    pub vendor_id: u32,
    pub device_id: u32,
    /// `driverVersion` decoded the way its vendor packs it.
    pub driver_version: String,
    pub driver_name: String,
    pub driver_info: String,
    pub timestamp_period_ns: f32,
    /// Valid bits of timestamps on the chosen compute queue family (0: none).
    pub timestamp_valid_bits: u32,
}

impl DeviceInfo {
    /// A CPU implementation (lavapipe): shaders run on the host's cores.
    pub fn is_cpu(&self) -> bool {
        self.device_type == type_name(vk::PhysicalDeviceType::CPU)
    }
}

pub fn version_string(v: u32) -> String {
    format!("{}.{}.{}", vk::api_version_major(v), vk::api_version_minor(v), vk::api_version_patch(v))
}

/// `driverVersion` as its vendor reads it: NVIDIA packs 10.8.8.6 bits, Intel's
/// Windows driver 18.14 bits; everyone else (Mesa, AMD) uses VK_MAKE_VERSION.
pub fn driver_version_string(vendor_id: u32, v: u32) -> String {
    match vendor_id {
        0x10DE => format!("{}.{}.{}.{}", v >> 22, (v >> 14) & 0xff, (v >> 6) & 0xff, v & 0x3f),
        0x8086 if cfg!(windows) => format!("{}.{}", v >> 14, v & 0x3fff),
        _ => version_string(v),
    }
}

pub fn type_name(t: vk::PhysicalDeviceType) -> &'static str {
    match t {
        vk::PhysicalDeviceType::DISCRETE_GPU => "discrete GPU",
        vk::PhysicalDeviceType::INTEGRATED_GPU => "integrated GPU",
        vk::PhysicalDeviceType::VIRTUAL_GPU => "virtual GPU",
        vk::PhysicalDeviceType::CPU => "CPU",
        _ => "other",
    }
}

/// Preference when no device is named: real GPUs before software rasterizers.
pub fn type_rank(t: vk::PhysicalDeviceType) -> u32 {
    match t {
        vk::PhysicalDeviceType::DISCRETE_GPU => 0,
        vk::PhysicalDeviceType::INTEGRATED_GPU => 1,
        vk::PhysicalDeviceType::VIRTUAL_GPU => 2,
        vk::PhysicalDeviceType::CPU => 3,
        _ => 4,
    }
}

/// Resolves a `--device` value: an index into the list, or a case-insensitive
/// substring of the device name.
pub fn pick(wanted: &str, devices: &[DeviceInfo]) -> Option<usize> {
    if let Ok(i) = wanted.trim().parse::<usize>() {
        return devices.iter().position(|d| d.index == i);
    }
    let w = wanted.to_lowercase();
    devices.iter().position(|d| d.name.to_lowercase().contains(&w))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn driver_versions_are_decoded_per_vendor() {
        // NVIDIA 535.104.05 packs as (535 << 22) | (104 << 14) | (5 << 6).
        assert_eq!(driver_version_string(0x10DE, (535 << 22) | (104 << 14) | (5 << 6)), "535.104.5.0");
        assert_eq!(driver_version_string(0x10005, vk::make_api_version(0, 22, 3, 6)), "22.3.6");
    }
}
