//! Image plane sweep volume illumination (Sundén, Ynnerman, Ropinski 2011),
//! approximating optical model (ii) of docs/optical-model.md; design and the
//! ways it differs from the paper in docs/ipsvi.md.
//!
//! The host plans the sweep ([`sweep_plan`]); every line block is its own
//! dispatch, followed by the barrier `cache_write_to_next_line_read` (or, in
//! the synchronization study, another [`SyncStrategy`]'s object from [`sync`]).
//! With `merge_sweeps`, step k of every independent sweep shares one dispatch
//! and one barrier ([`merged_steps`]).

pub mod block_records;
pub mod breakdown;
pub mod cache_images;
pub mod cache_plane;
pub mod cache_update;
mod controls;
pub mod exit_points;
pub mod gpu_params;
pub mod light_anchor;
pub mod line_group;
pub mod line_kernel;
pub mod line_shape;
pub mod lit_box;
pub mod merged_output;
pub mod merged_steps;
pub mod read_fronts;
pub mod renderer;
pub mod session;
pub mod settings;
pub mod study;
pub mod sweep_plan;
pub mod sync;
pub mod sync_strategy;
pub mod technique;
pub mod view_budget;
pub mod view_stops;

pub use breakdown::BreakdownStep;
pub use cache_update::{CacheUpdate, CacheWrite, WritePass, WriteRule, WriteValue};
pub use line_kernel::{KernelChoice, LineKernel};
pub use read_fronts::ReadFronts;
pub use renderer::{render, render_study, render_with};
pub use settings::{EarlyTermination, IpsviSettings};
pub use study::IpsviStudy;
pub use sync_strategy::SyncStrategy;
pub use technique::Ipsvi;
