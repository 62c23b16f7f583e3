//! IPSVI parameters from the scene file's `[ipsvi]` table (or `--set ipsvi.key=value`),
//! read when the scene is read ([`crate::scene::settings_table`]).

use super::cache_plane::{auto_cache_size, texel_pixels};
use super::cache_update::{CacheUpdate, CacheWrite, WritePass, WriteRule, WriteValue};
use super::line_kernel::{segmented_refusal, LineKernel, DEFAULT_ROUNDS};
use super::read_fronts::ReadFronts;
use super::sync_strategy::SyncStrategy;
use crate::scene::settings_controls::check_declared_ranges;
use crate::scene::settings_table::{from_name, SettingsError, SettingsTable};
use crate::scene::Scene;
use serde::Deserialize;

/// The widest line block `line_width` allows (checked here, clamped by the
/// sweep plan, offered by the viewer).
pub const MAX_LINE_WIDTH: u32 = 32;

/// The file's key names are those of the fields unless renamed; defaults below.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct IpsviSettings {
    /// Lines per dispatch, 1..=[`MAX_LINE_WIDTH`]; the first block of a sweep is always one line.
    pub line_width: u32,
    /// The cache is cache_size x cache_size texels; 0 (default): sized to the
    /// image ([`super::cache_plane::auto_cache_size`]), resolved by
    /// [`IpsviSettings::sized_for`].
    pub cache_size: u32,
    /// Piecewise integration from each sample toward the cache front (section 4.4).
    pub piecewise: bool,
    /// Piecewise integration: the march back to the cache from the blended
    /// depth of the four texels read (the paper's) or per group of them on
    /// one cache plane; `auto` (default): per texel on texels finer than a
    /// pixel ([`super::read_fronts::PER_TEXEL_BELOW_PX`]).
    #[serde(deserialize_with = "from_name")]
    pub read_fronts: ReadFronts,
    /// When view rays stop (section 5.1).
    pub early_termination: EarlyTermination,
    /// Share of light scattered in the forward cone (equation 2's albedo), 0..=1.
    pub albedo: f32,
    /// Half-angle of the forward scattering cone, degrees.
    #[serde(rename = "cone_angle")]
    pub cone_angle_deg: f32,
    /// Width in pixels over which the four zones of a point light are blended.
    #[serde(rename = "zone_blend")]
    pub zone_blend_px: f32,
    /// Step along light rays (cache updates and piecewise integration), voxels.
    #[serde(rename = "light_step")]
    pub light_step_voxels: f32,
    /// Full-resolution pixels per pre-pass pixel, per axis (exit-points only).
    pub ert_scale: u32,
    /// Who feeds the cache: the view samples (the paper) or each texel's light ray.
    #[serde(deserialize_with = "from_name")]
    pub cache_update: CacheUpdate,
    /// view-samples only: which of the samples ending in one texel is stored.
    #[serde(deserialize_with = "from_name")]
    pub cache_write: CacheWrite,
    /// view-samples with piecewise integration: what a write stores, the light
    /// on the texel's own ray (default) or the sample's own light (the paper's).
    #[serde(deserialize_with = "from_name")]
    pub write_value: WriteValue,
    /// view-samples: which samples take part in the runs that write the cache,
    /// those with non-zero opacity or every sample (the paper's).
    #[serde(deserialize_with = "from_name")]
    pub write_rule: WriteRule,
    /// view-samples with texel-ray writes: a run whose samples were all empty
    /// (only with `write_rule = "every-sample"`) stores its texel's light
    /// unchanged at the new depth, without marching the texel's own ray there.
    /// Cheaper; drops what medium that ray crosses over about one line.
    pub empty_runs_move_depth: bool,
    /// view-samples with texel-ray writes: the writing sample stores (the
    /// paper's placement) or one invocation per texel of the block's region
    /// stores the texels the block's runs end in (found by the claim march);
    /// the same image bit for bit (`tests/ipsvi_view_samples.rs`). `auto`
    /// (default): the texel pass wherever the writes allow it.
    #[serde(deserialize_with = "from_name")]
    pub write_pass: WritePass,
    /// Each ping-pong pair (history: value and front; samples: value and
    /// stamp | depth) as one rgba32ui image, the value as four halves beside
    /// its code: one store and one load per texel instead of two. The same
    /// image bit for bit (`tests/ipsvi_view_samples.rs`).
    pub packed_store: bool,
    /// Fit the cache, and clip the light rays, to the box of the volume's cells
    /// the transfer function can make visible (`lit_box.rs`), not the whole
    /// volume box: the medium outside it is exactly empty, so the light is the
    /// same, the texels smaller and the marches to a ray's box entry shorter.
    pub fit_to_visible: bool,
    /// Which kernel marches a block's pixels: `serial` (one invocation per
    /// pixel, its whole view ray), `segmented` (`segments` invocations per
    /// pixel, one depth segment each, combined by subgroup shuffles; the
    /// same dispatch and barrier per line block), `auto` (default): serial
    /// on a CPU device, segmented on a GPU where the modes allow it.
    #[serde(deserialize_with = "from_name")]
    pub line_kernel: LineKernel,
    /// Segmented kernel: invocations per pixel, a power of two up to 128; more
    /// than the device's smallest subgroup makes a workgroup of one pixel's
    /// segments, combined across its subgroups through shared memory; 0
    /// (default): the device's choice (32 on a GPU, 8 on a CPU device, never
    /// more than the smallest subgroup).
    pub segments: u32,
    /// Segmented kernel: invocations per cache texel, its marches toward the
    /// light (from where it was last written) split over them; a power of two
    /// up to `segments` and the smallest subgroup; 0 (default): an eighth of
    /// the segments, 1 to 8.
    pub texel_segments: u32,
    /// Segmented kernel: a ray's samples up to its stop are dealt to its
    /// segments in this many rounds of consecutive stretches, so that each
    /// invocation's share spreads along the ray (a dense stretch, whose
    /// samples march far toward the light, is shared out); the rounds'
    /// composites combine in depth order.
    pub segment_rounds: u32,
    /// How consecutive line blocks are synchronized (`racy` only for cost studies).
    #[serde(deserialize_with = "from_name")]
    pub sync: SyncStrategy,
    /// Step k of every independent sweep (the zones of a point or spot light,
    /// the sweeps of several lights) as one dispatch and one line barrier,
    /// each sweep with its own cache and colour accumulation (`merged_steps.rs`);
    /// false: the sweeps one after the other (what the sync study measures).
    pub merge_sweeps: bool,
}

/// When the view rays of the main pass stop.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(try_from = "EarlyTerminationValue")]
pub enum EarlyTermination {
    /// March every ray to its exit.
    Off,
    /// Stop once the transmittance is below 1e-4. With `cache_update =
    /// "light-rays"` exact (view rays never feed the cache); with
    /// "view-samples" what lies behind the stop never reaches the cache (figure 5).
    Plain,
    /// The paper's section 5.1: a low-resolution pre-pass (first-opaque and
    /// last-structure distances) and an exit-point sweep toward the light give
    /// l_max; a ray stops once it is opaque *and* past l_max.
    ExitPoints,
}

impl EarlyTermination {
    pub fn name(self) -> &'static str {
        match self {
            EarlyTermination::Off => "off",
            EarlyTermination::Plain => "plain",
            EarlyTermination::ExitPoints => "exit-points",
        }
    }
}

impl Default for IpsviSettings {
    fn default() -> Self {
        IpsviSettings {
            line_width: 1,
            cache_size: 0,
            piecewise: true,
            read_fronts: ReadFronts::Auto,
            early_termination: EarlyTermination::Plain,
            albedo: 0.0,
            cone_angle_deg: 15.0,
            zone_blend_px: 2.0,
            light_step_voxels: 0.5,
            ert_scale: 4,
            cache_update: CacheUpdate::ViewSamples,
            cache_write: CacheWrite::Farthest,
            write_value: WriteValue::TexelRay,
            write_rule: WriteRule::EverySample,
            empty_runs_move_depth: false,
            write_pass: WritePass::Auto,
            packed_store: false,
            fit_to_visible: false,
            line_kernel: LineKernel::Auto,
            segments: 0,
            texel_segments: 0,
            segment_rounds: DEFAULT_ROUNDS,
            sync: SyncStrategy::BarrierGlobal,
            merge_sweeps: false,
        }
    }
}

impl IpsviSettings {
    /// Whether the frame records the claim pass of `cache_write = "farthest"`
    /// / `"nearest"` (one writer per texel). Left out where every writer of a
    /// texel in a block stores the same value, so the winner cannot matter:
    /// one line per block (every block lies in one sweep plane), texel-ray
    /// writes with piecewise integration (the light is marched along the
    /// texel's own ray, from its stored depth to that plane, whichever sample
    /// writes), and every run marching (`empty_runs_move_depth` keeps the
    /// writing sample's own point). Saves the claim pass's medium march and
    /// atomics and the keys buffer; `tests/ipsvi_view_samples.rs` checks the
    /// image is the same bit for bit.
    /// With `write_pass = "texel"` the pass is always recorded: its keys name
    /// the texels each block writes.
    pub fn records_claims(&self) -> bool {
        self.claims_recorded(false)
    }

    /// [`records_claims`](Self::records_claims), or with
    /// `keep_redundant_claims` (a study's, [`super::study::IpsviStudy`]) also
    /// where the pass cannot change the image.
    pub fn claims_recorded(&self, keep_redundant_claims: bool) -> bool {
        let claims = self.cache_update == CacheUpdate::ViewSamples && self.cache_write.claims();
        let same_value_from_every_writer = self.line_width == 1
            && self.write_value == WriteValue::TexelRay
            && self.piecewise
            && !self.empty_runs_move_depth;
        claims && (keep_redundant_claims || self.texel_pass() || !same_value_from_every_writer)
    }

    /// These settings with `cache_size = 0` resolved for a `width` x `height`
    /// image of `scene` ([`super::cache_plane::auto_cache_size`]); a size set
    /// in the scene is kept.
    pub fn sized_for(&self, scene: &Scene, width: u32, height: u32) -> IpsviSettings {
        match self.cache_size {
            0 => IpsviSettings { cache_size: auto_cache_size(scene, self, width, height), ..self.clone() },
            _ => self.clone(),
        }
    }

    /// Whether piecewise integration marches from each texel's own depth
    /// (`read_fronts` resolved against the cache texel's width in a `width` x
    /// `height` image of `scene`).
    pub fn per_texel_fronts(&self, scene: &Scene, width: u32, height: u32) -> bool {
        self.piecewise && self.read_fronts.per_texel(|| texel_pixels(scene, self, width, height))
    }

    /// Whether view-sample writes are computed and stored per texel:
    /// `write_pass = "texel"` (`validate` refuses it where it cannot apply),
    /// or `"auto"` where it can.
    pub fn texel_pass(&self) -> bool {
        let view_samples = self.cache_update == CacheUpdate::ViewSamples;
        match self.write_pass {
            WritePass::Texel => view_samples,
            WritePass::Sample => false,
            WritePass::Auto => self.texel_pass_allowed(),
        }
    }

    /// Whether the writes allow the texel pass (view samples; `auto` takes it).
    pub fn texel_pass_allowed(&self) -> bool {
        self.cache_update == CacheUpdate::ViewSamples && self.texel_pass_needs().is_none()
    }

    /// The pass a frame runs (`auto` resolved); None for light rays, which have no view-sample writes.
    pub fn write_pass_run(&self) -> Option<WritePass> {
        match self.cache_update {
            CacheUpdate::ViewSamples if self.texel_pass() => Some(WritePass::Texel),
            CacheUpdate::ViewSamples => Some(WritePass::Sample),
            CacheUpdate::LightRays => None,
        }
    }

    /// The first setting that keeps the texel pass from computing a write
    /// without its sample, as `table.key = value` to ask for; None if none does.
    pub(super) fn texel_pass_needs(&self) -> Option<&'static str> {
        let needs = [
            (self.write_value == WriteValue::TexelRay, "write_value = \"texel-ray\""),
            (self.piecewise, "piecewise = true"),
            (!self.empty_runs_move_depth, "empty_runs_move_depth = false"),
            (self.cache_write.claims(), "cache_write = \"farthest\" or \"nearest\""),
        ];
        needs.iter().find(|(ok, _)| !ok).map(|(_, need)| *need)
    }
}

impl SettingsTable for IpsviSettings {
    const TABLE: &'static str = "ipsvi";

    fn validate(&self) -> Result<(), SettingsError> {
        let t = Self::TABLE;
        check_declared_ranges(self)?;
        for (name, value) in [("segments", self.segments), ("texel_segments", self.texel_segments)] {
            if value != 0 && self.line_kernel != LineKernel::Segmented {
                return Err(SettingsError::Technique(format!(
                    "{t}.{name} = {value} needs {t}.line_kernel = \"segmented\" (it is \"{}\")",
                    self.line_kernel.name()
                )));
            }
        }
        if self.line_kernel == LineKernel::Segmented {
            if let Some(why) = segmented_refusal(self) {
                return Err(SettingsError::Technique(why));
            }
        }
        if self.albedo > 0.0 && self.cache_update == CacheUpdate::ViewSamples {
            return Err(SettingsError::Technique(format!(
                "{t}.albedo = {} needs {t}.cache_update = \"light-rays\": forward-cone scattering blends \
                 neighbouring light rays, which view samples do not advance",
                self.albedo
            )));
        }
        if self.write_pass == WritePass::Texel && self.cache_update == CacheUpdate::ViewSamples {
            // A texel's write is then computed without its writing sample.
            if let Some(need) = self.texel_pass_needs() {
                return Err(SettingsError::Technique(format!(
                    "{t}.write_pass = \"texel\" needs {t}.{need}: a texel's write is computed from its own \
                     state and its writer's line plane, named by the claim keys, with no sample's light"
                )));
            }
        }
        Ok(())
    }
}

/// `early_termination` as written: `true` / `false` (plain / off) or a name.
#[derive(Deserialize)]
#[serde(untagged)]
enum EarlyTerminationValue {
    Flag(bool),
    Name(String),
}

impl TryFrom<EarlyTerminationValue> for EarlyTermination {
    type Error = String;
    fn try_from(value: EarlyTerminationValue) -> Result<Self, String> {
        match value {
            EarlyTerminationValue::Flag(true) => Ok(EarlyTermination::Plain),
            EarlyTerminationValue::Flag(false) => Ok(EarlyTermination::Off),
            EarlyTerminationValue::Name(name) => {
                [EarlyTermination::Off, EarlyTermination::Plain, EarlyTermination::ExitPoints]
                    .into_iter()
                    .find(|e| e.name() == name)
                    .ok_or_else(|| format!("is {name:?}, not \"off\", \"plain\", \"exit-points\", true or false"))
            }
        }
    }
}
