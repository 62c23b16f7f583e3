//! The techniques, one folder each, and the catalogue over them: the one
//! place that lists them ([`Technique`]), owns the scene-file tables they read
//! ([`CATALOGUE`]) and reads scenes with those tables ([`load_scene`] and its
//! siblings). `scene` and `render` know no technique; each technique folder
//! builds on them and knows neither another technique nor the catalogue;
//! front ends (CLI, viewer, benches) come here.

pub mod ao;
pub mod dvr;
pub mod half_angle;
pub mod ipsvi;
pub mod lightvolume;

pub mod comparison;
pub mod ground_truth_cache;
pub mod registry;
pub mod scenes;
pub mod tables;

pub use registry::{profiled_frame, render, session, Registration, RenderOutput, TableEntry, Technique, REGISTERED};
pub use scenes::{
    default_scene, default_scene_spec, load_scene, parse_scene_file, parse_scene_str, scene_for_volume_file,
    scene_from_toml_str, volume_file_scene_spec,
};
pub use tables::{Catalogue, CATALOGUE};
