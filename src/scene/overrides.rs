//! `--set key=value`: edits of a scene's TOML document before it is read.
//!
//! The key is a dotted path (`camera.azimuth`, `lights.0.intensity`,
//! `ipsvi.line_width`); a numeric segment indexes an array. Missing tables on the
//! way are created; an array index must exist. The value is parsed as a TOML
//! value (number, bool, string in quotes, array, inline table) and taken as a
//! plain string when it is not one, so `camera.projection=orthographic` works
//! without quotes. Whether the key means anything is checked later, when the
//! document is read into a scene: an edit of the document rather than of the
//! typed settings, so that the file and the command line share one parser and
//! one error message (`ipsvi.cone_angel`: did you mean `cone_angle`?).

use toml::{Table, Value};

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum OverrideError {
    #[error("--set `{arg}`: expected KEY=VALUE")]
    MissingEquals { arg: String },
    #[error("--set `{arg}`: empty key or empty part in the dotted key")]
    EmptyKey { arg: String },
    #[error("--set `{arg}`: index {index} is out of range, `{path}` has {}", entries(.len))]
    IndexOutOfRange { arg: String, path: String, index: usize, len: usize },
    #[error("--set `{arg}`: `{path}` is an array, so `{segment}` must be an index")]
    NotAnIndex { arg: String, path: String, segment: String },
    #[error("--set `{arg}`: `{path}` is {found}, not a table or array")]
    NotAContainer { arg: String, path: String, found: &'static str },
}

fn entries(len: &usize) -> String {
    crate::plural::count(*len as u64, "entry", "entries")
}

/// One parsed `--set` argument.
#[derive(Debug, Clone, PartialEq)]
pub struct Override {
    /// The argument as given, for error messages.
    pub arg: String,
    pub path: Vec<String>,
    pub value: Value,
}

/// Parses `key=value` (split at the first `=`; spaces around key and value are
/// ignored).
pub fn parse_override(arg: &str) -> Result<Override, OverrideError> {
    let (key, raw_value) = arg.split_once('=').ok_or_else(|| OverrideError::MissingEquals { arg: arg.to_string() })?;
    let path: Vec<String> = key.trim().split('.').map(|s| s.trim().to_string()).collect();
    if path.iter().any(|s| s.is_empty()) {
        return Err(OverrideError::EmptyKey { arg: arg.to_string() });
    }
    Ok(Override { arg: arg.to_string(), path, value: parse_value(raw_value.trim()) })
}

/// A TOML value if `text` is one, otherwise the text as a string.
fn parse_value(text: &str) -> Value {
    use serde::Deserialize;
    Value::deserialize(toml::de::ValueDeserializer::new(text)).unwrap_or_else(|_| Value::String(text.to_string()))
}

fn type_name(v: &Value) -> &'static str {
    match v {
        Value::String(_) => "a string",
        Value::Integer(_) => "an integer",
        Value::Float(_) => "a float",
        Value::Boolean(_) => "a boolean",
        Value::Datetime(_) => "a datetime",
        Value::Array(_) => "an array",
        Value::Table(_) => "a table",
    }
}

/// Sets `o.value` at `o.path` in `doc`.
pub fn apply_override(doc: &mut Table, o: &Override) -> Result<(), OverrideError> {
    let (first, rest) = o.path.split_first().ok_or_else(|| OverrideError::EmptyKey { arg: o.arg.clone() })?;
    if rest.is_empty() {
        doc.insert(first.clone(), o.value.clone());
        return Ok(());
    }
    let child = doc.entry(first.clone()).or_insert_with(|| Value::Table(Table::new()));
    set_below(child, 1, o)
}

/// Sets the value at `o.path[depth..]` below `here` (which sits at `o.path[..depth]`).
fn set_below(here: &mut Value, depth: usize, o: &Override) -> Result<(), OverrideError> {
    let segment = &o.path[depth];
    let path = o.path[..depth].join(".");
    let slot = match here {
        Value::Table(t) => t.entry(segment.clone()).or_insert_with(|| Value::Table(Table::new())),
        Value::Array(items) => {
            let len = items.len();
            let index: usize = segment.parse().map_err(|_| OverrideError::NotAnIndex {
                arg: o.arg.clone(),
                path: path.clone(),
                segment: segment.clone(),
            })?;
            items.get_mut(index).ok_or_else(|| OverrideError::IndexOutOfRange {
                arg: o.arg.clone(),
                path,
                index,
                len,
            })?
        }
        other => return Err(OverrideError::NotAContainer { arg: o.arg.clone(), path, found: type_name(other) }),
    };
    if depth + 1 == o.path.len() {
        *slot = o.value.clone();
        Ok(())
    } else {
        set_below(slot, depth + 1, o)
    }
}

/// Parses and applies every `--set` argument, in order (later ones win).
pub fn apply_overrides(doc: &mut Table, args: &[String]) -> Result<(), OverrideError> {
    for arg in args {
        apply_override(doc, &parse_override(arg)?)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn doc(text: &str) -> Table {
        text.parse().expect("test document is valid TOML")
    }

    fn set(d: &mut Table, arg: &str) -> Result<(), OverrideError> {
        apply_overrides(d, &[arg.to_string()])
    }

    #[test]
    fn values_are_parsed_as_toml_or_kept_as_strings() {
        assert_eq!(parse_override("a=45").unwrap().value, Value::Integer(45));
        assert_eq!(parse_override("a=0.5").unwrap().value, Value::Float(0.5));
        assert_eq!(parse_override("a=true").unwrap().value, Value::Boolean(true));
        assert_eq!(parse_override("a=orthographic").unwrap().value, Value::String("orthographic".into()));
        assert_eq!(parse_override("a=\"45\"").unwrap().value, Value::String("45".into()));
        assert_eq!(parse_override("a=data/x.raw").unwrap().value, Value::String("data/x.raw".into()));
        let array = parse_override("a=[1, 2.5]").unwrap().value;
        assert_eq!(array, Value::Array(vec![Value::Integer(1), Value::Float(2.5)]));
        let table = parse_override("a={ type = \"point\" }").unwrap().value;
        assert_eq!(table.get("type"), Some(&Value::String("point".into())));
        // A value with a second key smuggled in is not TOML value syntax: a string.
        assert_eq!(parse_override("a=1\nb=2").unwrap().value, Value::String("1\nb=2".into()));
        // Only the first `=` splits.
        assert_eq!(parse_override("a=b=c").unwrap().value, Value::String("b=c".into()));
        assert_eq!(parse_override(" camera.azimuth = 3 ").unwrap().path, ["camera", "azimuth"]);
    }

    #[test]
    fn malformed_arguments_are_errors_naming_them() {
        assert_eq!(parse_override("width"), Err(OverrideError::MissingEquals { arg: "width".into() }));
        assert_eq!(parse_override("=3"), Err(OverrideError::EmptyKey { arg: "=3".into() }));
        assert_eq!(parse_override("render..width=3"), Err(OverrideError::EmptyKey { arg: "render..width=3".into() }));
        let message = parse_override("width").unwrap_err().to_string();
        assert!(message.contains("--set `width`"), "{message}");
    }

    #[test]
    fn sets_nested_keys_creating_missing_tables() {
        let mut d = doc("[camera]\nazimuth = 30\n");
        set(&mut d, "camera.azimuth=45").unwrap();
        set(&mut d, "render.width=128").unwrap();
        set(&mut d, "ipsvi.sweep.lines=4").unwrap();
        set(&mut d, "top=1").unwrap();
        assert_eq!(d["camera"]["azimuth"], Value::Integer(45));
        assert_eq!(d["render"]["width"], Value::Integer(128));
        assert_eq!(d["ipsvi"]["sweep"]["lines"], Value::Integer(4));
        assert_eq!(d["top"], Value::Integer(1));
    }

    #[test]
    fn indexes_arrays_of_tables() {
        let mut d = doc("[[lights]]\nintensity = 1.0\n[[lights]]\nintensity = 2.0\n");
        set(&mut d, "lights.1.intensity=5").unwrap();
        set(&mut d, "lights.0.color=[1, 0, 0]").unwrap();
        assert_eq!(d["lights"][1]["intensity"], Value::Integer(5));
        assert_eq!(d["lights"][0]["intensity"], Value::Float(1.0));
        assert_eq!(d["lights"][0]["color"][0], Value::Integer(1));
        set(&mut d, "lights.0={ type = \"point\" }").unwrap();
        assert_eq!(d["lights"][0].get("intensity"), None);
    }

    #[test]
    fn bad_paths_are_errors() {
        let mut d = doc("[[lights]]\nintensity = 1.0\n[render]\nwidth = 5\n");
        let e = set(&mut d, "lights.3.intensity=5").unwrap_err();
        assert_eq!(
            e,
            OverrideError::IndexOutOfRange {
                arg: "lights.3.intensity=5".into(),
                path: "lights".into(),
                index: 3,
                len: 1
            }
        );
        assert!(e.to_string().contains("index 3 is out of range, `lights` has 1 entry"), "{e}");
        assert!(matches!(set(&mut d, "lights.first.intensity=5"), Err(OverrideError::NotAnIndex { .. })));
        let e = set(&mut d, "render.width.x=5").unwrap_err();
        assert!(matches!(&e, OverrideError::NotAContainer { path, found: "an integer", .. } if path == "render.width"));
    }
}
