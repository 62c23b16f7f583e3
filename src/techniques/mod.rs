//! The catalogue above the techniques: the one place that lists them
//! ([`Technique`]), owns the scene-file tables they read ([`CATALOGUE`]) and
//! reads scenes with those tables ([`load_scene`] and its siblings). Below it,
//! `scene` and `render` know no technique; each technique folder builds on
//! them; front ends (CLI, viewer, benches) come here.

pub mod comparison;
pub mod ground_truth_cache;
pub mod registry;
pub mod scenes;
pub mod tables;

pub use registry::{profiled_frame, render, session, RenderOutput, Technique};
pub use scenes::{
    default_scene, default_scene_spec, load_scene, parse_scene_file, parse_scene_str, scene_for_volume_file,
    scene_from_toml_str, volume_file_scene_spec,
};
pub use tables::{Catalogue, CATALOGUE};
