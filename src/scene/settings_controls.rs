//! A settings table's keys declared once, beside its settings type: each key's
//! kind of value, the range the table's check accepts, and how to read its
//! value from a scene. The viewer's panel is built from these declarations;
//! tests tie them to the typed settings (every key serde reads has one, and
//! each range's ends are accepted and just past them refused by the table's
//! own check).

use super::settings_table::SettingsTable;
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

/// One key of a table.
pub struct Control {
    pub table: &'static str,
    pub key: &'static str,
    pub kind: Kind,
    pub get: fn(&Scene) -> Current,
}

impl Control {
    pub fn new(table: &'static str, key: &'static str, kind: Kind, get: fn(&Scene) -> Current) -> Control {
        Control { table, key, kind, get }
    }

    /// A key of `S`'s table.
    pub fn of<S: SettingsTable>(key: &'static str, kind: Kind, get: fn(&Scene) -> Current) -> Control {
        Control::new(S::TABLE, key, kind, get)
    }

    /// `table.key`, as `--set` takes it.
    pub fn path(&self) -> String {
        format!("{}.{}", self.table, self.key)
    }
}

/// A settings type with its keys declared.
pub trait DeclaredSettings: SettingsTable {
    /// Every key serde reads, in the panel's order.
    fn controls() -> Vec<Control>;
}
