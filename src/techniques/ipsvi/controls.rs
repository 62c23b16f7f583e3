//! The [ipsvi] keys declared once: doc, kind, range and value of each, from which
//! the viewer's panel and the range checks are built (`crate::scene::settings_controls`).

use super::cache_plane::MAX_CACHE_SIZE;
use super::cache_update::{CacheUpdate, CacheWrite, WritePass, WriteRule, WriteValue};
use super::line_kernel::LineKernel;
use super::read_fronts::ReadFronts;
use super::settings::{EarlyTermination, IpsviSettings, MAX_LINE_WIDTH};
use super::sync_strategy::SyncStrategy;
use crate::scene::settings_controls::{Current, DeclaredSettings, Key, Kind};

impl DeclaredSettings for IpsviSettings {
    fn keys() -> Vec<Key<Self>> {
        use Current::{Bool, Name, Number};
        use Kind::{Choice, Numbers, Real, Toggle, Whole, WholeOrAuto};
        let control = Key::<Self>::new;
        let names = |all: &[&'static str]| all.to_vec();
        vec![
            control("line_width", "lines per dispatch (and per barrier)", Whole { lo: 1, hi: MAX_LINE_WIDTH }, |s| {
                Number(s.line_width as f64)
            }),
            control(
                "cache_size",
                "cache texels per side; 0: 256, more where a texel is wider than 1.5 px (render prints the width)",
                WholeOrAuto { lo: 16, hi: MAX_CACHE_SIZE },
                |s| Number(s.cache_size as f64),
            ),
            control(
                "piecewise",
                "piecewise integration: each sample's short march from the cache's front to the sample",
                Toggle,
                |s| Bool(s.piecewise),
            ),
            control(
                "read_fronts",
                "piecewise: how a read's four texels are carried; auto: per-texel under 1 px texels, else blended",
                Choice(names(&ReadFronts::ALL.map(|c| c.name()))),
                |s| Name(s.read_fronts.name()),
            ),
            control(
                "early_termination",
                "a ray stops at full opacity; exit-points adds a pre-pass (true = plain, false = off)",
                Choice(names(
                    &[EarlyTermination::Off, EarlyTermination::Plain, EarlyTermination::ExitPoints].map(|e| e.name()),
                )),
                |s| Name(s.early_termination.name()),
            ),
            control("albedo", "forward scattering share (light rays only)", Real { lo: 0.0, hi: 1.0 }, |s| {
                Number(s.albedo as f64)
            }),
            control("cone_angle", "forward scattering cone, degrees", Real { lo: 0.0, hi: 80.0 }, |s| {
                Number(s.cone_angle_deg as f64)
            }),
            control("zone_blend", "pixels over which the light's zones blend", Real { lo: 0.0, hi: 64.0 }, |s| {
                Number(s.zone_blend_px as f64)
            }),
            control(
                "light_step",
                "voxels per step of the marches toward the light",
                Real { lo: 0.01, hi: 16.0 },
                |s| Number(s.light_step_voxels as f64),
            ),
            control("ert_scale", "exit-points pre-pass: pixels per pre-pass pixel", Whole { lo: 1, hi: 16 }, |s| {
                Number(s.ert_scale as f64)
            }),
            control(
                "cache_update",
                "what writes the cache: the view samples (the paper's) or each texel's light ray",
                Choice(names(&CacheUpdate::ALL.map(|c| c.name()))),
                |s| Name(s.cache_update.name()),
            ),
            control(
                "cache_write",
                "view-samples: which claim a texel keeps (racy: the paper's store)",
                Choice(names(&CacheWrite::ALL.map(|c| c.name()))),
                |s| Name(s.cache_write.name()),
            ),
            control(
                "write_value",
                "view-samples: the light on the texel's ray, or the sample's own (the paper's)",
                Choice(names(&WriteValue::ALL.map(|c| c.name()))),
                |s| Name(s.write_value.name()),
            ),
            control(
                "write_rule",
                "view-samples: the samples that take part in runs (every-sample: the paper's)",
                Choice(names(&WriteRule::ALL.map(|c| c.name()))),
                |s| Name(s.write_rule.name()),
            ),
            control(
                "empty_runs_move_depth",
                "every-sample: an empty run moves its texel's depth without the texel-ray march",
                Toggle,
                |s| Bool(s.empty_runs_move_depth),
            ),
            control(
                "write_pass",
                "view-samples: who stores (auto: one store per claimed texel where allowed); same image",
                Choice(names(&WritePass::ALL.map(|c| c.name()))),
                |s| Name(s.write_pass.name()),
            ),
            control(
                "packed_store",
                "value and depth code in one rgba32ui texel: one store instead of two (same image)",
                Toggle,
                |s| Bool(s.packed_store),
            ),
            control(
                "fit_to_visible",
                "cache and light rays fitted to the box of the cells the transfer function can show",
                Toggle,
                |s| Bool(s.fit_to_visible),
            ),
            control(
                "line_kernel",
                "invocations per pixel: one (serial) or one per depth segment; auto: serial on a CPU device",
                Choice(names(&LineKernel::ALL.map(|c| c.name()))),
                |s| Name(s.line_kernel.name()),
            ),
            control(
                "segments",
                "segmented: invocations per pixel (past a subgroup: a workgroup each); 0: the device's choice",
                Numbers(&[0, 1, 2, 4, 8, 16, 32, 64, 128]),
                |s| Number(s.segments as f64),
            ),
            control(
                "texel_segments",
                "segmented: invocations per cache texel, its marches split over them; 0: segments / 8, at most 16",
                Numbers(&[0, 1, 2, 4, 8, 16]),
                |s| Number(s.texel_segments as f64),
            ),
            control(
                "segment_rounds",
                "segmented: rounds a ray's samples are dealt to its segments in",
                Whole { lo: 1, hi: 64 },
                |s| Number(s.segment_rounds as f64),
            ),
            control(
                "sync",
                "what separates one line from the next (racy: nothing, the study's control)",
                Choice(names(&SyncStrategy::ALL.map(|c| c.name()))),
                |s| Name(s.sync.name()),
            ),
            control("merge_sweeps", "step k of every sweep (zones, lights) in one dispatch and barrier", Toggle, |s| {
                Bool(s.merge_sweeps)
            }),
        ]
    }
}
