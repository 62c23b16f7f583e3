//! VTK XML ImageData (`.vti`): the point-data scalar array, inline (ascii or
//! base64) or appended (raw or base64), uncompressed or zlib-compressed in blocks.
//!
//! The XML part is parsed with quick-xml; the appended section after
//! `<AppendedData encoding="raw">_` is binary, so it is located by bytes and
//! never handed to the XML parser.

use glam::{UVec3, Vec3};
use quick_xml::events::{BytesStart, Event};
use quick_xml::{Reader, XmlVersion};

use super::base64;
use super::decode::{
    checked_dims, checked_spacing, parse_ascii_voxels, try_vec_with_capacity, Endian, Layout, VoxelType,
};
use super::error::FormatProblem;
use super::inflate::{check_ratio, inflate_append, Stream};
use crate::scene::volume::Volume;

const APPENDED_OPEN: &[u8] = b"<AppendedData";
const APPENDED_CLOSE: &[u8] = b"</AppendedData>";

/// Width of the size words in binary data headers (`header_type`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum HeaderType {
    U32,
    U64,
}

impl HeaderType {
    fn size(self) -> usize {
        match self {
            HeaderType::U32 => 4,
            HeaderType::U64 => 8,
        }
    }
}

/// A `<DataArray>` of `<PointData>`, with its inline text.
#[derive(Debug, Default)]
struct DataArray {
    name: Option<String>,
    type_name: String,
    components: Option<String>,
    format: Option<String>,
    offset: Option<String>,
    text: String,
}

/// What the XML part says about the image.
#[derive(Debug, Default)]
struct Document {
    file_type: Option<String>,
    byte_order: Option<String>,
    header_type: Option<String>,
    compressor: Option<String>,
    whole_extent: Option<String>,
    spacing: Option<String>,
    piece_extents: Vec<Option<String>>,
    scalars: Option<String>,
    arrays: Vec<DataArray>,
}

/// How the binary data of the file is framed.
#[derive(Clone, Copy, Debug)]
struct Framing {
    endian: Endian,
    header_type: HeaderType,
    compressed: bool,
}

pub fn load(bytes: &[u8], name: String) -> Result<Volume, FormatProblem> {
    let appended_at = find(bytes, APPENDED_OPEN);
    let xml = std::str::from_utf8(&bytes[..appended_at.unwrap_or(bytes.len())])
        .map_err(|e| FormatProblem::syntax(format!("the XML part is not UTF-8 text (byte {})", e.valid_up_to())))?;
    let document = parse_document(xml, appended_at.is_some())?;
    match document.file_type.as_deref() {
        Some("ImageData") => {}
        Some(other) => return Err(FormatProblem::unsupported(format!("VTKFile type=\"{other}\" (only ImageData)"))),
        None => return Err(FormatProblem::syntax("no <VTKFile type=\"ImageData\"> element")),
    }
    let framing = framing(&document)?;
    let (dims, spacing) = grid(&document)?;
    let array = scalar_array(&document)?;
    let layout = Layout { dims, spacing, voxel_type: voxel_type(array)?, endian: framing.endian };
    let len = layout.data_len();

    let voxels = match array.format.as_deref() {
        Some("ascii") => {
            let count = len / layout.voxel_type.size();
            let bytes = parse_ascii_voxels(&array.text, layout.voxel_type, count)?;
            // The ASCII values were converted to little-endian bytes.
            return Layout { endian: Endian::Little, ..layout }.into_volume(name, &bytes);
        }
        Some("binary") => {
            let block = base64::decode(array.text.as_bytes(), "inline DataArray")?;
            read_binary(&block, framing, len, "inline data")?
        }
        Some("appended") => {
            let at = appended_at
                .ok_or_else(|| FormatProblem::syntax("DataArray format=\"appended\" but no <AppendedData>"))?;
            let section = appended_section(bytes, at)?;
            read_appended(&section, array, framing, len)?
        }
        Some(other) => return Err(FormatProblem::bad_field("DataArray format", other, "ascii, binary or appended")),
        None => return Err(FormatProblem::MissingField("DataArray format".into())),
    };
    layout.into_volume(name, &voxels)
}

/// Byte order, header word width and compression from `<VTKFile>`.
fn framing(document: &Document) -> Result<Framing, FormatProblem> {
    let endian = match document.byte_order.as_deref() {
        None | Some("LittleEndian") => Endian::Little,
        Some("BigEndian") => Endian::Big,
        Some(other) => return Err(FormatProblem::bad_field("byte_order", other, "LittleEndian or BigEndian")),
    };
    let header_type = match document.header_type.as_deref() {
        None | Some("UInt32") => HeaderType::U32,
        Some("UInt64") => HeaderType::U64,
        Some(other) => return Err(FormatProblem::bad_field("header_type", other, "UInt32 or UInt64")),
    };
    let compressed = match document.compressor.as_deref() {
        None | Some("") => false,
        Some("vtkZLibDataCompressor") => true,
        Some(other) => {
            return Err(FormatProblem::unsupported(format!("compressor {other} (only vtkZLibDataCompressor)")))
        }
    };
    Ok(Framing { endian, header_type, compressed })
}

/// Dimensions from `WholeExtent` (one `<Piece>` must cover it) and `Spacing`.
fn grid(document: &Document) -> Result<(UVec3, Vec3), FormatProblem> {
    let extent_text =
        document.whole_extent.as_deref().ok_or_else(|| FormatProblem::MissingField("ImageData WholeExtent".into()))?;
    let extent = parse_extent("WholeExtent", extent_text)?;
    let dims = checked_dims(extent_dims(&extent, extent_text)?)?;
    match document.piece_extents.as_slice() {
        [] => return Err(FormatProblem::syntax("no <Piece> in <ImageData>")),
        [None] => {}
        [Some(piece)] => {
            if parse_extent("Piece Extent", piece)? != extent {
                return Err(FormatProblem::unsupported(format!(
                    "Piece Extent=\"{piece}\" differing from WholeExtent=\"{extent_text}\""
                )));
            }
        }
        pieces => return Err(FormatProblem::unsupported(format!("{} pieces in one file (only 1)", pieces.len()))),
    }
    let spacing = match document.spacing.as_deref() {
        Some(value) => checked_spacing(parse_numbers("Spacing", value)?)?,
        None => Vec3::ONE,
    };
    Ok((dims, spacing))
}

fn voxel_type(array: &DataArray) -> Result<VoxelType, FormatProblem> {
    if let Some(components) = array.components.as_deref() {
        if components.trim() != "1" {
            return Err(FormatProblem::unsupported(format!("NumberOfComponents=\"{components}\" (only scalar data)")));
        }
    }
    match array.type_name.as_str() {
        "UInt8" => Ok(VoxelType::U8),
        "UInt16" => Ok(VoxelType::U16),
        "Int16" => Ok(VoxelType::I16),
        "Float32" => Ok(VoxelType::F32),
        other => Err(FormatProblem::unsupported(format!(
            "DataArray type=\"{other}\" (supported: UInt8, UInt16, Int16, Float32)"
        ))),
    }
}

/// The array at its `offset` in the appended section.
fn read_appended(
    section: &AppendedSection,
    array: &DataArray,
    framing: Framing,
    len: usize,
) -> Result<Vec<u8>, FormatProblem> {
    let offset_text = array.offset.as_deref().ok_or_else(|| FormatProblem::MissingField("DataArray offset".into()))?;
    let offset: u64 = offset_text
        .trim()
        .parse()
        .map_err(|_| FormatProblem::bad_field("DataArray offset", offset_text, "a byte offset"))?;
    if offset > section.data.len() as u64 {
        return Err(FormatProblem::Truncated {
            what: "appended data".into(),
            expected: offset,
            found: section.data.len() as u64,
        });
    }
    let tail = &section.data[offset as usize..];
    if section.base64 {
        // Offsets count base64 characters; decoding the rest of the section is
        // simplest, and each array's runs are padded on their own.
        let block = base64::decode(tail, "appended data")?;
        read_binary(&block, framing, len, "appended data")
    } else {
        read_binary(tail, framing, len, "appended data")
    }
}

/// The point-data array named by `<PointData Scalars=...>`, else the first one.
fn scalar_array(document: &Document) -> Result<&DataArray, FormatProblem> {
    match document.scalars.as_deref() {
        Some(wanted) => document
            .arrays
            .iter()
            .find(|a| a.name.as_deref() == Some(wanted))
            .ok_or_else(|| FormatProblem::syntax(format!("<PointData Scalars=\"{wanted}\"> names no DataArray"))),
        None => document.arrays.first().ok_or_else(|| FormatProblem::syntax("no DataArray in <PointData>")),
    }
}

/// Walks the XML part; with `cut_at_appended`, it ends just before
/// `<AppendedData`, so only `<VTKFile>` may still be open.
fn parse_document(xml: &str, cut_at_appended: bool) -> Result<Document, FormatProblem> {
    let mut reader = Reader::from_str(xml);
    let mut document = Document::default();
    let mut stack: Vec<String> = Vec::new();
    // Index of the open DataArray in `document.arrays`, if inside PointData.
    let mut open_array: Option<usize> = None;
    loop {
        let event = reader
            .read_event()
            .map_err(|e| FormatProblem::syntax(format!("XML error near byte {}: {e}", reader.error_position())))?;
        match event {
            Event::Start(tag) => {
                let name = tag_name(&tag);
                let array = visit_element(&mut document, &stack, &name, &tag)?;
                open_array = array;
                stack.push(name);
            }
            Event::Empty(tag) => {
                let name = tag_name(&tag);
                visit_element(&mut document, &stack, &name, &tag)?;
            }
            Event::End(_) => {
                // quick-xml has checked that the end tag matches.
                stack.pop();
                open_array = None;
            }
            Event::Text(text) => {
                if let Some(i) = open_array {
                    document.arrays[i].text.push_str(&text.xml10_content());
                }
            }
            Event::CData(data) => {
                if let Some(i) = open_array {
                    document.arrays[i].text.push_str(&data);
                }
            }
            Event::GeneralRef(_) if open_array.is_some() => {
                return Err(FormatProblem::syntax("entity reference inside DataArray data"));
            }
            Event::Eof => break,
            _ => {}
        }
    }
    let expected_open: &[&str] = if cut_at_appended { &["VTKFile"] } else { &[] };
    if stack != expected_open {
        return Err(FormatProblem::syntax(match stack.last() {
            Some(open) => format!("the XML ends inside <{open}> (file truncated?)"),
            None => "<AppendedData> is not inside <VTKFile>".to_string(),
        }));
    }
    Ok(document)
}

fn tag_name(tag: &BytesStart) -> String {
    tag.name().as_ref().to_string()
}

fn attribute(tag: &BytesStart, key: &str) -> Result<Option<String>, FormatProblem> {
    let bad =
        |e: &dyn std::fmt::Display| FormatProblem::syntax(format!("bad attribute {key} of <{}>: {e}", tag_name(tag)));
    match tag.try_get_attribute(key).map_err(|e| bad(&e))? {
        Some(attribute) => {
            Ok(Some(attribute.normalized_value(XmlVersion::Implicit1_0).map_err(|e| bad(&e))?.into_owned()))
        }
        None => Ok(None),
    }
}

/// Records what an element contributes; returns the index of a new point-data array.
fn visit_element(
    document: &mut Document,
    stack: &[String],
    name: &str,
    tag: &BytesStart,
) -> Result<Option<usize>, FormatProblem> {
    let parent = stack.last().map(String::as_str);
    match (parent, name) {
        (None, "VTKFile") => {
            document.file_type = attribute(tag, "type")?;
            document.byte_order = attribute(tag, "byte_order")?;
            document.header_type = attribute(tag, "header_type")?;
            document.compressor = attribute(tag, "compressor")?;
        }
        (None, other) => return Err(FormatProblem::syntax(format!("root element is <{other}>, not <VTKFile>"))),
        (Some("VTKFile"), "ImageData") => {
            document.whole_extent = attribute(tag, "WholeExtent")?;
            document.spacing = attribute(tag, "Spacing")?;
        }
        (Some("ImageData"), "Piece") => document.piece_extents.push(attribute(tag, "Extent")?),
        (Some("Piece"), "PointData") => document.scalars = attribute(tag, "Scalars")?,
        (Some("PointData"), "DataArray") => {
            document.arrays.push(DataArray {
                name: attribute(tag, "Name")?,
                type_name: attribute(tag, "type")?.unwrap_or_default(),
                components: attribute(tag, "NumberOfComponents")?,
                format: attribute(tag, "format")?,
                offset: attribute(tag, "offset")?,
                text: String::new(),
            });
            return Ok(Some(document.arrays.len() - 1));
        }
        _ => {}
    }
    Ok(None)
}

fn parse_numbers<T: std::str::FromStr + Copy + Default, const N: usize>(
    field: &str,
    value: &str,
) -> Result<[T; N], FormatProblem> {
    super::fields::parse_array(field, value, &format!("{N} numbers"))
}

fn parse_extent(field: &str, value: &str) -> Result<[i64; 6], FormatProblem> {
    parse_numbers(field, value)
}

fn extent_dims(extent: &[i64; 6], text: &str) -> Result<[i64; 3], FormatProblem> {
    let mut dims = [0i64; 3];
    for (axis, d) in dims.iter_mut().enumerate() {
        *d = extent[2 * axis + 1]
            .checked_sub(extent[2 * axis])
            .and_then(|n| n.checked_add(1))
            .ok_or_else(|| FormatProblem::bad_field("WholeExtent", text, "a sane extent"))?;
    }
    Ok(dims)
}

/// The appended section: where its data starts (after `_`) and ends (at the last
/// `</AppendedData>`, which must be followed only by `</VTKFile>`).
struct AppendedSection<'a> {
    data: &'a [u8],
    base64: bool,
}

fn appended_section(bytes: &[u8], at: usize) -> Result<AppendedSection<'_>, FormatProblem> {
    let tag_len = bytes[at..]
        .iter()
        .position(|&b| b == b'>')
        .ok_or_else(|| FormatProblem::syntax("the <AppendedData> tag is not closed"))?;
    let tag_text = std::str::from_utf8(&bytes[at..=at + tag_len])
        .map_err(|_| FormatProblem::syntax("the <AppendedData> tag is not text"))?;
    let mut reader = Reader::from_str(tag_text);
    let encoding = match reader.read_event() {
        Ok(Event::Start(tag)) => attribute(&tag, "encoding")?,
        _ => return Err(FormatProblem::syntax("malformed <AppendedData> tag")),
    };
    let base64 = match encoding.as_deref() {
        None | Some("raw") => false,
        Some("base64") => true,
        Some(other) => return Err(FormatProblem::bad_field("AppendedData encoding", other, "raw or base64")),
    };
    let after_tag = at + tag_len + 1;
    let underscore = bytes[after_tag..]
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .map(|i| after_tag + i)
        .filter(|&i| bytes[i] == b'_')
        .ok_or_else(|| FormatProblem::syntax("the appended data does not start with `_`"))?;
    let start = underscore + 1;
    let end = rfind(&bytes[start..], APPENDED_CLOSE)
        .map(|i| start + i)
        .ok_or_else(|| FormatProblem::syntax("no </AppendedData> after the appended data (file truncated?)"))?;
    let rest = &bytes[end + APPENDED_CLOSE.len()..];
    if rest.trim_ascii() != b"</VTKFile>" {
        return Err(FormatProblem::syntax(
            "the file does not end with </VTKFile> after </AppendedData> (file truncated?)",
        ));
    }
    Ok(AppendedSection { data: &bytes[start..end], base64 })
}

/// Reads one size word of the binary header.
fn word(bytes: &[u8], index: usize, framing: Framing) -> u64 {
    let at = index * framing.header_type.size();
    let b = &bytes[at..at + framing.header_type.size()];
    match (framing.header_type, framing.endian) {
        (HeaderType::U32, Endian::Little) => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as u64,
        (HeaderType::U32, Endian::Big) => u32::from_be_bytes([b[0], b[1], b[2], b[3]]) as u64,
        (HeaderType::U64, Endian::Little) => u64::from_le_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]]),
        (HeaderType::U64, Endian::Big) => u64::from_be_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]]),
    }
}

fn need(block: &[u8], bytes: u64, what: &str) -> Result<(), FormatProblem> {
    if (block.len() as u64) < bytes {
        return Err(FormatProblem::Truncated { what: what.to_string(), expected: bytes, found: block.len() as u64 });
    }
    Ok(())
}

/// Decodes one binary array (its size header, then the data) starting at
/// `block`, which may run on past the array; the array must hold `len` bytes.
fn read_binary(block: &[u8], framing: Framing, len: usize, what: &str) -> Result<Vec<u8>, FormatProblem> {
    let word_size = framing.header_type.size() as u64;
    let size_mismatch = |holds: u64| {
        FormatProblem::syntax(format!("{what}: the DataArray holds {holds} bytes, but WholeExtent and type need {len}"))
    };
    if !framing.compressed {
        need(block, word_size, &format!("{what} header"))?;
        let size = word(block, 0, framing);
        if size != len as u64 {
            return Err(size_mismatch(size));
        }
        need(block, word_size + size, what)?;
        let data = &block[word_size as usize..][..len];
        let mut out = try_vec_with_capacity(len, what)?;
        out.extend_from_slice(data);
        return Ok(out);
    }

    // Compressed: [#blocks][block size][last block size][compressed size x #blocks].
    need(block, 3 * word_size, &format!("{what} compression header"))?;
    let blocks = word(block, 0, framing);
    let block_size = word(block, 1, framing);
    let last_size = word(block, 2, framing);
    let header_len = blocks
        .checked_add(3)
        .and_then(|w| w.checked_mul(word_size))
        .ok_or_else(|| FormatProblem::syntax(format!("{what}: absurd block count {blocks}")))?;
    need(block, header_len, &format!("{what} compression header"))?;
    let last_size = if last_size == 0 { block_size } else { last_size };
    let total = match blocks {
        0 => Some(0),
        n => (n - 1).checked_mul(block_size).and_then(|t| t.checked_add(last_size)),
    };
    match total {
        Some(total) if total == len as u64 => {}
        Some(total) => return Err(size_mismatch(total)),
        None => return Err(FormatProblem::syntax(format!("{what}: absurd block sizes"))),
    }
    if blocks > 1 && last_size > block_size {
        return Err(FormatProblem::syntax(format!(
            "{what}: last block ({last_size} bytes) larger than the block size ({block_size})"
        )));
    }

    // The header fits in `block`, so `blocks` is bounded by the file size here.
    let compressed_sizes: Vec<u64> = (0..blocks as usize).map(|i| word(block, 3 + i, framing)).collect();
    let compressed_total = compressed_sizes
        .iter()
        .try_fold(0u64, |sum, &s| sum.checked_add(s))
        .ok_or_else(|| FormatProblem::syntax(format!("{what}: absurd compressed sizes")))?;
    check_ratio(compressed_total, len as u64, what)?;

    let mut out = try_vec_with_capacity(len + 1, what)?;
    let mut position = header_len;
    for (index, &compressed) in compressed_sizes.iter().enumerate() {
        let block_what = format!("{what} block {index}");
        let available = (block.len() as u64).saturating_sub(position);
        if available < compressed {
            return Err(FormatProblem::Truncated { what: block_what, expected: compressed, found: available });
        }
        let input = &block[position as usize..(position + compressed) as usize];
        let size = if index + 1 == compressed_sizes.len() { last_size } else { block_size };
        inflate_append(input, Stream::Zlib, size as usize, &block_what, &mut out)?;
        position += compressed;
    }
    Ok(out)
}

fn find(haystack: &[u8], needle: &[u8]) -> Option<usize> {
    haystack.windows(needle.len()).position(|w| w == needle)
}

fn rfind(haystack: &[u8], needle: &[u8]) -> Option<usize> {
    haystack.windows(needle.len()).rposition(|w| w == needle)
}
