//! Calibrated timestamps (`VK_EXT_calibrated_timestamps`, or the KHR it was
//! promoted to): one device timestamp and the host's `CLOCK_MONOTONIC` read
//! together, so the profiler can put GPU scopes on the host's timeline (the
//! Perfetto trace). Absent on devices without either extension.

use super::error::{VkError, VkResultExt};
use super::layer_extensions::{self, LeftOut};
use ash::vk;
use std::ffi::CStr;

pub enum Calibrator {
    Khr(ash::khr::calibrated_timestamps::Device),
    Ext(ash::ext::calibrated_timestamps::Device),
}

/// A device timestamp and the host time of the same moment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Calibration {
    pub device_ticks: u64,
    /// `CLOCK_MONOTONIC`, in nanoseconds.
    pub host_ns: u64,
    /// The driver's bound on how far apart the two readings may be, in ns.
    pub max_deviation_ns: u64,
}

/// The calibration extension to enable, where the device can calibrate
/// against `CLOCK_MONOTONIC`: the EXT where the device offers it (the same
/// functions as the KHR it was promoted to, and known to every validation
/// layer since 2018), else the KHR where the running validation layer
/// (`layer`: its header version, `None` without validation) knows it
/// ([`super::layer_extensions`]). What was left out for the layer comes back
/// to be said.
pub fn extension_to_enable(
    entry: &ash::Entry,
    instance: &ash::Instance,
    physical_device: vk::PhysicalDevice,
    available: &[vk::ExtensionProperties],
    layer: Option<u32>,
) -> (Option<&'static CStr>, Vec<LeftOut>) {
    let has = |name: &CStr| available.iter().any(|e| e.extension_name_as_c_str() == Ok(name));
    let offered: Vec<&'static CStr> = [ash::ext::calibrated_timestamps::NAME, ash::khr::calibrated_timestamps::NAME]
        .into_iter()
        .filter(|n| has(n))
        .collect();
    let (usable, left_out) = layer_extensions::choose(&offered, layer);
    let Some(&name) = usable.first() else {
        return (None, left_out);
    };
    // SAFETY: a query on a valid physical device; the KHR and EXT entry points
    // are aliases, and the loader resolves whichever the driver exposes.
    let domains = unsafe {
        if name == ash::khr::calibrated_timestamps::NAME {
            ash::khr::calibrated_timestamps::Instance::new(entry, instance)
                .get_physical_device_calibrateable_time_domains(physical_device)
        } else {
            ash::ext::calibrated_timestamps::Instance::new(entry, instance)
                .get_physical_device_calibrateable_time_domains(physical_device)
        }
    };
    let wanted = [vk::TimeDomainKHR::DEVICE, vk::TimeDomainKHR::CLOCK_MONOTONIC];
    let calibrates = domains.is_ok_and(|d| wanted.iter().all(|w| d.contains(w)));
    (calibrates.then_some(name), left_out)
}

impl Calibrator {
    pub fn new(instance: &ash::Instance, device: &ash::Device, extension: &CStr) -> Calibrator {
        if extension == ash::khr::calibrated_timestamps::NAME {
            Calibrator::Khr(ash::khr::calibrated_timestamps::Device::new(instance, device))
        } else {
            Calibrator::Ext(ash::ext::calibrated_timestamps::Device::new(instance, device))
        }
    }

    pub fn calibrate(&self) -> Result<Calibration, VkError> {
        let info = [
            vk::CalibratedTimestampInfoKHR::default().time_domain(vk::TimeDomainKHR::DEVICE),
            vk::CalibratedTimestampInfoKHR::default().time_domain(vk::TimeDomainKHR::CLOCK_MONOTONIC),
        ];
        // SAFETY: the extension was enabled on this device; both domains were
        // reported calibrateable.
        let (stamps, deviation) = unsafe {
            match self {
                Calibrator::Khr(d) => d.get_calibrated_timestamps(&info),
                Calibrator::Ext(d) => d.get_calibrated_timestamps(&info),
            }
        }
        .call("vkGetCalibratedTimestamps")?;
        Ok(Calibration { device_ticks: stamps[0], host_ns: stamps[1], max_deviation_ns: deviation })
    }
}

/// `CLOCK_MONOTONIC` now, in nanoseconds (the host side of a calibration).
pub fn host_monotonic_ns() -> u64 {
    let mut ts = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: clock_gettime writes one timespec into the pointer it is given.
    unsafe { libc::clock_gettime(libc::CLOCK_MONOTONIC, &mut ts) };
    ts.tv_sec as u64 * 1_000_000_000 + ts.tv_nsec as u64
}
