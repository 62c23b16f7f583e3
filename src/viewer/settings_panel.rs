//! The panel's controls for every technique's settings table, built from the
//! keys each settings type declares beside itself
//! (`crate::scene::settings_controls`, `src/techniques/*/controls.rs`). Tests
//! tie the declarations to the typed settings: the keys are exactly the keys
//! serde reads for each table (a new field fails them until it has a control),
//! every key of `tests/scenes/all-keys.toml`'s technique tables has one, and
//! each range's ends are accepted and just past them refused by the table's
//! own check. A control proposes a `--set table.key=value` edit, checked like
//! the command line's.

use super::ui::UiEdit;
use crate::scene::settings_controls::{Control, Current, Kind};
use crate::scene::technique_settings::TableCatalogue;
use crate::scene::Scene;
use crate::techniques::CATALOGUE;
use std::collections::BTreeMap;

/// Every control, table by table: each technique's declared keys.
pub fn controls() -> Vec<Control> {
    CATALOGUE.controls()
}

/// The `--set` edit of `control` to `value`.
pub fn set_edit(control: &Control, value: &Current) -> String {
    let value = match value {
        Current::Bool(b) => b.to_string(),
        Current::Number(n) => n.to_string(),
        Current::Name(n) => format!("{n:?}"),
        Current::Text(t) => t.clone(),
        // No control edits a key back to unset (the panel shows an unset key's
        // fallback); should one, the table's check refuses the empty value by name.
        Current::Unset => "\"\"".to_string(),
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
        for &table in CATALOGUE.tables() {
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
        // What the key does, declared beside it, on hover.
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
            (Kind::WholeOrAuto { lo, hi }, Current::Number(n)) => {
                let current = *n as u32;
                let mut auto = current == 0;
                let mut v = if auto { *lo } else { current };
                let toggled = ui.checkbox(&mut auto, "auto").changed();
                let r = ui.add_enabled(!auto, egui::DragValue::new(&mut v).range(*lo..=*hi));
                ui.label(c.key);
                let chosen = if auto { 0 } else { v };
                if chosen != current && (toggled || !r.dragged()) {
                    push(Current::Number(chosen as f64));
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
        })
        .response
        .on_hover_text(c.doc);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::settings_table::known_keys;
    use crate::techniques::ao::AoSettings;
    use crate::techniques::half_angle::HalfAngleSettings;
    use crate::techniques::ipsvi::IpsviSettings;
    use crate::techniques::lightvolume::LightVolumeSettings;
    use crate::viewer::live_scene::{LiveScene, SceneSource};

    fn keys_of(table: &str) -> Vec<&'static str> {
        controls().into_iter().filter(|c| c.table == table).map(|c| c.key).collect()
    }

    #[test]
    fn every_control_says_what_its_key_does_in_one_line() {
        for c in controls() {
            assert!(
                !c.doc.trim().is_empty() && c.doc.len() <= 100 && !c.doc.contains('\n'),
                "{}: {:?}",
                c.path(),
                c.doc
            );
        }
    }

    #[test]
    fn the_controls_are_exactly_the_keys_serde_reads_for_each_table() {
        assert_eq!(CATALOGUE.tables(), ["ipsvi", "half_angle", "lightvolume", "ao"]);
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
        for &table in CATALOGUE.tables() {
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
                Kind::WholeOrAuto { lo, hi } => {
                    assert!(!out_of_range(c.table, c.key, 0.0, true), "{} = 0 (auto) is refused", c.path());
                    (lo as f64, hi as f64, 1.0, true)
                }
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
                    | (
                        Kind::Whole { .. } | Kind::WholeOrAuto { .. } | Kind::Real { .. } | Kind::Numbers(_),
                        Current::Number(_)
                    )
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
