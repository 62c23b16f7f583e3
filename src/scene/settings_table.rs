//! How a technique's `[table]` of the scene file becomes its typed settings: a
//! serde struct with unknown keys denied, then range checks. An unknown key is
//! reported with the nearest known one and the list of all of them; a value out
//! of range names `table.key = value` and the allowed range.

use serde::de::{self, DeserializeOwned, Deserializer, Visitor};
use toml::Value;

use super::suggest::nearest;

/// A technique's settings, read from the scene file table [`Self::TABLE`].
pub trait SettingsTable: DeserializeOwned + Default {
    const TABLE: &'static str;

    /// Checks every range; settings built in code (benchmarks) are checked by
    /// the technique before it renders.
    fn validate(&self) -> Result<(), SettingsError>;

    /// Checks the keys of nested tables (the top level's are checked for every
    /// type); none by default.
    fn check_nested_keys(_entries: &toml::Table) -> Result<(), SettingsError> {
        Ok(())
    }
}

/// An unknown key of `table` among `known`, with the nearest known one.
pub fn check_keys(
    table: &'static str,
    entries: &toml::Table,
    known: &'static [&'static str],
) -> Result<(), SettingsError> {
    match entries.keys().find(|k| !known.contains(&k.as_str())) {
        Some(key) => {
            let suggestion = nearest(key, known.iter().copied());
            Err(SettingsError::UnknownKey { table, key: key.clone(), suggestion, known })
        }
        None => Ok(()),
    }
}

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SettingsError {
    #[error("[{table}] must be a table of settings")]
    NotATable { table: &'static str },
    #[error("unknown key {table}.{key}{}; the known keys are {}", did_you_mean(.suggestion), .known.join(", "))]
    UnknownKey { table: &'static str, key: String, suggestion: Option<&'static str>, known: &'static [&'static str] },
    /// The wrong type, or a name that is not one of the choices.
    #[error("{key}: {message}")]
    Value { key: String, message: String },
    #[error("{key} = {value}: must be {allowed}")]
    OutOfRange { key: String, value: String, allowed: String },
    /// A technique's own check; the message names the key.
    #[error("{0}")]
    Technique(String),
}

fn did_you_mean(suggestion: &Option<&str>) -> String {
    suggestion.map(|s| format!(" (did you mean `{s}`?)")).unwrap_or_default()
}

/// Reads and checks the settings of `T` from its table.
pub fn read_table<T: SettingsTable>(value: Value) -> Result<T, SettingsError> {
    let table = T::TABLE;
    let Value::Table(entries) = value else { return Err(SettingsError::NotATable { table }) };
    check_keys(table, &entries, known_keys::<T>())?;
    T::check_nested_keys(&entries)?;
    let settings: T = Value::Table(entries.clone()).try_into().map_err(|e: toml::de::Error| {
        // toml names the key on the error's last line ("in `key`").
        let display = e.to_string();
        let inner = display.lines().rev().find_map(|l| l.trim().strip_prefix("in `")?.strip_suffix('`'));
        let message = super::user_terms::in_user_terms(e.message().trim_end());
        // A number of the wrong kind: say which numbers the key takes, and what was given.
        // ("invalid value": a negative number for an unsigned key.)
        let given = ["invalid type: ", "invalid value: "]
            .iter()
            .find_map(|p| message.strip_prefix(p))
            .and_then(|m| m.split_once(", expected"))
            .map(|(g, _)| g.to_string());
        let message = match (given, inner.and_then(|k| allowed_numbers::<T>(&entries, k))) {
            (Some(given), Some(allowed)) => format!("must be {allowed}, not the {given}"),
            _ => message,
        };
        SettingsError::Value { key: inner.map_or_else(|| table.to_string(), |k| format!("{table}.{k}")), message }
    })?;
    settings.validate()?;
    Ok(settings)
}

/// The range `key` accepts as the range check states it ("a whole number in
/// 1..=32"), found by trying values far outside any range in its place; `None`
/// for keys that are not plain numbers.
fn allowed_numbers<T: SettingsTable>(entries: &toml::Table, key: &str) -> Option<String> {
    let probes = [Value::Integer(0), Value::Integer(i64::from(u32::MAX)), Value::Float(-1e30), Value::Float(1e30)];
    probes.into_iter().find_map(|probe| {
        let mut probed = entries.clone();
        probed.insert(key.to_string(), probe);
        let settings: T = Value::Table(probed).try_into().ok()?;
        match settings.validate() {
            Err(SettingsError::OutOfRange { key: named, allowed, .. }) if named == format!("{}.{key}", T::TABLE) => {
                Some(allowed)
            }
            _ => None,
        }
    })
}

/// The keys serde reads for `T` (its field names as written in the file).
pub fn known_keys<T: DeserializeOwned>() -> &'static [&'static str] {
    let mut recorder = FieldRecorder(&[]);
    // Always an error: the recorder stops as soon as serde names the fields.
    let _ = T::deserialize(&mut recorder);
    recorder.0
}

/// A deserializer that only records the field list a derived struct asks for.
struct FieldRecorder(&'static [&'static str]);

impl<'de> Deserializer<'de> for &mut FieldRecorder {
    type Error = de::value::Error;

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        fields: &'static [&'static str],
        _visitor: V,
    ) -> Result<V::Value, Self::Error> {
        self.0 = fields;
        Err(de::Error::custom("field names recorded"))
    }

    fn deserialize_any<V: Visitor<'de>>(self, _visitor: V) -> Result<V::Value, Self::Error> {
        Err(de::Error::custom("not a struct"))
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf option unit
        unit_struct newtype_struct seq tuple tuple_struct map enum identifier ignored_any
    }
}

/// `table.key` in `lo..=hi`, finite.
pub fn check_range(table: &str, key: &str, value: f32, lo: f32, hi: f32) -> Result<(), SettingsError> {
    if value.is_finite() && (lo..=hi).contains(&value) {
        Ok(())
    } else {
        Err(out_of_range(table, key, value, format!("in {lo}..={hi}")))
    }
}

/// `table.key` a whole number in `lo..=hi`.
pub fn check_whole(table: &str, key: &str, value: u32, lo: u32, hi: u32) -> Result<(), SettingsError> {
    if (lo..=hi).contains(&value) {
        Ok(())
    } else {
        Err(out_of_range(table, key, value, format!("a whole number in {lo}..={hi}")))
    }
}

pub fn out_of_range(table: &str, key: &str, value: impl std::fmt::Display, allowed: String) -> SettingsError {
    SettingsError::OutOfRange { key: format!("{table}.{key}"), value: value.to_string(), allowed }
}

/// For `#[serde(deserialize_with)]`: a name parsed by the type's `FromStr`
/// (whose error lists the known names).
pub fn from_name<'de, D, T>(deserializer: D) -> Result<T, D::Error>
where
    D: Deserializer<'de>,
    T: std::str::FromStr<Err = String>,
{
    let name = <String as serde::Deserialize>::deserialize(deserializer)?;
    name.parse().map_err(de::Error::custom)
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Deserialize;

    #[derive(Deserialize, Default, Debug, PartialEq)]
    #[serde(deny_unknown_fields, default)]
    struct Example {
        width: u32,
        #[serde(rename = "step")]
        step_voxels: f32,
        #[serde(skip)]
        code_only: bool,
    }

    impl SettingsTable for Example {
        const TABLE: &'static str = "example";
        fn validate(&self) -> Result<(), SettingsError> {
            check_whole(Self::TABLE, "width", self.width, 0, 8)?;
            check_range(Self::TABLE, "step", self.step_voxels, 0.0, 1.0)
        }
    }

    fn read(text: &str) -> Result<Example, SettingsError> {
        read_table(Value::Table(text.parse().unwrap()))
    }

    #[test]
    fn known_keys_are_the_file_names_of_the_fields() {
        assert_eq!(known_keys::<Example>(), ["width", "step"]);
    }

    #[test]
    fn reads_values_and_keeps_defaults() {
        assert_eq!(read("step = 0.5").unwrap(), Example { step_voxels: 0.5, ..Example::default() });
        assert_eq!(read("").unwrap(), Example::default());
    }

    #[test]
    fn errors_name_table_key_and_what_is_allowed() {
        let e = read("stpe = 0.5").unwrap_err().to_string();
        assert_eq!(e, "unknown key example.stpe (did you mean `step`?); the known keys are width, step");
        let e = read("code_only = true").unwrap_err().to_string();
        assert!(e.contains("example.code_only") && !e.contains("did you mean"), "{e}");
        assert_eq!(read("step = 2.0").unwrap_err().to_string(), "example.step = 2: must be in 0..=1");
        assert_eq!(read("step = nan").unwrap_err().to_string(), "example.step = NaN: must be in 0..=1");
        assert_eq!(read("width = 9").unwrap_err().to_string(), "example.width = 9: must be a whole number in 0..=8");
        // A value of the wrong kind: what the key takes, in words, and what was given.
        let e = read("width = \"big\"").unwrap_err().to_string();
        assert_eq!(e, "example.width: must be a whole number in 0..=8, not the string \"big\"");
        // A negative number for an unsigned key: the key's range, not "0 or more".
        let e = read("width = -5").unwrap_err().to_string();
        assert_eq!(e, "example.width: must be a whole number in 0..=8, not the integer `-5`");
        let e = read_table::<Example>(Value::Integer(3)).unwrap_err().to_string();
        assert_eq!(e, "[example] must be a table of settings");
    }
}
