use crate::bench::protocol::ProtocolError;
use crate::bench::BenchError;
use crate::metrics::MetricsError;
use crate::render::RenderError;
use crate::vk::VkError;

/// Why an experiment could not be measured.
#[derive(Debug, thiserror::Error)]
pub enum ExperimentError {
    #[error(transparent)]
    Render(#[from] RenderError),
    #[error(transparent)]
    Vk(#[from] VkError),
    #[error(transparent)]
    Metrics(#[from] MetricsError),
    #[error("incremental mode did not converge in {0} frames")]
    NotConverged(usize),
    #[error("{0}")]
    Invalid(String),
    #[error(transparent)]
    Protocol(#[from] ProtocolError),
    #[error(transparent)]
    Report(#[from] BenchError),
    #[error("validation reported {what}: {}", messages.join("\n"))]
    Validation { what: String, messages: Vec<String> },
}
