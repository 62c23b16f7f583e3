//! A thin, explicit layer over ash. It knows nothing about volumes or techniques:
//! renderers record through [`commands::Recorder`] and the barriers of
//! [`barriers`], and every pass gets a debug label and a profiler scope of one name.

pub mod barriers;
pub mod calibration;
pub mod commands;
pub mod context;
pub mod creation_counts;
pub mod descriptor_pool_shelf;
pub mod descriptors;
pub mod device_info;
pub mod error;
pub mod events;
pub mod finished_frame;
pub mod interface;
pub mod lavapipe_shader_cache;
pub mod layer_extensions;
pub mod limits;
pub mod memory;
pub mod pipeline;
pub mod pipeline_cache;
pub mod pipeline_store;
pub mod profiler;
pub mod resources;
pub mod staging;
pub mod subgroups;
pub mod surface;
pub mod swapchain;
pub mod validated_thread;
pub mod validation;
pub mod validation_verdict;
pub mod wait_report;

pub use barriers::Barrier;
pub use commands::Recorder;
pub use context::{Context, ContextOptions};
pub use error::VkError;
pub use pipeline::{ComputePipeline, ComputePipelineDesc};
pub use profiler::{ProfileReport, Profiler, ScopeTimeline};
pub use resources::{Buffer, Image};
pub use surface::Surface;
pub use swapchain::Swapchain;
pub use wait_report::{WaitReport, WaitReporter};
