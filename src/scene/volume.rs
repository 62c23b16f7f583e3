//! A scalar volume as loaded from a file or built procedurally.
//!
//! Convention (see `docs/optical-model.md`): the normalized scalar `s` in [0, 1] is
//! what the transfer function reads. 8-bit data keeps `s = v / 255`; wider types
//! are rescaled from the data's own [min, max] when loaded, so every volume uses
//! the whole range of its storage format.

use glam::{UVec3, Vec3};

/// Voxel storage, matching the GPU formats r8_unorm, r16_unorm and r32_sfloat.
#[derive(Clone, Debug, PartialEq)]
pub enum VoxelData {
    U8(Vec<u8>),
    U16(Vec<u16>),
    /// Already normalized to [0, 1].
    F32(Vec<f32>),
}

impl VoxelData {
    pub fn len(&self) -> usize {
        match self {
            VoxelData::U8(v) => v.len(),
            VoxelData::U16(v) => v.len(),
            VoxelData::F32(v) => v.len(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Normalized value of voxel `index` (x fastest, then y, then z).
    #[inline]
    pub fn normalized(&self, index: usize) -> f32 {
        match self {
            VoxelData::U8(v) => v[index] as f32 / 255.0,
            VoxelData::U16(v) => v[index] as f32 / 65535.0,
            VoxelData::F32(v) => v[index],
        }
    }

    pub fn bytes_per_voxel(&self) -> usize {
        match self {
            VoxelData::U8(_) => 1,
            VoxelData::U16(_) => 2,
            VoxelData::F32(_) => 4,
        }
    }
}

/// How a position between voxel centres reads the volume.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Interpolation {
    /// Trilinear, clamp-to-edge: a scalar field (densities, CT values).
    #[default]
    Trilinear,
    /// The value of the voxel the position lies in: a labelled volume, whose
    /// values name parts. Blending two labels would give a third part's value
    /// (the Cornell box: every part's edge would wear the colours of the labels
    /// between its own and air's), so each voxel is its part's, and a part's
    /// faces lie on voxel faces.
    Nearest,
}

/// A volume: `dims` voxels, `spacing` world units between voxel centres along each
/// axis (anisotropic allowed), data stored x fastest.
#[derive(Clone, Debug)]
pub struct Volume {
    pub name: String,
    pub dims: UVec3,
    pub spacing: Vec3,
    pub data: VoxelData,
    /// Range of the raw values in the file's own units, before normalization.
    pub value_range: (f64, f64),
    /// NaN and infinite voxels of the file, which the loader mapped to 0 or 1
    /// (src/scene/loaders/decode.rs); 0 for procedural volumes. Carried so the
    /// user is warned ([`crate::scene::warnings`]).
    pub non_finite_voxels: u64,
    pub interpolation: Interpolation,
}

impl Volume {
    pub fn voxel_count(&self) -> usize {
        self.dims.x as usize * self.dims.y as usize * self.dims.z as usize
    }

    pub fn size_bytes(&self) -> usize {
        self.voxel_count() * self.data.bytes_per_voxel()
    }

    #[inline]
    pub fn voxel(&self, x: u32, y: u32, z: u32) -> f32 {
        let i = (z as usize * self.dims.y as usize + y as usize) * self.dims.x as usize + x as usize;
        self.data.normalized(i)
    }

    /// Sample at normalized texture coordinates `uvw` in [0, 1]^3, in f64 for the
    /// reference: [`Volume::trilinear_f64`], or for a labelled volume the voxel
    /// `uvw` lies in, clamped to the volume (volume_fetch.glsl).
    pub fn sample_f64(&self, uvw: [f64; 3]) -> f64 {
        match self.interpolation {
            Interpolation::Trilinear => self.trilinear_f64(uvw),
            Interpolation::Nearest => {
                let d = [self.dims.x, self.dims.y, self.dims.z];
                let i = |a: usize| (uvw[a] * d[a] as f64).floor().clamp(0.0, d[a] as f64 - 1.0) as u32;
                self.voxel(i(0), i(1), i(2)) as f64
            }
        }
    }

    /// Trilinear sample at normalized texture coordinates `uvw`, exactly as a
    /// Vulkan sampler with LINEAR filter and CLAMP_TO_EDGE does it (texel centres
    /// at (i + 0.5) / n): every volume's values, and the field the Phong
    /// gradient is taken from even in a labelled volume.
    pub fn trilinear_f64(&self, uvw: [f64; 3]) -> f64 {
        let d = [self.dims.x, self.dims.y, self.dims.z];
        let mut i0 = [0u32; 3];
        let mut i1 = [0u32; 3];
        let mut f = [0f64; 3];
        for a in 0..3 {
            let n = d[a] as f64;
            let t = (uvw[a] * n - 0.5).clamp(0.0, n - 1.0);
            let fl = t.floor();
            i0[a] = fl as u32;
            i1[a] = (i0[a] + 1).min(d[a] - 1);
            f[a] = t - fl;
        }
        let v = |x: u32, y: u32, z: u32| self.voxel(x, y, z) as f64;
        let c00 = v(i0[0], i0[1], i0[2]) * (1.0 - f[0]) + v(i1[0], i0[1], i0[2]) * f[0];
        let c10 = v(i0[0], i1[1], i0[2]) * (1.0 - f[0]) + v(i1[0], i1[1], i0[2]) * f[0];
        let c01 = v(i0[0], i0[1], i1[2]) * (1.0 - f[0]) + v(i1[0], i0[1], i1[2]) * f[0];
        let c11 = v(i0[0], i1[1], i1[2]) * (1.0 - f[0]) + v(i1[0], i1[1], i1[2]) * f[0];
        let c0 = c00 * (1.0 - f[1]) + c10 * f[1];
        let c1 = c01 * (1.0 - f[1]) + c11 * f[1];
        c0 * (1.0 - f[2]) + c1 * f[2]
    }

    /// Min and max of the normalized values.
    pub fn normalized_range(&self) -> (f32, f32) {
        let mut lo = f32::INFINITY;
        let mut hi = f32::NEG_INFINITY;
        for i in 0..self.voxel_count() {
            let v = self.data.normalized(i);
            lo = lo.min(v);
            hi = hi.max(v);
        }
        (lo, hi)
    }

    /// Histogram of the normalized values in `bins` equal bins over [0, 1].
    pub fn histogram(&self, bins: usize) -> Vec<u64> {
        let mut h = vec![0u64; bins.max(1)];
        let n = h.len();
        for i in 0..self.voxel_count() {
            let v = self.data.normalized(i).clamp(0.0, 1.0);
            h[((v * n as f32) as usize).min(n - 1)] += 1;
        }
        h
    }
}
