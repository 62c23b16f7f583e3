//! The cases of the stability suite, one definition for the CI test
//! (tests/stability.rs, the cases marked `ci`) and `sweeplab bench stability`
//! (all of them): a scene file's text and overrides each, the techniques that
//! must refuse it (and a word their refusal names), and the warning the scene
//! must come with.

use std::path::{Path, PathBuf};

use crate::scene::warnings::SceneWarning;

/// The volume side of every case built on the noise volume.
pub const VOLUME_SIZE: u32 = 16;

pub struct StabilityCase {
    /// Short name for `--cases`.
    pub id: &'static str,
    pub name: &'static str,
    /// Scene file text (its files in the folder given to [`stability_cases`]).
    pub toml: String,
    /// `--set` overrides on top of it.
    pub set: Vec<String>,
    /// Techniques that must refuse the case, and a word the refusal contains.
    pub refused: &'static [(&'static str, &'static str)],
    /// The warning the scene must come with; `None`: it must come with none.
    pub warns: Option<fn(&SceneWarning) -> bool>,
    /// Techniques (a name, or a column's label such as "ipsvi (view-samples)")
    /// that must warn they render the case beyond their bound, and a word the
    /// warning contains (`RenderTechnique::warnings`); the others must not warn.
    pub technique_warns: &'static [(&'static str, &'static str)],
    /// In the CI part (tests/stability.rs); the others only in the bench.
    pub ci: bool,
}

impl StabilityCase {
    fn new(id: &'static str, name: &'static str, toml: String) -> StabilityCase {
        StabilityCase { id, name, toml, set: Vec::new(), refused: &[], warns: None, technique_warns: &[], ci: true }
    }

    fn set(mut self, overrides: &[&str]) -> StabilityCase {
        self.set = overrides.iter().map(|s| s.to_string()).collect();
        self
    }

    fn refused(mut self, by: &'static [(&'static str, &'static str)]) -> StabilityCase {
        self.refused = by;
        self
    }

    fn warns(mut self, warning: fn(&SceneWarning) -> bool) -> StabilityCase {
        self.warns = Some(warning);
        self
    }

    fn technique_warns(mut self, by: &'static [(&'static str, &'static str)]) -> StabilityCase {
        self.technique_warns = by;
        self
    }

    fn bench_only(mut self) -> StabilityCase {
        self.ci = false;
        self
    }
}

/// A scene of `volume` (its `[volume]` and `[transfer]` tables) at `size` x
/// `size`, reference steps 0.25, an orbit camera unless `extra` places it, and
/// `extra` (lights, camera). Samples at the midpoints of their steps (no
/// jitter) and the orbit at the distance the bounds were measured at: the
/// table compares each technique with its model at fixed sample positions,
/// and the convergence study measures the midpoint rule's order.
fn scene_text(size: u32, volume: &str, extra: &str) -> String {
    let camera =
        if extra.contains("[camera]") { "" } else { "[camera]\nazimuth = 30.0\nelevation = 20.0\ndistance = 3.5137\n" };
    format!(
        "{volume}\n[render]\nwidth = {size}\nheight = {size}\njitter = false\n[reference]\nstep = 0.25\n\
         shadow_step = 0.25\n{camera}{extra}"
    )
}

const NOISE: &str = "[volume]\nsynthetic = \"noise\"\nsize = 16\n[transfer]\npreset = \"grayscale-ramp\"";
const LIGHT: &str = "[[lights]]\ntype = \"directional\"\ndirection = [-1.0, -1.0, -0.5]\nintensity = 2.0\n";
/// A camera on +z looking at the centre: the view travels along -z.
const CAMERA_ON_Z: &str = "[camera]\neye = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\nup = [0.0, 1.0, 0.0]\n";

fn noise_with_tf(points: &str) -> String {
    format!("[volume]\nsynthetic = \"noise\"\nsize = 16\n[transfer]\npoints = {points}")
}

fn directional(direction: &str) -> String {
    format!("[[lights]]\ntype = \"directional\"\ndirection = {direction}\nintensity = 2.0\n")
}

fn point(position: &str) -> String {
    format!("[[lights]]\ntype = \"point\"\nposition = {position}\nintensity = 2.0\n")
}

/// A raw little-endian NRRD of `values` (float, or uchar when `bytes`).
fn write_nrrd(dir: &Path, name: &str, dims: [u32; 3], spacing: [f32; 3], data: NrrdData) -> PathBuf {
    let kind = match data {
        NrrdData::Float(_) => "float",
        NrrdData::Uchar(_) => "uchar",
    };
    let mut bytes = format!(
        "NRRD0004\ntype: {kind}\ndimension: 3\nsizes: {} {} {}\nspacings: {} {} {}\nencoding: raw\nendian: little\n\n",
        dims[0], dims[1], dims[2], spacing[0], spacing[1], spacing[2]
    )
    .into_bytes();
    match data {
        NrrdData::Float(v) => v.iter().for_each(|x| bytes.extend_from_slice(&x.to_le_bytes())),
        NrrdData::Uchar(v) => bytes.extend_from_slice(&v),
    }
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap_or_else(|e| panic!("writing {}: {e}", path.display()));
    path
}

enum NrrdData {
    Float(Vec<f32>),
    Uchar(Vec<u8>),
}

/// A smooth blob over `dims` (1 at the centre), as 8-bit values.
fn blob(dims: [u32; 3]) -> Vec<u8> {
    let n = dims.iter().product::<u32>();
    (0..n)
        .map(|i| {
            let (x, y, z) = (i % dims[0], (i / dims[0]) % dims[1], i / (dims[0] * dims[1]));
            let r2: f32 = [x, y, z]
                .iter()
                .zip(dims)
                .map(|(&c, d)| {
                    let u = (c as f32 + 0.5) / d as f32 - 0.5;
                    4.0 * u * u
                })
                .sum();
            (255.0 * (-2.0 * r2).exp()) as u8
        })
        .collect()
}

/// Every case, with its files written to `dir`; images `size` x `size`.
pub fn stability_cases(dir: &Path, size: u32) -> Vec<StabilityCase> {
    // A smooth blob with NaN and Inf voxels sprinkled in.
    let nan_blob: Vec<f32> = (0..4096)
        .map(|i| {
            let (x, y, z) = ((i % 16) as f32 - 7.5, ((i / 16) % 16) as f32 - 7.5, (i / 256) as f32 - 7.5);
            match i % 97 {
                0 => f32::NAN,
                1 => f32::INFINITY,
                _ => (-(x * x + y * y + z * z) / 20.0).exp(),
            }
        })
        .collect();
    let cube = [16, 16, 16];
    let nan = write_nrrd(dir, "nan.nrrd", cube, [1.0; 3], NrrdData::Float(nan_blob));
    let constant = write_nrrd(dir, "constant.nrrd", cube, [1.0; 3], NrrdData::Float(vec![3.0; 4096]));
    let degenerate = |name: &str, dims: [u32; 3], spacing: [f32; 3]| {
        write_nrrd(dir, name, dims, spacing, NrrdData::Uchar(blob(dims)))
    };
    let one_voxel = write_nrrd(dir, "1x1x1.nrrd", [1, 1, 1], [1.0; 3], NrrdData::Uchar(vec![200]));
    let column = degenerate("1x1x64.nrrd", [1, 1, 64], [1.0; 3]);
    let rod = degenerate("4096x1x1.nrrd", [4096, 1, 1], [1.0; 3]);
    let flat = degenerate("aniso-1000.nrrd", [16, 16, 4], [1.0, 1.0, 1000.0]);
    let auto = |p: &Path| format!("[volume]\nfile = {:?}\n[transfer]\nauto = true", p.to_string_lossy());
    let ramp =
        |p: &Path| format!("[volume]\nfile = {:?}\n[transfer]\npreset = \"grayscale-ramp\"", p.to_string_lossy());
    let text = |volume: &str, extra: &str| scene_text(size, volume, extra);
    let light = |intensity: &str| LIGHT.replace("intensity = 2.0", &format!("intensity = {intensity}"));
    vec![
        StabilityCase::new("baseline", "baseline", text(NOISE, LIGHT)),
        // Steps.
        StabilityCase::new("step-4", "step 4 voxels", text(NOISE, LIGHT))
            .set(&["render.step=4", "reference.step=4"])
            .technique_warns(&[("half-angle", "slices")]),
        StabilityCase::new("step-1/64", "step 1/64 voxel", text(NOISE, LIGHT))
            .set(&["render.step=0.015625", "reference.step=0.015625"])
            .bench_only(),
        StabilityCase::new("step-2e-4", "step 2e-4 (past the loop cap)", text(NOISE, LIGHT))
            .set(&["render.step=2e-4"])
            .refused(&[("ipsvi", "render.step"), ("half-angle", "render.step")]),
        // Stiff extinction: opacity 0.999 .. 1 per voxel (sigma 6.9 .. 13.8,
        // the transfer function's cap), at the largest step too. The reference
        // marches at the techniques' view step: light that falls within a
        // fraction of a voxel changes within a view step, and a reference at
        // another step is no nearer the limit (at 32x32 the reference at 0.5
        // and 0.25 voxel is 10.5 and 13.4 dB from itself at 1/64 on all-opaque,
        // 15.7 and 20.0 dB on stiff), so equal steps measure the light
        // transport a technique approximates; the convergence check measures
        // the step.
        StabilityCase::new("stiff", "stiff: opacity 0.999..1", text(&noise_with_tf(STIFF), LIGHT))
            .set(&[STIFF_REFERENCE_STEP])
            .technique_warns(LIGHT_GRIDS),
        StabilityCase::new("stiff-step-4", "stiff, step 4 (sigma x step 55)", text(&noise_with_tf(STIFF), LIGHT))
            .set(&["render.step=4", "reference.step=4"])
            .technique_warns(LIGHT_GRIDS),
        StabilityCase::new("opaque", "all-opaque TF", text(&noise_with_tf(OPAQUE), LIGHT))
            .set(&[STIFF_REFERENCE_STEP])
            .technique_warns(LIGHT_GRIDS),
        StabilityCase::new("alpha-0.5", "TF alpha 0.5", text(&noise_with_tf(HALF), LIGHT)).technique_warns(LIGHT_GRIDS),
        // Transfer functions with zero-width features.
        StabilityCase::new("tf-step", "TF step (two points at 0.5)", text(&noise_with_tf(TF_STEP), LIGHT))
            .technique_warns(LIGHT_GRIDS),
        StabilityCase::new("tf-needle", "TF peak narrower than the LUT", text(&noise_with_tf(TF_NEEDLE), LIGHT))
            .warns(|w| matches!(w, SceneWarning::TransferPeakMissed { index: 2, .. }))
            .technique_warns(LIGHT_GRIDS),
        StabilityCase::new("transparent", "all-transparent TF", text(&noise_with_tf(TRANSPARENT), LIGHT))
            .warns(|w| matches!(w, SceneWarning::AllTransparent { .. })),
        // Light intensity.
        StabilityCase::new("light-1e-6", "light 1e-6", text(NOISE, &light("1e-6"))),
        StabilityCase::new("light-1e6", "light 1e6", text(NOISE, &light("1e6"))),
        StabilityCase::new(
            "lights-1e-3-1e3",
            "lights 1e-3 and 1e3",
            text(NOISE, &format!("{}{}", light("1e-3"), point("[1.5, 0.5, 0.0]").replace("2.0\n", "1e3\n"))),
        )
        .refused(&[("half-angle", "one light")]),
        // Light placement.
        StabilityCase::new("far-1e3", "point light at 1e3", text(NOISE, &point("[0.0, 1e3, 1e3]"))),
        StabilityCase::new("far-1e8", "point light at 1e8", text(NOISE, &point("[0.0, 1e8, 1e8]"))),
        StabilityCase::new("far-1e20", "point light at 1e20", text(NOISE, &point("[1e20, 0.0, 0.0]"))),
        StabilityCase::new(
            "grazing",
            "light grazing a face (1e-4 rad)",
            text(NOISE, &directional("[-1.0, -1e-4, 0.0]")),
        ),
        StabilityCase::new(
            "light-along-view",
            "light along the view",
            text(NOISE, &format!("{CAMERA_ON_Z}{}", directional("[0.0, 0.0, -1.0]"))),
        ),
        StabilityCase::new(
            "light-against-view",
            "light against the view",
            text(NOISE, &format!("{CAMERA_ON_Z}{}", directional("[0.0, 0.0, 1.0]"))),
        ),
        StabilityCase::new("light-inside", "point light inside the volume", text(NOISE, &point("[0.1, 0.05, 0.0]")))
            .refused(&[("half-angle", "outside the volume")]),
        StabilityCase::new(
            "camera-inside",
            "camera inside the volume",
            text(NOISE, &format!("[camera]\neye = [0.05, 0.1, 0.2]\ntarget = [0.0, 0.0, -1.0]\n{LIGHT}")),
        )
        .technique_warns(&[("ipsvi (view-samples)", "inside the volume"), ("half-angle", "inside the volume")]),
        // Degenerate and anisotropic volumes.
        StabilityCase::new("1x1x1", "1x1x1 volume", text(&ramp(&one_voxel), LIGHT))
            .technique_warns(&[("half-angle", "slices")]),
        StabilityCase::new("1x1x64", "1x1x64 volume", text(&ramp(&column), LIGHT)),
        StabilityCase::new("4096x1x1", "4096x1x1 volume", text(&ramp(&rod), LIGHT)).bench_only(),
        StabilityCase::new("spacing-1000", "spacing 1:1:1000", text(&ramp(&flat), LIGHT)),
        StabilityCase::new("nan-voxels", "NaN/Inf voxels", text(&auto(&nan), LIGHT))
            // +inf voxels on the faces read as 1: dense spikes, too few (1 %)
            // for a cut medium, and the cells stay within their bounds.
            .warns(|w| matches!(w, SceneWarning::NonFiniteVoxels { .. })),
        StabilityCase::new("constant", "constant volume, automatic TF", text(&auto(&constant), LIGHT))
            .warns(|w| matches!(w, SceneWarning::ConstantVolume { .. })),
    ]
}

/// The techniques that hold light on a grid, which warn of a stiff medium
/// (`render::light_grid_limits`).
/// The stiff cases' reference step: the techniques' view step (`render.step`'s default).
const STIFF_REFERENCE_STEP: &str = "reference.step=0.5";

const LIGHT_GRIDS: &[(&str, &str)] =
    &[("ipsvi", "optical depth"), ("half-angle", "optical depth"), ("lightvolume", "optical depth")];

const STIFF: &str = "[[0.0, 0.2, 0.3, 0.9, 0.999], [1.0, 0.9, 0.8, 0.7, 1.0]]";
const OPAQUE: &str = "[[0.0, 1, 1, 1, 1], [1.0, 1, 1, 1, 1]]";
const HALF: &str = "[[0.0, 1, 1, 1, 0.5], [1.0, 1, 1, 1, 0.5]]";
const TRANSPARENT: &str = "[[0.0, 1, 1, 1, 0], [1.0, 1, 1, 1, 0]]";
const TF_STEP: &str =
    "[[0.0, 0.9, 0.6, 0.3, 0.0], [0.5, 0.9, 0.6, 0.3, 0.0], [0.5, 0.9, 0.8, 0.7, 0.6], [1.0, 0.9, 0.8, 0.7, 0.6]]";
/// An opaque spike at 0.5996 on an alpha 0.3 floor, 8e-4 wide: between two
/// of the lookup table's 1024 texel centres (0.59912 and 0.60010), so the
/// baked table never sees it.
const TF_NEEDLE: &str =
    "[[0.0, 1, 1, 1, 0.3], [0.5992, 1, 1, 1, 0.3], [0.5996, 1, 1, 1, 1.0], [0.6, 1, 1, 1, 0.3], [1.0, 1, 1, 1, 0.3]]";
