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
}
