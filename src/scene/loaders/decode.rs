//! Voxel types and byte orders of volume files, the limits every header must pass,
//! and the conversion of raw voxel bytes into normalized [`VoxelData`].
//!
//! Normalization (see `src/scene/volume.rs`): uint8 is kept as is (s = v / 255);
//! uint16 and int16 are rescaled from the data's own [min, max] onto the full u16
//! range; float32 is rescaled from [min, max] onto [0, 1]; constant data maps to 0.

use glam::{UVec3, Vec3};

use super::error::FormatProblem;
use crate::scene::volume::{Interpolation, Volume, VoxelData};

/// Longest axis accepted: above any GPU's 3D image limit, and small enough that a
/// hostile header cannot make us compute absurd sizes.
pub const MAX_DIM: i64 = 32_768;
/// Most voxels accepted in one volume (16 GiB as float32).
pub const MAX_VOXELS: u64 = 1 << 32;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VoxelType {
    U8,
    U16,
    I16,
    F32,
}

impl VoxelType {
    pub fn size(self) -> usize {
        match self {
            VoxelType::U8 => 1,
            VoxelType::U16 | VoxelType::I16 => 2,
            VoxelType::F32 => 4,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            VoxelType::U8 => "uint8",
            VoxelType::U16 => "uint16",
            VoxelType::I16 => "int16",
            VoxelType::F32 => "float32",
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Endian {
    Little,
    Big,
}

/// Checks dimensions read from a header: each in 1..=MAX_DIM, product <= MAX_VOXELS.
pub fn checked_dims(dims: [i64; 3]) -> Result<UVec3, FormatProblem> {
    let bad = |reason: String| FormatProblem::BadDims { dims, reason };
    if dims.iter().any(|&d| d < 1) {
        return Err(bad("every dimension must be at least 1".into()));
    }
    if dims.iter().any(|&d| d > MAX_DIM) {
        return Err(bad(format!("a dimension exceeds the limit of {MAX_DIM}")));
    }
    // Each factor is <= 2^15, so the product fits in u64.
    let voxels = dims.iter().map(|&d| d as u64).product::<u64>();
    if voxels > MAX_VOXELS {
        return Err(bad(format!("{voxels} voxels exceed the limit of {MAX_VOXELS}")));
    }
    Ok(UVec3::new(dims[0] as u32, dims[1] as u32, dims[2] as u32))
}

/// Checks a spacing read from a header: finite and > 0, also after rounding to f32.
pub fn checked_spacing(spacing: [f64; 3]) -> Result<Vec3, FormatProblem> {
    let single = Vec3::new(spacing[0] as f32, spacing[1] as f32, spacing[2] as f32);
    let valid = |s: f32| s.is_finite() && s > 0.0;
    if spacing.iter().all(|s| s.is_finite()) && single.to_array().into_iter().all(valid) {
        Ok(single)
    } else {
        Err(FormatProblem::BadSpacing { spacing })
    }
}

/// Bytes of voxel data for checked `dims` (at most 16 GiB, so no overflow).
pub fn data_len(dims: UVec3, voxel_type: VoxelType) -> usize {
    dims.x as usize * dims.y as usize * dims.z as usize * voxel_type.size()
}

/// A volume's layout as a header describes it, before its data is read.
#[derive(Clone, Copy, Debug)]
pub struct Layout {
    pub dims: UVec3,
    pub spacing: Vec3,
    pub voxel_type: VoxelType,
    pub endian: Endian,
}

impl Layout {
    pub fn data_len(&self) -> usize {
        data_len(self.dims, self.voxel_type)
    }

    /// Decodes `bytes` (exactly [`Layout::data_len`] of them) into a volume.
    pub fn into_volume(self, name: String, bytes: &[u8]) -> Result<Volume, FormatProblem> {
        let expected = self.data_len();
        if bytes.len() < expected {
            return Err(FormatProblem::Truncated {
                what: "voxel data".into(),
                expected: expected as u64,
                found: bytes.len() as u64,
            });
        }
        if bytes.len() > expected {
            return Err(FormatProblem::TooLong {
                what: "voxel data".into(),
                expected: expected as u64,
                found: bytes.len() as u64,
            });
        }
        let (data, value_range, non_finite_voxels) = decode_voxels(bytes, self.voxel_type, self.endian)?;
        Ok(Volume {
            name,
            dims: self.dims,
            spacing: self.spacing,
            data,
            value_range,
            non_finite_voxels,
            interpolation: Interpolation::Trilinear,
        })
    }
}

/// Converts raw voxels into normalized storage; returns it with the raw [min, max]
/// and the count of non-finite voxels. Non-finite floats are left out of the
/// range; NaN and -inf map to 0, +inf to 1 (counted, so the user can be warned).
pub fn decode_voxels(
    bytes: &[u8],
    voxel_type: VoxelType,
    endian: Endian,
) -> Result<(VoxelData, (f64, f64), u64), FormatProblem> {
    let count = bytes.len() / voxel_type.size();
    match voxel_type {
        VoxelType::U8 => {
            let (lo, hi) = bytes.iter().fold((u8::MAX, u8::MIN), |(lo, hi), &v| (lo.min(v), hi.max(v)));
            let range = if bytes.is_empty() { (0.0, 0.0) } else { (lo as f64, hi as f64) };
            Ok((VoxelData::U8(copy_bytes(bytes)?), range, 0))
        }
        VoxelType::U16 => {
            let values = bytes.chunks_exact(2).map(|c| read_u16(c, endian) as i32);
            let (data, range) = rescale_integers(values, count)?;
            Ok((data, range, 0))
        }
        VoxelType::I16 => {
            let values = bytes.chunks_exact(2).map(|c| read_u16(c, endian) as i16 as i32);
            let (data, range) = rescale_integers(values, count)?;
            Ok((data, range, 0))
        }
        VoxelType::F32 => {
            let values = bytes.chunks_exact(4).map(|c| f32::from_bits(read_u32(c, endian)));
            let non_finite = values.clone().filter(|v| !v.is_finite()).count() as u64;
            let (data, range) = rescale_floats(values, count)?;
            Ok((data, range, non_finite))
        }
    }
}

fn copy_bytes(bytes: &[u8]) -> Result<Vec<u8>, FormatProblem> {
    let mut out = try_vec_with_capacity(bytes.len(), "voxel data")?;
    out.extend_from_slice(bytes);
    Ok(out)
}

/// `Vec::with_capacity` that reports a failed allocation instead of aborting.
pub fn try_vec_with_capacity<T>(len: usize, what: &str) -> Result<Vec<T>, FormatProblem> {
    let mut v = Vec::new();
    v.try_reserve_exact(len).map_err(|_| FormatProblem::OutOfMemory {
        what: what.to_string(),
        bytes: (len as u64).saturating_mul(std::mem::size_of::<T>() as u64),
    })?;
    Ok(v)
}

fn read_u16(c: &[u8], endian: Endian) -> u16 {
    let b = [c[0], c[1]];
    match endian {
        Endian::Little => u16::from_le_bytes(b),
        Endian::Big => u16::from_be_bytes(b),
    }
}

fn read_u32(c: &[u8], endian: Endian) -> u32 {
    let b = [c[0], c[1], c[2], c[3]];
    match endian {
        Endian::Little => u32::from_le_bytes(b),
        Endian::Big => u32::from_be_bytes(b),
    }
}

/// Maps [min, max] of 16-bit integers onto 0..=65535, rounding to nearest.
fn rescale_integers(
    values: impl Iterator<Item = i32> + Clone,
    count: usize,
) -> Result<(VoxelData, (f64, f64)), FormatProblem> {
    let (lo, hi) = values.clone().fold((i32::MAX, i32::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
    let mut out = try_vec_with_capacity(count, "voxel data")?;
    if count == 0 {
        return Ok((VoxelData::U16(out), (0.0, 0.0)));
    }
    let span = (hi - lo) as u64;
    if span == 0 {
        out.resize(count, 0);
    } else {
        // Integer arithmetic so rounding is exact: (2 * d * 65535 + span) / (2 * span).
        out.extend(values.map(|v| {
            let d = (v - lo) as u64;
            ((2 * d * 65535 + span) / (2 * span)) as u16
        }));
    }
    Ok((VoxelData::U16(out), (lo as f64, hi as f64)))
}

/// Maps [min, max] of the finite floats onto [0, 1].
fn rescale_floats(
    values: impl Iterator<Item = f32> + Clone,
    count: usize,
) -> Result<(VoxelData, (f64, f64)), FormatProblem> {
    let (lo, hi) = values
        .clone()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v as f64), hi.max(v as f64)));
    let mut out = try_vec_with_capacity(count, "voxel data")?;
    if lo > hi {
        // No finite value at all: treat as constant.
        out.extend(values.map(|v| if v == f32::INFINITY { 1.0 } else { 0.0 }));
        return Ok((VoxelData::F32(out), (0.0, 0.0)));
    }
    let span = hi - lo;
    out.extend(values.map(|v| {
        if v.is_nan() || v == f32::NEG_INFINITY {
            0.0
        } else if v == f32::INFINITY {
            1.0
        } else if span == 0.0 {
            0.0
        } else {
            ((v as f64 - lo) / span) as f32
        }
    }));
    Ok((VoxelData::F32(out), (lo, hi)))
}

/// Parses whitespace-separated numbers of `voxel_type` (ASCII encodings) into
/// little-endian bytes; exactly `count` values are expected.
pub fn parse_ascii_voxels(text: &str, voxel_type: VoxelType, count: usize) -> Result<Vec<u8>, FormatProblem> {
    let found = text.split_ascii_whitespace().count();
    if found < count {
        return Err(FormatProblem::Truncated {
            what: format!("ASCII voxel data ({count} values expected, {found} found)"),
            expected: (count * voxel_type.size()) as u64,
            found: (found * voxel_type.size()) as u64,
        });
    }
    if found > count {
        return Err(FormatProblem::syntax(format!("ASCII voxel data has {found} values, expected {count}")));
    }
    let mut out = try_vec_with_capacity(count * voxel_type.size(), "voxel data")?;
    for (index, token) in text.split_ascii_whitespace().enumerate() {
        let bad =
            || FormatProblem::syntax(format!("ASCII voxel {index}: `{token}` is not a {} value", voxel_type.name()));
        match voxel_type {
            VoxelType::U8 => out.push(token.parse::<u8>().map_err(|_| bad())?),
            VoxelType::U16 => out.extend_from_slice(&token.parse::<u16>().map_err(|_| bad())?.to_le_bytes()),
            VoxelType::I16 => out.extend_from_slice(&token.parse::<i16>().map_err(|_| bad())?.to_le_bytes()),
            VoxelType::F32 => out.extend_from_slice(&token.parse::<f32>().map_err(|_| bad())?.to_le_bytes()),
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dims_must_be_positive_and_bounded() {
        assert!(checked_dims([1, 2, 3]).is_ok());
        assert!(checked_dims([0, 2, 3]).is_err());
        assert!(checked_dims([-4, 2, 3]).is_err());
        assert!(checked_dims([MAX_DIM + 1, 1, 1]).is_err());
        assert!(checked_dims([MAX_DIM, MAX_DIM, MAX_DIM]).is_err());
        assert!(checked_dims([i64::MAX, i64::MAX, i64::MAX]).is_err());
    }

    #[test]
    fn spacing_must_be_positive_and_finite_in_f32() {
        assert!(checked_spacing([1.0, 0.5, 2.5]).is_ok());
        assert!(checked_spacing([0.0, 1.0, 1.0]).is_err());
        assert!(checked_spacing([1.0, -1.0, 1.0]).is_err());
        assert!(checked_spacing([1.0, 1.0, f64::NAN]).is_err());
        assert!(checked_spacing([1.0, f64::INFINITY, 1.0]).is_err());
        // Positive in f64 but 0 or inf once stored as f32.
        assert!(checked_spacing([1e-60, 1.0, 1.0]).is_err());
        assert!(checked_spacing([1e60, 1.0, 1.0]).is_err());
    }

    #[test]
    fn int16_rescales_min_to_0_and_max_to_65535() {
        let values: [i16; 4] = [-100, 0, 50, 100];
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_be_bytes()).collect();
        let (data, range, _) = decode_voxels(&bytes, VoxelType::I16, Endian::Big).unwrap();
        assert_eq!(range, (-100.0, 100.0));
        // 100/200 * 65535 = 32767.5 rounds up; 150/200 * 65535 = 49151.25 rounds down.
        assert_eq!(data, VoxelData::U16(vec![0, 32768, 49151, 65535]));
    }

    #[test]
    fn constant_data_maps_to_zero() {
        let bytes: Vec<u8> = [7u16; 5].iter().flat_map(|v| v.to_le_bytes()).collect();
        let (data, range, _) = decode_voxels(&bytes, VoxelType::U16, Endian::Little).unwrap();
        assert_eq!(range, (7.0, 7.0));
        assert_eq!(data, VoxelData::U16(vec![0; 5]));
        let bytes: Vec<u8> = [2.5f32; 3].iter().flat_map(|v| v.to_le_bytes()).collect();
        let (data, _, _) = decode_voxels(&bytes, VoxelType::F32, Endian::Little).unwrap();
        assert_eq!(data, VoxelData::F32(vec![0.0; 3]));
    }

    #[test]
    fn non_finite_floats_stay_out_of_the_range() {
        let values = [f32::NAN, 1.0, 3.0, f32::INFINITY, f32::NEG_INFINITY, 2.0];
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let (data, range, _) = decode_voxels(&bytes, VoxelType::F32, Endian::Little).unwrap();
        assert_eq!(range, (1.0, 3.0));
        assert_eq!(data, VoxelData::F32(vec![0.0, 0.0, 1.0, 1.0, 0.0, 0.5]));
    }

    #[test]
    fn ascii_values_are_checked_against_the_type() {
        let bytes = parse_ascii_voxels("1 2\n 300", VoxelType::U16, 3).unwrap();
        assert_eq!(bytes, vec![1, 0, 2, 0, 44, 1]);
        assert!(parse_ascii_voxels("1 2 300", VoxelType::U8, 3).is_err());
        assert!(parse_ascii_voxels("1 2", VoxelType::U8, 3).is_err());
        assert!(parse_ascii_voxels("1 2 3 4", VoxelType::U8, 3).is_err());
        assert!(parse_ascii_voxels("1 x 3", VoxelType::F32, 3).is_err());
    }
}
