//! Which device extensions the running validation layer knows. A layer built
//! against an older Vulkan header than the driver's warns about every enabled
//! extension it does not know ("Device Extension ... is not supported by this
//! layer"), and any warning fails a validated run: Debian 12's layer (1.3.239)
//! against a 2026 driver that offers `VK_KHR_calibrated_timestamps` (header
//! 1.3.273) failed every validated comparison. So with validation on, an
//! extension enters the device only where the layer's header version is at
//! least the one that introduced it; [`choose`] says what it left out and why.

use ash::vk;
use std::ffi::CStr;

/// The header version that introduced each device extension sweeplab may
/// enable (the Vulkan registry's first header with it).
pub const KNOWN_SINCE: [(&CStr, u32); 4] = [
    (ash::khr::swapchain::NAME, vk::make_api_version(0, 1, 0, 0)),
    (ash::khr::push_descriptor::NAME, vk::make_api_version(0, 1, 0, 39)),
    (ash::ext::calibrated_timestamps::NAME, vk::make_api_version(0, 1, 1, 89)),
    (ash::khr::calibrated_timestamps::NAME, vk::make_api_version(0, 1, 3, 273)),
];

/// The header version that introduced `name`; `None` for one sweeplab does
/// not enable (and so does not list).
pub fn known_since(name: &CStr) -> Option<u32> {
    KNOWN_SINCE.iter().find(|(n, _)| *n == name).map(|(_, v)| *v)
}

/// Whether a layer of header version `layer` knows `name`; without a layer
/// (validation off) every extension may be enabled. An extension missing from
/// [`KNOWN_SINCE`] counts as unknown, so a new one cannot slip past the check.
pub fn layer_knows(name: &CStr, layer: Option<u32>) -> bool {
    match layer {
        None => true,
        Some(version) => known_since(name).is_some_and(|since| since <= version),
    }
}

/// An extension the device offers that stays off because the layer would not know it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LeftOut {
    pub name: String,
    pub since: String,
    pub layer: String,
}

impl LeftOut {
    /// `VK_KHR_calibrated_timestamps (header 1.3.273) left out: the validation layer is 1.3.239`.
    pub fn describe(&self) -> String {
        format!("{} (header {}) left out: the validation layer is {}", self.name, self.since, self.layer)
    }
}

/// Of `wanted` (in order of preference, each a name the device offers), the
/// ones the layer knows, and what was left out.
pub fn choose(wanted: &[&'static CStr], layer: Option<u32>) -> (Vec<&'static CStr>, Vec<LeftOut>) {
    let mut chosen = Vec::new();
    let mut left_out = Vec::new();
    for &name in wanted {
        if layer_knows(name, layer) {
            chosen.push(name);
        } else {
            left_out.push(LeftOut {
                name: name.to_string_lossy().into_owned(),
                since: known_since(name).map_or("unknown".into(), super::device_info::version_string),
                layer: layer.map_or(String::new(), super::device_info::version_string),
            });
        }
    }
    (chosen, left_out)
}

/// The extension name of a layer message that says the layer does not know
/// an enabled extension (`Device Extension X is not supported by this layer`).
pub fn unknown_extension_in(message: &str) -> Option<&str> {
    let (_, after) = message.split_once("Extension ")?;
    let (name, rest) = after.split_once(' ')?;
    rest.starts_with("is not supported by this layer").then_some(name)
}

#[cfg(test)]
mod tests {
    use super::*;

    const DEBIAN_12: u32 = vk::make_api_version(0, 1, 3, 239);

    #[test]
    fn an_older_layer_gets_the_calibration_extension_it_knows() {
        let khr = ash::khr::calibrated_timestamps::NAME;
        let ext = ash::ext::calibrated_timestamps::NAME;
        let (chosen, left) = choose(&[khr, ext], Some(DEBIAN_12));
        assert_eq!(chosen, [ext]);
        assert_eq!(left.len(), 1);
        assert_eq!(
            left[0].describe(),
            "VK_KHR_calibrated_timestamps (header 1.3.273) left out: the validation layer is 1.3.239"
        );
        let (chosen, left) = choose(&[khr, ext], Some(vk::make_api_version(0, 1, 3, 280)));
        assert_eq!((chosen, left.len()), (vec![khr, ext], 0));
        let (chosen, left) = choose(&[khr], None);
        assert_eq!((chosen, left.len()), (vec![khr], 0), "without validation nothing is left out");
        assert!(!layer_knows(c"VK_KHR_not_in_the_table", Some(u32::MAX)), "an unlisted extension is not trusted");
    }

    #[test]
    fn the_layer_message_names_the_unknown_extension() {
        // As the Debian 12 layer wrote it on the H200 (MessageID 0x79de34d4).
        let message = "Validation Warning: [ VUID_Undefined ] Object 0: handle = 0x555fbbbfddc0, type = \
                       VK_OBJECT_TYPE_DEVICE; | MessageID = 0x79de34d4 | Device Extension \
                       VK_KHR_calibrated_timestamps is not supported by this layer.  Using this extension may \
                       adversely affect validation results and/or produce undefined behavior.";
        assert_eq!(unknown_extension_in(message), Some("VK_KHR_calibrated_timestamps"));
        assert_eq!(unknown_extension_in("Validation Error: [ SYNC-HAZARD-READ-AFTER-WRITE ] ..."), None);
    }
}
