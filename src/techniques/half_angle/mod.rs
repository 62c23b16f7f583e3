//! Half-angle slicing (Kniss, Premoze, Hansen, Shirley, McPherson 2003), the
//! baseline the IPSVI paper compares against (its figure 8): the volume is cut
//! into slices perpendicular to the half-angle vector between the view and light
//! directions and processed in order from the light's side, each slice one
//! dispatch followed by the barrier `slice_write_to_next_slice_read`. A light
//! buffer (ping-pong pair in light space) carries the transmittance from slice to
//! slice; the eye buffer accumulates the image. A slice updates only the light
//! buffer texels whose rays cross its slab or the previous slice's inside the
//! box (src/render/light_region.rs), the image the same bit for bit: on a
//! cube-like volume that is nearly the whole buffer, on an elongated one
//! (a rod, anisotropic spacing) a small part of it. Approximates optical model (i)
//! (docs/optical-model.md). One light (directional, or a point/spot light outside
//! the volume's bounding sphere); none renders the emission term alone.

mod controls;
pub mod settings;
pub mod technique;

pub use settings::{HalfAngleSettings, SLICE_STEP_RANGE};
pub use technique::HalfAngle;

use crate::render::frame_params::{frame_params, MarchSteps};
use crate::render::frame_result::FrameResult;
use crate::render::image_space::ImageSpace;
use crate::render::light_region::{slab_region, TexelRect};
use crate::render::light_space::{LightProjection, LightSpacePlane};
use crate::render::view_chunks::ChunkSync;
use crate::render::{render_recorded, GpuScene, RecordedFrame, RenderError};
use crate::scene::settings_table::SettingsTable;
use crate::scene::{LightKind, Scene};
use crate::shaders::half_angle_slice as shader;
use crate::vk::barriers::{Access, Barrier};
use crate::vk::descriptors::Resource;
use crate::vk::pipeline::{ComputePipeline, ComputePipelineDesc};
use crate::vk::{Buffer, Image, Profiler, Recorder};
use ash::vk;
use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use std::any::Any;
use std::sync::Arc;

#[repr(C)]
#[derive(Clone, Copy, Default, Pod, Zeroable)]
struct LightBufferParams {
    origin: [f32; 4],
    axis: [f32; 4],
    u: [f32; 4],
    v: [f32; 4],
    size: u32,
    light: u32,
    pad0: u32,
    pad1: u32,
}

crate::assert_gpu_layout!(
    LightBufferParams,
    shader::layout::LIGHT_SPACE,
    [origin, axis, u, v, size, light, pad0, pad1]
);

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct SlicePush {
    half_vector: [f32; 4],
    spacing: [f32; 4],
    rect: [u32; 4],
    light_rect: [u32; 4],
    pixel_count: u32,
}

crate::assert_gpu_layout!(SlicePush, shader::layout::SLICE, [half_vector, spacing, rect, light_rect, pixel_count]);

/// Which light buffer texels a slice updates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightRegions {
    /// Those whose rays cross this slice's or the previous slice's slab inside
    /// the box ([`slab_region`]): what `render` does.
    Slices,
    /// Every texel, every slice: the same image bit for bit, kept as the
    /// check that the regions leave nothing out (tests/half_angle.rs).
    Whole,
}

/// The slicing of the volume: half-angle vector, order and slice planes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Slicing {
    pub half_vector: Vec3,
    /// True when the eye sees the slices front to back (light behind the viewer).
    pub front_to_back: bool,
    pub first_plane: f32,
    pub spacing: f32,
    pub count: u32,
}

/// Checks the slice step and the light's place before any GPU work.
pub fn check(scene: &Scene) -> Result<(), RenderError> {
    if scene.lights.len() == 1 {
        let settings = scene.settings.get::<HalfAngleSettings>();
        slicing(scene, &settings)?;
        light_outside(scene, &settings)?;
    }
    Ok(())
}

/// Why half-angle slicing cannot light `scene` (None: it can): it takes one
/// light, outside the volume's bounding sphere. For benches that run it
/// beside another technique and leave it out, saying why.
pub fn unavailable(scene: &Scene) -> Option<String> {
    match scene.lights.len() {
        1 => light_outside(scene, &scene.settings.get::<HalfAngleSettings>()).err().map(|e| e.to_string()),
        n => Some(format!("half-angle slicing takes one light; the scene has {n}")),
    }
}

/// The light buffer is a plane the slices sweep away from the light: a light
/// inside the volume's bounding sphere has none (it would need the octahedral
/// map IPSVI uses there), so half-angle slicing refuses it.
fn light_outside(scene: &Scene, settings: &HalfAngleSettings) -> Result<LightSpacePlane, RenderError> {
    let geometry =
        LightSpacePlane::fit(&scene.rendered_lights()[0].kind, &scene.volume_box(), settings.light_buffer_size);
    if geometry.projection == LightProjection::Octahedral {
        return Err(RenderError::Invalid(
            "half-angle slicing needs the light outside the volume's bounding sphere".into(),
        ));
    }
    Ok(geometry)
}

pub fn slicing(scene: &Scene, settings: &HalfAngleSettings) -> Result<Slicing, RenderError> {
    let bx = scene.volume_box();
    let view = scene.camera.forward();
    let light = match scene.rendered_lights().first().map(|l| l.kind) {
        Some(LightKind::Directional { direction }) => direction.normalize_or(Vec3::NEG_Y),
        Some(LightKind::Point { position }) | Some(LightKind::Spot { position, .. }) => {
            (-position).normalize_or(Vec3::NEG_Y)
        }
        None => return Err(RenderError::Invalid("half-angle slicing needs a light".into())),
    };
    let (half_vector, front_to_back) =
        if view.dot(light) >= 0.0 { ((view + light).normalize(), true) } else { ((light - view).normalize(), false) };
    let (lo, hi) = bx.corners().iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), c| {
        let s = c.dot(half_vector);
        (lo.min(s), hi.max(s))
    });
    let step = settings.slice_step_voxels(scene);
    let extent_voxels = (hi - lo) / bx.voxel_length;
    check_slice_step(settings, step, extent_voxels)?;
    let spacing = step * bx.voxel_length;
    let count = ((hi - lo) / spacing).ceil().max(1.0) as u32;
    Ok(Slicing { half_vector, front_to_back, first_plane: lo, spacing, count })
}

/// Most slices a frame may take: one dispatch, barrier and profiler scope each.
pub const MAX_SLICES: f32 = 16_384.0;

/// The slice distance in voxels, from `half_angle.slice_step` or else
/// `render.step`, refused by name outside the range `slice_step` allows or
/// past [`MAX_SLICES`] over the volume's `extent_voxels` along the half vector.
fn check_slice_step(settings: &HalfAngleSettings, step: f32, extent_voxels: f32) -> Result<(), RenderError> {
    let setting = if settings.slice_step.is_some() { "half_angle.slice_step" } else { "render.step" };
    let smallest = SLICE_STEP_RANGE.0.max(extent_voxels / MAX_SLICES);
    let largest = SLICE_STEP_RANGE.1;
    if step.is_nan() || step < smallest || step > largest {
        return Err(RenderError::Invalid(format!(
            "{setting} = {step:e} voxels is outside what half-angle supports on this scene (one slice per step): from the smallest step {smallest:.3e} ({} slices at most) to {largest} voxels",
            MAX_SLICES as u32
        )));
    }
    Ok(())
}

fn r32f(gpu: &GpuScene, name: &str, n: u32) -> Result<Arc<Image>, RenderError> {
    let usage = vk::ImageUsageFlags::TRANSFER_DST;
    Ok(gpu.frame_images.storage_2d(gpu.ctx, name, vk::Format::R32_SFLOAT, (n, n), usage)?)
}

pub fn render(gpu: &GpuScene, width: u32, height: u32, profiler: &mut Profiler) -> Result<FrameResult, RenderError> {
    render_with(gpu, width, height, profiler, LightRegions::Slices)
}

/// [`render`] with the light buffer updated as `regions` says.
pub fn render_with(
    gpu: &GpuScene,
    width: u32,
    height: u32,
    profiler: &mut Profiler,
    regions: LightRegions,
) -> Result<FrameResult, RenderError> {
    // With no light, `record` draws the emission-only ray cast.
    render_recorded(gpu, |rec| record_with(gpu, width, height, rec, profiler, regions))
}

/// Records one frame into `rec` (see [`RecordedFrame`]): what `render` submits
/// with its read-back and the viewer records into its own command buffer.
pub fn record(
    gpu: &GpuScene,
    width: u32,
    height: u32,
    rec: &mut Recorder,
    profiler: &mut Profiler,
) -> Result<RecordedFrame, RenderError> {
    record_with(gpu, width, height, rec, profiler, LightRegions::Slices)
}

fn record_with(
    gpu: &GpuScene,
    width: u32,
    height: u32,
    rec: &mut Recorder,
    profiler: &mut Profiler,
    regions: LightRegions,
) -> Result<RecordedFrame, RenderError> {
    let scene = gpu.scene;
    let settings = &scene.settings.get::<HalfAngleSettings>();
    settings.validate()?;
    match scene.lights.len() {
        0 => {
            let shading = crate::render::raycast::Shading::EmissionOnly;
            return crate::render::raycast::record_with(
                gpu,
                shading,
                (width, height),
                rec,
                profiler,
                ChunkSync::Barrier,
            );
        }
        1 => {}
        n => return Err(RenderError::Invalid(format!("half-angle slicing takes one light; the scene has {n}"))),
    }
    if width == 0 || height == 0 {
        return Err(RenderError::Invalid(format!("image size {width}x{height} is empty")));
    }
    let ctx = gpu.ctx;
    let bx = scene.volume_box();
    let geometry = light_outside(scene, settings)?;
    let sl = slicing(scene, settings)?;
    let space = ImageSpace { basis: scene.camera.basis(width, height), width, height };
    let rect = space.projected_box(&bx);
    let rect = [rect.x0, rect.y0, rect.x1 - rect.x0, rect.y1 - rect.y0];
    // Front to back, the last slice adds the background to every pixel.
    let whole_image = [0, 0, width, height];

    let params = frame_params(scene, width, height, gpu.lut_size, MarchSteps::render(scene));
    let frame = Buffer::with_data(ctx, "frame params", &[params], vk::BufferUsageFlags::STORAGE_BUFFER)?;
    let g = &geometry;
    let light_params = LightBufferParams {
        origin: g.origin.extend(g.projection as u32 as f32).to_array(),
        axis: g.axis.extend(g.texel).to_array(),
        u: g.u.extend(g.a0).to_array(),
        v: g.v.extend(g.b0).to_array(),
        size: g.size,
        light: 0,
        pad0: 0,
        pad1: 0,
    };
    let light_buffer_params =
        Buffer::with_data(ctx, "half-angle light buffer", &[light_params], vk::BufferUsageFlags::STORAGE_BUFFER)?;
    let n = settings.light_buffer_size;
    let light = [r32f(gpu, "half-angle light a", n)?, r32f(gpu, "half-angle light b", n)?];
    let eye = gpu.frame_images.output(ctx, "half-angle eye buffer", width, height)?;
    let desc =
        ComputePipelineDesc { name: "half_angle_slice", shader: &shader::INTERFACE, specialization: &[], max_sets: 1 };
    let mut pipeline = ComputePipeline::new(ctx, &desc)?;
    let set = pipeline.create_set(&[
        (shader::FRAME_BUFFER, Resource::StorageBuffer(&frame)),
        (shader::VOLUME_TEX, Resource::SampledImage(&gpu.volume, &gpu.sampler)),
        (shader::TRANSFER_LUT, Resource::StorageBuffer(&gpu.lut)),
        (shader::LIGHTS, Resource::StorageBuffer(&gpu.lights)),
        (shader::LIGHT_BUFFERS, Resource::StorageBuffer(&light_buffer_params)),
        (shader::EYE, Resource::StorageImage(&eye.image)),
    ])?;
    // Slice parity 0 reads light side a and writes b; parity 1 the opposite.
    let mut side = |from: usize, to: usize| {
        pipeline.create_set1(&[
            (shader::LIGHT_IN, Resource::StorageImage(&light[from])),
            (shader::LIGHT_OUT, Resource::StorageImage(&light[to])),
        ])
    };
    let sides = [side(0, 1)?, side(1, 0)?];
    let bg = scene.render.background;
    let start = if sl.front_to_back { [0.0, 0.0, 0.0, 1.0] } else { [bg.x, bg.y, bg.z, 1.0] };
    for (image, value) in [(&*light[0], [1.0f32; 4]), (&*light[1], [1.0; 4]), (&eye.image, start)] {
        rec.clear_for_compute(image, value, "slice_buffers_discard_to_clear", "slice_buffers_clear_to_first_slice");
    }
    let scope = profiler.begin(rec, "half_angle")?;
    rec.bind(&pipeline, set);
    let corners = bx.corners();
    let mut previous = TexelRect::default();
    for k in 0..sl.count {
        let plane = sl.first_plane + (k as f32 + 0.5) * sl.spacing;
        // A texel samples the slab at its own phase within it (the shader's
        // `attenuate`): the whole slab's region, and the previous slice's.
        let own = slab_region(&geometry, &corners, sl.half_vector, plane - 0.5 * sl.spacing, plane + 0.5 * sl.spacing);
        let light_rect = match regions {
            LightRegions::Slices => own.union(&previous),
            LightRegions::Whole => TexelRect::full(n),
        };
        previous = own;
        let detail = profiler.begin_detail(rec, "half_angle_slice")?;
        rec.bind_set1(&pipeline, sides[(k % 2) as usize]);
        let background = sl.front_to_back && k + 1 == sl.count;
        let rect = if background { whole_image } else { rect };
        let pixel_count = rect[2] * rect[3];
        let push = SlicePush {
            half_vector: sl.half_vector.extend(plane).to_array(),
            spacing: [sl.spacing, if sl.front_to_back { 1.0 } else { 0.0 }, 0.0, if background { 1.0 } else { 0.0 }],
            rect,
            light_rect: [light_rect.x0, light_rect.y0, light_rect.w, light_rect.h],
            pixel_count,
        };
        rec.push(&pipeline, &push);
        rec.dispatch((pixel_count + light_rect.count()).div_ceil(64), 1, 1);
        profiler.end(rec, detail)?;
        // This slice's light and eye writes are what the next slice reads.
        rec.barrier(&Barrier::memory(
            "slice_write_to_next_slice_read",
            Access::COMPUTE_WRITE,
            Access::COMPUTE_READ_WRITE,
        ));
    }
    profiler.end(rec, scope)?;
    let [light_a, light_b] = light;
    let keep_alive: Vec<Box<dyn Any>> =
        vec![Box::new(frame), Box::new(light_buffer_params), Box::new(light_a), Box::new(light_b), Box::new(pipeline)];
    Ok(RecordedFrame::counted(rec, eye, keep_alive))
}
