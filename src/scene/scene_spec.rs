//! A scene read and checked, before its volume is loaded, and how it becomes a
//! [`Scene`] once the volume is there: automatic transfer function and camera
//! framing depend on the volume.

use std::path::PathBuf;

use glam::Vec3;

use super::camera::{Camera, Projection};
use super::framing::{fit_orbit, visible_box, WorldBox};
use super::light::Light;
use super::loaders;
use super::presets::transfer_from_histogram;
use super::scene_file::SceneError;
use super::synthetic::SyntheticKind;
use super::transfer::TransferFunction;
use super::volume::Volume;
use super::{PhongSettings, ReferenceSettings, RenderSettings, Scene, TechniqueSettings, VolumeBox};

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
    /// The camera for an image size, filling in auto-framed values: the
    /// distance (or orthographic height) that puts the corners of `framed`
    /// (what the transfer function shows, [`super::framing::visible_box`]) at
    /// [`super::framing::FRAME_FILL`] of the view; an orthographic eye stays outside the
    /// volume's bounding sphere.
    pub fn resolve(&self, volume_box: &VolumeBox, framed: &WorldBox, width: u32, height: u32) -> Camera {
        let aspect = width as f32 / height.max(1) as f32;
        let outside = 3.0 * volume_box.half_extent.length();
        match self.placement {
            CameraPlacement::Orbit { target, azimuth_deg, elevation_deg, distance } => {
                let fov_y_deg = match self.projection {
                    ProjectionSpec::Perspective { fov_y_deg } => fov_y_deg,
                    ProjectionSpec::Orthographic { .. } => 30.0,
                };
                let fit = fit_orbit(framed, target, azimuth_deg, elevation_deg, fov_y_deg, aspect);
                let (projection, auto_distance) = match self.projection {
                    ProjectionSpec::Perspective { fov_y_deg } => (Projection::Perspective { fov_y_deg }, fit.distance),
                    // Any distance outside the box shows the same image.
                    ProjectionSpec::Orthographic { height } => {
                        (Projection::Orthographic { height: height.unwrap_or(fit.ortho_height) }, outside)
                    }
                };
                Camera::orbit(target, distance.unwrap_or(auto_distance), azimuth_deg, elevation_deg, projection)
            }
            CameraPlacement::LookAt { eye, target, up } => {
                let projection = match self.projection {
                    ProjectionSpec::Perspective { fov_y_deg } => Projection::Perspective { fov_y_deg },
                    ProjectionSpec::Orthographic { height } => {
                        // Framed as seen from the eye's direction around the target.
                        let d = (eye - target).normalize_or(Vec3::Z);
                        let (az, el) = (d.x.atan2(d.z).to_degrees(), d.y.clamp(-1.0, 1.0).asin().to_degrees());
                        let fit = fit_orbit(framed, target, az, el, 30.0, aspect);
                        Projection::Orthographic { height: height.unwrap_or(fit.ortho_height) }
                    }
                };
                Camera { eye, target, up, projection }
            }
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
    /// See [`Scene::technique_tables`].
    pub technique_tables: Vec<&'static str>,
}

impl SceneSpec {
    pub fn load_volume(&self) -> Result<Volume, SceneError> {
        match &self.volume {
            VolumeSource::File(path) if !path.exists() => Err(SceneError::MissingVolume {
                origin: self.origin.clone(),
                path: path.clone(),
                hint: super::missing_file::missing_file_hint(path),
            }),
            VolumeSource::File(path) => loaders::load_volume(path).map_err(|error| SceneError::Volume {
                origin: self.origin.clone(),
                path: path.clone(),
                error: Box::new(error),
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
        let framed = visible_box(&volume, &transfer, &volume_box);
        let camera = self.camera.resolve(&volume_box, &framed, self.render.width, self.render.height);
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
            technique_tables: self.technique_tables,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::framing::FRAME_FILL;

    #[test]
    fn auto_framing_fits_the_framed_box() {
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
        let whole = WorldBox::of_volume(&cube);
        let camera = spec.resolve(&cube, &whole, 200, 100);
        // Seen head-on, the cube's near face (z = 0.5) is the widest: its top
        // edge (y = 0.5) reaches FRAME_FILL of tan(15 deg) at that depth.
        let expected = 0.5 / (15f32.to_radians().tan() * FRAME_FILL) + 0.5;
        assert!((camera.eye.length() - expected).abs() < 1e-4, "{} vs {expected}", camera.eye.length());
        // A tall image is limited by its narrower horizontal field of view.
        let tall = spec.resolve(&cube, &whole, 100, 200);
        assert!(tall.eye.length() > expected * 1.5);
        // A smaller object is framed closer.
        let small = WorldBox { min: Vec3::splat(-0.2), max: Vec3::splat(0.2) };
        assert!(spec.resolve(&cube, &small, 200, 100).eye.length() < 0.5 * expected);
    }
}
