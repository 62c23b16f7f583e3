//! What can go wrong in AO preprocessing: bad settings, an unusable training
//! set, the GPU backend, and cache file I/O.

use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum AoError {
    /// A setting out of range or misspelt; the message names `ao.key = value`
    /// and what is allowed.
    #[error("{0}")]
    Invalid(String),
    /// The training set rule selects no voxel of this volume.
    #[error("ao training set is empty: {0}")]
    EmptyTrainingSet(String),
    /// The GPU backend failed (a Vulkan call, an allocation, a shader).
    #[error("ao on the GPU: {0}")]
    Gpu(#[from] crate::vk::VkError),
    /// The GPU backend cannot run these settings on this volume.
    #[error("ao on the GPU: {0}")]
    GpuLimit(String),
    #[error("ao cache {path}: {source}")]
    CacheIo {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
}

/// How a frame of technique `ao` reports its preprocessing's errors: `render`
/// knows no technique, so it carries them as a technique's error.
impl From<AoError> for crate::render::RenderError {
    fn from(e: AoError) -> Self {
        crate::render::RenderError::Technique(Box::new(e))
    }
}
