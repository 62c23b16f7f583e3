//! What every GPU technique shares: the scene uploaded once ([`GpuScene`]), the
//! frame parameters, the output image and its readback, the light-space and
//! image-space geometry, the plain ray cast, and the [`RenderTechnique`] trait
//! each technique implements in its own module. `render` knows no technique:
//! the catalogue above them (`crate::techniques`) lists them. The frame's
//! images come from [`FrameImages`]: each frame's own, or kept (the viewer).

pub mod device_fit;
pub mod early_termination;
pub mod empty_cells;
pub mod error;
pub mod frame_images;
pub mod frame_params;
pub mod frame_result;
pub mod gpu_scene;
pub mod image_space;
pub mod light_grid_limits;
pub mod light_region;
pub mod light_space;
pub mod line_shape;
pub mod output;
pub mod raycast;
pub mod recorded_frame;
pub mod session;
pub mod technique;
pub mod view_chunks;

pub use error::RenderError;
pub use frame_images::FrameImages;
pub use frame_result::FrameResult;
pub use gpu_scene::{GpuScene, UploadedVolume, VolumeTexels};
pub use line_shape::{ChainsByRole, LineShape, StopsPassShape};
pub use output::OutputImage;
pub use recorded_frame::{render_recorded, RecordedFrame};
pub use session::FrameSession;
pub use technique::{RenderTechnique, ResourceNeed};
