//! sweeplab's own raw-volume header (`.vhdr`): a few `key = value` lines next to
//! a headerless data file. See docs/volume-formats.md.
//!
//! ```text
//! # CT of a walnut
//! dims = 256 256 200
//! spacing = 0.1 0.1 0.12
//! type = uint16
//! endian = little
//! data = walnut.raw
//! offset = 0
//! ```

use std::collections::HashMap;
use std::path::Path;

use glam::Vec3;

use super::data_file::{self, Skip};
use super::decode::{checked_dims, checked_spacing, Endian, Layout, VoxelType};
use super::error::FormatProblem;
use super::fields::{lines, parse_array, parse_one};
use crate::scene::volume::Volume;

const KEYS: [&str; 6] = ["dims", "spacing", "type", "endian", "data", "offset"];

pub fn load(path: &Path, bytes: &[u8], name: String) -> Result<Volume, FormatProblem> {
    let fields = parse_fields(bytes)?;
    let get = |key: &str| fields.get(key).map(String::as_str);
    let require = |key: &str| get(key).ok_or_else(|| FormatProblem::MissingField(key.into()));

    let dims = checked_dims(parse_array("dims", require("dims")?, "3 integers (x y z)")?)?;
    let spacing = match get("spacing") {
        Some(value) => checked_spacing(parse_array("spacing", value, "3 numbers (x y z)")?)?,
        None => Vec3::ONE,
    };
    let voxel_type = match require("type")?.to_ascii_lowercase().as_str() {
        "uint8" => VoxelType::U8,
        "uint16" => VoxelType::U16,
        "int16" => VoxelType::I16,
        "float32" => VoxelType::F32,
        _ => return Err(FormatProblem::bad_field("type", require("type")?, "uint8, uint16, int16 or float32")),
    };
    // The byte order of multi-byte voxels must be stated: guessing silently
    // produces noise that looks like data.
    let endian_word = get("endian").map(str::to_ascii_lowercase);
    let endian = match (endian_word.as_deref(), voxel_type) {
        (Some("little"), _) | (None, VoxelType::U8) => Endian::Little,
        (Some("big"), _) => Endian::Big,
        (Some(other), _) => return Err(FormatProblem::bad_field("endian", other, "little or big")),
        (None, _) => return Err(FormatProblem::MissingField("endian".into())),
    };
    let offset = match get("offset") {
        Some(value) => parse_one::<u64>("offset", value, "a byte count >= 0")?,
        None => 0,
    };
    let data_path = data_file::resolve(path, require("data")?);
    let layout = Layout { dims, spacing, voxel_type, endian };
    let data = data_file::read_exact(&data_path, Skip::Bytes(offset), layout.data_len())?;
    layout.into_volume(name, &data)
}

fn parse_fields(bytes: &[u8]) -> Result<HashMap<String, String>, FormatProblem> {
    let mut fields = HashMap::new();
    for line in lines(bytes) {
        let line = line?;
        let text = line.text.trim();
        if text.is_empty() || text.starts_with('#') {
            continue;
        }
        let (key, value) = text.split_once('=').ok_or_else(|| {
            FormatProblem::syntax(format!("line {}: expected `key = value`, found `{text}`", line.number))
        })?;
        let key = key.trim().to_ascii_lowercase();
        if !KEYS.contains(&key.as_str()) {
            return Err(FormatProblem::syntax(format!(
                "line {}: unknown key `{key}` (known: {})",
                line.number,
                KEYS.join(", ")
            )));
        }
        if fields.insert(key.clone(), value.trim().to_string()).is_some() {
            return Err(FormatProblem::syntax(format!("line {}: `{key}` is given twice", line.number)));
        }
    }
    Ok(fields)
}
