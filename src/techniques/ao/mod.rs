//! Ambient occlusion and colour bleeding from clustered local histograms
//! (Ropinski et al., EG 2008): the preprocessing, on the CPU. See `docs/ao.md`.
//!
//! [`preprocess`] streams: local histograms ([`histogram`]) -> packing scheme
//! from the global histogram ([`packing`]) -> training set ([`training_set`])
//! -> LBG training on packed histograms ([`quantize`]) -> nearest-codeword
//! assignment of every voxel's two hemispheres, while the unpacked histograms
//! of each cluster are summed into the final codebook. No step holds the
//! histograms of all voxels: the training set's are held packed, everything
//! else lives one slab at a time. [`preprocess_cached`] puts the disk cache
//! ([`cache`]) in front.

pub mod bin_runs;
pub mod cache;
mod codebook_lanes;
mod controls;
pub mod environment;
pub mod error;
pub mod gpu;
pub mod gradient;
pub mod ground_truth;
pub mod histogram;
pub mod lane_rows;
mod lloyd_bounds;
pub mod packing;
pub mod parallel;
pub mod preprocess;
pub mod progress;
pub mod quantize;
pub mod render;
pub mod render_settings;
pub mod row_runs;
pub mod search;
pub mod session;
pub mod settings;
pub mod technique;
pub mod terminal_progress;
pub mod training_set;

pub use cache::{AoCache, CacheKey, CacheMiss};
pub use error::AoError;
pub use preprocess::{
    preprocess, preprocess_cached, preprocess_cached_on, preprocess_on, AoPreprocessed, CacheOutcome, ClusterSums,
    PreprocessStats, StepTimings, VolumeAssignment,
};
pub use progress::Progress;
pub use render_settings::AoMode;
pub use settings::{AoSettings, Backend, Metric, TrainingSet};
