use crate::vk::VkError;

#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error(transparent)]
    Vk(#[from] VkError),
    #[error("{0}")]
    Invalid(String),
}
