//! Command-line arguments (clap derive).

use ash::vk::PresentModeKHR;
use clap::{Args, Parser, Subcommand};
use std::path::PathBuf;
use sweeplab::bench::experiments::table1::SegmentCount;
use sweeplab::scene::suggest::nearest;
use sweeplab::techniques::ipsvi::LineKernel;
use sweeplab::techniques::Technique;
use sweeplab::vk::swapchain::PRESENT_MODES;

/// `--technique` short help: the registry's names.
fn technique_names() -> String {
    Technique::named().map(|t| t.name()).collect::<Vec<_>>().join(" | ")
}

/// `--kernels`: an IPSVI line kernel by name.
fn line_kernel(name: &str) -> Result<LineKernel, String> {
    name.trim().parse()
}

/// `--present-mode` by name, with the nearest name for a typo.
fn present_mode(name: &str) -> Result<PresentModeKHR, String> {
    PRESENT_MODES.iter().find(|(n, _)| *n == name).map(|(_, m)| *m).ok_or_else(|| {
        let names = PRESENT_MODES.map(|(n, _)| n);
        let near = nearest(name, names).map(|n| format!(" (did you mean {n}?)")).unwrap_or_default();
        format!("{name:?}{near}; known: {}", names.join(", "))
    })
}

/// The technique of `render`, `compare` and `view` without `--technique`.
fn default_technique() -> String {
    Technique::DEFAULT.name().to_string()
}

/// Where a bench (or `report`) writes: the same two flags everywhere.
#[derive(Args, Debug, Clone)]
pub struct OutDirArgs {
    /// Output folder. Without it, each run writes a new folder under the
    /// command's own (e.g. bench-sync/2026-12-05_10-31-02); a folder that
    /// already holds files is refused, unless --force.
    #[arg(long, value_name = "DIR")]
    pub out_dir: Option<PathBuf>,
    /// Write into an --out-dir that holds files: what the previous bench run
    /// wrote there is replaced; files it did not write are kept.
    #[arg(long, requires = "out_dir")]
    pub force: bool,
}

/// `sweeplab --version`: the crate's version and the commit of the build (`build.rs`), as bench
/// headers write them, so that a report that records only the binary's answer names its build.
const VERSION: &str = concat!(env!("CARGO_PKG_VERSION"), " at ", env!("SWEEPLAB_GIT_COMMIT"));

#[derive(Parser, Debug)]
#[command(name = "sweeplab", version = VERSION, about = "Volume illumination with explicit Vulkan synchronization")]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// List Vulkan devices with API version, driver and timestamp support.
    Devices(DevicesArgs),
    /// Render a scene (the embedded default scene without --scene/--volume).
    Render(RenderArgs),
    /// Render a technique and the ground truth; print error and GPU time.
    Compare(CompareArgs),
    /// Interactive viewer: a window on a Vulkan swapchain, the technique's
    /// frames presented live (mouse: orbit, pan, zoom; S screenshot, P profile).
    View(ViewArgs),
    /// Parameter sweeps: error against GPU time, CSV/JSON/Markdown and plots.
    #[command(subcommand)]
    Bench(BenchCommand),
    /// Put `bench sync` results from several devices side by side: one table
    /// and one chart of per-boundary cost per strategy per device.
    Report(ReportArgs),
    /// Every technique table's keys: default, what each does, its range
    /// (`--set TABLE.KEY=VALUE` and scene files take them).
    Keys(KeysArgs),
}

#[derive(Subcommand, Debug)]
pub enum BenchCommand {
    /// IPSVI over line width x cache size x piecewise integration x early ray
    /// termination x mode (view samples under each write rule, light rays) x
    /// image size, each run compared with the GPU ground truth. Long at the
    /// defaults (450 configurations per size; the progress line shows the time left);
    /// --breakdown takes about 2.5 min at 128-512 on lavapipe with 2 cores.
    Ipsvi(BenchIpsviArgs),
    /// What a line boundary of the IPSVI sweep costs per sync strategy, each
    /// quantity apart with its 95 % interval from shuffled, paired rounds: (a)
    /// its fixed cost (empty workload), (b) what it costs the sweep per line
    /// (frames without per-line timestamps), (c) the per-line timestamps' own
    /// effect, and the calibration (chain workload: fixed cost + serialized
    /// fraction x chain latency); one Perfetto trace per strategy and
    /// workload. About 10 minutes on lavapipe at the defaults, a minute with --quick.
    Sync(BenchSyncArgs),
    /// The IPSVI paper's Table 1: frame rates over image size and line width for
    /// engine (CT Engine), aneurism (beside US Baby) and LIDC2 (anisotropic, beside
    /// the giraffe), next to the paper's, with the ratios compared. The
    /// progress line shows the time left.
    Table1(BenchTable1Args),
    /// The selective-light-updates paper's Table 1 and Figure 10 for the light
    /// volume: entire updates (sequential and coherence-based propagation),
    /// selective updates of one light (state change, on/off), scaling over 1-40
    /// lights, memory, and error against time. About 7 min on engine.vti on
    /// lavapipe with 2 cores.
    Lights(BenchLightsArgs),
    /// The stability table: every technique (IPSVI in both cache
    /// updates) on every stiff or extreme case, each cell within the
    /// technique's bound against the reference of its model, refused or
    /// warned by name, or FAILED; the convergence order of each technique over
    /// step 1..1/16 voxel; CSV/JSON/Markdown and a heat map PNG. Exit status 1
    /// if any cell failed. About 2 min on lavapipe with 2 cores.
    Stability(BenchStabilityArgs),
    /// Ambient occlusion from clustered histograms (the 2008 paper): sweeps r,
    /// bits, packed dimension, n_c and metric with preprocessing time per step,
    /// codebook error, image RMSE against the unclustered histograms and the
    /// ground truth, TF-change update and frame time against Blinn-Phong.
    /// About 2.5 min on the Cornell box on lavapipe with 2 cores (seconds with
    /// the preprocessing cached).
    Ao(BenchAoArgs),
}

#[derive(Args, Debug)]
pub struct BenchStabilityArgs {
    #[command(flatten)]
    pub gpu: GpuArgs,
    #[command(flatten)]
    pub out: OutDirArgs,
    /// Square image size of every cell (the CPU reference renders it too).
    #[arg(long, default_value_t = 16)]
    pub size: u32,
    /// Cases by short name, comma-separated; empty (the default): all. An
    /// unknown name lists them.
    #[arg(long, value_delimiter = ',')]
    pub cases: Vec<String>,
    /// Techniques, comma-separated; empty (the default): all.
    #[arg(long, value_delimiter = ',')]
    pub techniques: Vec<String>,
    /// Timed frames per cell after one untimed warm-up frame; the median GPU
    /// time is reported, with its 95 % interval from 6 frames on.
    #[arg(long, default_value_t = 1)]
    pub repeat: u32,
}

#[derive(Args, Debug)]
pub struct BenchAoArgs {
    /// Without --scene/--volume: the Cornell box (tests/scenes/cornell-box.toml). --size sets the
    /// image (default 256x256).
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub gpu: GpuArgs,
    #[command(flatten)]
    pub out: OutDirArgs,
    /// Sphere radii r (voxels). Comma-separated.
    #[arg(long, value_delimiter = ',', default_values_t = vec![8])]
    pub radii: Vec<u32>,
    /// Intensity bits b (2^b bins). Comma-separated.
    #[arg(long, value_delimiter = ',', default_values_t = vec![8])]
    pub bits: Vec<u32>,
    /// Packed histogram dimensions. Comma-separated.
    #[arg(long, value_delimiter = ',', default_values_t = vec![64])]
    pub packed_dims: Vec<u32>,
    /// Codebook sizes n_c (the paper's figure 6: 256, 512, 1024). Comma-separated.
    #[arg(long, value_delimiter = ',', default_values_t = vec![256, 512, 1024, 2048])]
    pub clusters: Vec<u32>,
    /// Metrics of the vector quantization: l2, l1, lmax. Comma-separated.
    #[arg(long, value_delimiter = ',', default_values_t = vec!["l2".to_string(), "l1".to_string(), "lmax".to_string()])]
    pub metrics: Vec<String>,
    /// Direction pairs of the ground truth per voxel.
    #[arg(long, default_value_t = 32)]
    pub reference_pairs: u32,
    /// Timed rounds after a warm-up round: every configuration's frame and
    /// update (and Blinn-Phong's frame) once per round, in shuffled order.
    /// 6 or more give 95 % intervals.
    #[arg(long, default_value_t = 6)]
    pub repeat: u32,
    #[command(flatten)]
    pub rounds: RoundsArgs,
}

#[derive(Args, Debug)]
pub struct BenchLightsArgs {
    /// --size sets the image of the error rows (default 256x256).
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub gpu: GpuArgs,
    #[command(flatten)]
    pub out: OutDirArgs,
    /// Data voxels per illumination voxel for the Table 1 rows (the paper's DR*1 and DR*1/4). Comma-separated.
    #[arg(long, value_delimiter = ',', default_values_t = vec![1, 4])]
    pub scales: Vec<u32>,
    /// Lights of the Table 1 rows (2..=16, taken in order from a fixed coloured set;
    /// the paper's Engine rows have 2 and 3). Comma-separated.
    #[arg(long, value_delimiter = ',', default_values_t = vec![2, 3])]
    pub light_counts: Vec<u32>,
    /// Light counts of the scaling test (the paper's Figure 10: 1-40 lights of one direction). Comma-separated.
    #[arg(long, value_delimiter = ',', default_values_t = vec![1, 2, 4, 8, 16, 24, 32, 40])]
    pub scaling_counts: Vec<u32>,
    /// Scale of the scaling test (sequential propagation at 40 lights is 80 passes).
    #[arg(long, default_value_t = 4)]
    pub scaling_scale: u32,
    /// Scales of the error-against-time rows (one full frame each, against the ground truth). Comma-separated.
    #[arg(long, value_delimiter = ',', default_values_t = vec![1, 2, 4])]
    pub error_scales: Vec<u32>,
    /// Incremental mode: passes per frame to converge with (at the scaling scale,
    /// with the most Table 1 lights, from an empty volume). Comma-separated.
    #[arg(long, value_delimiter = ',', default_values_t = vec![1, 2])]
    pub incremental_passes: Vec<u32>,
    /// Timed rounds after a warm-up round: per part, every configuration once a
    /// round, in a shuffled order. 6 or more give 95 % intervals.
    #[arg(long, default_value_t = 6)]
    pub repeat: u32,
    #[command(flatten)]
    pub rounds: RoundsArgs,
}

#[derive(Args, Debug)]
pub struct BenchTable1Args {
    #[command(flatten)]
    pub gpu: GpuArgs,
    #[command(flatten)]
    pub out: OutDirArgs,
    /// Square image sizes (the paper's: 64,128,256,512,1024). Comma-separated.
    #[arg(long, value_delimiter = ',', value_parser = sweeplab::bench::experiments::image_sizes::side_length, default_values_t = vec![64, 128, 256, 512, 1024])]
    pub sizes: Vec<u32>,
    /// Timed rounds per data set and size after one warm-up round, every line
    /// width once a round in a shuffled order; 6 or more give 95 % intervals.
    #[arg(long, default_value_t = 6)]
    pub repeat: u32,
    #[command(flatten)]
    pub rounds: RoundsArgs,
    /// Extra scene overrides applied to every data set.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Only these data sets (engine.vti, aneurism.vti, LIDC2.mha); default all three.
    #[arg(long, value_delimiter = ',')]
    pub data_sets: Vec<String>,
    /// IPSVI line kernels measured side by side (auto, serial, segmented);
    /// each row names the kernel as it ran.
    #[arg(long, value_delimiter = ',', default_value = "auto", value_parser = line_kernel)]
    pub kernels: Vec<LineKernel>,
    /// Segments per pixel the segmented kernel runs at, each beside the
    /// others (0: the device's choice), as S or S/T with T lanes per cache
    /// texel (default: an eighth of S), e.g. 32,128,128/8. Comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "0")]
    pub segments: Vec<SegmentCount>,
    /// Leave out the ground truth (IPSVI's model, rendered once per data set
    /// and size on the device) and the rows' RMSE against it: on a CPU device
    /// it costs minutes at 256 and above.
    #[arg(long)]
    pub no_errors: bool,
}

#[derive(Args, Debug)]
pub struct BenchSyncArgs {
    /// Without --size: 256x256.
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub gpu: GpuArgs,
    #[command(flatten)]
    pub out: OutDirArgs,
    /// Sync strategies compared with no barriers, comma-separated:
    /// barrier-global, barrier-image, events, secondary, submits.
    #[arg(long, value_delimiter = ',', default_values_t = ["barrier-global", "barrier-image", "events", "secondary", "submits"].map(String::from).to_vec())]
    pub strategies: Vec<String>,
    /// Lines per dispatch (1..=32), at least two: the per-boundary cost is the
    /// slope of frame time over the number of blocks. Comma-separated; default
    /// 1,2,4,8,16,32 (with --quick: 1,4,16,32).
    #[arg(long, value_delimiter = ',')]
    pub line_widths: Option<Vec<u32>>,
    /// What each line dispatch does: `sweep` (the scene's IPSVI frame),
    /// `empty` (shaders that return at once: dispatches and sync alone),
    /// `chain` (the calibration: per line a dependent chain of known length).
    /// Comma-separated; default all three (with --quick: empty).
    #[arg(long, value_delimiter = ',')]
    pub workloads: Option<Vec<String>>,
    /// Untimed rounds of every configuration first (shader compiles, caches).
    #[arg(long, default_value_t = 1)]
    pub warm_up: u32,
    /// Timed rounds, at least (6 or more: a 95 % interval of a median needs 6);
    /// more follow, up to --max-rounds, until the intervals are as narrow as
    /// --target-ci asks or the time is up. (Also --min-rounds.)
    #[arg(long, alias = "min-rounds", default_value_t = 6)]
    pub repeat: u32,
    /// Most timed rounds (the time budget usually ends them first).
    #[arg(long, default_value_t = 300)]
    pub max_rounds: u32,
    /// Stop once every sync cost's 95 % interval has a half-width of at most
    /// this fraction of the estimate ...
    #[arg(long, default_value_t = 0.25)]
    pub target_ci: f64,
    /// ... or at most this many microseconds.
    #[arg(long, default_value_t = 3.0)]
    pub target_ci_us: f64,
    /// Stop after the round that would end past this many minutes (never
    /// before --repeat rounds); default 10 (with --quick: 1.5).
    #[arg(long)]
    pub max_minutes: Option<f64>,
    /// Seed of the shuffled round orders (default: from the clock; recorded in sync.json).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Leave out the baseline's frames with a timestamp around every line
    /// dispatch (the timestamps' own effect) and the traced frames.
    #[arg(long)]
    pub no_line_timestamps: bool,
    /// About a minute on lavapipe: the empty workload (the sync primitives
    /// alone) at 64x64, line widths 1,4,16,32, as many rounds as fit in 1.5
    /// minutes. Presets only what is not given: --size, --workloads,
    /// --line-widths and --max-minutes given on the command line are used
    /// (and the run says so).
    #[arg(long)]
    pub quick: bool,
}

/// `sweeplab report`: bench results from different devices side by side.
#[derive(Args, Debug)]
pub struct ReportArgs {
    /// sync.json files written by `sweeplab bench sync` (one per device or run).
    #[arg(required = true, num_args = 1..)]
    pub inputs: Vec<PathBuf>,
    /// Where report.md, report.csv and the charts go.
    #[command(flatten)]
    pub out: OutDirArgs,
}

#[derive(Args, Debug)]
pub struct BenchIpsviArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub gpu: GpuArgs,
    #[command(flatten)]
    pub out: OutDirArgs,
    /// Lines per dispatch (1..=32). Comma-separated.
    #[arg(long, value_delimiter = ',', default_values_t = vec![1, 2, 4, 8, 16])]
    pub line_widths: Vec<u32>,
    /// Illumination cache texels per side (16..=4096). Comma-separated.
    #[arg(long, value_delimiter = ',', default_values_t = vec![64, 128, 256, 512, 1024])]
    pub cache_sizes: Vec<u32>,
    /// Square image sizes. Comma-separated.
    #[arg(long, value_delimiter = ',', value_parser = sweeplab::bench::experiments::image_sizes::side_length, default_values_t = vec![256, 512])]
    pub sizes: Vec<u32>,
    /// Timed rounds: per image size every configuration runs once a round, in a
    /// shuffled order, after a warm-up frame; the median GPU time is reported,
    /// with its 95 % interval and paired ratios from 6 rounds up.
    #[arg(long, default_value_t = 6)]
    pub repeat: u32,
    #[command(flatten)]
    pub rounds: RoundsArgs,
    /// With --max-rounds: stop after the round that, once more, would pass this many minutes of a measurement (never before --repeat).
    #[arg(long)]
    pub max_minutes: Option<f64>,
    /// Only the baseline settings and one factor varied at a time (no full grid).
    #[arg(long)]
    pub one_at_a_time: bool,
    /// Half-angle slicing runs beside IPSVI (slice spacing in voxels), compared
    /// with the ground truth of model (i). Comma-separated; the flag with no
    /// value leaves them out.
    #[arg(long, value_delimiter = ',', num_args = 0.., default_values_t = vec![1.0, 0.5, 0.25])]
    pub half_angle_slices: Vec<f32>,
    /// IPSVI line kernels measured (serial, segmented, auto: the device's).
    /// Comma-separated. With several, the grid runs with the device's and
    /// every mode at every cache size with the others; the breakdown runs
    /// every mode with each.
    #[arg(long, value_delimiter = ',', default_value = "serial,segmented", value_parser = line_kernel)]
    pub kernels: Vec<LineKernel>,
    /// Instead of the grid: the cost of one frame of the scene's settings, step
    /// by step (DVR as one dispatch; the same pixels ray-cast line by line in the
    /// sweep's order without and with the barriers; + cache reads; + piecewise
    /// integration; + cache writes), in both cache-update modes, at --sizes;
    /// and the whole frame at each of --line-widths (ipsvi_line_widths.*).
    /// The grid's own flags (--cache-sizes, --one-at-a-time,
    /// --half-angle-slices) do not apply, and are refused with it.
    #[arg(long, conflicts_with_all = ["cache_sizes", "one_at_a_time", "half_angle_slices"])]
    pub breakdown: bool,
}

#[derive(Args, Debug)]
pub struct KeysArgs {
    /// Only this table (e.g. ipsvi).
    pub table: Option<String>,
}

#[derive(Args, Debug)]
pub struct DevicesArgs {
    /// Print JSON instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// `view --preview`.
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum PreviewArg {
    Auto,
    On,
    Off,
}

/// What `--validate` checks.
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum ValidateMode {
    /// Validation and synchronization validation.
    Sync,
    /// Also best practices, with the NVIDIA and AMD vendor checks.
    BestPractices,
}

/// How a bench's configurations share the rounds beyond `--repeat`.
#[derive(Args, Debug, Clone)]
pub struct RoundsArgs {
    /// Go on past --repeat rounds, up to this many, until every configuration's
    /// 95 % interval is within --target-ci of its median (default: --repeat).
    #[arg(long)]
    pub max_rounds: Option<u32>,
    /// The relative half-width --max-rounds aims at.
    #[arg(long, default_value_t = 0.05)]
    pub target_ci: f64,
    /// Seed of the shuffled round orders (default: from the clock; recorded with the results).
    #[arg(long)]
    pub seed: Option<u64>,
}

/// Options every GPU command shares.
#[derive(Args, Debug, Clone)]
pub struct GpuArgs {
    /// Vulkan device: index or name substring (also SWEEPLAB_DEVICE).
    #[arg(long)]
    pub device: Option<String>,
    /// Khronos validation with synchronization validation; any message fails the
    /// run (also SWEEPLAB_VALIDATE=1). `--validate=best-practices` adds the
    /// best-practices checks with NVIDIA and AMD vendor checks, counted per
    /// message id (also SWEEPLAB_VALIDATE=best-practices).
    #[arg(long, num_args = 0..=1, require_equals = true, default_missing_value = "sync", value_enum)]
    pub validate: Option<ValidateMode>,
    /// Store the volume as r32 float (exact trilinear filtering on lavapipe,
    /// which filters 8-bit volumes with 8-bit weights).
    #[arg(long)]
    pub float_volume: bool,
}

#[derive(Args, Debug, Clone)]
pub struct SceneArgs {
    /// TOML scene file.
    #[arg(long, conflicts_with = "volume")]
    pub scene: Option<PathBuf>,
    /// Any volume file (.vti .mhd .mha .nrrd .nhdr .nii .nii.gz .vhdr) with default
    /// transfer function, camera and light.
    #[arg(long)]
    pub volume: Option<PathBuf>,
    /// Override a scene parameter, e.g. --set camera.azimuth=45 --set lights.0.intensity=3
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Image size, e.g. 512x512 (overrides render.width/height).
    // Hyphen values are taken so that `--size -64x64` gets a size message, not
    // "unexpected argument '-6'".
    #[arg(long, value_name = "WxH", allow_hyphen_values = true)]
    pub size: Option<String>,
}

#[derive(Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub gpu: GpuArgs,
    #[arg(long, default_value_t = default_technique(), help = technique_names(), long_help = Technique::help())]
    pub technique: String,
    /// Output PNG (8-bit sRGB of the linear image); the run prints where it wrote.
    #[arg(long, value_name = "FILE", default_value = "sweeplab.png")]
    pub out: PathBuf,
    /// Per-pass GPU profile as JSON.
    #[arg(long, value_name = "FILE")]
    pub profile_json: Option<PathBuf>,
    /// Chrome trace of the GPU scopes (opens in Perfetto).
    #[arg(long, value_name = "FILE")]
    pub trace: Option<PathBuf>,
    /// Per-dispatch timestamps, e.g. IPSVI's per-line row (the default; adds a
    /// flush per dispatch on lavapipe).
    #[arg(long, overrides_with = "no_detail")]
    pub detail: bool,
    /// Pass totals only, without per-dispatch timestamps.
    #[arg(long, overrides_with = "detail")]
    pub no_detail: bool,
}

#[derive(Args, Debug)]
pub struct CompareArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub gpu: GpuArgs,
    // Compared with the ground truth of the model it approximates (RenderTechnique::reference_model).
    #[arg(long, default_value_t = default_technique(), help = technique_names(), long_help = Technique::help())]
    pub technique: String,
    /// Ground truth on the gpu (brute-force shadow rays) or the cpu (f64).
    #[arg(long, default_value = "gpu", value_parser = ["gpu", "cpu"])]
    pub reference: String,
    /// Write the figures as JSON.
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Write the error heat map (with its colour scale) as PNG, and as SVG beside it.
    #[arg(long, value_name = "FILE")]
    pub heatmap: Option<PathBuf>,
    /// Write the technique's image.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Write the reference image.
    #[arg(long, value_name = "FILE")]
    pub reference_out: Option<PathBuf>,
    /// Keep the ground truth in DIR, and take it from there when this scene, model, size and device have one.
    #[arg(long, value_name = "DIR")]
    pub reference_cache: Option<PathBuf>,
}

#[derive(Args, Debug)]
pub struct ViewArgs {
    /// --size sets the window's first size.
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub gpu: GpuArgs,
    #[arg(long, default_value_t = default_technique(), help = technique_names(), long_help = Technique::help())]
    pub technique: String,
    /// Stop after N presented frames.
    #[arg(long, value_name = "N")]
    pub frames: Option<u64>,
    /// Write the last presented frame (8-bit sRGB, as the swapchain holds it) as PNG; needs --frames.
    #[arg(long, value_name = "FILE")]
    pub screenshot: Option<PathBuf>,
    /// fifo (default, always available), mailbox, immediate, fifo-relaxed.
    #[arg(long, default_value = "fifo", value_parser = present_mode)]
    pub present_mode: PresentModeKHR,
    /// Steps by frame: `3 set lights.0.intensity=2`, `5 resize 96x64`, `7 key S`.
    #[arg(long, value_name = "FILE")]
    pub script: Option<PathBuf>,
    /// No control panel: the frame alone (as `render` would write it).
    #[arg(long)]
    pub no_ui: bool,
    /// Start with the control panel hidden (H or Tab shows and hides it).
    #[arg(long)]
    pub hide_panel: bool,
    /// While the camera, a light or a setting is dragged, render a reduced
    /// resolution preview where a full frame is slow (over 0.25 s: IPSVI on
    /// lavapipe), full quality once the input is still. auto: on, except in
    /// scripted runs (--frames), which render every frame at full quality.
    #[arg(long, value_enum, default_value = "auto")]
    pub preview: PreviewArg,
    /// Leave out the barrier between the technique's frame and the present
    /// pass: a race, only for the test that proves validation reports it.
    #[arg(long, hide = true)]
    pub racy_no_handoff_barrier: bool,
    /// Per-frame log as JSON: passes, GPU and frame times, light volume decisions.
    #[arg(long, value_name = "FILE")]
    pub log_json: Option<PathBuf>,
}
