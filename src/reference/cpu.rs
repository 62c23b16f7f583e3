//! The view march shared by every CPU renderer: front-to-back emission-absorption
//! with one sample per step (at the midpoint, or the pixel's jittered phase,
//! [`super::ray_start`]) and opacity correction, a source term per sample
//! (see [`super::sources`]), early termination and the background behind.

use glam::DVec3;

use super::medium::Medium;
use super::parallel::render_rows;
use super::ray_start::ray_start_phase;
use super::sources::{phong, scattering};
use super::validate::{check_scene, CpuRenderError};
use crate::linear_image::LinearImage;
use crate::scene::{Light, OpticalModel, RayBasis, Scene};

/// DVR and Phong stop a view ray once its transmittance falls below this (the
/// shaders get the same constant from build.rs).
pub use crate::render::early_termination::EARLY_TERMINATION_TRANSMITTANCE;

/// What one sample sends toward the eye.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CpuRenderKind {
    /// Unshaded emission-absorption: `S = rgb`, `render.step_voxels`.
    Dvr,
    /// Gradient Blinn-Phong without shadows, `render.step_voxels`.
    Phong,
    /// Ground truth with shadow rays: model (i) or (ii), `reference.*` steps.
    Reference(OpticalModel),
}

impl CpuRenderKind {
    /// The reference model the scene asks for (`reference.model`).
    pub fn reference_of(scene: &Scene) -> Self {
        CpuRenderKind::Reference(scene.reference.model)
    }
}

/// A scene prepared for rendering at one size: checked, LUT baked, camera rays set.
pub struct CpuRenderer<'a> {
    scene: &'a Scene,
    /// [`Scene::rendered_lights`]: far lights at their directional limit.
    lights: Vec<Light>,
    kind: CpuRenderKind,
    medium: Medium<'a>,
    basis: RayBasis,
    width: u32,
    height: u32,
    step_voxels: f64,
    min_transmittance: f64,
}

impl<'a> CpuRenderer<'a> {
    pub fn new(scene: &'a Scene, kind: CpuRenderKind, width: u32, height: u32) -> Result<Self, CpuRenderError> {
        check_scene(scene, kind)?;
        let (step_voxels, min_transmittance) = match kind {
            CpuRenderKind::Dvr | CpuRenderKind::Phong => (scene.render.step_voxels, EARLY_TERMINATION_TRANSMITTANCE),
            CpuRenderKind::Reference(_) => (scene.reference.step_voxels, scene.reference.min_transmittance as f64),
        };
        Ok(CpuRenderer {
            scene,
            lights: scene.rendered_lights(),
            kind,
            medium: Medium::new(&scene.volume, &scene.transfer),
            basis: scene.camera.basis(width, height),
            width,
            height,
            step_voxels: step_voxels as f64,
            min_transmittance,
        })
    }

    /// Linear RGB of pixel (x, y), in f64.
    pub fn pixel(&self, x: u32, y: u32) -> Result<[f64; 3], CpuRenderError> {
        if x >= self.width || y >= self.height {
            return Err(CpuRenderError::PixelOutOfRange { x, y, width: self.width, height: self.height });
        }
        Ok(self.march_pixel(x, y).to_array())
    }

    /// The whole image, rows spread over all cores; deterministic.
    pub fn render(&self) -> LinearImage {
        let pixels = render_rows(self.width, self.height, |x, y| self.march_pixel(x, y).as_vec3().to_array());
        LinearImage { width: self.width, height: self.height, pixels }
    }

    fn march_pixel(&self, x: u32, y: u32) -> DVec3 {
        let (nx, ny) = RayBasis::ndc(x, y, self.width, self.height);
        let (o, d) = self.basis.ray_f64(nx as f64, ny as f64);
        let phase = ray_start_phase(self.scene.render.jitter, x, y);
        self.march(DVec3::from_array(o), DVec3::from_array(d), phase)
    }

    /// Sample `i` lies at `t0 + (i + phase) * h` ([`ray_start_phase`]).
    fn march(&self, o: DVec3, d: DVec3, phase: f64) -> DVec3 {
        let background = self.scene.render.background.as_dvec3();
        let Some((t0, t1)) = self.medium.intersect(o, d) else {
            return background;
        };
        let vl = self.medium.voxel_length();
        let length = t1 - t0;
        let steps = (length / (self.step_voxels * vl)).ceil().max(1.0);
        let h = length / steps;
        let hv = h / vl;
        let mut color = DVec3::ZERO;
        let mut transmittance = 1.0;
        for i in 0..steps as u64 {
            let p = o + d * (t0 + (i as f64 + phase) * h);
            let m = self.medium.at(p);
            let alpha = 1.0 - (-m.sigma * hv).exp();
            if alpha > 0.0 {
                color += transmittance * alpha * self.source(p, m.rgb, d);
                transmittance *= 1.0 - alpha;
            }
            if transmittance < self.min_transmittance {
                break;
            }
        }
        color + transmittance * background
    }

    fn source(&self, p: DVec3, rgb: DVec3, d: DVec3) -> DVec3 {
        let scene = self.scene;
        match self.kind {
            CpuRenderKind::Dvr => rgb,
            CpuRenderKind::Phong => phong(&self.medium, &scene.phong, &self.lights, p, rgb, d),
            CpuRenderKind::Reference(model) => scattering(
                &self.medium,
                &self.lights,
                model,
                scene.reference.chromatic,
                scene.render.emission as f64,
                scene.reference.shadow_step_voxels as f64,
                p,
                rgb,
            ),
        }
    }
}

/// Renders `scene` at `width` x `height` on the CPU in f64 (stored as f32).
pub fn render_cpu(scene: &Scene, kind: CpuRenderKind, width: u32, height: u32) -> Result<LinearImage, CpuRenderError> {
    Ok(CpuRenderer::new(scene, kind, width, height)?.render())
}

/// One pixel of the `width` x `height` image, in f64: for checks of single rays.
pub fn render_pixel_cpu(
    scene: &Scene,
    kind: CpuRenderKind,
    width: u32,
    height: u32,
    x: u32,
    y: u32,
) -> Result<[f64; 3], CpuRenderError> {
    CpuRenderer::new(scene, kind, width, height)?.pixel(x, y)
}
