//! `sweeplab view`: a winit window on a Vulkan swapchain. Each frame the
//! technique renders through the same code as `render` (its session keeps what
//! it may keep across frames, e.g. the light volume), then the present pass
//! blits the linear frame into the sRGB swapchain image and presents it, with
//! frames in flight synchronized by per-slot fences and semaphores.
//!
//! One idea per file: the window and its events ([`window`]), frames in
//! flight ([`frames`]), the present pass ([`present_pass`]), the frame loop
//! ([`frame_loop`]) and one frame's submission ([`frame_submit`]), previews
//! while dragging ([`preview`]), the window's size and the image's place in
//! it ([`window_fit`]), the edited scene ([`live_scene`]), mouse camera control
//! ([`controls`]), scripted runs ([`script`]), the per-frame log ([`report`]),
//! the control panel and live profiler ([`ui`]), its transfer-function editor
//! ([`tf_editor`]) and its controls for every technique's settings
//! ([`settings_panel`]).
//! The surface and swapchain wrappers live in `crate::vk`.

pub mod controls;
pub mod error;
pub mod frame_loop;
pub mod frame_submit;
pub mod frames;
pub mod live_scene;
pub mod present_pass;
pub mod preview;
pub mod report;
pub mod script;
pub mod settings_panel;
pub mod tf_editor;
pub mod ui;
pub mod window;
pub mod window_fit;

pub use error::ViewerError;
pub use frame_loop::{run, ViewerOptions};
pub use live_scene::SceneSource;
pub use report::{FrameRecord, ViewerReport};
pub use script::Script;
