//! Everything a frame is made of: volume, transfer function, camera, lights and
//! the settings of renderers, as loaded from a scene file or built procedurally.

pub mod camera;
pub mod default_scene;
pub mod framing;
pub mod geometry;
pub mod light;
pub mod light_paths;
pub mod loaders;
pub mod missing_file;
pub mod overrides;
pub mod presets;
pub mod scene_file;
pub mod scene_schema;
pub mod scene_spec;
pub mod settings_controls;
pub mod settings_docs;
pub mod settings_table;
pub mod suggest;
pub mod synthetic;
pub mod technique_settings;
pub mod transfer;
pub mod user_terms;
pub mod volume;
pub mod volume_filter;
pub mod warnings;

pub use camera::{Camera, Projection, RayBasis};
pub use geometry::VolumeBox;
pub use light::{Falloff, Light, LightKind};
pub use technique_settings::TechniqueSettings;
pub use transfer::{ControlPoint, TransferFunction, TransferLut};
pub use volume::{Interpolation, Volume, VoxelData};
pub use volume_filter::VolumeFilter;

use glam::Vec3;

/// Which ground-truth optical model (docs/optical-model.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OpticalModel {
    /// (i) Emission-absorption plus single scattering of every light, attenuated by
    /// the transmittance of a shadow ray (selective-light paper, eq. 1-2).
    SingleScattering,
    /// (ii) As (i), but the light reaching a sample also carries the emission of
    /// the media between it and the light (IPSVI paper, eq. 1-3).
    EmissiveScattering,
}

#[derive(Clone, Debug, PartialEq)]
pub struct RenderSettings {
    pub width: u32,
    pub height: u32,
    /// Ray-marching step in voxels (of the smallest spacing).
    pub step_voxels: f32,
    /// Linear RGB seen where rays leave the volume.
    pub background: Vec3,
    /// Emission scale: the medium emits `emission * rgb(s)` (the ambient term).
    pub emission: f32,
    /// Each pixel's view samples at its own phase within their steps
    /// (reference::ray_start) instead of at the midpoints.
    pub jitter: bool,
    /// How the GPU filters the volume between texels (docs/filtering.md).
    pub filter: VolumeFilter,
}

#[derive(Clone, Debug, PartialEq)]
pub struct ReferenceSettings {
    pub model: OpticalModel,
    /// View-ray step in voxels.
    pub step_voxels: f32,
    /// Shadow-ray step in voxels.
    pub shadow_step_voxels: f32,
    /// View rays stop once their transmittance falls below this (0 disables).
    pub min_transmittance: f32,
    /// Coloured extinction along shadow rays: each channel's optical depth is
    /// `sigma * (1 - rgb)` (the light volume's `chromatic` propagation).
    pub chromatic: bool,
}

#[derive(Clone, Debug, PartialEq)]
pub struct PhongSettings {
    pub ambient: f32,
    pub diffuse: f32,
    pub specular: f32,
    pub shininess: f32,
}

#[derive(Clone, Debug)]
pub struct Scene {
    pub volume: Volume,
    pub transfer: TransferFunction,
    pub camera: Camera,
    pub lights: Vec<Light>,
    pub render: RenderSettings,
    pub reference: ReferenceSettings,
    pub phong: PhongSettings,
    /// Settings of the techniques with their own table (`[ipsvi]`,
    /// `[lightvolume]`, `[half_angle]`), checked when the scene file is read.
    pub settings: TechniqueSettings,
    /// The technique tables the scene gave (in the file or by `--set`), so a
    /// table no running technique reads can be named.
    pub technique_tables: Vec<&'static str>,
}

impl Scene {
    pub fn volume_box(&self) -> VolumeBox {
        VolumeBox::new(self.volume.dims, self.volume.spacing)
    }

    /// The lights as every technique and the reference render them: a far
    /// point or spot light becomes the directional light it approaches
    /// ([`Light::far_limit`]). Read here, not from `lights`, so a scene built
    /// or changed in code (not from a file) gets the same rule.
    pub fn rendered_lights(&self) -> Vec<Light> {
        let radius = self.volume_box().half_extent.length();
        self.lights.iter().map(|l| l.far_limit(radius)).collect()
    }
}
