//! The [ipsvi] keys declared once: kind, range and value of each, from which
//! the viewer's panel and the range checks are built (`crate::scene::settings_controls`).

use super::cache_update::{CacheUpdate, CacheWrite, WritePass, WriteRule, WriteValue};
use super::line_kernel::LineKernel;
use super::read_fronts::ReadFronts;
use super::settings::{EarlyTermination, IpsviSettings, MAX_LINE_WIDTH};
use super::sync_strategy::SyncStrategy;
use crate::scene::settings_controls::{Current, DeclaredSettings, Key, Kind};

impl DeclaredSettings for IpsviSettings {
    fn keys() -> Vec<Key<Self>> {
        use Current::{Bool, Name, Number};
        use Kind::{Choice, Numbers, Real, Toggle, Whole};
        let control = Key::<Self>::new;
        let names = |all: &[&'static str]| all.to_vec();
        vec![
            control("line_width", Whole { lo: 1, hi: MAX_LINE_WIDTH }, |s| Number(s.line_width as f64)),
            control("cache_size", Whole { lo: 16, hi: 4096 }, |s| Number(s.cache_size as f64)),
            control("piecewise", Toggle, |s| Bool(s.piecewise)),
            control("read_fronts", Choice(names(&ReadFronts::ALL.map(|c| c.name()))), |s| Name(s.read_fronts.name())),
            control(
                "early_termination",
                Choice(names(
                    &[EarlyTermination::Off, EarlyTermination::Plain, EarlyTermination::ExitPoints].map(|e| e.name()),
                )),
                |s| Name(s.early_termination.name()),
            ),
            control("albedo", Real { lo: 0.0, hi: 1.0 }, |s| Number(s.albedo as f64)),
            control("cone_angle", Real { lo: 0.0, hi: 80.0 }, |s| Number(s.cone_angle_deg as f64)),
            control("zone_blend", Real { lo: 0.0, hi: 64.0 }, |s| Number(s.zone_blend_px as f64)),
            control("light_step", Real { lo: 0.01, hi: 16.0 }, |s| Number(s.light_step_voxels as f64)),
            control("ert_scale", Whole { lo: 1, hi: 16 }, |s| Number(s.ert_scale as f64)),
            control("cache_update", Choice(names(&CacheUpdate::ALL.map(|c| c.name()))), |s| {
                Name(s.cache_update.name())
            }),
            control("cache_write", Choice(names(&CacheWrite::ALL.map(|c| c.name()))), |s| Name(s.cache_write.name())),
            control("write_value", Choice(names(&WriteValue::ALL.map(|c| c.name()))), |s| Name(s.write_value.name())),
            control("write_rule", Choice(names(&WriteRule::ALL.map(|c| c.name()))), |s| Name(s.write_rule.name())),
            control("empty_runs_move_depth", Toggle, |s| Bool(s.empty_runs_move_depth)),
            control("write_pass", Choice(names(&WritePass::ALL.map(|c| c.name()))), |s| Name(s.write_pass.name())),
            control("packed_store", Toggle, |s| Bool(s.packed_store)),
            control("fit_to_visible", Toggle, |s| Bool(s.fit_to_visible)),
            control("line_kernel", Choice(names(&LineKernel::ALL.map(|c| c.name()))), |s| Name(s.line_kernel.name())),
            control("segments", Numbers(&[0, 1, 2, 4, 8, 16, 32, 64, 128]), |s| Number(s.segments as f64)),
            control("segment_rounds", Whole { lo: 1, hi: 64 }, |s| Number(s.segment_rounds as f64)),
            control("sync", Choice(names(&SyncStrategy::ALL.map(|c| c.name()))), |s| Name(s.sync.name())),
            control("merge_sweeps", Toggle, |s| Bool(s.merge_sweeps)),
        ]
    }
}
