//! MetaImage (ITK): `.mhd` header with a detached data file, or `.mha` with the
//! data after the header (`ElementDataFile = LOCAL`), raw or zlib-compressed.

use std::collections::HashMap;
use std::path::Path;

use glam::Vec3;

use super::data_file::{self, Skip};
use super::decode::{checked_dims, checked_spacing, Endian, Layout, VoxelType};
use super::error::FormatProblem;
use super::fields::{lines, parse_array, parse_bool, parse_one};
use super::inflate::{inflate_exact, Stream};
use crate::scene::volume::Volume;

/// The header: fields by lower-case name, and where the data starts when LOCAL.
struct Header {
    fields: HashMap<String, (String, String)>,
    data_start: usize,
}

impl Header {
    fn get(&self, key: &str) -> Option<(&str, &str)> {
        self.fields.get(&key.to_ascii_lowercase()).map(|(name, value)| (name.as_str(), value.as_str()))
    }

    fn require(&self, key: &str) -> Result<(&str, &str), FormatProblem> {
        self.get(key).ok_or_else(|| FormatProblem::MissingField(key.into()))
    }

    fn flag(&self, key: &str) -> Result<Option<bool>, FormatProblem> {
        self.get(key).map(|(name, value)| parse_bool(name, value)).transpose()
    }
}

pub fn load(path: &Path, bytes: &[u8], name: String) -> Result<Volume, FormatProblem> {
    let header = parse_header(bytes)?;

    if let Some((field, kind)) = header.get("ObjectType") {
        if !kind.eq_ignore_ascii_case("Image") {
            return Err(FormatProblem::bad_field(field, kind, "Image"));
        }
    }
    let (field, ndims) = header.require("NDims")?;
    if parse_one::<u32>(field, ndims, "3")? != 3 {
        return Err(FormatProblem::unsupported(format!("NDims = {ndims}: only 3-D images are volumes")));
    }
    if let Some((field, channels)) = header.get("ElementNumberOfChannels") {
        if parse_one::<u32>(field, channels, "1")? != 1 {
            return Err(FormatProblem::unsupported(format!(
                "ElementNumberOfChannels = {channels}: only scalar volumes are supported"
            )));
        }
    }
    let (field, dims) = header.require("DimSize")?;
    let dims = checked_dims(parse_array(field, dims, "3 integers")?)?;
    let spacing = match header.get("ElementSpacing").or(header.get("ElementSize")) {
        Some((field, value)) => checked_spacing(parse_array(field, value, "3 numbers")?)?,
        None => Vec3::ONE,
    };
    let voxel_type = element_type(header.require("ElementType")?)?;
    if header.flag("BinaryData")? == Some(false) {
        return Err(FormatProblem::unsupported("ASCII data (BinaryData = False)"));
    }
    let endian = byte_order(&header)?;
    let compressed = header.flag("CompressedData")?.unwrap_or(false);
    let compressed_size = header
        .get("CompressedDataSize")
        .map(|(field, value)| parse_one::<u64>(field, value, "a byte count"))
        .transpose()?;
    let skip = match header.get("HeaderSize") {
        None => Skip::Bytes(0),
        Some((field, value)) => match parse_one::<i64>(field, value, "a byte count or -1")? {
            -1 => Skip::ToTail,
            n if n >= 0 => Skip::Bytes(n as u64),
            _ => return Err(FormatProblem::bad_field(field, value, "a byte count or -1")),
        },
    };

    let layout = Layout { dims, spacing, voxel_type, endian };
    let len = layout.data_len();
    let (_, data_file) = header.require("ElementDataFile")?;
    let voxels = if data_file.eq_ignore_ascii_case("LOCAL") {
        let data = &bytes[header.data_start..];
        if compressed {
            let stream = compressed_stream(data, skip, compressed_size, "data after the header")?;
            inflate_exact(stream, Stream::Zlib, len, "compressed data")?
        } else {
            data_file::exact_slice(data, skip, len, "data after the header")?.to_vec()
        }
    } else {
        if data_file.eq_ignore_ascii_case("LIST") || data_file.contains('%') {
            return Err(FormatProblem::unsupported(format!(
                "ElementDataFile = {data_file}: data split over several files"
            )));
        }
        let data_path = data_file::resolve(path, data_file);
        if compressed {
            let data = data_file::read_rest(&data_path, 0)?;
            let what = format!("data file {}", data_path.display());
            let stream = compressed_stream(&data, skip, compressed_size, &what)?;
            inflate_exact(stream, Stream::Zlib, len, &what)?
        } else {
            data_file::read_exact(&data_path, skip, len)?
        }
    };
    layout.into_volume(name, &voxels)
}

/// Lines up to and including `ElementDataFile`, which MetaImage requires to be last.
fn parse_header(bytes: &[u8]) -> Result<Header, FormatProblem> {
    let mut fields = HashMap::new();
    for line in lines(bytes) {
        let line = line?;
        let text = line.text.trim();
        if text.is_empty() {
            continue;
        }
        let (name, value) = text.split_once('=').ok_or_else(|| {
            FormatProblem::syntax(format!(
                "header line {}: expected `Key = Value`, found `{}`",
                line.number,
                shorten(text)
            ))
        })?;
        let name = name.trim();
        let key = name.to_ascii_lowercase();
        let is_last = key == "elementdatafile";
        fields.insert(key, (name.to_string(), value.trim().to_string()));
        if is_last {
            return Ok(Header { fields, data_start: line.end });
        }
    }
    Err(FormatProblem::MissingField("ElementDataFile".into()))
}

fn shorten(text: &str) -> String {
    match text.char_indices().nth(40) {
        Some((cut, _)) => format!("{}...", &text[..cut]),
        None => text.to_string(),
    }
}

fn element_type((field, value): (&str, &str)) -> Result<VoxelType, FormatProblem> {
    match value.to_ascii_uppercase().as_str() {
        "MET_UCHAR" => Ok(VoxelType::U8),
        "MET_USHORT" => Ok(VoxelType::U16),
        "MET_SHORT" => Ok(VoxelType::I16),
        "MET_FLOAT" => Ok(VoxelType::F32),
        other if other.starts_with("MET_") => Err(FormatProblem::unsupported(format!(
            "{field} = {value} (supported: MET_UCHAR, MET_USHORT, MET_SHORT, MET_FLOAT)"
        ))),
        _ => Err(FormatProblem::bad_field(field, value, "MET_UCHAR, MET_USHORT, MET_SHORT or MET_FLOAT")),
    }
}

/// Both byte-order fields exist in the wild; they must agree when both are given.
fn byte_order(header: &Header) -> Result<Endian, FormatProblem> {
    let binary = header.flag("BinaryDataByteOrderMSB")?;
    let element = header.flag("ElementByteOrderMSB")?;
    let msb = match (binary, element) {
        (Some(a), Some(b)) if a != b => {
            return Err(FormatProblem::syntax("BinaryDataByteOrderMSB and ElementByteOrderMSB disagree"))
        }
        (Some(msb), _) | (None, Some(msb)) => msb,
        (None, None) => false,
    };
    Ok(if msb { Endian::Big } else { Endian::Little })
}

/// The compressed bytes: after `skip`, exactly `CompressedDataSize` when given.
fn compressed_stream<'a>(
    data: &'a [u8],
    skip: Skip,
    compressed_size: Option<u64>,
    what: &str,
) -> Result<&'a [u8], FormatProblem> {
    let start = match skip {
        Skip::Bytes(n) => n,
        Skip::ToTail => return Err(FormatProblem::unsupported("HeaderSize = -1 with compressed data")),
    };
    if (data.len() as u64) < start {
        return Err(FormatProblem::Truncated { what: what.to_string(), expected: start, found: data.len() as u64 });
    }
    let stream = &data[start as usize..];
    match compressed_size {
        None => Ok(stream),
        Some(size) => data_file::exact_slice(stream, Skip::Bytes(0), size as usize, what),
    }
}
