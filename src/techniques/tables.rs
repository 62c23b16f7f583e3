//! The catalogue: the registered techniques looked up by name, and their
//! scene-file tables, which the scene reader gets as a [`TableCatalogue`].
//! [`CATALOGUE`] is the library's, over [`REGISTERED`]; a test builds one
//! over its own list (a toy technique beside the real ones).

use std::sync::OnceLock;
use toml::Value;

use super::registry::{Registration, Technique, REGISTERED};
use crate::scene::settings_controls::Control;
use crate::scene::settings_table::SettingsError;
use crate::scene::technique_settings::{TableCatalogue, TechniqueTable};
use crate::scene::Scene;

/// Techniques and their tables.
pub struct Catalogue<'a> {
    registrations: &'a [Registration],
    /// The table names, in registration order (built on first use).
    tables: OnceLock<Vec<&'static str>>,
}

/// The one catalogue every scene reader of the library is given.
pub static CATALOGUE: Catalogue<'static> = Catalogue::new(REGISTERED);

impl<'a> Catalogue<'a> {
    pub const fn new(registrations: &'a [Registration]) -> Catalogue<'a> {
        Catalogue { registrations, tables: OnceLock::new() }
    }

    pub fn registrations(&self) -> &'a [Registration] {
        self.registrations
    }

    /// The technique called `name`; the error suggests the nearest name and lists all.
    pub fn technique(&self, name: &str) -> Result<Technique, String> {
        let names: Vec<&'static str> = self.registrations.iter().map(|r| r.technique.name()).collect();
        match self.registrations.iter().find(|r| r.technique.name() == name) {
            Some(r) => Ok(r.technique),
            None => {
                let near = crate::scene::suggest::nearest(name, names.iter().copied());
                let near = near.map(|n| format!(" (did you mean {n}?)")).unwrap_or_default();
                Err(format!("unknown technique {name:?}{near}; known: {}", names.join(", ")))
            }
        }
    }

    /// The table `technique` reads, if any.
    pub fn table_of(&self, technique: Technique) -> Option<&'static str> {
        let registration = self.registrations.iter().find(|r| r.technique == technique)?;
        registration.table.map(|t| t.name)
    }

    /// Every declared key of every table, table by table.
    pub fn controls(&self) -> Vec<Control> {
        self.registrations.iter().filter_map(|r| r.table).flat_map(|t| (t.controls)()).collect()
    }

    /// Every technique table's key reference, in the registry's order, a blank
    /// line between tables.
    pub fn documented_tables(&self) -> String {
        let tables: Vec<String> = self.registrations.iter().filter_map(|r| r.table).map(|t| (t.documented)()).collect();
        tables.join("\n")
    }

    /// One table's key reference; `None` for a name no technique registers.
    pub fn documented_table(&self, table: &str) -> Option<String> {
        self.registrations.iter().filter_map(|r| r.table).find(|t| t.name == table).map(|t| (t.documented)())
    }

    /// A warning for each technique table of `scene` that `technique` does not read.
    pub fn unused_settings(&self, technique: Technique, scene: &Scene) -> Vec<String> {
        let own = self.table_of(technique);
        scene
            .technique_tables
            .iter()
            .filter(|&&table| own != Some(table))
            .map(|&table| {
                let reader = self.registrations.iter().find(|r| r.table.map(|t| t.name) == Some(table));
                let reader =
                    reader.map_or_else(|| "another technique".to_string(), |r| format!("technique {}", r.technique));
                format!(
                    "the [{table}] settings are read only by {reader}, not by {technique}, which runs: they have no effect"
                )
            })
            .collect()
    }
}

impl TableCatalogue for Catalogue<'_> {
    fn tables(&self) -> &[&'static str] {
        self.tables.get_or_init(|| self.registrations.iter().filter_map(|r| r.table.map(|t| t.name)).collect())
    }

    fn read(&self, table: &str, value: Value) -> Option<Result<Box<dyn TechniqueTable>, SettingsError>> {
        let entry = self.registrations.iter().filter_map(|r| r.table).find(|t| t.name == table)?;
        Some((entry.read)(value))
    }
}
