//! NRRD (teem): `.nrrd` with the data after the header's blank line or in a
//! detached file (`data file:`), and `.nhdr` headers; raw, gzip and ASCII encodings.

use std::collections::HashMap;
use std::path::Path;

use glam::Vec3;

use super::data_file::{self, Skip};
use super::decode::{checked_dims, checked_spacing, parse_ascii_voxels, Endian, Layout, VoxelType};
use super::error::FormatProblem;
use super::fields::{lines, parse_array, parse_one};
use super::inflate::{inflate_exact, Stream};
use crate::scene::volume::Volume;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Encoding {
    Raw,
    Gzip,
    Ascii,
}

struct Header {
    /// Field values by identifier, lower-case and without spaces ("datafile"),
    /// since NRRD spells several both ways.
    fields: HashMap<String, String>,
    /// Offset of the attached data, after the blank line ending the header.
    data_start: Option<usize>,
}

impl Header {
    fn get(&self, field: &str) -> Option<&str> {
        self.fields.get(&normalize(field)).map(String::as_str)
    }

    fn require(&self, field: &str) -> Result<&str, FormatProblem> {
        self.get(field).ok_or_else(|| FormatProblem::MissingField(field.into()))
    }
}

fn normalize(field: &str) -> String {
    field.chars().filter(|c| !c.is_whitespace()).flat_map(char::to_lowercase).collect()
}

pub fn load(path: &Path, bytes: &[u8], name: String) -> Result<Volume, FormatProblem> {
    let header = parse_header(bytes)?;

    let dimension = header.require("dimension")?;
    if parse_one::<u32>("dimension", dimension, "3")? != 3 {
        return Err(FormatProblem::unsupported(format!("dimension: {dimension} (only 3-D scalar volumes)")));
    }
    let voxel_type = voxel_type(header.require("type")?)?;
    let dims = checked_dims(parse_array("sizes", header.require("sizes")?, "3 integers")?)?;
    let spacing = spacing(&header)?;
    let encoding = match header.require("encoding")?.to_ascii_lowercase().as_str() {
        "raw" => Encoding::Raw,
        "gzip" | "gz" => Encoding::Gzip,
        "ascii" | "text" | "txt" => Encoding::Ascii,
        other => return Err(FormatProblem::unsupported(format!("encoding: {other} (supported: raw, gzip, ascii)"))),
    };
    // ASCII values are converted to little-endian bytes; `endian` is then moot.
    let endian = match (header.get("endian"), encoding) {
        (_, Encoding::Ascii) => Endian::Little,
        (Some(value), _) => match value.to_ascii_lowercase().as_str() {
            "little" => Endian::Little,
            "big" => Endian::Big,
            _ => return Err(FormatProblem::bad_field("endian", value, "little or big")),
        },
        (None, _) if voxel_type.size() == 1 => Endian::Little,
        (None, _) => return Err(FormatProblem::MissingField("endian".into())),
    };
    let line_skip = match header.get("line skip") {
        Some(value) => parse_one::<u64>("line skip", value, "a line count >= 0")?,
        None => 0,
    };
    let byte_skip = match header.get("byte skip") {
        None => Skip::Bytes(0),
        Some(value) => match parse_one::<i64>("byte skip", value, "a byte count or -1")? {
            -1 if encoding == Encoding::Raw => Skip::ToTail,
            -1 => return Err(FormatProblem::unsupported("byte skip: -1 with a compressed or ASCII encoding")),
            n if n >= 0 => Skip::Bytes(n as u64),
            _ => return Err(FormatProblem::bad_field("byte skip", value, "a byte count or -1")),
        },
    };

    let layout = Layout { dims, spacing, voxel_type, endian };
    let source = match header.get("data file") {
        Some(file) => {
            if file.eq_ignore_ascii_case("LIST") || file.contains('%') {
                return Err(FormatProblem::unsupported(format!("data file: {file} (data split over several files)")));
            }
            DataSource::Detached(data_file::resolve(path, file))
        }
        None => match header.data_start {
            Some(start) => DataSource::Attached(&bytes[start..]),
            None => {
                return Err(FormatProblem::syntax(
                    "no data: the header has no `data file` field and no blank line before attached data",
                ))
            }
        },
    };
    let read = ReadPlan { encoding, line_skip, byte_skip, layout };
    let voxels = read.voxels(source)?;
    layout.into_volume(name, &voxels)
}

enum DataSource<'a> {
    Attached(&'a [u8]),
    Detached(std::path::PathBuf),
}

struct ReadPlan {
    encoding: Encoding,
    line_skip: u64,
    byte_skip: Skip,
    layout: Layout,
}

impl ReadPlan {
    /// The voxel bytes (for ASCII: converted to little-endian binary).
    fn voxels(&self, source: DataSource) -> Result<Vec<u8>, FormatProblem> {
        let len = self.layout.data_len();
        let (owned, what);
        let data: &[u8] = match source {
            DataSource::Detached(path) => {
                what = format!("data file {}", path.display());
                // The common case reads only the voxels, checked against the file size.
                if self.encoding == Encoding::Raw && self.line_skip == 0 {
                    return data_file::read_exact(&path, self.byte_skip, len);
                }
                owned = data_file::read_rest(&path, 0)?;
                &owned
            }
            DataSource::Attached(data) => {
                what = "attached data".to_string();
                data
            }
        };
        let data = &data[data_file::skip_lines(data, self.line_skip, &what)?..];
        match self.encoding {
            Encoding::Raw => Ok(data_file::exact_slice(data, self.byte_skip, len, &what)?.to_vec()),
            Encoding::Gzip => {
                // Teem applies byte skip to the inflated data.
                let skip = match self.byte_skip {
                    Skip::Bytes(n) => usize::try_from(n)
                        .map_err(|_| FormatProblem::bad_field("byte skip", &n.to_string(), "a smaller count"))?,
                    Skip::ToTail => 0, // refused when parsing
                };
                let total = skip
                    .checked_add(len)
                    .ok_or_else(|| FormatProblem::bad_field("byte skip", &skip.to_string(), "a smaller count"))?;
                let mut inflated = inflate_exact(data, Stream::Gzip, total, &what)?;
                inflated.drain(..skip);
                Ok(inflated)
            }
            Encoding::Ascii => {
                let text = std::str::from_utf8(data)
                    .map_err(|_| FormatProblem::syntax(format!("{what}: ASCII encoding but the data is not text")))?;
                let count = len / self.layout.voxel_type.size();
                parse_ascii_voxels(text, self.layout.voxel_type, count)
            }
        }
    }
}

fn parse_header(bytes: &[u8]) -> Result<Header, FormatProblem> {
    let mut all = lines(bytes);
    let magic = all.next().transpose()?.map(|line| line.text).unwrap_or_default();
    let version = magic.strip_prefix("NRRD000").unwrap_or_default();
    if !matches!(version, "1" | "2" | "3" | "4" | "5") {
        return Err(FormatProblem::syntax("not a NRRD file: the first line must be NRRD0001 to NRRD0005"));
    }
    let mut fields = HashMap::new();
    for line in all {
        let line = line?;
        if line.text.is_empty() {
            return Ok(Header { fields, data_start: Some(line.end) });
        }
        if line.text.starts_with('#') {
            continue;
        }
        let (field, value) = line
            .text
            .split_once(':')
            .ok_or_else(|| FormatProblem::syntax(format!("header line {}: expected `field: value`", line.number)))?;
        if value.starts_with('=') {
            continue; // a `key:=value` pair: free-form metadata
        }
        let key = normalize(field);
        if fields.insert(key, value.trim().to_string()).is_some() {
            return Err(FormatProblem::syntax(format!(
                "header line {}: field `{}` is given twice",
                line.number,
                field.trim()
            )));
        }
    }
    Ok(Header { fields, data_start: None })
}

fn voxel_type(name: &str) -> Result<VoxelType, FormatProblem> {
    match name {
        "uchar" | "unsigned char" | "uint8" | "uint8_t" => Ok(VoxelType::U8),
        "ushort" | "unsigned short" | "unsigned short int" | "uint16" | "uint16_t" => Ok(VoxelType::U16),
        "short" | "short int" | "signed short" | "signed short int" | "int16" | "int16_t" => Ok(VoxelType::I16),
        "float" => Ok(VoxelType::F32),
        other => Err(FormatProblem::unsupported(format!("type: {other} (supported: uchar, ushort, short, float)"))),
    }
}

/// From `space directions` (lengths of the axis vectors) or `spacings`; 1 when absent.
fn spacing(header: &Header) -> Result<Vec3, FormatProblem> {
    if let Some(value) = header.get("space directions") {
        let vectors = parse_vectors(value)
            .ok_or_else(|| FormatProblem::bad_field("space directions", value, "3 vectors like (1,0,0)"))?;
        let lengths: [f64; 3] = match vectors.as_slice() {
            [a, b, c] => [a, b, c].map(|v| v.iter().map(|x| x * x).sum::<f64>().sqrt()),
            _ => return Err(FormatProblem::bad_field("space directions", value, "3 vectors, one per axis")),
        };
        return checked_spacing(lengths);
    }
    match header.get("spacings") {
        Some(value) => checked_spacing(parse_array("spacings", value, "3 numbers")?),
        None => Ok(Vec3::ONE),
    }
}

/// `(1,0,0) (0,1.5,0) (0,0,2)`; `None` on any syntax problem or `none` axis.
fn parse_vectors(value: &str) -> Option<Vec<Vec<f64>>> {
    let mut vectors = Vec::new();
    let mut rest = value.trim();
    while !rest.is_empty() {
        let inner = rest.strip_prefix('(')?;
        let close = inner.find(')')?;
        let components =
            inner[..close].split(',').map(|c| c.trim().parse::<f64>().ok()).collect::<Option<Vec<f64>>>()?;
        vectors.push(components);
        rest = inner[close + 1..].trim_start();
    }
    Some(vectors)
}

#[cfg(test)]
mod tests {
    use super::parse_vectors;

    #[test]
    fn space_direction_vectors() {
        let v = parse_vectors("(1,0,0) ( 0, 1.5 ,0)(0,0,-2)").unwrap();
        assert_eq!(v, vec![vec![1.0, 0.0, 0.0], vec![0.0, 1.5, 0.0], vec![0.0, 0.0, -2.0]]);
        assert!(parse_vectors("(1,0,0) none (0,0,1)").is_none());
        assert!(parse_vectors("(1,0,0").is_none());
        assert!(parse_vectors("(1,a,0)").is_none());
    }
}
