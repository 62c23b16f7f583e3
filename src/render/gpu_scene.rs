//! The scene on the GPU, uploaded once and shared by every technique of a run:
//! the volume (3D image, linear sampler), the baked transfer LUT and the lights.
//! Uploading also picks how every pipeline created afterwards on its context
//! filters the volume (`render.filter`, volume_fetch.glsl, docs/filtering.md).
//! The viewer uploads the volume once ([`UploadedVolume`]) and builds a scene
//! on it for every edit (camera, lights, transfer function, settings): only the
//! transfer LUT and the lights are uploaded again, and the frame's images are
//! kept ([`FrameImages`]).

use super::empty_cells::EmptyCells;
use super::error::RenderError;
use super::frame_images::FrameImages;
use super::frame_params::{gpu_lights, GpuLight};
use crate::scene::{Interpolation, Scene, TransferLut, VolumeFilter, VoxelData};
use crate::vk::barriers::{Access, Barrier};
use crate::vk::commands::submit_and_wait;
use crate::vk::limits::{Limit, Need};
use crate::vk::resources::{ImageDesc, Sampler};
use crate::vk::{Buffer, Context, Image, VkError};
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::sync::{Arc, OnceLock};

pub struct GpuScene<'a> {
    pub ctx: &'a Context,
    pub scene: &'a Scene,
    pub volume: Arc<Image>,
    pub volume_format: vk::Format,
    pub sampler: Arc<Sampler>,
    pub lut: Buffer,
    pub lut_size: usize,
    /// At least one record, so the binding is valid with no lights.
    pub lights: Buffer,
    /// How the pipelines created after this upload filter the volume: the
    /// scene's `render.filter`, or `SWEEPLAB_FILTER` where set.
    pub filter: VolumeFilter,
    /// Where the frames' images come from: each frame's own, or kept (the viewer).
    pub frame_images: Arc<FrameImages>,
    /// The ground truth's empty cells, found at its first frame (no other
    /// technique reads them).
    pub empty_cells: OnceLock<EmptyCells>,
}

/// The volume on the GPU, to build scenes with the same volume on
/// ([`GpuScene::on_volume`]) without uploading it again.
#[derive(Clone)]
pub struct UploadedVolume {
    pub image: Arc<Image>,
    pub format: vk::Format,
    pub sampler: Arc<Sampler>,
}

/// volume_fetch.glsl's `VOLUME_FILTER` constant id (no shader uses it for anything else).
pub const VOLUME_FILTER_CONSTANT_ID: u32 = 900;

/// The filter a scene is rendered with: `SWEEPLAB_FILTER` over `render.filter`;
/// `exact` for a labelled volume, which is read nearest and has no sub-texel
/// weights to round (its variable is still checked).
pub fn effective_filter(scene: &Scene) -> Result<VolumeFilter, RenderError> {
    let filter = VolumeFilter::from_env().map_err(RenderError::Invalid)?.unwrap_or(scene.render.filter);
    Ok(if scene.volume.interpolation == Interpolation::Nearest { VolumeFilter::Exact } else { filter })
}

/// volume_fetch.glsl's `VOLUME_FILTER`: the filter's mode, or 2 (nearest) for a
/// labelled volume.
fn volume_fetch_mode(scene: &Scene, filter: VolumeFilter) -> u32 {
    match scene.volume.interpolation {
        Interpolation::Trilinear => filter.shader_constant(),
        Interpolation::Nearest => 2,
    }
}

impl<'a> GpuScene<'a> {
    pub fn upload(ctx: &'a Context, scene: &'a Scene) -> Result<GpuScene<'a>, RenderError> {
        GpuScene::upload_with(ctx, scene, VolumeTexels::Native)
    }

    pub fn upload_with(ctx: &'a Context, scene: &'a Scene, texels: VolumeTexels) -> Result<GpuScene<'a>, RenderError> {
        let volume = UploadedVolume::upload(ctx, scene, texels)?;
        GpuScene::on_volume(ctx, scene, &volume, FrameImages::each_frame_anew())
    }

    /// `scene` on a volume uploaded before (its voxels are the scene's): the
    /// transfer LUT and the lights uploaded, the filter chosen, and the frames'
    /// images taken from `frame_images`.
    pub fn on_volume(
        ctx: &'a Context,
        scene: &'a Scene,
        volume: &UploadedVolume,
        frame_images: Arc<FrameImages>,
    ) -> Result<GpuScene<'a>, RenderError> {
        let filter = effective_filter(scene)?;
        // Every pipeline created on this context from now on filters this way
        // (a context renders one uploaded scene at a time).
        ctx.set_shared_specialization(VOLUME_FILTER_CONSTANT_ID, volume_fetch_mode(scene, filter));
        let lut_table: TransferLut = scene.transfer.bake(TransferLut::DEFAULT_SIZE);
        let lut = Buffer::with_data(ctx, "transfer lut", &lut_table.texels, vk::BufferUsageFlags::STORAGE_BUFFER)?;
        let mut lights_data = gpu_lights(scene);
        if lights_data.is_empty() {
            lights_data.push(GpuLight::default());
        }
        let lights = Buffer::with_data(ctx, "lights", &lights_data, vk::BufferUsageFlags::STORAGE_BUFFER)?;
        Ok(GpuScene {
            ctx,
            scene,
            volume: volume.image.clone(),
            volume_format: volume.format,
            sampler: volume.sampler.clone(),
            lut,
            lut_size: lut_table.texels.len(),
            lights,
            filter,
            frame_images,
            empty_cells: OnceLock::new(),
        })
    }

    /// The volume this scene was built on, for another scene of the same volume.
    pub fn uploaded_volume(&self) -> UploadedVolume {
        UploadedVolume { image: self.volume.clone(), format: self.volume_format, sampler: self.sampler.clone() }
    }
}

impl UploadedVolume {
    /// Uploads `scene`'s volume (one submission, waited for).
    pub fn upload(ctx: &Context, scene: &Scene, texels: VolumeTexels) -> Result<UploadedVolume, RenderError> {
        let v = &scene.volume;
        if v.data.len() != v.voxel_count() || v.voxel_count() == 0 {
            return Err(RenderError::Invalid(format!(
                "volume {} has {} voxels for dims {}",
                v.name,
                v.data.len(),
                v.dims
            )));
        }
        let dims = v.dims.max_element() as u64;
        let limits = crate::vk::limits::DeviceLimits::from_vk(&ctx.limits);
        let need = Need::new(
            Limit::ImageDimension3D,
            dims,
            format!("volume {} ({}x{}x{})", v.name, v.dims.x, v.dims.y, v.dims.z),
            "the volume's size (resample it, or pick a smaller synthetic size)",
        );
        limits.check(&ctx.info.name, &[need]).map_err(VkError::from)?;
        // Refused before the upload, as `on_volume` would after it.
        effective_filter(scene)?;
        let (format, bytes) = volume_texels(ctx, &v.data, texels)?;
        let extent = vk::Extent3D { width: v.dims.x, height: v.dims.y, depth: v.dims.z };
        let volume = Image::new(
            ctx,
            &format!("volume {}", v.name),
            ImageDesc {
                image_type: vk::ImageType::TYPE_3D,
                format,
                extent,
                usage: vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST,
            },
        )?;
        let staging = Buffer::staging(
            ctx,
            "volume staging",
            bytes.len() as u64,
            vk::BufferUsageFlags::TRANSFER_SRC,
            MemoryLocation::CpuToGpu,
        )?;
        let mut staging = staging;
        staging.write_bytes(0, &bytes)?;
        submit_and_wait(ctx, "upload_volume", |rec| {
            rec.barrier(&Barrier::image(
                "volume_discard_to_upload_write",
                &volume,
                Access::NONE,
                Access::TRANSFER_WRITE,
                vk::ImageLayout::UNDEFINED,
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
            ));
            rec.copy_buffer_to_image(&staging, &volume);
            rec.barrier(&Barrier::image(
                "volume_upload_write_to_shader_read",
                &volume,
                Access::TRANSFER_WRITE,
                Access::COMPUTE_SAMPLED_READ,
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL,
            ));
            Ok(())
        })?;
        drop(staging);
        let sampler = Sampler::linear_clamp(ctx, "volume sampler")?;
        Ok(UploadedVolume { image: Arc::new(volume), format, sampler: Arc::new(sampler) })
    }
}

/// How the volume is stored on the GPU.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum VolumeTexels {
    /// r8 / r16 unorm or r32 float, as the data comes. Hardware filtering of the
    /// narrow formats may use few sub-texel bits (lavapipe filters r8 with 8-bit
    /// weights; NVIDIA, AMD and Intel filter every format so): up to 3/512 of
    /// the largest neighbour difference off the exact trilinear value, about
    /// 1e-2 at hard edges (docs/filtering.md; `render.filter = "gpu-8bit"`
    /// shows it on any device).
    #[default]
    Native,
    /// Always r32 float: exact trilinear filtering on lavapipe, for comparisons
    /// with the CPU f64 renderers.
    Float32,
}

/// Picks r8/r16 unorm or r32 float by the voxel type, falling back to r32 float
/// where the device cannot filter the narrower format linearly.
fn volume_texels(ctx: &Context, data: &VoxelData, texels: VolumeTexels) -> Result<(vk::Format, Vec<u8>), VkError> {
    let need = vk::FormatFeatureFlags::SAMPLED_IMAGE
        | vk::FormatFeatureFlags::SAMPLED_IMAGE_FILTER_LINEAR
        | vk::FormatFeatureFlags::TRANSFER_DST;
    let native = match data {
        VoxelData::U8(v) => Some((vk::Format::R8_UNORM, bytemuck::cast_slice(v).to_vec())),
        VoxelData::U16(v) => Some((vk::Format::R16_UNORM, bytemuck::cast_slice(v).to_vec())),
        VoxelData::F32(_) => None,
    };
    if let Some((format, bytes)) = native.filter(|_| texels == VolumeTexels::Native) {
        if ctx.format_supports(format, need) {
            return Ok((format, bytes));
        }
    }
    if !ctx.format_supports(vk::Format::R32_SFLOAT, need) {
        return Err(VkError::NoFormat {
            kind: "volume",
            candidates: "R8_UNORM, R16_UNORM, R32_SFLOAT".into(),
            usage: "linear filtering",
        });
    }
    let floats: Vec<f32> = (0..data.len()).map(|i| data.normalized(i)).collect();
    Ok((vk::Format::R32_SFLOAT, bytemuck::cast_slice(&floats).to_vec()))
}
