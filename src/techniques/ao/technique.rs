//! Technique `ao` behind [`RenderTechnique`]: the preprocessing (cached on
//! disk, and the last result kept in memory for the process), the lookup
//! recomputed on the GPU from the transfer function, and the frame
//! ([`super::render`]).

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

use super::render::{self, AoRenderer};
use super::session::AoSession;
use super::{preprocess_cached_on, AoError, AoPreprocessed, AoSettings, Backend, CacheKey, CacheOutcome, Progress};
use crate::render::view_chunks::check_view_step;
use crate::render::{FrameResult, FrameSession, GpuScene, RenderError, RenderTechnique, ResourceNeed};
use crate::scene::{OpticalModel, Scene, Volume};
use crate::vk::{Context, Profiler};

pub struct Ao;

/// Calls of [`preprocess_cached`] this process made (a disk-cache hit counts
/// too: it is the preprocessing step, loaded).
static PREPROCESS_RUNS: AtomicU64 = AtomicU64::new(0);

/// The last preprocessing result, by its cache key.
static LAST: Mutex<Option<(CacheKey, Arc<AoPreprocessed>)>> = Mutex::new(None);

/// How many times this process ran (or loaded) the preprocessing.
pub fn preprocess_runs() -> u64 {
    PREPROCESS_RUNS.load(Ordering::SeqCst)
}

/// The preprocessing of `volume` with `settings`: the result kept from the
/// last call when volume content and parameters are the same, else
/// [`preprocess_cached`] with `progress`.
///
/// With a device, the per-voxel work runs where `ao.backend` says; unset, on a
/// GPU, but on the host's cores for a CPU device (lavapipe), where the GPU
/// path is 3-10x slower than the CPU one on the same cores (docs/ao.md).
pub fn preprocessed(
    volume: &Volume,
    settings: &AoSettings,
    device: Option<&Context>,
    progress: &mut dyn FnMut(&Progress),
) -> Result<Arc<AoPreprocessed>, AoError> {
    preprocessed_telling(volume, settings, device, progress).map(|(result, _)| result)
}

/// [`preprocessed`], and where the result came from: `None` when it was kept
/// in memory from the last call, else how the disk cache served it (loaded,
/// computed and stored, or computed with the cache off), so the command line
/// can say so.
pub fn preprocessed_telling(
    volume: &Volume,
    settings: &AoSettings,
    device: Option<&Context>,
    progress: &mut dyn FnMut(&Progress),
) -> Result<(Arc<AoPreprocessed>, Option<CacheOutcome>), AoError> {
    let device = device.filter(|ctx| settings.backend == Some(Backend::Gpu) || !ctx.info.is_cpu());
    let key = CacheKey::new(volume, settings);
    let mut last = LAST.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    if let Some((k, result)) = last.as_ref() {
        if *k == key {
            return Ok((result.clone(), None));
        }
    }
    PREPROCESS_RUNS.fetch_add(1, Ordering::SeqCst);
    let (result, outcome) = preprocess_cached_on(volume, settings, device, progress)?;
    let result = Arc::new(result);
    *last = Some((key, result.clone()));
    Ok((result, Some(outcome)))
}

impl RenderTechnique for Ao {
    fn name(&self) -> &'static str {
        render::PASS
    }
    fn summary(&self) -> &'static str {
        "ambient occlusion and colour bleeding from clustered local histograms (Ropinski et al. 2008; \
         preprocessing cached, ao.mode: isosurface, dvr, phase, glow)"
    }
    /// Its ground truth is the AO reference (src/techniques/ao/ground_truth/), not a model
    /// of light transport; frames compared with the scene's model use the
    /// scene's choice.
    fn reference_model(&self, scene: &Scene) -> OpticalModel {
        scene.reference.model
    }
    fn resources(&self, scene: &Scene, width: u32, height: u32) -> Vec<ResourceNeed> {
        render::resources(scene, &scene.settings.get::<AoSettings>(), width, height)
    }
    fn check(&self, scene: &Scene) -> Result<(), RenderError> {
        AoSettings::from_scene(scene)?;
        check_view_step(scene, self.name())
    }
    fn render(
        &self,
        gpu: &GpuScene,
        width: u32,
        height: u32,
        profiler: &mut Profiler,
    ) -> Result<FrameResult, RenderError> {
        let settings = AoSettings::from_scene(gpu.scene)?;
        let pre = preprocessed(&gpu.scene.volume, &settings, Some(gpu.ctx), &mut |_| {})?;
        let renderer = AoRenderer::new(gpu, &pre, &settings)?;
        renderer.update_environment(gpu, profiler)?;
        renderer.frame(gpu, (width, height), profiler)
    }
    /// Keeps the uploaded codebook and the lookup across viewer frames.
    fn session<'s>(&self, gpu: &'s GpuScene<'s>) -> Result<Option<Box<dyn FrameSession + 's>>, RenderError> {
        Ok(Some(Box::new(AoSession::new(gpu)?)))
    }
    fn settings_note(&self, scene: &Scene) -> Option<String> {
        let s = &scene.settings.get::<AoSettings>();
        Some(format!(
            "ao: mode {}, r = {}, b = {}, n_c = {}, {}",
            s.mode.name(),
            s.radius,
            s.bits,
            s.clusters,
            s.metric.name()
        ))
    }
}
