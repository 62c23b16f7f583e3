//! `sweeplab bench table1` as an experiment: the IPSVI paper's Table 1 on our
//! data and device. Per data set and image size, the frames of every line
//! width and line kernel are measured side by side ([`Interleaved`]), so the
//! frame rate of each, its ratio to line width 1 and the segmented kernel's
//! ratio to the serial one (paired round by round) see the same rounds of a
//! shared machine; and each one's RMSE against the ground truth of IPSVI's
//! model, rendered once per size on the device, beside the serial kernel's.

mod experiment;
pub mod paper;

pub use experiment::Table1Experiment;

use crate::bench::experiments::table1::paper::{PaperColumn, CT_ENGINE, CT_GIRAFFE, LINE_WIDTHS, US_BABY};
use crate::bench::{
    ipsvi_frame, BenchRow, BenchTable, Estimate, ExperimentError, Interleaved, OutFolder, Progress, RunInfo, Sample,
};
use crate::linear_image::LinearImage;
use crate::metrics::compare;
use crate::render::{GpuScene, LineShape};
use crate::scene::loaders::data_dir;
use crate::scene::OpticalModel;
use crate::techniques::ipsvi::cache_plane::AUTO_CACHE_MIN;
use crate::techniques::ipsvi::line_kernel::LineKernel;
use crate::techniques::ipsvi::renderer::IpsviRenderer;
use crate::techniques::ipsvi::{IpsviSettings, SyncStrategy};
use crate::techniques::{render, scene_for_volume_file, Technique};
use crate::vk::{Context, Profiler};
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::str::FromStr;

/// Our data sets and the paper column each stands beside.
pub const PAPER_PAIRS: [(&str, &PaperColumn); 3] =
    [("engine.vti", &CT_ENGINE), ("aneurism.vti", &US_BABY), ("LIDC2.mha", &CT_GIRAFFE)];

/// What `bench table1` measures.
#[derive(Clone)]
pub struct Table1Plan {
    /// Square image sizes.
    pub sizes: Vec<u32>,
    /// The rounds of each (data set, size) measurement.
    pub interleaved: Interleaved,
    /// Scene overrides (`KEY=VALUE`) applied to every data set.
    pub set: Vec<String>,
    /// The volume files and the paper columns they stand beside.
    pub data_sets: Vec<(PathBuf, &'static PaperColumn)>,
    /// The line kernels measured (`auto`: the device's), each with its
    /// segments per pixel and texel lanes (the segmented kernel's only).
    pub kernels: Vec<(LineKernel, SegmentCount)>,
    /// The ground truth of IPSVI's model (ii) per data set and size, and each
    /// configuration's RMSE against it (on a CPU device minutes at 256 and up).
    pub errors: bool,
}

/// The segmented kernel's split as `--segments` names it: `S` (segments per
/// pixel, 0: the device's) or `S/T` (and `T` lanes per cache texel; without
/// it, or 0, the default for `S`), so that one run sets texel lanes side by
/// side as well as segment counts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SegmentCount {
    pub segments: u32,
    pub texel_segments: u32,
}

impl SegmentCount {
    pub const DEVICE: SegmentCount = SegmentCount { segments: 0, texel_segments: 0 };
}

impl FromStr for SegmentCount {
    type Err = String;
    fn from_str(text: &str) -> Result<Self, String> {
        let number = |part: &str| {
            part.trim()
                .parse::<u32>()
                .map_err(|_| format!("{text:?} is not S or S/T (segments, texel lanes: whole numbers)"))
        };
        match text.split_once('/') {
            None => Ok(SegmentCount { segments: number(text)?, texel_segments: 0 }),
            Some((s, t)) => Ok(SegmentCount { segments: number(s)?, texel_segments: number(t)? }),
        }
    }
}

impl Table1Plan {
    /// The paper's three data sets, from the data folder.
    pub fn paper(sizes: Vec<u32>, interleaved: Interleaved, set: Vec<String>) -> Table1Plan {
        let data_sets = PAPER_PAIRS.iter().map(|(file, paper)| (data_dir().join(file), *paper)).collect();
        let kernels = vec![(LineKernel::Auto, SegmentCount::DEVICE)];
        Table1Plan { sizes, interleaved, set, data_sets, kernels, errors: true }
    }

    /// `kernels`, the segmented one at each of `segments` (the others once).
    pub fn kernels_at(kernels: &[LineKernel], segments: &[SegmentCount]) -> Vec<(LineKernel, SegmentCount)> {
        let counts = if segments.is_empty() { &[SegmentCount::DEVICE][..] } else { segments };
        let mut out = Vec::new();
        for &k in kernels {
            match k {
                LineKernel::Segmented => out.extend(counts.iter().map(|&s| (k, s))),
                _ => out.push((k, SegmentCount::DEVICE)),
            }
        }
        out
    }

    /// Only the data sets whose file names are in `files` (of [`PAPER_PAIRS`]);
    /// the error names the unknown one.
    pub fn only(mut self, files: &[String]) -> Result<Table1Plan, ExperimentError> {
        if files.is_empty() {
            return Ok(self);
        }
        for f in files {
            if !PAPER_PAIRS.iter().any(|(file, _)| file == f) {
                let known: Vec<&str> = PAPER_PAIRS.iter().map(|p| p.0).collect();
                return Err(ExperimentError::Invalid(format!("--data-sets: {f:?} is not one of {}", known.join(", "))));
            }
        }
        self.data_sets.retain(|(path, _)| files.iter().any(|f| path.file_name().is_some_and(|n| n == f.as_str())));
        Ok(self)
    }
}

/// A kernel as the rows name it before it is resolved.
fn kernel_settings(
    base: &IpsviSettings,
    (line_kernel, count): (LineKernel, SegmentCount),
    line_width: u32,
) -> IpsviSettings {
    let SegmentCount { segments, texel_segments } = count;
    IpsviSettings { line_width, line_kernel, segments, texel_segments, ..base.clone() }
}

/// How the progress line names a kernel before it is resolved.
fn kernel_name((line_kernel, count): (LineKernel, SegmentCount)) -> String {
    match (count.segments, count.texel_segments) {
        (0, 0) => line_kernel.name().to_string(),
        (s, 0) => format!("{} x{s}", line_kernel.name()),
        (s, t) => format!("{} x{s}, texels x{t}", line_kernel.name()),
    }
}

/// The configuration (kernel `k`, line width index `i`: `k * n + i`) with the
/// lowest median frame time among the kernels at line width index `i`.
fn fastest_at_line_width(medians: &[f64], n: usize, i: usize) -> usize {
    (i..medians.len()).step_by(n).min_by(|&a, &b| medians[a].total_cmp(&medians[b])).unwrap_or(i)
}

/// Frames per second from a frame's GPU ms, its interval turned over with it.
fn fps_of(ms: &Estimate) -> Estimate {
    Estimate { value: 1000.0 / ms.value, lo: 1000.0 / ms.hi, hi: 1000.0 / ms.lo, n: ms.n }
}

/// One data set at one size: per (kernel, line width) the frame rate, its
/// paired ratio to line width 1 of the same kernel and to the first kernel at
/// the same line width, and the kernel as it ran.
struct SizeMeasurement {
    /// Median frame ms and its interval.
    gpu_ms: Vec<(f64, Option<Estimate>)>,
    /// lw1 time over this time, paired (how many times lw1's fps).
    over_lw1: Vec<Option<Estimate>>,
    /// The first kernel's time over this time, paired.
    over_first_kernel: Vec<Option<Estimate>>,
    /// The configuration of the fastest kernel (lowest median) at this one's
    /// line width, and this time over its, paired.
    fastest: Vec<usize>,
    over_fastest: Vec<Option<Estimate>>,
    /// The kernel's label (`serial`, `segmented x32`) and its frame's shape.
    kernels: Vec<(String, Option<LineShape>)>,
    /// The last frame's RMSE against the ground truth, and the ground truth's GPU ms.
    rmse: Vec<Option<f64>>,
    reference_ms: Option<f64>,
}

/// Every data set of `plan` at every size, the rows saved in `out_folder`
/// (as `table1.csv`/`.json`) after each data set; `run` with the sizes and
/// rounds added is the table's run.
pub fn run(
    ctx: &Context,
    plan: &Table1Plan,
    run: RunInfo,
    out_folder: &OutFolder,
    profiler_capacity: u32,
) -> Result<BenchTable, ExperimentError> {
    let sizes = plan.sizes.iter().map(|s| s.to_string()).collect::<Vec<_>>().join(",");
    let mut table = BenchTable::with_run(plan.interleaved.recorded_in(run.input("sizes", sizes)));
    let mut profiler = Profiler::new(ctx, profiler_capacity)?;
    let mut progress = Progress::weighted(step_weights(plan));
    for (path, paper) in &plan.data_sets {
        let file = path.file_name().map_or_else(|| path.display().to_string(), |f| f.to_string_lossy().into_owned());
        let mut scene = scene_for_volume_file(path, &plan.set)
            .map_err(|e| ExperimentError::Invalid(format!("loading {}: {e}", path.display())))?;
        // IPSVI's model, whatever the data set's scene names (as `compare` does).
        scene.reference.model = OpticalModel::EmissiveScattering;
        let mut base = IpsviSettings { piecewise: true, ..scene.settings.get::<IpsviSettings>().into_owned() };
        // The cache the H200 record's Table 1 ran at, unless `--set` names one.
        if base.cache_size == 0 {
            base.cache_size = AUTO_CACHE_MIN;
        }
        let gpu = GpuScene::upload(ctx, &scene)?;
        let mut measured = BTreeMap::new();
        let n = LINE_WIDTHS.len();
        for &size in &plan.sizes {
            let truth = if plan.errors {
                let reference = render(&gpu, Technique::Reference, size, size, &mut profiler)?;
                Some((reference.image, reference.profile.gpu_ms_total))
            } else {
                None
            };
            let mut renderers = plan
                .kernels
                .iter()
                .flat_map(|&k| LINE_WIDTHS.iter().map(move |&lw| (k, lw)))
                .map(|(k, lw)| IpsviRenderer::new(&gpu, &kernel_settings(&base, k, lw), size, size))
                .collect::<Result<Vec<_>, _>>()?;
            let kernels: Vec<String> = plan.kernels.iter().map(|&k| kernel_name(k)).collect();
            let label = format!(
                "{file} {size}x{size} lw={} kernels={}",
                LINE_WIDTHS.map(|w| w.to_string()).join(","),
                kernels.join(",")
            );
            let timings = plan.interleaved.measure(&mut progress, &label, renderers.len(), |c, _| {
                ipsvi_frame(ctx, &mut renderers[c], &mut profiler, SyncStrategy::BarrierGlobal)
                    .map(|s| Sample { ms: s.ms, output: (s.output.frame.shape, s.output.frame.image) })
                    .map_err(ExperimentError::from)
            })?;
            let gpu_ms = timings.iter().map(|t| (t.median(), t.estimate())).collect();
            let over_lw1 = timings.iter().enumerate().map(|(c, t)| timings[c / n * n].paired_ratio(t)).collect();
            let over_first_kernel = timings.iter().enumerate().map(|(c, t)| timings[c % n].paired_ratio(t)).collect();
            let medians: Vec<f64> = timings.iter().map(|t| t.median()).collect();
            let fastest: Vec<usize> = (0..timings.len()).map(|c| fastest_at_line_width(&medians, n, c % n)).collect();
            let over_fastest = timings.iter().enumerate().map(|(c, t)| t.paired_ratio(&timings[fastest[c]])).collect();
            let kernels = renderers.iter().zip(&timings).map(|(r, t)| (r.kernel().label(), t.last.0.clone())).collect();
            let rmse = timings.iter().map(|t| rmse_against(&t.last.1, truth.as_ref())).collect::<Result<_, _>>()?;
            let reference_ms = truth.as_ref().map(|t| t.1);
            let m = SizeMeasurement {
                gpu_ms,
                over_lw1,
                over_first_kernel,
                fastest,
                over_fastest,
                kernels,
                rmse,
                reference_ms,
            };
            measured.insert(size, m);
        }
        for &size in &plan.sizes {
            for k in 0..plan.kernels.len() {
                for (i, &lw) in LINE_WIDTHS.iter().enumerate() {
                    let mut row = row(&file, paper, plan, &measured, size, k * n + i, lw);
                    row.set("cache_size", base.cache_size);
                    table.push(row);
                }
            }
        }
        out_folder.save_rows("table1", &table)?;
    }
    progress.finish();
    Ok(table)
}

/// A frame's RMSE against the ground truth, where there is one.
fn rmse_against(image: &LinearImage, truth: Option<&(LinearImage, f64)>) -> Result<Option<f64>, ExperimentError> {
    let Some((truth, _)) = truth else { return Ok(None) };
    Ok(Some(compare(image, truth)?.rmse))
}

/// The row of configuration `i` (kernel `i / 3`, line width `LINE_WIDTHS[i %
/// 3]`) at `size`: ours beside the paper's.
fn row(
    file: &str,
    paper: &PaperColumn,
    plan: &Table1Plan,
    measured: &BTreeMap<u32, SizeMeasurement>,
    size: u32,
    i: usize,
    lw: u32,
) -> BenchRow {
    let fps = |size: u32, i: usize| 1000.0 / measured[&size].gpu_ms[i].0;
    // The paper measured 64 to 1024 pixels a side: elsewhere its columns stay empty.
    let paper_fps = |size: u32, lw: u32| paper.fps_at(size, lw);
    let m = &measured[&size];
    let (ms, ms_estimate) = m.gpu_ms[i];
    let ours = fps(size, i);
    let lw1 = i / LINE_WIDTHS.len() * LINE_WIDTHS.len();
    let mut row = BenchRow::new();
    row.set("data_set", file).set("paper_data_set", paper.data_set).set("width", size).set("line_width", lw);
    row.set("line_kernel", m.kernels[i].0.as_str());
    row.set("fps", ours);
    if let Some(e) = ms_estimate {
        row.set("fps_lo", fps_of(&e).lo).set("fps_hi", fps_of(&e).hi);
    }
    if let Some(fps) = paper_fps(size, lw) {
        row.set("paper_fps", fps);
    }
    row.set("gpu_ms", ms).set_estimate("gpu_ms", ms_estimate);
    if lw != 1 {
        row.set("fps_over_lw1", ours / fps(size, lw1)).set_estimate("fps_over_lw1", m.over_lw1[i]);
        if let (Some(at), Some(lw1)) = (paper_fps(size, lw), paper_fps(size, 1)) {
            row.set("paper_fps_over_lw1", at / lw1);
        }
    }
    if i >= LINE_WIDTHS.len() {
        let first = i % LINE_WIDTHS.len();
        row.set("fps_over_first_kernel", ours / fps(size, first));
        row.set_estimate("fps_over_first_kernel", m.over_first_kernel[i]);
    }
    if plan.kernels.len() > 1 {
        // Which kernel (and count) to default to: each against the fastest at
        // this line width, paired round by round.
        let fastest = m.fastest[i];
        row.set("fastest_kernel", m.kernels[fastest].0.as_str());
        row.set("gpu_ms_over_fastest", ms / m.gpu_ms[fastest].0);
        row.set_estimate("gpu_ms_over_fastest", m.over_fastest[i]);
    }
    if let Some(&half) = plan.sizes.iter().find(|&&h| h * 2 == size) {
        row.set("fps_over_half_size", ours / fps(half, i));
        if let (Some(at), Some(at_half)) = (paper_fps(size, lw), paper_fps(half, lw)) {
            row.set("paper_fps_over_half_size", at / at_half);
        }
    }
    if let (Some(rmse), Some(reference_ms)) = (m.rmse[i], m.reference_ms) {
        row.set("rmse", rmse).set("reference_model", "emissive-scattering");
        row.set("reference_gpu_ms", reference_ms);
        // The serial kernel's at this line width: the segmented kernel's goal is within 2 % of it.
        let serial =
            (i % LINE_WIDTHS.len()..m.rmse.len()).step_by(LINE_WIDTHS.len()).find(|&c| m.kernels[c].0 == "serial");
        if let Some(serial_rmse) = serial.and_then(|c| m.rmse[c]).filter(|&r| r > 0.0) {
            row.set("rmse_over_serial", rmse / serial_rmse);
        }
    }
    if let Some(shape) = &m.kernels[i].1 {
        super::ipsvi::set_shape(&mut row, shape);
        // The frame spread over its lines: on a GPU, where a line is its longest
        // chain's latency, this over the chain is that latency per sample.
        row.set("frame_us_per_line", ms * 1e3 / f64::from(shape.line_dispatches.max(1)));
    }
    row
}

/// The relative size of each progress step (one per data set and size, all
/// line widths in it): pixels times the cube root of the data set's file size
/// (a ray's length in voxels), so the time left counts large images and large
/// volumes as such.
fn step_weights(plan: &Table1Plan) -> Vec<f64> {
    let mut weights = Vec::new();
    for (path, _) in &plan.data_sets {
        let bytes = std::fs::metadata(path).map(|m| m.len() as f64).unwrap_or(1.0);
        for &size in &plan.sizes {
            let pixels = f64::from(size) * f64::from(size);
            weights.push(pixels * bytes.max(1.0).cbrt() * (LINE_WIDTHS.len() * plan.kernels.len()) as f64);
        }
    }
    weights
}

/// What the terminal shows: one line per row, ours beside the paper's; every
/// column is in the files.
pub fn print_summary(table: &BenchTable) {
    for r in &table.rows {
        println!("{}", summary_line(r));
    }
}

/// One row's line: our frame rate with its interval, then the paper's where
/// it measured this size and line width.
fn summary_line(r: &BenchRow) -> String {
    let interval = match (r.get_f64("fps_lo"), r.get_f64("fps_hi")) {
        (Some(lo), Some(hi)) => format!(" (95 % CI {lo:.2}-{hi:.2})"),
        _ => String::new(),
    };
    let paper = match r.get_f64("paper_fps") {
        Some(fps) => format!("paper, {}: {fps:.1} fps", r.text("paper_data_set")),
        None => format!("the paper has no figure at this size and line width for {}", r.text("paper_data_set")),
    };
    let against_fastest = match (r.get("fastest_kernel"), r.get_f64("gpu_ms_over_fastest")) {
        (Some(_), _) if r.text("fastest_kernel") == r.text("line_kernel") => {
            "; the fastest kernel here (lowest median)".to_string()
        }
        (Some(_), Some(ratio)) => {
            // One paired estimate of one ratio: within noise only where it holds 1.
            let interval = match (r.get_f64("gpu_ms_over_fastest_lo"), r.get_f64("gpu_ms_over_fastest_hi")) {
                (Some(lo), Some(hi)) if lo <= 1.0 => format!(" (95 % CI {lo:.2}-{hi:.2}, paired: within noise)"),
                (Some(lo), Some(hi)) => format!(" (95 % CI {lo:.2}-{hi:.2}, paired)"),
                _ => String::new(),
            };
            format!("; {ratio:.2}x the time of {}{interval}", r.text("fastest_kernel"))
        }
        _ => String::new(),
    };
    let error = match (r.get_f64("rmse"), r.get_f64("rmse_over_serial")) {
        (Some(rmse), Some(over)) if r.text("line_kernel") != "serial" => {
            format!("; RMSE {rmse:.4}, {over:.3}x the serial kernel's")
        }
        (Some(rmse), _) => format!("; RMSE {rmse:.4}"),
        _ => String::new(),
    };
    format!(
        "{} {}x{} lw={} {}: {:.2} fps{interval} ({paper}){against_fastest}{error}",
        r.text("data_set"),
        r.text("width"),
        r.text("width"),
        r.text("line_width"),
        r.text("line_kernel"),
        r.get_f64("fps").unwrap_or(f64::NAN),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_frame_rate_interval_is_the_frame_time_interval_turned_over() {
        let fps = fps_of(&Estimate { value: 20.0, lo: 16.0, hi: 25.0, n: 8 });
        assert_eq!((fps.value, fps.lo, fps.hi, fps.n), (50.0, 40.0, 62.5, 8));
    }

    #[test]
    fn the_segmented_kernel_runs_at_each_count_and_the_others_once() {
        let at = |text: &str| text.parse::<SegmentCount>().unwrap();
        let (device, x32, x128, x128_8) = (SegmentCount::DEVICE, at("32"), at("128"), at("128/8"));
        assert_eq!((x128.segments, x128.texel_segments, x128_8.texel_segments), (128, 0, 8));
        let k = Table1Plan::kernels_at(&[LineKernel::Serial, LineKernel::Segmented], &[x32, x128, x128_8]);
        let segmented = LineKernel::Segmented;
        assert_eq!(k, [(LineKernel::Serial, device), (segmented, x32), (segmented, x128), (segmented, x128_8)]);
        assert_eq!(Table1Plan::kernels_at(&[LineKernel::Auto], &[x32]), [(LineKernel::Auto, device)]);
        assert_eq!(kernel_name((segmented, at("64"))), "segmented x64");
        assert_eq!(kernel_name((segmented, x128_8)), "segmented x128, texels x8");
        assert_eq!(kernel_name((segmented, device)), "segmented");
        let s = kernel_settings(&IpsviSettings::default(), (segmented, x128_8), 2);
        assert_eq!((s.segments, s.texel_segments, s.line_width), (128, 8, 2));
        for bad in ["x", "128/", "/8", "128/8/2", "-1"] {
            assert!(bad.parse::<SegmentCount>().unwrap_err().contains("S/T"), "{bad}");
        }
    }

    #[test]
    fn the_paper_stands_beside_a_row_only_where_it_measured_that_size() {
        let line = |size: u32| {
            let mut row = BenchRow::new();
            row.set("data_set", "engine.vti").set("paper_data_set", CT_ENGINE.data_set).set("width", size);
            row.set("line_width", 2).set("line_kernel", "serial").set("fps", 4.0);
            if let Some(fps) = CT_ENGINE.fps_at(size, 2) {
                row.set("paper_fps", fps);
            }
            summary_line(&row)
        };
        assert_eq!(line(256), "engine.vti 256x256 lw=2 serial: 4.00 fps (paper, CT Engine 256x256x256: 15.4 fps)");
        let small = line(16);
        assert!(
            small.ends_with("(the paper has no figure at this size and line width for CT Engine 256x256x256)"),
            "{small}"
        );
        assert!(!small.contains("NaN"), "{small}");
    }

    #[test]
    fn a_row_names_its_error_and_the_segmented_kernels_against_the_serial_ones() {
        let line = |kernel: &str| {
            let mut row = BenchRow::new();
            row.set("data_set", "engine.vti").set("paper_data_set", CT_ENGINE.data_set).set("width", 256);
            row.set("line_width", 1).set("line_kernel", kernel).set("fps", 4.0).set("rmse", 0.01234);
            row.set("rmse_over_serial", if kernel == "serial" { 1.0 } else { 1.0004 });
            summary_line(&row)
        };
        assert!(line("serial").ends_with("256x256x256); RMSE 0.0123"), "{}", line("serial"));
        let segmented = line("segmented x32");
        assert!(segmented.ends_with("256x256x256); RMSE 0.0123, 1.000x the serial kernel's"), "{segmented}");
    }

    #[test]
    fn each_row_stands_against_the_fastest_kernel_at_its_line_width() {
        // Three kernels at three line widths: kernel k's line width i is k * 3 + i.
        let medians = [9.0, 5.0, 3.0, 4.0, 6.0, 2.0, 7.0, 4.5, 2.5];
        let fastest: Vec<usize> = (0..3).map(|i| fastest_at_line_width(&medians, 3, i)).collect();
        assert_eq!(fastest, [3, 7, 5]);
        let line = |kernel: &str, ratio: f64, interval: Option<(f64, f64)>| {
            let mut row = BenchRow::new();
            row.set("data_set", "engine.vti").set("paper_data_set", CT_ENGINE.data_set).set("width", 16);
            row.set("line_width", 1).set("line_kernel", kernel).set("fps", 4.0);
            row.set("fastest_kernel", "segmented x128, texels x16").set("gpu_ms_over_fastest", ratio);
            if let Some((lo, hi)) = interval {
                row.set("gpu_ms_over_fastest_lo", lo).set("gpu_ms_over_fastest_hi", hi);
            }
            summary_line(&row)
        };
        assert!(line("segmented x128, texels x16", 1.0, None).ends_with("; the fastest kernel here (lowest median)"));
        let slower = line("segmented x32, texels x4", 1.5, Some((1.25, 1.75)));
        let said = "; 1.50x the time of segmented x128, texels x16 (95 % CI 1.25-1.75, paired)";
        assert!(slower.ends_with(said), "{slower}");
        assert!(line("serial", 30.0, None).ends_with("; 30.00x the time of segmented x128, texels x16"));
        let close = line("segmented x64, texels x8", 1.05, Some((0.97, 1.12)));
        assert!(close.ends_with(" (95 % CI 0.97-1.12, paired: within noise)"), "{close}");
    }

    #[test]
    fn one_progress_step_per_data_set_and_size() {
        let plan = Table1Plan::paper(vec![8, 16], Interleaved::fixed(1, 1).unwrap(), Vec::new());
        let weights = step_weights(&plan);
        assert_eq!(weights.len(), 3 * 2);
        assert!(weights[1] > weights[0], "a larger image weighs more: {weights:?}");
    }
}
