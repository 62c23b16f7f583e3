//! The real data sets load with the grid and spacing of data/README.md, and
//! with voxels equal to an independent decoding of the same file done here
//! with flate2 and byte slicing.

use std::io::Read;

use flate2::read::ZlibDecoder;
use sweeplab::scene::{Volume, VoxelData};

use super::{load_ok, sample};

fn find(haystack: &[u8], needle: &[u8]) -> usize {
    haystack
        .windows(needle.len())
        .position(|w| w == needle)
        .unwrap_or_else(|| panic!("{:?} not in file", String::from_utf8_lossy(needle)))
}

fn min_max_u8(bytes: &[u8]) -> (f64, f64) {
    let lo = *bytes.iter().min().unwrap();
    let hi = *bytes.iter().max().unwrap();
    (lo as f64, hi as f64)
}

/// Real data are neither empty nor solid: the values spread over several bins.
fn assert_plausible(volume: &Volume) {
    let (lo, hi) = volume.value_range;
    assert!(hi > lo, "{}: constant data {lo}..{hi}", volume.name);
    let histogram = volume.histogram(16);
    let busy = histogram.iter().filter(|&&n| n as f64 >= 0.001 * volume.voxel_count() as f64).count();
    assert!(busy >= 3, "{}: values crowd into {busy} of 16 bins: {histogram:?}", volume.name);
}

fn assert_spacing(volume: &Volume, readme: [f32; 3]) {
    for axis in 0..3 {
        let got = volume.spacing[axis];
        assert!(
            (got - readme[axis]).abs() <= 1e-6 * readme[axis],
            "{}: spacing {:?}, README says {readme:?}",
            volume.name,
            volume.spacing
        );
    }
}

/// The data of a `.vti` whose appended section holds one zlib-compressed
/// array with UInt64 little-endian headers, decoded by hand.
fn inflate_vti_appended(bytes: &[u8]) -> Vec<u8> {
    let tag = b"<AppendedData encoding=\"raw\">";
    let start = find(bytes, tag) + tag.len();
    let data = &bytes[start + find(&bytes[start..], b"_") + 1..];
    let word = |i: usize| u64::from_le_bytes(data[8 * i..8 * i + 8].try_into().unwrap()) as usize;
    let blocks = word(0);
    let mut position = 8 * (3 + blocks);
    let mut out = Vec::new();
    for i in 0..blocks {
        let size = word(3 + i);
        ZlibDecoder::new(&data[position..position + size]).read_to_end(&mut out).unwrap();
        position += size;
    }
    out
}

/// The value of attribute `name` in the file's XML text.
fn xml_attribute(bytes: &[u8], name: &str) -> f64 {
    let key = format!("{name}=\"");
    let start = find(bytes, key.as_bytes()) + key.len();
    let end = start + find(&bytes[start..], b"\"");
    std::str::from_utf8(&bytes[start..end]).unwrap().trim().parse().unwrap()
}

fn check_vti(file: &str, dims: [u32; 3]) {
    let path = sample(file);
    let volume = load_ok(&path);
    assert_eq!(volume.dims.to_array(), dims, "{file}: dims");
    assert_spacing(&volume, [1.0, 1.0, 1.0]);
    let bytes = std::fs::read(&path).unwrap();
    let expected = inflate_vti_appended(&bytes);
    assert_eq!(expected.len(), volume.voxel_count(), "{file}: independent decoding");
    // The writer recorded the range of the array in the file.
    let recorded = (xml_attribute(&bytes, "RangeMin"), xml_attribute(&bytes, "RangeMax"));
    assert_eq!(min_max_u8(&expected), recorded, "{file}: independent decoding");
    assert_eq!(volume.value_range, recorded, "{file}: value range");
    match &volume.data {
        VoxelData::U8(data) => assert!(data == &expected, "{file}: voxels differ"),
        _ => panic!("{file}: uint8 data not stored as U8"),
    }
    assert_plausible(&volume);
}

#[test]
fn engine_vti_loads() {
    check_vti("engine.vti", [256, 256, 128]);
}

#[test]
fn aneurism_vti_loads() {
    check_vti("aneurism.vti", [256, 256, 256]);
}

#[test]
fn lidc2_mha_loads() {
    let path = sample("LIDC2.mha");
    let volume = load_ok(&path);
    assert_eq!(volume.dims.to_array(), [256, 256, 133]);
    assert_spacing(&volume, [1.40625, 1.40625, 2.5]);
    let bytes = std::fs::read(&path).unwrap();
    let marker = b"ElementDataFile = LOCAL\n";
    let start = find(&bytes, marker) + marker.len();
    let mut expected = Vec::new();
    ZlibDecoder::new(&bytes[start..]).read_to_end(&mut expected).unwrap();
    assert_eq!(expected.len(), 256 * 256 * 133);
    assert_eq!(volume.value_range, min_max_u8(&expected));
    match &volume.data {
        VoxelData::U8(data) => assert!(data == &expected, "LIDC2.mha: voxels differ"),
        _ => panic!("LIDC2.mha: uint8 data not stored as U8"),
    }
    assert_plausible(&volume);
}

#[test]
fn small_heart_mhd_loads() {
    let volume = load_ok(&sample("smallHeart.mhd"));
    assert_eq!(volume.dims.to_array(), [128, 128, 114]);
    assert_spacing(&volume, [1.421876, 1.421876, 1.400024]);
    let raw: Vec<u16> = std::fs::read(sample("smallHeart.raw"))
        .unwrap()
        .chunks_exact(2)
        .map(|c| u16::from_le_bytes([c[0], c[1]]))
        .collect();
    assert_eq!(raw.len(), 128 * 128 * 114);
    let lo = *raw.iter().min().unwrap() as f64;
    let hi = *raw.iter().max().unwrap() as f64;
    assert_eq!(volume.value_range, (lo, hi));
    let expected: Vec<u16> = raw.iter().map(|&v| ((v as f64 - lo) / (hi - lo) * 65535.0).round() as u16).collect();
    match &volume.data {
        VoxelData::U16(data) => assert!(data == &expected, "smallHeart.mhd: voxels differ"),
        _ => panic!("smallHeart.mhd: uint16 data not stored as U16"),
    }
    assert_plausible(&volume);
}

#[test]
fn nucleon_nrrd_loads() {
    let volume = load_ok(&sample("nucleon.nrrd"));
    assert_eq!(volume.name, "nucleon");
    assert_eq!(volume.dims.to_array(), [41, 41, 41]);
    assert_spacing(&volume, [1.0, 1.0, 1.0]);
    let raw = std::fs::read(sample("nucleon.raw")).unwrap();
    assert_eq!(volume.value_range, min_max_u8(&raw));
    assert_eq!(volume.data, VoxelData::U8(raw));
    assert_plausible(&volume);
}
