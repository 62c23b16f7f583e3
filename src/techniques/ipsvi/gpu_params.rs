//! Host mirrors of glsl/ipsvi_common.glsl's `Sweep` block and `Planes` buffer.

use super::light_anchor::LightAnchor;
use crate::render::light_space::LightSpacePlane;
use crate::scene::framing::WorldBox;
use crate::scene::RayBasis;
use bytemuck::{Pod, Zeroable};
use glam::{Vec3, Vec4};

/// The only per-light flag; what is fixed per renderer (piecewise integration,
/// early termination) is a specialization constant of glsl/ipsvi_line.comp.
pub const FLAG_FIRST_LIGHT: u32 = 1;

#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct SweepParams {
    pub cache_origin: [f32; 4],
    pub cache_axis: [f32; 4],
    pub cache_u: [f32; 4],
    pub cache_v: [f32; 4],
    /// Light anchor in pixels.
    pub anchor: [f32; 2],
    /// Width of the blend between zones, pixels.
    pub blend_px: f32,
    /// The cache stores E / light_scale.
    pub light_scale: f32,
    /// N: the cache is N x N.
    pub cache_size: u32,
    pub light_index: u32,
    /// FLAG_*.
    pub flags: u32,
    pub max_piecewise_steps: u32,
    /// Multiple-scattering share.
    pub albedo: f32,
    /// tan(cone half-angle).
    pub cone_tan: f32,
    /// Full-resolution pixels per pre-pass pixel.
    pub ert_scale: f32,
    pub pad: f32,
    /// The box light rays are clipped to (world; w unused): the volume box, or
    /// with `fit_to_visible` the lit box.
    pub lit_min: [f32; 4],
    pub lit_max: [f32; 4],
}

crate::assert_gpu_layout!(
    SweepParams,
    crate::shaders::ipsvi_line::layout::SWEEP_PARAMS,
    [
        cache_origin,
        cache_axis,
        cache_u,
        cache_v,
        anchor,
        blend_px,
        light_scale,
        cache_size,
        light_index,
        flags,
        max_piecewise_steps,
        albedo,
        cone_tan,
        ert_scale,
        pad,
        lit_min,
        lit_max,
    ]
);

/// One line block (glsl/ipsvi_line.comp `BlockParams`), read by its dispatch
/// through the block index it gets as push constant.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct BlockParams {
    pub line_first: u32,
    pub line_width: u32,
    pub span_start: u32,
    pub span_len: u32,
    pub columns: u32,
    pub zone: u32,
    pub plane: u32,
    pub pixel_count: u32,
    /// Cache texels this block advances (and carries forward): x0, y0, w, h.
    pub region: [u32; 4],
    /// 0: read the a images and write b; 1: the other way round.
    pub parity: u32,
    /// Index of the light (and of its record in the sweeps buffer).
    pub light: u32,
    /// view-samples: 1 + the block's index in its sweep, stamped on its sample writes.
    pub stamp: u32,
    /// cache_write = "farthest": pixels of the next block this dispatch claims texels for.
    pub claim_count: u32,
    /// First row of the block's sweep's cache in the cache images (`merge_sweeps`; else 0).
    pub cache_row: u32,
    /// First row of its sweep's colour accumulation in the output binding (`merge_sweeps`; else 0).
    pub out_row: u32,
    /// std430 rounds the struct (it holds a uvec4) to 16 bytes.
    pub pad: [u32; 2],
}

crate::assert_gpu_layout!(
    BlockParams,
    crate::shaders::ipsvi_line::layout::BLOCK_PARAMS,
    [
        line_first,
        line_width,
        span_start,
        span_len,
        columns,
        zone,
        plane,
        pixel_count,
        region,
        parity,
        light,
        stamp,
        claim_count,
        cache_row,
        out_row,
        pad
    ]
);

pub struct SweepInputs<'a> {
    pub geometry: &'a LightSpacePlane,
    pub anchor: LightAnchor,
    pub blend_px: f32,
    pub light_scale: f32,
    pub light_index: u32,
    pub flags: u32,
    pub max_piecewise_steps: u32,
    pub albedo: f32,
    pub cone_angle_deg: f32,
    pub ert_scale: u32,
    pub lit_box: WorldBox,
}

pub fn sweep_params(s: &SweepInputs) -> SweepParams {
    let g = s.geometry;
    let anchor = match s.anchor {
        LightAnchor::Source(p) | LightAnchor::Sink(p) => p,
        LightAnchor::AtInfinity(_) => glam::Vec2::ZERO,
    };
    SweepParams {
        cache_origin: g.origin.extend(g.projection as u32 as f32).to_array(),
        cache_axis: g.axis.extend(g.texel).to_array(),
        cache_u: g.u.extend(g.a0).to_array(),
        cache_v: g.v.extend(g.b0).to_array(),
        anchor: anchor.to_array(),
        blend_px: s.blend_px,
        light_scale: s.light_scale,
        cache_size: g.size,
        light_index: s.light_index,
        flags: s.flags,
        max_piecewise_steps: s.max_piecewise_steps,
        albedo: s.albedo,
        cone_tan: s.cone_angle_deg.to_radians().tan(),
        ert_scale: s.ert_scale as f32,
        pad: 0.0,
        lit_min: s.lit_box.min.extend(0.0).to_array(),
        lit_max: s.lit_box.max.extend(0.0).to_array(),
    }
}

/// The plane of every sweep line through its pixel centres: rows 0..H, then
/// columns 0..W, as (normal, d) with normal . x + d = 0.
pub fn line_planes(basis: &RayBasis, width: u32, height: u32) -> Vec<[f32; 4]> {
    let (o, f, r, u) = (basis.origin, basis.forward, basis.right, basis.up);
    let plane = |n: Vec3, point: Vec3| -> [f32; 4] {
        let n = n.normalize_or(Vec3::Y);
        Vec4::from((n, -n.dot(point))).to_array()
    };
    let mut out = Vec::with_capacity((width + height) as usize);
    for y in 0..height {
        let ny = 1.0 - (y as f32 + 0.5) / height as f32 * 2.0;
        out.push(if basis.orthographic { plane(r.cross(f), o + u * ny) } else { plane(r.cross(f + u * ny), o) });
    }
    for x in 0..width {
        let nx = (x as f32 + 0.5) / width as f32 * 2.0 - 1.0;
        out.push(if basis.orthographic { plane(u.cross(f), o + r * nx) } else { plane(u.cross(f + r * nx), o) });
    }
    out
}
