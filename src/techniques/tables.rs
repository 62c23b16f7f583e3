//! The scene-file tables of the techniques: which exist and which settings
//! type reads each. The scene reader gets them as a [`TableCatalogue`].

use toml::Value;

use crate::scene::settings_table::{read_table, SettingsError, SettingsTable};
use crate::scene::technique_settings::{TableCatalogue, TechniqueTable};
use crate::techniques::ao::AoSettings;
use crate::techniques::half_angle::HalfAngleSettings;
use crate::techniques::ipsvi::IpsviSettings;
use crate::techniques::lightvolume::LightVolumeSettings;

/// The techniques' tables.
pub struct Catalogue;

/// The one catalogue every scene reader of the library is given.
pub static CATALOGUE: Catalogue = Catalogue;

const TABLES: [&str; 4] =
    [IpsviSettings::TABLE, LightVolumeSettings::TABLE, HalfAngleSettings::TABLE, AoSettings::TABLE];

fn boxed<T: TechniqueTable + SettingsTable>(value: Value) -> Result<Box<dyn TechniqueTable>, SettingsError> {
    Ok(Box::new(read_table::<T>(value)?))
}

impl TableCatalogue for Catalogue {
    fn tables(&self) -> &[&'static str] {
        &TABLES
    }

    fn read(&self, table: &str, value: Value) -> Option<Result<Box<dyn TechniqueTable>, SettingsError>> {
        Some(match table {
            IpsviSettings::TABLE => boxed::<IpsviSettings>(value),
            LightVolumeSettings::TABLE => boxed::<LightVolumeSettings>(value),
            HalfAngleSettings::TABLE => boxed::<HalfAngleSettings>(value),
            AoSettings::TABLE => boxed::<AoSettings>(value),
            _ => return None,
        })
    }
}
