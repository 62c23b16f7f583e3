//! What a technique's frame returns before the registry adds its profile.

use crate::linear_image::LinearImage;

pub struct FrameResult {
    pub image: LinearImage,
    /// Compute dispatches and pipeline barriers recorded for the frame.
    pub dispatches: u32,
    pub barriers: u32,
}
