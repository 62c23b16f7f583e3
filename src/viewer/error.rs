//! What can stop the viewer: no display, the window, Vulkan, the scene, the
//! technique, the script, writing files.

use crate::render::RenderError;
use crate::scene::scene_file::SceneError;
use crate::vk::VkError;

#[derive(Debug, thiserror::Error)]
pub enum ViewerError {
    #[error("no display: {0}")]
    NoDisplay(String),
    #[error("window: {0}")]
    Window(String),
    #[error(transparent)]
    Vk(#[from] VkError),
    #[error(transparent)]
    Render(#[from] RenderError),
    #[error(transparent)]
    Scene(#[from] SceneError),
    #[error("{0}")]
    Script(String),
    #[error("cannot write {path}: {message}")]
    Write { path: String, message: String },
}
