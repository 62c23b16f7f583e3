//! What a technique's frame returns before the registry adds its profile.

use super::line_shape::LineShape;
use crate::linear_image::LinearImage;

pub struct FrameResult {
    pub image: LinearImage,
    /// Compute dispatches and pipeline barriers recorded for the frame.
    pub dispatches: u32,
    pub barriers: u32,
    /// A line-sweep frame's shape (IPSVI); None for the other techniques.
    pub shape: Option<LineShape>,
}
