//! The panel's controls for every technique's settings table (`[ipsvi]`,
//! `[lightvolume]`, `[half_angle]`, `[ao]`), listed here key by key with
//! the kind of value and the range the table's check accepts. Tests tie the
//! list to the typed settings: its keys are exactly the keys serde reads for
//! each table (a new field fails them until it has a control), every key of
//! `tests/scenes/all-keys.toml`'s technique tables has one, and each range's
//! ends are accepted and just past them refused by the table's own check.
//! A control proposes a `--set table.key=value` edit, checked like the
//! command line's.

use super::ui::UiEdit;
use crate::scene::Scene;
use crate::techniques::ao::render_settings::{AoMode, MAX_GLOW, MAX_PHASE_G};
use crate::techniques::ao::settings::{Metric, TrainingSet};
use crate::techniques::ao::AoSettings;
use crate::techniques::half_angle::HalfAngleSettings;
use crate::techniques::ipsvi::cache_update::{CacheUpdate, CacheWrite, WritePass, WriteRule, WriteValue};
use crate::techniques::ipsvi::line_kernel::LineKernel;
use crate::techniques::ipsvi::read_fronts::ReadFronts;
use crate::techniques::ipsvi::settings::EarlyTermination;
use crate::techniques::ipsvi::sync_strategy::SyncStrategy;
use crate::techniques::ipsvi::IpsviSettings;
use crate::techniques::lightvolume::CostEstimate;
use crate::techniques::lightvolume::LightVolumeSettings;
use std::collections::BTreeMap;

/// What a control edits.
#[derive(Clone, Debug, PartialEq)]
pub enum Kind {
    Toggle,
    /// A whole number in `lo..=hi`.
    Whole {
        lo: u32,
        hi: u32,
    },
    /// A real number in `lo..=hi` (`hi` infinite where only `lo` bounds it).
    Real {
        lo: f64,
        hi: f64,
    },
    /// One of these names (a string in the file).
    Choice(Vec<&'static str>),
    /// One of these numbers.
    Numbers(&'static [u32]),
    /// A TOML value as written (a nested table, a path).
    Text,
}

/// A control's value in the scene now.
#[derive(Clone, Debug, PartialEq)]
pub enum Current {
    Bool(bool),
    Number(f64),
    Name(&'static str),
    /// TOML as written.
    Text(String),
}

pub struct Control {
    pub table: &'static str,
    pub key: &'static str,
    pub kind: Kind,
    pub get: fn(&Scene) -> Current,
}

impl Control {
    /// `table.key`, as `--set` takes it.
    pub fn path(&self) -> String {
        format!("{}.{}", self.table, self.key)
    }
}

/// The technique tables, in the panel's order.
pub const TABLES: [&str; 4] = ["ipsvi", "lightvolume", "half_angle", "ao"];

fn control(table: &'static str, key: &'static str, kind: Kind, get: fn(&Scene) -> Current) -> Control {
    Control { table, key, kind, get }
}

/// Every control, table by table.
pub fn controls() -> Vec<Control> {
    use Current::{Bool, Name, Number, Text};
    use Kind::{Choice, Numbers, Real, Toggle, Whole};
    let names = |all: &[&'static str]| all.to_vec();
    vec![
        control("ipsvi", "line_width", Whole { lo: 1, hi: crate::techniques::ipsvi::settings::MAX_LINE_WIDTH }, |s| {
            Number(s.settings.get::<IpsviSettings>().line_width as f64)
        }),
        control("ipsvi", "cache_size", Whole { lo: 16, hi: 4096 }, |s| {
            Number(s.settings.get::<IpsviSettings>().cache_size as f64)
        }),
        control("ipsvi", "piecewise", Toggle, |s| Bool(s.settings.get::<IpsviSettings>().piecewise)),
        control("ipsvi", "read_fronts", Choice(names(&ReadFronts::ALL.map(|c| c.name()))), |s| {
            Name(s.settings.get::<IpsviSettings>().read_fronts.name())
        }),
        control(
            "ipsvi",
            "early_termination",
            Choice(names(
                &[EarlyTermination::Off, EarlyTermination::Plain, EarlyTermination::ExitPoints].map(|e| e.name()),
            )),
            |s| Name(s.settings.get::<IpsviSettings>().early_termination.name()),
        ),
        control("ipsvi", "albedo", Real { lo: 0.0, hi: 1.0 }, |s| {
            Number(s.settings.get::<IpsviSettings>().albedo as f64)
        }),
        control("ipsvi", "cone_angle", Real { lo: 0.0, hi: 80.0 }, |s| {
            Number(s.settings.get::<IpsviSettings>().cone_angle_deg as f64)
        }),
        control("ipsvi", "zone_blend", Real { lo: 0.0, hi: 64.0 }, |s| {
            Number(s.settings.get::<IpsviSettings>().zone_blend_px as f64)
        }),
        control("ipsvi", "light_step", Real { lo: 0.01, hi: 16.0 }, |s| {
            Number(s.settings.get::<IpsviSettings>().light_step_voxels as f64)
        }),
        control("ipsvi", "ert_scale", Whole { lo: 1, hi: 16 }, |s| {
            Number(s.settings.get::<IpsviSettings>().ert_scale as f64)
        }),
        control("ipsvi", "cache_update", Choice(names(&CacheUpdate::ALL.map(|c| c.name()))), |s| {
            Name(s.settings.get::<IpsviSettings>().cache_update.name())
        }),
        control("ipsvi", "cache_write", Choice(names(&CacheWrite::ALL.map(|c| c.name()))), |s| {
            Name(s.settings.get::<IpsviSettings>().cache_write.name())
        }),
        control("ipsvi", "write_value", Choice(names(&WriteValue::ALL.map(|c| c.name()))), |s| {
            Name(s.settings.get::<IpsviSettings>().write_value.name())
        }),
        control("ipsvi", "write_rule", Choice(names(&WriteRule::ALL.map(|c| c.name()))), |s| {
            Name(s.settings.get::<IpsviSettings>().write_rule.name())
        }),
        control("ipsvi", "empty_runs_move_depth", Toggle, |s| {
            Bool(s.settings.get::<IpsviSettings>().empty_runs_move_depth)
        }),
        control("ipsvi", "write_pass", Choice(names(&WritePass::ALL.map(|c| c.name()))), |s| {
            Name(s.settings.get::<IpsviSettings>().write_pass.name())
        }),
        control("ipsvi", "packed_store", Toggle, |s| Bool(s.settings.get::<IpsviSettings>().packed_store)),
        control("ipsvi", "fit_to_visible", Toggle, |s| Bool(s.settings.get::<IpsviSettings>().fit_to_visible)),
        control("ipsvi", "line_kernel", Choice(names(&LineKernel::ALL.map(|c| c.name()))), |s| {
            Name(s.settings.get::<IpsviSettings>().line_kernel.name())
        }),
        control("ipsvi", "segments", Numbers(&[0, 1, 2, 4, 8, 16, 32, 64, 128]), |s| {
            Number(s.settings.get::<IpsviSettings>().segments as f64)
        }),
        control("ipsvi", "segment_rounds", Whole { lo: 1, hi: 64 }, |s| {
            Number(s.settings.get::<IpsviSettings>().segment_rounds as f64)
        }),
        control("ipsvi", "sync", Choice(names(&SyncStrategy::ALL.map(|c| c.name()))), |s| {
            Name(s.settings.get::<IpsviSettings>().sync.name())
        }),
        control("ipsvi", "merge_sweeps", Toggle, |s| Bool(s.settings.get::<IpsviSettings>().merge_sweeps)),
        control("lightvolume", "scale", Numbers(&[1, 2, 4]), |s| {
            Number(s.settings.get::<LightVolumeSettings>().scale as f64)
        }),
        control("lightvolume", "coherent", Toggle, |s| Bool(s.settings.get::<LightVolumeSettings>().coherent)),
        control("lightvolume", "compensated", Toggle, |s| Bool(s.settings.get::<LightVolumeSettings>().compensated)),
        control(
            "lightvolume",
            "cost_estimate",
            Choice(names(
                &[CostEstimate::Share, CostEstimate::Passes, CostEstimate::Selective, CostEstimate::Entire]
                    .map(|c| c.name()),
            )),
            |s| Name(s.settings.get::<LightVolumeSettings>().cost_estimate.name()),
        ),
        control("lightvolume", "max_passes_per_frame", Whole { lo: 0, hi: 1_000_000 }, |s| {
            Number(s.settings.get::<LightVolumeSettings>().max_passes_per_frame as f64)
        }),
        control("lightvolume", "pass_lights", Whole { lo: 1, hi: 64 }, |s| {
            Number(s.settings.get::<LightVolumeSettings>().pass_lights as f64)
        }),
        control("lightvolume", "rebase_tolerance", Real { lo: f64::MIN_POSITIVE, hi: f64::INFINITY }, |s| {
            Number(s.settings.get::<LightVolumeSettings>().rebase_tolerance)
        }),
        control("lightvolume", "substep", Real { lo: 0.05, hi: 4.0 }, |s| {
            Number(s.settings.get::<LightVolumeSettings>().substep as f64)
        }),
        control("lightvolume", "shared_medium", Toggle, |s| {
            Bool(s.settings.get::<LightVolumeSettings>().shared_medium)
        }),
        control("lightvolume", "chromatic", Toggle, |s| Bool(s.settings.get::<LightVolumeSettings>().chromatic)),
        control("lightvolume", "racy", Toggle, |s| Bool(s.settings.get::<LightVolumeSettings>().racy)),
        // Unset: the scene's render.step, shown as such.
        control("half_angle", "slice_step", Real { lo: 0.01, hi: 16.0 }, |s| {
            Number(s.settings.get::<HalfAngleSettings>().slice_step_voxels(s) as f64)
        }),
        control("half_angle", "light_buffer_size", Whole { lo: 16, hi: 4096 }, |s| {
            Number(s.settings.get::<HalfAngleSettings>().light_buffer_size as f64)
        }),
        control("ao", "radius", Whole { lo: 1, hi: 64 }, |s| Number(s.settings.get::<AoSettings>().radius as f64)),
        control("ao", "bits", Whole { lo: 1, hi: 12 }, |s| Number(s.settings.get::<AoSettings>().bits as f64)),
        // At most 2^bits: the check refuses more.
        control("ao", "packed_dim", Whole { lo: 2, hi: 4096 }, |s| {
            Number(s.settings.get::<AoSettings>().packed_dim as f64)
        }),
        control("ao", "clusters", Whole { lo: 2, hi: 2048 }, |s| {
            Number(s.settings.get::<AoSettings>().clusters as f64)
        }),
        control("ao", "metric", Choice(names(&Metric::ALL.map(|m| m.name()))), |s| {
            Name(s.settings.get::<AoSettings>().metric.name())
        }),
        control("ao", "training", Kind::Text, |s| Text(training_toml(&s.settings.get::<AoSettings>().training))),
        control("ao", "lbg_iterations", Whole { lo: 1, hi: 1000 }, |s| {
            Number(s.settings.get::<AoSettings>().lbg_iterations as f64)
        }),
        control("ao", "lbg_threshold", Real { lo: 0.0, hi: 0.999_999 }, |s| {
            Number(s.settings.get::<AoSettings>().lbg_threshold)
        }),
        control("ao", "cache", Toggle, |s| Bool(s.settings.get::<AoSettings>().cache)),
        control("ao", "cache_dir", Kind::Text, |s| {
            Text(s.settings.get::<AoSettings>().cache_dir.as_ref().map_or(String::new(), |d| format!("{d:?}")))
        }),
        control("ao", "mode", Choice(names(&AoMode::ALL.map(|m| m.name()))), |s| {
            Name(s.settings.get::<AoSettings>().mode.name())
        }),
        control("ao", "isovalue", Real { lo: 0.0, hi: 1.0 }, |s| {
            Number(s.settings.get::<AoSettings>().isovalue as f64)
        }),
        control("ao", "phase_g", Real { lo: -MAX_PHASE_G as f64, hi: MAX_PHASE_G as f64 }, |s| {
            Number(s.settings.get::<AoSettings>().phase_g as f64)
        }),
        control("ao", "glow_max", Real { lo: 1.0, hi: MAX_GLOW as f64 }, |s| {
            Number(s.settings.get::<AoSettings>().glow_max as f64)
        }),
        control("ao", "glow_range", Kind::Text, |s| {
            let [lo, hi] = s.settings.get::<AoSettings>().glow_range;
            Text(format!("[{lo}, {hi}]"))
        }),
        // Unset: the GPU when there is a device, shown as empty.
        control("ao", "backend", Kind::Text, |s| {
            Text(s.settings.get::<AoSettings>().backend.map_or(String::new(), |b| format!("{:?}", b.name())))
        }),
    ]
}

/// `ao.training` as the file writes it.
fn training_toml(t: &TrainingSet) -> String {
    match *t {
        TrainingSet::Random { count, seed } => format!("{{ rule = \"random\", count = {count}, seed = {seed} }}"),
        TrainingSet::Gradient { eps, count, seed } => {
            format!("{{ rule = \"gradient\", eps = {eps}, count = {count}, seed = {seed} }}")
        }
    }
}

/// The `--set` edit of `control` to `value`.
pub fn set_edit(control: &Control, value: &Current) -> String {
    let value = match value {
        Current::Bool(b) => b.to_string(),
        Current::Number(n) => n.to_string(),
        Current::Name(n) => format!("{n:?}"),
        Current::Text(t) => t.clone(),
    };
    format!("{}={value}", control.path())
}

/// What the settings section keeps between frames: text being typed.
#[derive(Default)]
pub struct SettingsPanel {
    drafts: BTreeMap<String, String>,
}

impl SettingsPanel {
    /// One collapsible section per table, `open` (the technique's) open.
    pub fn show(&mut self, ui: &mut egui::Ui, scene: &Scene, open: Option<&str>, edits: &mut Vec<UiEdit>) {
        let all = controls();
        for table in TABLES {
            egui::CollapsingHeader::new(format!("[{table}]")).default_open(open == Some(table)).show(ui, |ui| {
                for c in all.iter().filter(|c| c.table == table) {
                    self.show_control(ui, c, scene, edits);
                }
            });
        }
    }

    fn show_control(&mut self, ui: &mut egui::Ui, c: &Control, scene: &Scene, edits: &mut Vec<UiEdit>) {
        let current = (c.get)(scene);
        let mut push = |v: Current| edits.push(UiEdit::Set(set_edit(c, &v)));
        ui.horizontal(|ui| match (&c.kind, &current) {
            (Kind::Toggle, Current::Bool(on)) => {
                let mut v = *on;
                if ui.checkbox(&mut v, c.key).changed() {
                    push(Current::Bool(v));
                }
            }
            (Kind::Whole { lo, hi }, Current::Number(n)) => {
                let mut v = *n as u32;
                let r = ui.add(egui::DragValue::new(&mut v).range(*lo..=*hi));
                ui.label(c.key);
                // Applied when the drag ends: each value rebuilds the technique.
                if v != *n as u32 && !r.dragged() {
                    push(Current::Number(v as f64));
                }
            }
            (Kind::Real { lo, hi }, Current::Number(n)) => {
                let mut v = *n;
                let speed = if hi.is_finite() { (hi - lo) / 200.0 } else { n.abs().max(1e-6) / 20.0 };
                let r = ui.add(egui::DragValue::new(&mut v).range(*lo..=*hi).speed(speed).max_decimals(6));
                ui.label(c.key);
                if v != *n && !r.dragged() {
                    push(Current::Number(v));
                }
            }
            (Kind::Choice(names), Current::Name(name)) => {
                let mut chosen = *name;
                egui::ComboBox::from_label(c.key).selected_text(chosen).show_ui(ui, |ui| {
                    for &n in names {
                        ui.selectable_value(&mut chosen, n, n);
                    }
                });
                if chosen != *name {
                    push(Current::Name(chosen));
                }
            }
            (Kind::Numbers(values), Current::Number(n)) => {
                ui.label(c.key);
                for &v in values.iter() {
                    if ui.selectable_label(*n as u32 == v, v.to_string()).clicked() && *n as u32 != v {
                        push(Current::Number(v as f64));
                    }
                }
            }
            (Kind::Text, Current::Text(text)) => {
                let draft = self.drafts.entry(c.path()).or_insert_with(|| text.clone());
                ui.label(c.key);
                let r = ui.text_edit_singleline(draft);
                if r.lost_focus() && *draft != *text && !draft.trim().is_empty() {
                    push(Current::Text(draft.clone()));
                }
                if !r.has_focus() && !r.lost_focus() {
                    // Not being typed in: follow the scene.
                    *draft = text.clone();
                }
            }
            (kind, value) => {
                ui.label(format!("{}: {value:?} ({kind:?})", c.key));
            }
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::settings_table::known_keys;
    use crate::scene::technique_settings::TableCatalogue;
    use crate::techniques::CATALOGUE;
    use crate::viewer::live_scene::{LiveScene, SceneSource};

    fn keys_of(table: &str) -> Vec<&'static str> {
        controls().into_iter().filter(|c| c.table == table).map(|c| c.key).collect()
    }

    #[test]
    fn the_controls_are_exactly_the_keys_serde_reads_for_each_table() {
        assert_eq!(TABLES, CATALOGUE.tables());
        assert_eq!(keys_of("ipsvi"), known_keys::<IpsviSettings>());
        assert_eq!(keys_of("lightvolume"), known_keys::<LightVolumeSettings>());
        assert_eq!(keys_of("half_angle"), known_keys::<HalfAngleSettings>());
        assert_eq!(keys_of("ao"), known_keys::<AoSettings>());
    }

    #[test]
    fn every_technique_key_of_all_keys_toml_has_a_control() {
        let text = include_str!("../../tests/scenes/all-keys.toml");
        let file: toml::Table = text.parse().unwrap();
        // Commented-out keys (`# slice_step = ...`) are keys too.
        let commented = |table: &str| -> Vec<String> {
            let mut inside = false;
            let mut keys = Vec::new();
            for line in text.lines() {
                let l = line.trim();
                if l.starts_with('[') {
                    inside = l.trim_start_matches('[').starts_with(&format!("{table}]"));
                } else if let (true, Some(rest)) = (inside, l.strip_prefix("# ")) {
                    if let Some((key, _)) = rest.split_once(" = ") {
                        keys.push(key.trim().to_string());
                    }
                }
            }
            keys
        };
        let mut checked = 0;
        for table in TABLES {
            let written = file[table].as_table().unwrap().keys().cloned().chain(commented(table));
            for key in written {
                assert!(keys_of(table).contains(&key.as_str()), "{table}.{key} has no control");
                checked += 1;
            }
        }
        // And every control is of a key the file documents.
        assert_eq!(checked, controls().len());
    }

    /// Whether the table's own check refuses `table.key = value` as out of range.
    fn out_of_range(table: &str, key: &str, value: f64, whole: bool) -> bool {
        let text = if whole { format!("{key} = {}", value as i64) } else { format!("{key} = {value:?}") };
        match CATALOGUE.read(table, toml::Value::Table(text.parse().unwrap())).expect("a technique table") {
            Ok(_) => false,
            Err(e) => {
                let e = e.to_string();
                let ours = e.starts_with(&format!("{table}.{key} = "));
                ours && (e.contains(": must be ") || e.contains(": allowed "))
            }
        }
    }

    #[test]
    fn each_range_is_the_one_the_table_checks() {
        for c in controls() {
            let (lo, hi, step, whole) = match c.kind {
                Kind::Whole { lo, hi } => (lo as f64, hi as f64, 1.0, true),
                Kind::Real { lo, hi } => (lo, hi, 1e-3 * (if hi.is_finite() { hi - lo } else { 1.0 }), false),
                _ => continue,
            };
            let path = c.path();
            assert!(!out_of_range(c.table, c.key, lo, whole), "{path} = {lo} is refused");
            assert!(out_of_range(c.table, c.key, lo - step, whole) || lo - step < 0.0 && whole, "{path} below {lo}");
            if hi.is_finite() {
                // packed_dim's upper end depends on bits: checked with bits = 12.
                if c.path() != "ao.packed_dim" {
                    assert!(!out_of_range(c.table, c.key, hi, whole), "{path} = {hi} is refused");
                }
                assert!(out_of_range(c.table, c.key, hi + step, whole), "{path} above {hi}");
            }
        }
    }

    #[test]
    fn every_control_shows_the_scenes_value_and_its_edit_is_accepted() {
        let mut live = LiveScene::load(SceneSource::Default, &["volume.size=8".to_string()]).unwrap();
        for c in controls() {
            let current = (c.get)(&live.scene);
            let kind_fits = matches!(
                (&c.kind, &current),
                (Kind::Toggle, Current::Bool(_))
                    | (Kind::Whole { .. } | Kind::Real { .. } | Kind::Numbers(_), Current::Number(_))
                    | (Kind::Choice(_), Current::Name(_))
                    | (Kind::Text, Current::Text(_))
            );
            assert!(kind_fits, "{}: {current:?} for {:?}", c.path(), c.kind);
            if let Kind::Choice(names) = &c.kind {
                assert!(names.contains(match &current {
                    Current::Name(n) => n,
                    _ => unreachable!(),
                }));
            }
            // The unset cache_dir has no value to write back.
            if current != Current::Text(String::new()) {
                live.set(&set_edit(&c, &current)).unwrap_or_else(|e| panic!("{}: {e}", set_edit(&c, &current)));
                assert_eq!((c.get)(&live.scene), current, "{} reads back", c.path());
            }
        }
    }
}
