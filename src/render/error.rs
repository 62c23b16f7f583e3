use crate::scene::settings_table::SettingsError;
use crate::vk::VkError;

#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error(transparent)]
    Vk(#[from] VkError),
    /// Technique settings out of range (set in code; a scene file's are checked when read).
    #[error(transparent)]
    Settings(#[from] SettingsError),
    #[error("{0}")]
    Invalid(String),
    /// A technique's own error (ambient occlusion's preprocessing, ...), which
    /// `render` knows only as an error.
    #[error(transparent)]
    Technique(Box<dyn std::error::Error + Send + Sync>),
    /// The frame came back with NaN or infinite pixels: never written or compared.
    #[error("{technique} rendered {bad} of {total} pixels as NaN or infinity; the image is not written")]
    NonFinite { technique: &'static str, bad: usize, total: usize },
}
