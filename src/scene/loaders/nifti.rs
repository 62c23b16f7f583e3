//! NIfTI-1 single files (`.nii`, and `.nii.gz` gzip-compressed): the 348-byte
//! header read by hand (see docs/volume-formats.md for why not the `nifti` crate).
//!
//! Header fields used (byte offsets): sizeof_hdr (0), dim[8] (40, i16), datatype
//! (70, i16), bitpix (72, i16), pixdim[8] (76, f32), vox_offset (108, f32),
//! scl_slope (112, f32), scl_inter (116, f32), magic (344, "n+1\0").

use std::io::Read;

use flate2::read::MultiGzDecoder;

use super::decode::{checked_dims, checked_spacing, try_vec_with_capacity, Endian, Layout, VoxelType};
use super::error::FormatProblem;
use super::inflate::check_ratio;
use crate::scene::volume::Volume;

const HEADER_LEN: usize = 348;
/// Largest accepted vox_offset: header extensions beyond this are not plausible,
/// and a hostile value must not make us inflate gigabytes just to skip them.
const MAX_VOX_OFFSET: u64 = 1 << 30;

struct Header {
    layout: Layout,
    vox_offset: u64,
    /// (slope, intercept) when the header asks to scale the stored values.
    scaling: Option<(f64, f64)>,
}

/// Loads a `.nii` file already in memory.
pub fn load(bytes: &[u8], name: String) -> Result<Volume, FormatProblem> {
    let header = parse_header(bytes)?;
    let len = header.layout.data_len();
    let start = header.vox_offset;
    let expected = start + len as u64;
    let found = bytes.len() as u64;
    if found < expected {
        return Err(FormatProblem::Truncated { what: "voxel data".into(), expected, found });
    }
    if found > expected {
        return Err(FormatProblem::TooLong { what: "file".into(), expected, found });
    }
    finish(header, name, &bytes[start as usize..])
}

/// Loads a `.nii.gz` file: inflates the header first, so that the data size it
/// promises bounds everything inflated after it.
pub fn load_gzip(compressed: &[u8], name: String) -> Result<Volume, FormatProblem> {
    let what = "gzip stream";
    let bad_stream = |e: std::io::Error| FormatProblem::Decompress { what: what.into(), reason: e.to_string() };
    let mut stream = MultiGzDecoder::new(compressed);
    let mut header_bytes = [0u8; HEADER_LEN];
    let got = read_up_to(&mut stream, &mut header_bytes).map_err(bad_stream)?;
    if got < HEADER_LEN {
        return Err(FormatProblem::InflatedTooShort {
            what: "NIfTI header in the gzip stream".into(),
            expected: HEADER_LEN as u64,
            found: got as u64,
        });
    }
    let header = parse_header(&header_bytes)?;
    let len = header.layout.data_len();
    let total = header.vox_offset + len as u64;
    check_ratio(compressed.len() as u64, total, what)?;

    let gap = header.vox_offset - HEADER_LEN as u64;
    let skipped = std::io::copy(&mut (&mut stream).take(gap), &mut std::io::sink()).map_err(bad_stream)?;
    let mut data = try_vec_with_capacity(len + 1, "voxel data")?;
    (&mut stream).take(len as u64 + 1).read_to_end(&mut data).map_err(bad_stream)?;
    let inflated = HEADER_LEN as u64 + skipped + data.len() as u64;
    if inflated < total {
        return Err(FormatProblem::InflatedTooShort { what: what.into(), expected: total, found: inflated });
    }
    if data.len() > len {
        return Err(FormatProblem::InflatedTooLong { what: what.into(), expected: total });
    }
    finish(header, name, &data)
}

/// Reads until `buf` is full or the stream ends; returns the bytes read.
fn read_up_to(stream: &mut impl Read, buf: &mut [u8]) -> std::io::Result<usize> {
    let mut filled = 0;
    while filled < buf.len() {
        match stream.read(&mut buf[filled..]) {
            Ok(0) => break,
            Ok(n) => filled += n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(filled)
}

fn finish(header: Header, name: String, data: &[u8]) -> Result<Volume, FormatProblem> {
    let mut volume = header.layout.into_volume(name, data)?;
    if let Some((slope, intercept)) = header.scaling {
        // The stored values map affinely to real ones; with slope > 0 the normalized
        // data is unchanged, only the range is in real units.
        let (lo, hi) = volume.value_range;
        volume.value_range = (lo * slope + intercept, hi * slope + intercept);
    }
    Ok(volume)
}

struct Fields<'a> {
    bytes: &'a [u8],
    endian: Endian,
}

impl Fields<'_> {
    fn i16(&self, at: usize) -> i16 {
        let b = [self.bytes[at], self.bytes[at + 1]];
        match self.endian {
            Endian::Little => i16::from_le_bytes(b),
            Endian::Big => i16::from_be_bytes(b),
        }
    }

    fn i32(&self, at: usize) -> i32 {
        let b = [self.bytes[at], self.bytes[at + 1], self.bytes[at + 2], self.bytes[at + 3]];
        match self.endian {
            Endian::Little => i32::from_le_bytes(b),
            Endian::Big => i32::from_be_bytes(b),
        }
    }

    fn f32(&self, at: usize) -> f32 {
        f32::from_bits(self.i32(at) as u32)
    }
}

fn parse_header(bytes: &[u8]) -> Result<Header, FormatProblem> {
    if bytes.len() < HEADER_LEN {
        return Err(FormatProblem::Truncated {
            what: "NIfTI header".into(),
            expected: HEADER_LEN as u64,
            found: bytes.len() as u64,
        });
    }
    let bytes = &bytes[..HEADER_LEN];
    // sizeof_hdr is 348 in the file's byte order, which it thereby reveals.
    let sizeof_hdr = [bytes[0], bytes[1], bytes[2], bytes[3]];
    let endian = match (i32::from_le_bytes(sizeof_hdr), i32::from_be_bytes(sizeof_hdr)) {
        (348, _) => Endian::Little,
        (_, 348) => Endian::Big,
        (540, _) | (_, 540) => return Err(FormatProblem::unsupported("NIfTI-2 file")),
        _ => return Err(FormatProblem::syntax("not a NIfTI-1 file: sizeof_hdr is not 348")),
    };
    let f = Fields { bytes, endian };
    match &bytes[344..348] {
        b"n+1\0" => {}
        b"ni1\0" => {
            return Err(FormatProblem::unsupported("NIfTI-1 header/image pair (magic ni1); only single .nii files"))
        }
        _ => return Err(FormatProblem::syntax("not a NIfTI-1 file: magic is not n+1")),
    }

    let dim: [i16; 8] = std::array::from_fn(|i| f.i16(40 + 2 * i));
    let rank = dim[0];
    if !(1..=7).contains(&rank) {
        return Err(FormatProblem::syntax(format!("dim[0] = {rank}: must be 1 to 7")));
    }
    if rank < 3 {
        return Err(FormatProblem::unsupported(format!("{rank}-D image (dim[0] = {rank}); volumes need 3")));
    }
    if let Some(axis) = (4..=rank as usize).find(|&i| dim[i] != 1) {
        return Err(FormatProblem::unsupported(format!(
            "dim[{axis}] = {}: time series and vector data (only dim[4..] = 1)",
            dim[axis]
        )));
    }
    let dims = checked_dims([dim[1] as i64, dim[2] as i64, dim[3] as i64])?;

    let datatype = f.i16(70);
    let bitpix = f.i16(72);
    let voxel_type = match datatype {
        2 => VoxelType::U8,
        4 => VoxelType::I16,
        512 => VoxelType::U16,
        16 => VoxelType::F32,
        other => {
            return Err(FormatProblem::unsupported(format!(
                "datatype {other} (supported: 2 uint8, 4 int16, 512 uint16, 16 float32)"
            )))
        }
    };
    if bitpix as usize != 8 * voxel_type.size() {
        return Err(FormatProblem::syntax(format!(
            "bitpix {bitpix} does not match datatype {datatype} ({})",
            voxel_type.name()
        )));
    }

    let pixdim: [f64; 3] = std::array::from_fn(|i| f.f32(76 + 4 * (i + 1)) as f64);
    let spacing = checked_spacing(pixdim)?;

    let vox_offset = f.f32(108);
    let valid_offset = vox_offset.is_finite()
        && vox_offset.fract() == 0.0
        && vox_offset >= HEADER_LEN as f32
        && (vox_offset as u64) <= MAX_VOX_OFFSET;
    if !valid_offset {
        return Err(FormatProblem::syntax(format!(
            "vox_offset {vox_offset}: must be a whole number of bytes from {HEADER_LEN} to {MAX_VOX_OFFSET}"
        )));
    }

    let slope = f.f32(112) as f64;
    let intercept = f.f32(116) as f64;
    // slope 0 (or not a number) means "no scaling" per the NIfTI-1 standard.
    let scaling = if slope == 0.0 || !slope.is_finite() {
        None
    } else if slope < 0.0 || !intercept.is_finite() {
        return Err(FormatProblem::unsupported(format!(
            "value scaling scl_slope = {slope}, scl_inter = {intercept} (slope must be > 0)"
        )));
    } else {
        Some((slope, intercept))
    };

    Ok(Header { layout: Layout { dims, spacing, voxel_type, endian }, vox_offset: vox_offset as u64, scaling })
}
