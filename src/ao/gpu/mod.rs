//! The AO preprocessing's per-voxel work on the GPU: the space sweep of local
//! histograms ([`sweep`]) and the nearest-codeword assignment ([`assign`]),
//! with the final codebook summed on the CPU from the streamed read-back.
//! The CPU path (`crate::ao::preprocess` with `ao.backend = "cpu"`) stays the
//! reference. See docs/ao.md, "GPU space sweep".

pub mod assign;
pub mod plan;
pub mod sweep;

pub use assign::{assign_packed, SearchState};
pub use sweep::{BatchOutput, GpuSweep, PassTimes, SliceSync, SweepInputs, BATCH_BYTES};
