//! Small synthetic files of every format, voxel type, byte order and storage
//! variant load back as the voxels written, normalized per the convention.

use super::synthetic::{assert_matches, synthetic, ENDIANS, TYPES};
use super::writers::*;
use super::{load_ok, Scratch};

#[test]
fn raw_header_round_trips() {
    let scratch = Scratch::new("raw_header_round_trips");
    for (seed, type_name) in TYPES.iter().enumerate() {
        let v = synthetic(type_name, seed as u64);
        for endian in ENDIANS {
            for offset in [0, 17] {
                let name = format!("{type_name}_{endian:?}_{offset}");
                let path = write_vhdr(scratch.path(), &name, &v, endian, offset);
                let volume = load_ok(&path);
                assert_eq!(volume.name, name);
                assert_matches(&volume, &v, &name);
            }
        }
    }
}

#[test]
fn metaimage_round_trips() {
    let scratch = Scratch::new("metaimage_round_trips");
    for (seed, type_name) in TYPES.iter().enumerate() {
        let v = synthetic(type_name, 10 + seed as u64);
        for endian in ENDIANS {
            for local in [false, true] {
                for (compressed, compressed_size) in [(false, false), (true, false), (true, true)] {
                    let options = MetaOptions {
                        endian,
                        compressed,
                        local,
                        compressed_size,
                        alternative_keys: endian == Endian::Big && !local,
                    };
                    let name = format!("{type_name}_{endian:?}_{local}_{compressed}_{compressed_size}");
                    let path = write_metaimage(scratch.path(), &name, &v, options);
                    assert_matches(&load_ok(&path), &v, &format!("{options:?} {type_name}"));
                }
            }
        }
    }
}

use super::synthetic::Endian;

#[test]
fn nrrd_round_trips() {
    let scratch = Scratch::new("nrrd_round_trips");
    let encodings = [NrrdEncoding::Raw, NrrdEncoding::Gzip, NrrdEncoding::Ascii];
    // (detached, nhdr)
    let placements = [(false, false), (true, false), (true, true)];
    for (seed, type_name) in TYPES.iter().enumerate() {
        let v = synthetic(type_name, 20 + seed as u64);
        for endian in ENDIANS {
            for encoding in encodings {
                for (detached, nhdr) in placements {
                    for directions in [false, true] {
                        let options = NrrdOptions { endian, encoding, detached, nhdr, directions };
                        let name = format!("{type_name}_{endian:?}_{encoding:?}_{detached}_{nhdr}_{directions}");
                        let path = write_nrrd(scratch.path(), &name, &v, options);
                        let volume = load_ok(&path);
                        let context = format!("{options:?} {type_name}");
                        if directions {
                            // Spacing from vector lengths: equal up to rounding.
                            let mut exact = volume.clone();
                            for axis in 0..3 {
                                let got = volume.spacing[axis];
                                let want = v.spacing[axis];
                                assert!((got - want).abs() <= 1e-6, "{context}: spacing {got} vs {want}");
                                exact.spacing[axis] = want;
                            }
                            assert_matches(&exact, &v, &context);
                        } else {
                            assert_matches(&volume, &v, &context);
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn nifti_round_trips() {
    let scratch = Scratch::new("nifti_round_trips");
    for (seed, type_name) in TYPES.iter().enumerate() {
        let v = synthetic(type_name, 30 + seed as u64);
        for endian in ENDIANS {
            for gzip in [false, true] {
                for four_dims in [false, true] {
                    let options = NiftiOptions { endian, gzip, scaling: (0.0, 0.0), four_dims };
                    let name = format!("{type_name}_{endian:?}_{gzip}_{four_dims}");
                    let path = write_nifti(scratch.path(), &name, &v, options);
                    let volume = load_ok(&path);
                    assert_eq!(volume.name, name);
                    assert_matches(&volume, &v, &format!("{options:?} {type_name}"));
                }
            }
        }
    }
}

#[test]
fn nifti_scaling_applies_to_the_value_range_only() {
    let scratch = Scratch::new("nifti_scaling");
    let v = synthetic("int16", 40);
    let options = NiftiOptions { endian: Endian::Little, gzip: false, scaling: (2.0, -10.0), four_dims: false };
    let volume = load_ok(&write_nifti(scratch.path(), "scaled", &v, options));
    let (lo, hi) = v.values.range();
    assert_eq!(volume.value_range, (2.0 * lo - 10.0, 2.0 * hi - 10.0));
    // A positive affine map does not change the normalized voxels.
    let mut unscaled = volume.clone();
    unscaled.value_range = (lo, hi);
    assert_matches(&unscaled, &v, "scaled NIfTI");
}

#[test]
fn vti_round_trips() {
    let scratch = Scratch::new("vti_round_trips");
    let storages =
        [VtiStorage::AppendedRaw, VtiStorage::AppendedBase64, VtiStorage::InlineBinary, VtiStorage::InlineAscii];
    // 16-byte blocks: several blocks, the last one partial or (float32) full.
    for (seed, type_name) in TYPES.iter().enumerate() {
        let v = synthetic(type_name, 50 + seed as u64);
        for endian in ENDIANS {
            for storage in storages {
                for block_size in [None, Some(16), Some(1000)] {
                    for header_u64 in [false, true] {
                        let options = VtiOptions { endian, storage, block_size, header_u64 };
                        let name = format!("{type_name}_{endian:?}_{storage:?}_{block_size:?}_{header_u64}");
                        let path = write_vti(scratch.path(), &name, &v, options);
                        assert_matches(&load_ok(&path), &v, &format!("{options:?} {type_name}"));
                    }
                }
            }
        }
    }
}

#[test]
fn extensions_are_case_insensitive() {
    let scratch = Scratch::new("case_insensitive");
    let v = synthetic("uint8", 60);
    let options =
        VtiOptions { endian: Endian::Little, storage: VtiStorage::AppendedRaw, block_size: None, header_u64: false };
    let lower = write_vti(scratch.path(), "lower", &v, options);
    let upper = scratch.path().join("UPPER.VTI");
    std::fs::rename(&lower, &upper).unwrap();
    let volume = load_ok(&upper);
    assert_eq!(volume.name, "UPPER");
    assert_matches(&volume, &v, "UPPER.VTI");
}
