//! A settings table's keys declared once, beside its settings type: each key's
//! name, what it does, its kind of value and range, and how to read its value
//! from the settings (its default is the value in `S::default()`). Built from
//! these declarations: the viewer's panel ([`controls_of`], the doc on hover),
//! the range checks of whole and real keys that a table's `validate` runs
//! ([`check_declared_ranges`]: a `--set` edit, a scene file and settings built
//! in code are checked against the range the panel offers), and the key
//! reference that `sweeplab keys` prints and `tests/scenes/all-keys.toml`
//! holds ([`super::settings_docs`]). Tests tie the declarations to the typed
//! settings (every key serde reads has one).

use std::sync::Arc;

use super::settings_table::{check_range, check_whole, out_of_range, SettingsError, SettingsTable};
use super::technique_settings::TechniqueTable;
use super::Scene;

/// What a control edits.
#[derive(Clone, Debug, PartialEq)]
pub enum Kind {
    Toggle,
    /// A whole number in `lo..=hi`.
    Whole {
        lo: u32,
        hi: u32,
    },
    /// 0, which the technique resolves itself (the doc says how), or a whole
    /// number in `lo..=hi`.
    WholeOrAuto {
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

/// A key's value.
#[derive(Clone, Debug, PartialEq)]
pub enum Current {
    Bool(bool),
    Number(f64),
    Name(&'static str),
    /// TOML as written.
    Text(String),
    /// Not set: the technique falls back on something else (the panel shows
    /// [`DeclaredSettings::shown_unset`]).
    Unset,
}

/// One key of `S`'s table.
pub struct Key<S> {
    pub key: &'static str,
    /// What the key does, with its unit: one short line.
    pub doc: &'static str,
    pub kind: Kind,
    pub value: fn(&S) -> Current,
}

impl<S> Key<S> {
    pub fn new(key: &'static str, doc: &'static str, kind: Kind, value: fn(&S) -> Current) -> Key<S> {
        Key { key, doc, kind, value }
    }
}

/// A settings type with its keys declared.
pub trait DeclaredSettings: SettingsTable + TechniqueTable + Clone {
    /// Every key serde reads, in the panel's order.
    fn keys() -> Vec<Key<Self>>;

    /// What the panel shows for `key` while it is unset in `scene`.
    fn shown_unset(_key: &str, _scene: &Scene) -> Current {
        Current::Unset
    }
}

/// One key as the viewer's panel takes it, whatever its table's type.
pub struct Control {
    pub table: &'static str,
    pub key: &'static str,
    pub doc: &'static str,
    pub kind: Kind,
    /// The key's value in a scene (its fallback where unset).
    pub get: Arc<dyn Fn(&Scene) -> Current + Send + Sync>,
}

impl Control {
    /// `table.key`, as `--set` takes it.
    pub fn path(&self) -> String {
        format!("{}.{}", self.table, self.key)
    }
}

/// The controls of `S`'s declared keys.
pub fn controls_of<S: DeclaredSettings>() -> Vec<Control> {
    S::keys()
        .into_iter()
        .map(|Key { key, doc, kind, value }| {
            let get = move |scene: &Scene| match value(&scene.settings.get::<S>()) {
                Current::Unset => S::shown_unset(key, scene),
                set => set,
            };
            Control { table: S::TABLE, key, doc, kind, get: Arc::new(get) }
        })
        .collect()
}

/// Every numeric key of `settings` within its declared range: whole and real
/// ranges, real ranges open above (`> 0` where the range starts at the
/// smallest positive number, else `>= lo`), and lists of allowed numbers. The
/// error names `table.key = value` and the range.
pub fn check_declared_ranges<S: DeclaredSettings>(settings: &S) -> Result<(), SettingsError> {
    for Key { key, kind, value, .. } in S::keys() {
        let Current::Number(v) = value(settings) else { continue };
        match kind {
            Kind::Whole { lo, hi } => check_whole(S::TABLE, key, v as u32, lo, hi)?,
            Kind::WholeOrAuto { lo, hi } if v != 0.0 && !(f64::from(lo)..=f64::from(hi)).contains(&v) => {
                return Err(out_of_range(S::TABLE, key, v, format!("0 (auto) or a whole number in {lo}..={hi}")));
            }
            // The keys are f32: the value and the ends as the table holds them.
            Kind::Real { lo, hi } if hi.is_finite() => check_range(S::TABLE, key, v as f32, lo as f32, hi as f32)?,
            Kind::Real { lo, .. } if !(v.is_finite() && v >= lo) => {
                let bound = if lo == f64::MIN_POSITIVE { "> 0".to_string() } else { format!(">= {lo}") };
                return Err(out_of_range(S::TABLE, key, v, format!("finite and {bound}")));
            }
            Kind::Numbers(allowed) if !allowed.iter().any(|&a| f64::from(a) == v) => {
                return Err(out_of_range(S::TABLE, key, v, or_list(allowed)));
            }
            _ => {}
        }
    }
    Ok(())
}

/// `1, 2 or 4`.
pub fn or_list(items: &[impl std::fmt::Display]) -> String {
    let texts: Vec<String> = items.iter().map(|i| i.to_string()).collect();
    match texts.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => texts.join(""),
    }
}
