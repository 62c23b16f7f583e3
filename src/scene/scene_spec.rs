//! A scene read and checked, before its volume is loaded, and how it becomes a
//! [`Scene`] once the volume is there: automatic transfer function and camera
//! framing depend on the volume.

use std::path::PathBuf;

use glam::Vec3;

use super::camera::{Camera, Projection};
use super::light::Light;
use super::loaders;
use super::presets::transfer_from_histogram;
use super::scene_file::SceneError;
use super::synthetic::SyntheticKind;
use super::transfer::TransferFunction;
use super::volume::Volume;
use super::{PhongSettings, ReferenceSettings, RenderSettings, Scene, TechniqueSettings, VolumeBox};

/// Auto-framing leaves this much room around the volume's bounding sphere.
pub const FRAMING_MARGIN: f32 = 1.05;

/// Where the volume comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum VolumeSource {
    File(PathBuf),
    Synthetic { kind: SyntheticKind, size: u32, seed: u64 },
}

#[derive(Clone, Debug, PartialEq)]
pub enum TransferSpec {
    Given(TransferFunction),
    /// [`transfer_from_histogram`] of the volume, once loaded.
    FromHistogram,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CameraPlacement {
    /// [`Camera::orbit`]; `distance: None` frames the volume.
    Orbit {
        target: Vec3,
        azimuth_deg: f32,
        elevation_deg: f32,
        distance: Option<f32>,
    },
    LookAt {
        eye: Vec3,
        target: Vec3,
        up: Vec3,
    },
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ProjectionSpec {
    Perspective {
        fov_y_deg: f32,
    },
    /// `height: None` frames the volume.
    Orthographic {
        height: Option<f32>,
    },
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraSpec {
    pub placement: CameraPlacement,
    pub projection: ProjectionSpec,
}

impl CameraSpec {
    /// The camera for a volume box and image size, filling in auto-framed values:
    /// the box's bounding sphere fits the view with 5 % margin, horizontally too.
    pub fn resolve(&self, volume_box: &VolumeBox, width: u32, height: u32) -> Camera {
        let radius = volume_box.half_extent.length() * FRAMING_MARGIN;
        let aspect = width as f32 / height.max(1) as f32;
        let projection = match self.projection {
            ProjectionSpec::Perspective { fov_y_deg } => Projection::Perspective { fov_y_deg },
            ProjectionSpec::Orthographic { height } => {
                Projection::Orthographic { height: height.unwrap_or(2.0 * radius / aspect.min(1.0)) }
            }
        };
        match self.placement {
            CameraPlacement::Orbit { target, azimuth_deg, elevation_deg, distance } => {
                let distance = distance.unwrap_or_else(|| match projection {
                    Projection::Perspective { fov_y_deg } => {
                        let half_y = fov_y_deg.to_radians() * 0.5;
                        let half_x = (half_y.tan() * aspect).atan();
                        radius / half_y.min(half_x).sin()
                    }
                    // Any distance outside the box shows the same image.
                    Projection::Orthographic { .. } => 3.0 * radius,
                });
                Camera::orbit(target, distance, azimuth_deg, elevation_deg, projection)
            }
            CameraPlacement::LookAt { eye, target, up } => Camera { eye, target, up, projection },
        }
    }
}

/// A scene file read and checked, before its volume is loaded.
#[derive(Clone, Debug)]
pub struct SceneSpec {
    /// Where it came from, for messages.
    pub origin: String,
    pub volume: VolumeSource,
    pub transfer: TransferSpec,
    pub camera: CameraSpec,
    pub lights: Vec<Light>,
    pub render: RenderSettings,
    pub reference: ReferenceSettings,
    pub phong: PhongSettings,
    pub settings: TechniqueSettings,
}

impl SceneSpec {
    pub fn load_volume(&self) -> Result<Volume, SceneError> {
        match &self.volume {
            VolumeSource::File(path) if !path.exists() => Err(SceneError::MissingVolume {
                origin: self.origin.clone(),
                path: path.clone(),
                hint: super::missing_file::missing_file_hint(path),
            }),
            VolumeSource::File(path) => loaders::load_volume(path).map_err(|source| SceneError::Volume {
                origin: self.origin.clone(),
                path: path.clone(),
                source: Box::new(source),
            }),
            VolumeSource::Synthetic { kind, size, seed } => Ok(kind.generate(*size, *seed)),
        }
    }

    pub fn build(self) -> Result<Scene, SceneError> {
        let volume = self.load_volume()?;
        Ok(self.build_with_volume(volume))
    }

    /// Builds the scene around an already loaded volume (which replaces
    /// `self.volume`; the transfer function and framing follow it).
    pub fn build_with_volume(self, volume: Volume) -> Scene {
        let transfer = match self.transfer {
            TransferSpec::Given(tf) => tf,
            TransferSpec::FromHistogram => transfer_from_histogram(&volume),
        };
        let volume_box = VolumeBox::new(volume.dims, volume.spacing);
        let camera = self.camera.resolve(&volume_box, self.render.width, self.render.height);
        Scene {
            volume,
            transfer,
            camera,
            // Far point and spot lights become the directional
            // lights they approach, one rule for every technique.
            lights: self.lights.iter().map(|l| l.far_limit(volume_box.half_extent.length())).collect(),
            render: self.render,
            reference: self.reference,
            phong: self.phong,
            settings: self.settings,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn auto_framing_fits_the_bounding_sphere() {
        let spec = CameraSpec {
            placement: CameraPlacement::Orbit {
                target: Vec3::ZERO,
                azimuth_deg: 0.0,
                elevation_deg: 0.0,
                distance: None,
            },
            projection: ProjectionSpec::Perspective { fov_y_deg: 30.0 },
        };
        let cube = VolumeBox::new(glam::UVec3::splat(10), Vec3::ONE);
        let camera = spec.resolve(&cube, 200, 100);
        // Cube of side 1: bounding radius sqrt(3)/2, seen under the half fov of 15 deg.
        let expected = 3f32.sqrt() / 2.0 * FRAMING_MARGIN / 15f32.to_radians().sin();
        assert!((camera.eye.length() - expected).abs() < 1e-4, "{} vs {expected}", camera.eye.length());
        // A tall image is limited by its narrower horizontal field of view.
        let tall = spec.resolve(&cube, 100, 200);
        assert!(tall.eye.length() > expected * 1.5);
    }
}
