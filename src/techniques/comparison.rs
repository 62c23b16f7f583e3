//! One technique's frame against the reference of the model it approximates
//! (`sweeplab compare`): the scene's reference switched to that model, the
//! technique and the reference rendered at the scene's size, and the error
//! statistics with both costs.

use super::ground_truth_cache::{GroundTruth, GroundTruthCache, GroundTruthCacheError, GroundTruthKey};
use super::registry::{render, RenderOutput, Technique};
use crate::linear_image::LinearImage;
use crate::metrics::{compare, MetricsError};
use crate::reference::cpu::{render_cpu, CpuRenderKind};
use crate::reference::validate::CpuRenderError;
use crate::render::{GpuScene, RenderError, VolumeTexels};
use crate::scene::Scene;
use crate::vk::{Context, Profiler, VkError};
use serde::Serialize;
use std::time::Instant;

/// Where the reference image comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReferenceSource {
    /// The CPU ray marcher (exact arithmetic, slow).
    Cpu,
    /// The GPU ground truth (`Technique::Reference`).
    Gpu,
}

impl ReferenceSource {
    pub fn name(self) -> &'static str {
        match self {
            ReferenceSource::Cpu => "cpu",
            ReferenceSource::Gpu => "gpu",
        }
    }
}

impl std::str::FromStr for ReferenceSource {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "cpu" => Ok(ReferenceSource::Cpu),
            "gpu" => Ok(ReferenceSource::Gpu),
            other => Err(format!("unknown reference {other:?}: cpu or gpu")),
        }
    }
}

/// Why a comparison could not be made.
#[derive(Debug, thiserror::Error)]
pub enum ComparisonError {
    #[error("rendering {technique}: {source}")]
    Render { technique: Technique, source: RenderError },
    #[error("CPU reference: {0}")]
    CpuReference(#[from] CpuRenderError),
    #[error("comparing against the reference: {0}")]
    Metrics(#[from] MetricsError),
    #[error(transparent)]
    Vk(#[from] VkError),
    #[error(transparent)]
    Cache(#[from] GroundTruthCacheError),
}

/// The figures of a comparison (what `--json` writes) and both images.
#[derive(Debug, Serialize)]
pub struct Comparison {
    pub technique: &'static str,
    pub reference: &'static str,
    /// The optical model of the reference, e.g. `EmissiveScattering`.
    pub model: String,
    pub chromatic: bool,
    pub width: u32,
    pub height: u32,
    pub rmse: f64,
    pub max_abs: f64,
    /// Infinite for identical images: written as `"inf"` (JSON has no infinity).
    #[serde(serialize_with = "number_or_inf")]
    pub psnr: f64,
    pub gpu_ms: f64,
    pub reference_gpu_ms: Option<f64>,
    pub reference_cpu_s: Option<f64>,
    /// The reference came from the ground-truth cache (its times are those of
    /// the run that rendered it).
    pub reference_cached: bool,
    pub dispatches: u32,
    pub gpu_memory_bytes: u64,
    pub device: String,
    /// A line-sweep frame's shape (IPSVI).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub line_shape: Option<crate::render::LineShape>,
    #[serde(skip)]
    pub image: LinearImage,
    #[serde(skip)]
    pub reference_image: LinearImage,
}

/// `scene` as `technique` is compared: its reference set to the model (and
/// colour) the technique approximates.
pub fn comparison_scene(scene: &Scene, technique: Technique) -> Scene {
    let mut scene = scene.clone();
    scene.reference.model = technique.reference_model(&scene);
    scene.reference.chromatic = technique.reference_chromatic(&scene);
    scene
}

/// Renders `technique` and the reference on `scene` (see [`comparison_scene`])
/// and compares them; with `cache`, the reference is taken from it when there
/// and stored in it when rendered.
pub fn compare_with_reference(
    ctx: &Context,
    scene: &Scene,
    technique: Technique,
    source: ReferenceSource,
    texels: VolumeTexels,
    profiler_capacity: u32,
    cache: Option<&GroundTruthCache>,
) -> Result<Comparison, ComparisonError> {
    let (w, h) = (scene.render.width, scene.render.height);
    let failed = |technique| move |source| ComparisonError::Render { technique, source };
    let gpu = GpuScene::upload_with(ctx, scene, texels).map_err(failed(technique))?;
    let mut profiler = Profiler::new(ctx, profiler_capacity)?;
    let tested: RenderOutput = render(&gpu, technique, w, h, &mut profiler).map_err(failed(technique))?;
    let key = GroundTruthKey::new(scene, source.name(), texels, &ctx.info);
    let cached = match cache {
        Some(cache) => cache.load(&key)?,
        None => None,
    };
    let reference_cached = cached.is_some();
    let truth = match (cached, source) {
        (Some(truth), _) => truth,
        (None, ReferenceSource::Cpu) => {
            let start = Instant::now();
            let image = render_cpu(scene, CpuRenderKind::reference_of(scene), w, h)?;
            GroundTruth { image, gpu_ms: None, cpu_s: Some(start.elapsed().as_secs_f64()) }
        }
        (None, ReferenceSource::Gpu) => {
            let out = render(&gpu, Technique::Reference, w, h, &mut profiler).map_err(failed(Technique::Reference))?;
            GroundTruth { image: out.image, gpu_ms: Some(out.profile.gpu_ms_total), cpu_s: None }
        }
    };
    if let (Some(cache), false) = (cache, reference_cached) {
        cache.store(&key, &truth)?;
    }
    let GroundTruth { image: reference_image, gpu_ms: reference_gpu_ms, cpu_s: reference_cpu_s } = truth;
    let stats = compare(&tested.image, &reference_image)?;
    Ok(Comparison {
        technique: technique.name(),
        reference: source.name(),
        model: format!("{:?}", scene.reference.model),
        chromatic: scene.reference.chromatic,
        width: w,
        height: h,
        rmse: stats.rmse,
        max_abs: stats.max_abs,
        psnr: stats.psnr,
        gpu_ms: tested.profile.gpu_ms_total,
        reference_gpu_ms,
        reference_cpu_s,
        reference_cached,
        dispatches: tested.dispatches,
        gpu_memory_bytes: tested.profile.gpu_memory_bytes,
        device: tested.profile.device.clone(),
        line_shape: tested.shape,
        image: tested.image,
        reference_image,
    })
}

fn number_or_inf<S: serde::Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
    if v.is_finite() {
        s.serialize_f64(*v)
    } else {
        s.serialize_str("inf")
    }
}

impl Comparison {
    /// The terminal's lines: one figure each, aligned.
    pub fn lines(&self) -> Vec<String> {
        let coloured = if self.chromatic { ", chromatic" } else { "" };
        let mut lines = vec![
            format!("technique        {}", self.technique),
            format!("reference        {} ({} model{coloured})", self.reference, self.model),
            format!("image            {}x{}", self.width, self.height),
            format!("rmse             {:.6e}", self.rmse),
            format!("max_abs          {:.6e}", self.max_abs),
            format!("psnr             {:.2} dB", self.psnr),
            format!("gpu_ms           {:.3}", self.gpu_ms),
        ];
        lines.extend(self.reference_gpu_ms.map(|ms| format!("reference_gpu_ms {ms:.3}")));
        lines.extend(self.reference_cpu_s.map(|s| format!("reference_cpu_s  {s:.3}")));
        if self.reference_cached {
            lines.push("reference_from   the ground-truth cache (times of the run that rendered it)".to_string());
        }
        lines.push(format!("dispatches       {}", self.dispatches));
        lines.push(format!("gpu_memory_bytes {}", self.gpu_memory_bytes));
        lines.extend(self.line_shape.as_ref().map(|s| s.summary()));
        lines
    }
}
