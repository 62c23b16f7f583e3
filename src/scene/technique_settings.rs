//! The settings of the techniques that have a scene-file table (`[ipsvi]`,
//! `[lightvolume]`, ...), stored without knowing their types: the scene layer
//! sits below the techniques. Which tables exist and how each is read is the
//! catalogue's (`crate::techniques`), handed to the scene reader as a
//! [`TableCatalogue`]; a bad key still fails when the scene is read.

use std::any::Any;
use std::borrow::Cow;
use std::fmt;

use toml::Value;

use super::settings_table::{SettingsError, SettingsTable};

/// The technique tables a scene reader knows, and how to read each.
pub trait TableCatalogue: Sync {
    /// Every table name, for the did-you-mean of an unknown one.
    fn tables(&self) -> &[&'static str];

    /// Reads and checks `table`; `None` when no technique has a table of that name.
    fn read(&self, table: &str, value: Value) -> Option<Result<Box<dyn TechniqueTable>, SettingsError>>;
}

/// A catalogue with no technique tables: for scenes read below the techniques
/// (the scene layer's own tests); any technique table is then unknown.
pub struct NoTechniqueTables;

impl TableCatalogue for NoTechniqueTables {
    fn tables(&self) -> &[&'static str] {
        &[]
    }

    fn read(&self, _table: &str, _value: Value) -> Option<Result<Box<dyn TechniqueTable>, SettingsError>> {
        None
    }
}

/// One technique's typed settings, behind a type the scene does not know.
pub trait TechniqueTable: Any + fmt::Debug + Send + Sync {
    fn table(&self) -> &'static str;
    fn clone_box(&self) -> Box<dyn TechniqueTable>;
    /// The defaults of this table's type, for comparing with a table not set.
    fn default_box(&self) -> Box<dyn TechniqueTable>;
    fn same_as(&self, other: &dyn TechniqueTable) -> bool;
    fn as_any(&self) -> &dyn Any;
    fn as_any_mut(&mut self) -> &mut dyn Any;
}

impl<T: SettingsTable + Clone + PartialEq + fmt::Debug + Send + Sync + 'static> TechniqueTable for T {
    fn table(&self) -> &'static str {
        T::TABLE
    }

    fn clone_box(&self) -> Box<dyn TechniqueTable> {
        Box::new(self.clone())
    }

    fn default_box(&self) -> Box<dyn TechniqueTable> {
        Box::new(T::default())
    }

    fn same_as(&self, other: &dyn TechniqueTable) -> bool {
        other.as_any().downcast_ref::<T>() == Some(self)
    }

    fn as_any(&self) -> &dyn Any {
        self
    }

    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
}

/// The technique settings of a scene: one value per table the scene gave or
/// code set; a table not there reads as its type's defaults.
#[derive(Default)]
pub struct TechniqueSettings {
    tables: Vec<Box<dyn TechniqueTable>>,
}

impl TechniqueSettings {
    /// The settings of `T`'s table: the stored ones, else `T`'s defaults.
    pub fn get<T: TechniqueTable + SettingsTable + Clone>(&self) -> Cow<'_, T> {
        match self.find(T::TABLE) {
            Some(t) => Cow::Borrowed(t.as_any().downcast_ref::<T>().expect("a table is stored as its own type")),
            None => Cow::Owned(T::default()),
        }
    }

    /// The settings of `T`'s table to change (its defaults first, if not set).
    pub fn get_mut<T: TechniqueTable + SettingsTable + Clone>(&mut self) -> &mut T {
        let i = match self.tables.iter().position(|t| t.table() == T::TABLE) {
            Some(i) => i,
            None => {
                self.tables.push(Box::new(T::default()));
                self.tables.len() - 1
            }
        };
        self.tables[i].as_any_mut().downcast_mut::<T>().expect("a table is stored as its own type")
    }

    /// Sets `T`'s table to `settings`.
    pub fn set<T: TechniqueTable + SettingsTable + Clone>(&mut self, settings: T) {
        *self.get_mut::<T>() = settings;
    }

    /// Stores a table a [`TableCatalogue`] read, replacing one of the same name.
    pub fn insert(&mut self, table: Box<dyn TechniqueTable>) {
        self.tables.retain(|t| t.table() != table.table());
        self.tables.push(table);
    }

    fn find(&self, table: &str) -> Option<&dyn TechniqueTable> {
        self.tables.iter().find(|t| t.table() == table).map(|t| t.as_ref())
    }
}

impl Clone for TechniqueSettings {
    fn clone(&self) -> Self {
        TechniqueSettings { tables: self.tables.iter().map(|t| t.clone_box()).collect() }
    }
}

impl fmt::Debug for TechniqueSettings {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(&self.tables).finish()
    }
}

/// Equal when every table either holds the same settings or, absent on one
/// side, holds the defaults on the other: how a table reads is what counts.
impl PartialEq for TechniqueSettings {
    fn eq(&self, other: &Self) -> bool {
        let covered = |a: &Self, b: &Self| {
            a.tables.iter().all(|t| match b.find(t.table()) {
                Some(u) => t.same_as(u),
                None => t.same_as(t.default_box().as_ref()),
            })
        };
        covered(self, other) && covered(other, self)
    }
}
