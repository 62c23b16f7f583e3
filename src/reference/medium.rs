//! The medium as every CPU march sees it: the volume box in world space, the
//! trilinear volume sampler and the baked transfer LUT, all read in f64.

use glam::DVec3;

use crate::scene::geometry::intersect_f64;
use crate::scene::{TransferFunction, TransferLut, Volume, VolumeBox};

/// Colour and optical depth per voxel at one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MediumSample {
    pub rgb: DVec3,
    /// Optical depth per voxel length (`-ln(1 - alpha)` of the transfer function).
    pub sigma: f64,
}

pub struct Medium<'a> {
    volume: &'a Volume,
    lut: TransferLut,
    half_extent: DVec3,
    voxel_length: f64,
}

impl<'a> Medium<'a> {
    /// Bakes the LUT once, with [`TransferLut::DEFAULT_SIZE`] entries like the GPU.
    pub fn new(volume: &'a Volume, transfer: &TransferFunction) -> Self {
        let bx = VolumeBox::new(volume.dims, volume.spacing);
        Medium {
            volume,
            lut: transfer.bake(TransferLut::DEFAULT_SIZE),
            half_extent: bx.half_extent.as_dvec3(),
            voxel_length: bx.voxel_length as f64,
        }
    }

    pub fn lut(&self) -> &TransferLut {
        &self.lut
    }

    pub fn half_extent(&self) -> DVec3 {
        self.half_extent
    }

    /// World length of one voxel: the unit of step sizes and of `sigma`.
    pub fn voxel_length(&self) -> f64 {
        self.voxel_length
    }

    /// Voxel counts per axis, as f64 (the Phong gradient's offsets are 1 / dims).
    pub fn dims(&self) -> DVec3 {
        self.volume.dims.as_dvec3()
    }

    pub fn uvw(&self, p: DVec3) -> DVec3 {
        (p + self.half_extent) / (2.0 * self.half_extent)
    }

    /// Normalized scalar at texture coordinates `uvw` (GPU linear sampler, or
    /// the voxel's own value in a labelled volume).
    pub fn scalar_at_uvw(&self, uvw: DVec3) -> f64 {
        self.volume.sample_f64(uvw.to_array())
    }

    /// The trilinear scalar at `uvw`, labelled volumes included: the field
    /// the Phong gradient differentiates (volume_fetch.glsl's
    /// `volume_smooth_at_uvw`).
    pub fn smooth_scalar_at_uvw(&self, uvw: DVec3) -> f64 {
        self.volume.trilinear_f64(uvw.to_array())
    }

    /// Transfer function applied to the scalar at world position `p`.
    pub fn at(&self, p: DVec3) -> MediumSample {
        let [r, g, b, sigma] = self.lut.sample(self.scalar_at_uvw(self.uvw(p)));
        MediumSample { rgb: DVec3::new(r, g, b), sigma }
    }

    /// Box hit `(t0, t1)` of the ray `o + t * d`, `None` on a miss.
    pub fn intersect(&self, o: DVec3, d: DVec3) -> Option<(f64, f64)> {
        intersect_f64(self.half_extent.to_array(), o.to_array(), d.to_array())
    }

    /// Distance from `p` along `w` to where the ray leaves the box; 0 if it never
    /// is inside.
    pub fn exit_distance(&self, p: DVec3, w: DVec3) -> f64 {
        self.intersect(p, w).map_or(0.0, |(_, t1)| t1)
    }
}
