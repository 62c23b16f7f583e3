//! Errors of the Vulkan layer carry the failing call and its `vk::Result`.

use ash::vk;

#[derive(Debug, thiserror::Error)]
pub enum VkError {
    #[error(
        "cannot load the Vulkan loader (libvulkan.so.1): {0}; install libvulkan1 and a driver (tools/setup.sh does)"
    )]
    Loader(String),
    #[error("{call} failed: {result:?}")]
    Call { call: &'static str, result: vk::Result },
    #[error("no Vulkan device found; install mesa-vulkan-drivers (lavapipe) or a GPU driver")]
    NoDevice,
    #[error("no Vulkan device matches {wanted:?}; available: {available}")]
    DeviceNotFound { wanted: String, available: String },
    #[error("device {device} lacks {missing}")]
    MissingFeature { device: String, missing: String },
    #[error("validation layer VK_LAYER_KHRONOS_validation is not installed (apt-get install vulkan-validationlayers)")]
    NoValidationLayer,
    #[error("memory allocation for {name} failed: {message}")]
    Allocation { name: String, message: String },
    #[error("no {kind} format among {candidates} supports {usage} on this device")]
    NoFormat { kind: &'static str, candidates: String, usage: &'static str },
    #[error("shader {shader}: binding {binding} {problem}")]
    Binding { shader: &'static str, binding: &'static str, problem: String },
    #[error("shader {shader}: {problem}")]
    Shader { shader: &'static str, problem: String },
    #[error("the Vulkan loader lacks instance extension {0}, which a window needs")]
    MissingExtension(String),
    #[error("{0}")]
    Presentation(String),
    #[error("profiler misuse: {0}")]
    Profiler(String),
    #[error("pipeline cache {path}: {message}")]
    PipelineCache { path: String, message: String },
    #[error(transparent)]
    Limit(#[from] super::limits::LimitExceeded),
}

/// Adds the name of the failing call to a raw `vk::Result`.
pub trait VkResultExt<T> {
    fn call(self, call: &'static str) -> Result<T, VkError>;
}

impl<T> VkResultExt<T> for Result<T, vk::Result> {
    fn call(self, call: &'static str) -> Result<T, VkError> {
        self.map_err(|result| VkError::Call { call, result })
    }
}
