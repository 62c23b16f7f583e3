//! The stability table: every technique on every case of
//! [`cases`], each cell within the technique's stated bound
//! against the CPU f64 reference of its model, or an explicit refusal naming
//! the setting, or a warning the scene comes with; then each technique's
//! convergence as the step shrinks, with its observed order. What the CI test
//! and `sweeplab bench stability` share.

pub mod bench;
pub mod cases;
mod experiment;

pub use experiment::StabilityExperiment;

use crate::techniques::ipsvi::IpsviSettings;
use std::path::Path;

use crate::bench::harness::{Harness, Sample};
use crate::bench::Estimate;
use crate::linear_image::LinearImage;
use crate::metrics::compare;
use crate::reference::cpu::{render_cpu, CpuRenderKind};
use crate::render::{GpuScene, RenderError, VolumeTexels};
use crate::scene::warnings::{scene_warnings, SceneWarning};
use crate::scene::Scene;
use crate::techniques::ipsvi::CacheUpdate;
use crate::techniques::scene_from_toml_str;
use crate::techniques::{render, Technique};
use crate::vk::{Context, Profiler};
use cases::StabilityCase;

/// The view steps (voxels) of the convergence check.
pub const CONVERGENCE_STEPS: [f32; 5] = [1.0, 0.5, 0.25, 0.125, 0.0625];

/// A column of the table: a technique, and for IPSVI its cache update (both
/// modes are columns: their artefacts differ).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Variant {
    pub technique: Technique,
    pub cache_update: Option<CacheUpdate>,
}

impl Variant {
    /// Every technique; IPSVI in both cache updates.
    pub fn all() -> Vec<Variant> {
        Technique::all()
            .flat_map(|technique| {
                let modes: Vec<Option<CacheUpdate>> =
                    if technique == Technique::Ipsvi { CacheUpdate::ALL.map(Some).to_vec() } else { vec![None] };
                modes.into_iter().map(move |cache_update| Variant { technique, cache_update })
            })
            .collect()
    }

    pub fn label(&self) -> String {
        match self.cache_update {
            Some(mode) => format!("{} ({})", self.technique, mode.name()),
            None => self.technique.to_string(),
        }
    }

    /// `scene` as this column renders it, compared with the reference of its model.
    pub fn prepare(&self, scene: &Scene) -> Scene {
        let mut scene = scene.clone();
        if let Some(mode) = self.cache_update {
            scene.settings.get_mut::<IpsviSettings>().cache_update = mode;
        }
        scene.reference.model = self.technique.reference_model(&scene);
        scene.reference.chromatic = self.technique.reference_chromatic(&scene);
        scene
    }
}

/// What the CPU f64 renderer of a technique's own model is.
pub fn model_kind(t: Technique, scene: &Scene) -> CpuRenderKind {
    match t.name() {
        "dvr" => CpuRenderKind::Dvr,
        "phong" => CpuRenderKind::Phong,
        _ => CpuRenderKind::Reference(t.reference_model(scene)),
    }
}

/// Least PSNR (dB) a technique keeps against the CPU f64 reference of its
/// model on every case that it renders. DVR, Phong and the GPU reference
/// march exactly the CPU's discretization: float rounding only (measured on
/// lavapipe: >= 63 dB, the least at step 2e-4). The others approximate the
/// model (measured: IPSVI >= 49 dB, half-angle >= 41 dB, light volume >= 41 dB);
/// the bounds leave a few dB for another device's arithmetic.
pub fn bound_db(t: Technique) -> f64 {
    match t.name() {
        "dvr" | "phong" | "reference" => 55.0,
        "ipsvi" => 42.0,
        "half-angle" => 36.0,
        "lightvolume" => 36.0,
        other => panic!("no bound stated for {other}"),
    }
}

/// A cell's verdict.
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// Rendered within its bound, no warning.
    Ok,
    /// Rendered with the warning the case expects: the scene's (and within
    /// the bound), or the technique's own that it renders the case beyond it.
    Warned(String),
    /// Refused, as the case expects, by an error naming the setting.
    Refused(String),
    /// Anything else: below its bound, a refusal or warning not expected or
    /// not naming its cause, one expected and missing.
    Failed(String),
}

impl Verdict {
    pub fn name(&self) -> &'static str {
        match self {
            Verdict::Ok => "ok",
            Verdict::Warned(_) => "warned",
            Verdict::Refused(_) => "refused",
            Verdict::Failed(_) => "FAILED",
        }
    }

    pub fn message(&self) -> &str {
        match self {
            Verdict::Ok => "",
            Verdict::Warned(m) | Verdict::Refused(m) | Verdict::Failed(m) => m,
        }
    }
}

/// One case x technique cell.
#[derive(Clone, Debug)]
pub struct Cell {
    pub case: &'static str,
    pub variant: Variant,
    pub verdict: Verdict,
    /// PSNR against the CPU reference of the model, where it rendered.
    pub psnr_db: Option<f64>,
    pub bound_db: f64,
    /// Median GPU time of the timed frames.
    pub gpu_ms: Option<f64>,
    /// That median with its 95 % interval (6 or more timed frames).
    pub gpu_ms_interval: Option<Estimate>,
    /// IPSVI: the line kernel the frames ran (`serial`, `segmented x32`).
    pub line_kernel: Option<String>,
}

impl Cell {
    /// A cell with `verdict` and no measurement (yet).
    pub fn unmeasured(case: &StabilityCase, variant: Variant, verdict: Verdict) -> Cell {
        let bound_db = bound_db(variant.technique);
        Cell {
            case: case.name,
            variant,
            verdict,
            psnr_db: None,
            bound_db,
            gpu_ms: None,
            gpu_ms_interval: None,
            line_kernel: None,
        }
    }
}

/// A case's scene and its warnings, or why it did not load.
pub fn load_case(case: &StabilityCase, dir: &Path) -> Result<(Scene, Vec<SceneWarning>), String> {
    let scene = scene_from_toml_str(&case.toml, dir, case.name, &case.set).map_err(|e| format!("{e:#}"))?;
    let warnings = scene_warnings(&scene);
    Ok((scene, warnings))
}

/// Whether the scene's warnings are what the case expects: `Ok(Some(text))`
/// the expected one, `Ok(None)` none and none expected, `Err` otherwise.
fn check_warnings(case: &StabilityCase, warnings: &[SceneWarning]) -> Result<Option<String>, String> {
    match case.warns {
        Some(expected) => match warnings.iter().find(|w| expected(w)) {
            Some(w) => Ok(Some(w.to_string())),
            None => Err(format!("no warning ({warnings:?})")),
        },
        None if warnings.is_empty() => Ok(None),
        None => Err(format!("unexpected warnings {warnings:?}")),
    }
}

/// What the timed frames of a cell gave: the last image, the median GPU time
/// with its interval, and (IPSVI) the line kernel they ran.
struct TimedFrame {
    image: LinearImage,
    ms: f64,
    interval: Option<Estimate>,
    line_kernel: Option<String>,
}

/// A GPU frame of `t` on `scene`, timed by `harness`: its check first, as
/// the command line does.
fn gpu_frame(ctx: &Context, scene: &Scene, t: Technique, size: u32, harness: Harness) -> Result<TimedFrame, String> {
    t.check(scene).map_err(|e| e.to_string())?;
    let gpu = GpuScene::upload_with(ctx, scene, VolumeTexels::Float32).map_err(|e| e.to_string())?;
    let mut profiler = Profiler::new(ctx, Profiler::FRAME_CAPACITY).map_err(|e| e.to_string())?;
    let measured = harness
        .measure(|| {
            let out = render(&gpu, t, size, size, &mut profiler)?;
            let line_kernel = out.shape.map(|shape| shape.kernel);
            Ok::<_, RenderError>(Sample::timed(out.profile.gpu_ms_total, (out.image, line_kernel)))
        })
        .map_err(|e| e.to_string())?;
    let (ms, interval) = (measured.median(), measured.estimate());
    let (image, line_kernel) = measured.last;
    Ok(TimedFrame { image, ms, interval, line_kernel })
}

/// One cell: `variant` on the case's `scene` at `size` x `size`.
pub fn run_cell(
    ctx: &Context,
    case: &StabilityCase,
    scene: &Scene,
    warnings: &[SceneWarning],
    variant: Variant,
    size: u32,
    harness: Harness,
) -> Cell {
    let t = variant.technique;
    let mut cell = Cell::unmeasured(case, variant, Verdict::Ok);
    let warning = match check_warnings(case, warnings) {
        Ok(w) => w,
        Err(e) => {
            cell.verdict = Verdict::Failed(e);
            return cell;
        }
    };
    let scene = variant.prepare(scene);
    let label = variant.label();
    let expected_warning = case.technique_warns.iter().find(|(name, _)| *name == label || *name == t.name());
    let technique_warnings = t.warnings(&scene);
    let technique_warning = match expected_warning {
        Some((_, word)) => match technique_warnings.iter().find(|w| w.contains(word)) {
            Some(w) => Some(w.clone()),
            None => {
                cell.verdict = Verdict::Failed(format!("no warning naming {word:?} ({technique_warnings:?})"));
                return cell;
            }
        },
        None if technique_warnings.is_empty() => None,
        None => {
            cell.verdict = Verdict::Failed(format!("unexpected warnings {technique_warnings:?}"));
            return cell;
        }
    };
    let expected_refusal = case.refused.iter().find(|(name, _)| *name == t.name());
    let frame = gpu_frame(ctx, &scene, t, size, harness);
    cell.verdict = match (frame, expected_refusal) {
        (Err(e), Some((_, word))) if e.contains(word) && e.contains(t.name()) => Verdict::Refused(e),
        (Err(e), Some((_, word))) => Verdict::Failed(format!("refusal does not name {word:?} and {t}: {e}")),
        (Err(e), None) => Verdict::Failed(e),
        (Ok(_), Some(_)) => Verdict::Failed("should be refused, rendered".into()),
        (Ok(f), None) if !f.image.all_finite() => {
            (cell.gpu_ms, cell.gpu_ms_interval, cell.line_kernel) = (Some(f.ms), f.interval, f.line_kernel);
            Verdict::Failed("render let a non-finite frame through".into())
        }
        (Ok(f), None) => {
            (cell.gpu_ms, cell.gpu_ms_interval, cell.line_kernel) = (Some(f.ms), f.interval, f.line_kernel);
            match render_cpu(&scene, model_kind(t, &scene), size, size) {
                Err(e) => Verdict::Failed(format!("CPU reference: {e}")),
                Ok(reference) => {
                    let db = compare(&f.image, &reference).map(|s| s.psnr).unwrap_or(f64::NAN);
                    cell.psnr_db = Some(db);
                    if let Some(w) = technique_warning {
                        // Beyond the bound by the technique's own account.
                        Verdict::Warned(w)
                    } else if db.is_nan() || db < cell.bound_db {
                        Verdict::Failed(format!("{db:.1} dB < {} dB", cell.bound_db))
                    } else if let Some(w) = warning {
                        Verdict::Warned(w)
                    } else {
                        Verdict::Ok
                    }
                }
            }
        }
    };
    cell
}

/// A technique's error against its model's limit over [`CONVERGENCE_STEPS`].
#[derive(Clone, Debug)]
pub struct Convergence {
    pub variant: Variant,
    /// RMSE relative to the limit's peak, one per step.
    pub errors: Vec<f64>,
    /// log2 of each error over the next: the observed order between steps.
    pub orders: Vec<f64>,
    /// Why the errors do not behave, if they do not.
    pub failures: Vec<String>,
}

impl Convergence {
    /// The order over the whole range (first error over last, per halving).
    pub fn overall_order(&self) -> f64 {
        let (first, last) = (self.errors[0], self.errors[self.errors.len() - 1]);
        (first / last).log2() / (self.errors.len() - 1) as f64
    }
}

/// `variant` on `base` over [`CONVERGENCE_STEPS`], against its model's f64
/// march at a far finer view step (1/64 voxel; the light steps stay).
pub fn convergence(ctx: &Context, base: &Scene, variant: Variant, size: u32) -> Result<Convergence, String> {
    let t = variant.technique;
    let mut scene = variant.prepare(base);
    // The order of the midpoint rule: jittered phases (render.jitter) are
    // another quadrature, first order per pixel.
    scene.render.jitter = false;
    let mut fine = scene.clone();
    fine.render.step_voxels = 1.0 / 64.0;
    fine.reference.step_voxels = 1.0 / 64.0;
    let limit = render_cpu(&fine, model_kind(t, &fine), size, size).map_err(|e| e.to_string())?;
    let peak = limit.max_value() as f64;
    let mut errors = Vec::new();
    for &h in &CONVERGENCE_STEPS {
        scene.render.step_voxels = h;
        scene.reference.step_voxels = h;
        let image = gpu_frame(ctx, &scene, t, size, Harness::once_after(0))?.image;
        errors.push(compare(&image, &limit).map_err(|e| e.to_string())?.rmse / peak);
    }
    let orders: Vec<f64> = errors.windows(2).map(|e| (e[0] / e[1]).log2()).collect();
    let mut failures = Vec::new();
    let label = variant.label();
    if variant.cache_update == Some(CacheUpdate::ViewSamples) {
        // The paper's cache holds each texel's light at the one depth its
        // writing sample had, so below half a voxel the view step no longer
        // moves the error: it stays on that floor (measured 1.45e-3 at step
        // 0.5, 1.70e-3 .. 1.92e-3 below), within 1.5x of its step-0.5 error.
        for (i, &e) in errors.iter().enumerate().skip(2) {
            if e > 1.5 * errors[1] {
                failures.push(format!(
                    "{label}: step {} left the floor: {e:.2e} (step 0.5: {:.2e})",
                    CONVERGENCE_STEPS[i], errors[1]
                ));
            }
        }
    } else {
        // Non-increasing within noise: 5 % of the previous error, or 1e-4 of
        // the peak once the technique sits on its approximation floor.
        for (i, e) in errors.windows(2).enumerate() {
            if e[1] > e[0] * 1.05 + 1e-4 {
                failures.push(format!(
                    "{label}: error grew from step {} to {}: {:.2e} -> {:.2e}",
                    CONVERGENCE_STEPS[i],
                    CONVERGENCE_STEPS[i + 1],
                    e[0],
                    e[1]
                ));
            }
        }
    }
    Ok(Convergence { variant, errors, orders, failures })
}

/// The scene the convergence check runs on: the baseline case.
pub fn convergence_scene(cases: &[StabilityCase], dir: &Path) -> Result<Scene, String> {
    let base = cases.iter().find(|c| c.name == "baseline").ok_or("no baseline case")?;
    load_case(base, dir).map(|(scene, _)| scene)
}
