//! Small synthetic volumes and the normalized values the loaders must produce
//! for them, computed here from the convention (not from the library).

use sweeplab::scene::{Volume, VoxelData};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Endian {
    Little,
    Big,
}

pub const ENDIANS: [Endian; 2] = [Endian::Little, Endian::Big];

#[derive(Clone, Debug, PartialEq)]
pub enum Values {
    U8(Vec<u8>),
    U16(Vec<u16>),
    I16(Vec<i16>),
    F32(Vec<f32>),
}

impl Values {
    pub fn len(&self) -> usize {
        match self {
            Values::U8(v) => v.len(),
            Values::U16(v) => v.len(),
            Values::I16(v) => v.len(),
            Values::F32(v) => v.len(),
        }
    }

    /// The voxels as stored in a file of the given byte order.
    pub fn bytes(&self, endian: Endian) -> Vec<u8> {
        let big = endian == Endian::Big;
        match self {
            Values::U8(v) => v.clone(),
            Values::U16(v) => v.iter().flat_map(|x| if big { x.to_be_bytes() } else { x.to_le_bytes() }).collect(),
            Values::I16(v) => v.iter().flat_map(|x| if big { x.to_be_bytes() } else { x.to_le_bytes() }).collect(),
            Values::F32(v) => v.iter().flat_map(|x| if big { x.to_be_bytes() } else { x.to_le_bytes() }).collect(),
        }
    }

    /// Whitespace-separated decimal text of the voxels (ASCII encodings).
    pub fn ascii(&self) -> String {
        let tokens: Vec<String> = match self {
            Values::U8(v) => v.iter().map(|x| x.to_string()).collect(),
            Values::U16(v) => v.iter().map(|x| x.to_string()).collect(),
            Values::I16(v) => v.iter().map(|x| x.to_string()).collect(),
            // Rust prints the shortest text that parses back to the same f32.
            Values::F32(v) => v.iter().map(|x| x.to_string()).collect(),
        };
        tokens.chunks(7).map(|line| line.join(" ")).collect::<Vec<_>>().join("\n")
    }

    /// Raw values as f64, in file units.
    pub fn as_f64(&self) -> Vec<f64> {
        match self {
            Values::U8(v) => v.iter().map(|&x| x as f64).collect(),
            Values::U16(v) => v.iter().map(|&x| x as f64).collect(),
            Values::I16(v) => v.iter().map(|&x| x as f64).collect(),
            Values::F32(v) => v.iter().map(|&x| x as f64).collect(),
        }
    }

    pub fn range(&self) -> (f64, f64) {
        let v = self.as_f64();
        let lo = v.iter().cloned().fold(f64::INFINITY, f64::min);
        let hi = v.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        (lo, hi)
    }
}

#[derive(Clone, Debug)]
pub struct Synthetic {
    pub dims: [u32; 3],
    pub spacing: [f32; 3],
    pub values: Values,
}

/// Deterministic pseudo-random numbers (a 64-bit LCG), so that tests repeat.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        self.0 >> 33
    }
}

/// A 5 x 4 x 3 volume with anisotropic spacing; the values span most of the type's
/// range and include values that round both ways when rescaled.
pub fn synthetic(type_name: &str, seed: u64) -> Synthetic {
    let dims = [5, 4, 3];
    let count = 60;
    let mut rng = Lcg(seed);
    let values = match type_name {
        "uint8" => Values::U8((0..count).map(|_| (rng.next() % 256) as u8).collect()),
        "uint16" => Values::U16((0..count).map(|_| (rng.next() % 60000) as u16 + 300).collect()),
        "int16" => Values::I16((0..count).map(|_| (rng.next() % 60000) as i32 - 31000).map(|v| v as i16).collect()),
        "float32" => Values::F32((0..count).map(|_| (rng.next() % 100_000) as f32 / 3.0 - 5000.0).collect()),
        other => panic!("no synthetic type {other}"),
    };
    Synthetic { dims, spacing: [0.5, 1.25, 2.0], values }
}

pub const TYPES: [&str; 4] = ["uint8", "uint16", "int16", "float32"];

/// Checks dims, spacing, value range and every normalized voxel of `volume`
/// against the convention: uint8 kept (s = v / 255), 16-bit rescaled from
/// [min, max] onto 0..=65535 rounding to nearest, float32 rescaled onto [0, 1].
pub fn assert_matches(volume: &Volume, expected: &Synthetic, context: &str) {
    assert_eq!(volume.dims.to_array(), expected.dims, "{context}: dims");
    assert_eq!(volume.spacing.to_array(), expected.spacing, "{context}: spacing");
    let (lo, hi) = expected.values.range();
    assert_eq!(volume.value_range, (lo, hi), "{context}: value range");
    let raw = expected.values.as_f64();
    match (&expected.values, &volume.data) {
        (Values::U8(v), VoxelData::U8(got)) => assert_eq!(got, v, "{context}: voxels"),
        (Values::U16(_) | Values::I16(_), VoxelData::U16(got)) => {
            let want: Vec<u16> = raw.iter().map(|&x| ((x - lo) / (hi - lo) * 65535.0).round() as u16).collect();
            assert_eq!(got, &want, "{context}: voxels");
        }
        (Values::F32(_), VoxelData::F32(got)) => {
            assert_eq!(got.len(), raw.len(), "{context}: voxel count");
            for (i, (&g, &x)) in got.iter().zip(&raw).enumerate() {
                let want = (x - lo) / (hi - lo);
                assert!((g as f64 - want).abs() <= 1e-6, "{context}: voxel {i} is {g}, expected {want}");
            }
        }
        (values, data) => {
            panic!("{context}: {} voxels loaded as {:?}-type storage", type_label(values), std::mem::discriminant(data))
        }
    }
}

fn type_label(values: &Values) -> &'static str {
    match values {
        Values::U8(_) => "uint8",
        Values::U16(_) => "uint16",
        Values::I16(_) => "int16",
        Values::F32(_) => "float32",
    }
}
