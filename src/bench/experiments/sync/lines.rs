//! What a configuration of the study renders: the IPSVI sweep (sweep and
//! empty workloads) or the chain workload's lines, behind one frame call.

use super::chain::ChainLines;
use crate::bench::experiments::ExperimentError;
use crate::linear_image::LinearImage;
use crate::techniques::ipsvi::renderer::IpsviRenderer;
use crate::techniques::ipsvi::SyncStrategy;
use crate::vk::Profiler;
use ash::vk;

/// One configuration's renderer (boxed: a renderer holds its descriptors and
/// images inline, and a study holds dozens).
pub enum StudyLines<'a> {
    Ipsvi(Box<IpsviRenderer<'a>>),
    Chain(Box<ChainLines<'a>>),
}

/// What one frame recorded, and its image (the IPSVI frames').
pub struct StudyFrame {
    pub dispatches: u32,
    pub barriers: u32,
    pub image: Option<LinearImage>,
}

impl StudyLines<'_> {
    /// One frame with `sync` between lines (per-line scopes where the
    /// profiler's detail is on).
    pub fn frame(&mut self, profiler: &mut Profiler, sync: SyncStrategy) -> Result<StudyFrame, ExperimentError> {
        Ok(match self {
            StudyLines::Ipsvi(r) => {
                let f = r.frame(profiler, sync)?;
                StudyFrame { dispatches: f.dispatches, barriers: f.barriers, image: Some(f.image) }
            }
            StudyLines::Chain(c) => {
                let f = c.frame(profiler, sync)?;
                StudyFrame { dispatches: f.dispatches, barriers: f.barriers, image: None }
            }
        })
    }

    /// Every pipeline a frame dispatches (a warmed one skips its warm-up frame).
    pub fn pipelines(&self) -> Vec<vk::Pipeline> {
        match self {
            StudyLines::Ipsvi(r) => r.pipelines(),
            StudyLines::Chain(c) => c.pipelines(),
        }
    }

    /// The profiler scope of one line.
    pub fn line_scope(&self) -> &'static str {
        match self {
            StudyLines::Ipsvi(_) => "ipsvi_line",
            StudyLines::Chain(_) => super::chain::LINE_SCOPE,
        }
    }
}
