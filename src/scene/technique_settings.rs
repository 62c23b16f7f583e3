//! The typed settings of every technique that has a scene-file table, read
//! when the scene is read: a bad `[ipsvi]` key fails at load time, whichever
//! technique then runs. Each settings type lives with its technique.

use toml::Value;

use super::settings_table::{read_table, SettingsError, SettingsTable};
use crate::ao::AoSettings;
use crate::half_angle::HalfAngleSettings;
use crate::ipsvi::IpsviSettings;
use crate::lightvolume::LightVolumeSettings;

#[derive(Clone, Debug, Default, PartialEq)]
pub struct TechniqueSettings {
    pub ipsvi: IpsviSettings,
    pub lightvolume: LightVolumeSettings,
    pub half_angle: HalfAngleSettings,
    /// Ambient occlusion (`[ao]`): its preprocessing and technique `ao`.
    pub ao: AoSettings,
}

impl TechniqueSettings {
    /// The scene-file tables of the techniques.
    pub const TABLES: [&'static str; 4] =
        [IpsviSettings::TABLE, LightVolumeSettings::TABLE, HalfAngleSettings::TABLE, AoSettings::TABLE];

    /// Reads the technique table `table`; `Ok(false)` when no technique has one
    /// of that name.
    pub fn read(&mut self, table: &str, value: Value) -> Result<bool, SettingsError> {
        match table {
            IpsviSettings::TABLE => self.ipsvi = read_table(value)?,
            LightVolumeSettings::TABLE => self.lightvolume = read_table(value)?,
            HalfAngleSettings::TABLE => self.half_angle = read_table(value)?,
            // AO checks its nested `training` table's keys itself.
            AoSettings::TABLE => {
                self.ao = AoSettings::from_toml(&value).map_err(|e| SettingsError::Technique(e.to_string()))?
            }
            _ => return Ok(false),
        }
        Ok(true)
    }
}
