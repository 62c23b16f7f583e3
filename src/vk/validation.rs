//! Validation-layer messages: a debug-utils messenger collects every warning and
//! error so that a run can print them and fail, and tests can assert on them.

use ash::vk;
use std::ffi::CStr;
use std::sync::{Arc, Mutex};

/// Messages the validation layer reported, shared with the messenger callback.
#[derive(Clone, Default)]
pub struct ValidationLog {
    messages: Arc<Mutex<Vec<String>>>,
}

impl ValidationLog {
    pub fn messages(&self) -> Vec<String> {
        self.messages.lock().map(|m| m.clone()).unwrap_or_default()
    }

    /// Takes the messages collected so far, leaving the log empty.
    pub fn take(&self) -> Vec<String> {
        self.messages.lock().map(|mut m| std::mem::take(&mut *m)).unwrap_or_default()
    }

    /// Pointer handed to the messenger as user data; valid while `self` lives
    /// (the context keeps the log until after the messenger is destroyed).
    pub(crate) fn as_user_data(&self) -> *mut std::ffi::c_void {
        Arc::as_ptr(&self.messages) as *mut std::ffi::c_void
    }
}

/// Severities that count as validation failures.
pub fn reported_severities() -> vk::DebugUtilsMessageSeverityFlagsEXT {
    vk::DebugUtilsMessageSeverityFlagsEXT::WARNING | vk::DebugUtilsMessageSeverityFlagsEXT::ERROR
}

/// The debug-utils messenger callback.
///
/// # Safety
/// Called by the Vulkan loader only: `data` is valid for the call and `user_data`
/// is the message list of a live [`ValidationLog`].
pub unsafe extern "system" fn messenger_callback(
    severity: vk::DebugUtilsMessageSeverityFlagsEXT,
    kind: vk::DebugUtilsMessageTypeFlagsEXT,
    data: *const vk::DebugUtilsMessengerCallbackDataEXT<'_>,
    user_data: *mut std::ffi::c_void,
) -> vk::Bool32 {
    // SAFETY: the loader passes a valid callback-data pointer for the duration of
    // the call; user_data is the Arc'd message list that outlives the messenger.
    let (text, messages) = unsafe {
        let text = if data.is_null() || (*data).p_message.is_null() {
            "<no message>".to_string()
        } else {
            CStr::from_ptr((*data).p_message).to_string_lossy().into_owned()
        };
        (text, &*(user_data as *const Mutex<Vec<String>>))
    };
    let line = format!("[{severity:?} {kind:?}] {text}");
    if let Ok(mut m) = messages.lock() {
        m.push(line);
    }
    vk::FALSE
}
