//! Broken files give errors that name the file, never panics: truncated real
//! and synthetic files, and headers with bad values.

use std::path::{Path, PathBuf};

use sweeplab::scene::loaders::{FormatProblem, LoadError};

use super::synthetic::{synthetic, Endian, Synthetic};
use super::writers::*;
use super::{load_err, sample, truncated_copy, Scratch};

/// The variant of a format problem, for tables of expected failures.
fn kind(error: &LoadError) -> &'static str {
    match error {
        LoadError::Io { .. } => "Io",
        LoadError::UnknownExtension { .. } => "UnknownExtension",
        LoadError::Format { problem, .. } => match problem {
            FormatProblem::Syntax(_) => "Syntax",
            FormatProblem::MissingField(_) => "MissingField",
            FormatProblem::BadField { .. } => "BadField",
            FormatProblem::Unsupported(_) => "Unsupported",
            FormatProblem::BadDims { .. } => "BadDims",
            FormatProblem::BadSpacing { .. } => "BadSpacing",
            FormatProblem::Truncated { .. } => "Truncated",
            FormatProblem::TooLong { .. } => "TooLong",
            FormatProblem::Decompress { .. } => "Decompress",
            FormatProblem::InflatedTooShort { .. } => "InflatedTooShort",
            FormatProblem::InflatedTooLong { .. } => "InflatedTooLong",
            FormatProblem::OutOfMemory { .. } => "OutOfMemory",
            FormatProblem::DataFile { .. } => "DataFile",
        },
    }
}

fn assert_kind(path: &Path, expected: &[&str], context: &str) {
    let error = load_err(path);
    assert!(expected.contains(&kind(&error)), "{context}: expected {expected:?}, got {}: {error}", kind(&error));
}

/// Truncates `cut` to many lengths short of its full size, restoring it
/// afterwards; loading `load` (the header) must fail each time. Every length is
/// tried in the first 400 bytes (headers) and the last 64 (trailers, closing
/// tags), every 7th in between. Losing only trailing whitespace changes
/// nothing, so those lengths are skipped.
fn assert_every_truncation_fails(cut: &Path, load: &Path) {
    let full = std::fs::read(cut).unwrap();
    for len in 0..full.len() {
        let tried = len < 400 || len + 64 >= full.len() || len % 7 == 0;
        if !tried || full[len..].iter().all(u8::is_ascii_whitespace) {
            continue;
        }
        std::fs::write(cut, &full[..len]).unwrap();
        let error = load_err(load);
        assert!(!matches!(error, LoadError::UnknownExtension { .. }), "{} cut to {len} bytes: {error}", cut.display());
    }
    std::fs::write(cut, &full).unwrap();
}

fn copy_into(dir: &Path, source: &Path) -> PathBuf {
    let target = dir.join(source.file_name().unwrap());
    std::fs::copy(source, &target).unwrap();
    target
}

#[test]
fn truncated_real_samples_fail() {
    let scratch = Scratch::new("truncated_real_samples");
    let dir = scratch.path();
    // Single files: cut anywhere, including just before the closing tags.
    for file in ["engine.vti", "aneurism.vti", "LIDC2.mha"] {
        let source = sample(file);
        let len = std::fs::metadata(&source).unwrap().len() as usize;
        for cut in [0, 1, 100, 700, len / 3, len / 2, len - 30, len - 8, len - 2] {
            let target = dir.join(file);
            truncated_copy(&source, &target, cut);
            load_err(&target);
        }
    }
    // Header + data pairs: cut the header (not just its final newline), or the data.
    for (header, data) in [("nucleon.nrrd", "nucleon.raw"), ("smallHeart.mhd", "smallHeart.raw")] {
        let header_source = sample(header);
        let data_source = sample(data);
        let header_len = std::fs::metadata(&header_source).unwrap().len() as usize;
        let target = dir.join(header);
        copy_into(dir, &data_source);
        for cut in [0, 1, header_len / 3, header_len / 2, header_len - 2] {
            truncated_copy(&header_source, &target, cut);
            load_err(&target);
        }
        copy_into(dir, &header_source);
        let data_len = std::fs::metadata(&data_source).unwrap().len() as usize;
        for cut in [0, 1, data_len / 2, data_len - 1] {
            truncated_copy(&data_source, &dir.join(data), cut);
            assert_kind(&target, &["Truncated"], &format!("{data} cut at {cut}"));
        }
    }
}

#[test]
fn vti_block_cut_out_of_intact_framing_is_reported_as_truncated() {
    let scratch = Scratch::new("vti_block_cut");
    let bytes = std::fs::read(sample("engine.vti")).unwrap();
    // Keep the XML and the closing tags, drop the second half of the blocks.
    let tail = b"\n  </AppendedData>\n</VTKFile>\n";
    let mut cut = bytes[..bytes.len() / 2].to_vec();
    cut.extend_from_slice(tail);
    let path = scratch.path().join("engine.vti");
    std::fs::write(&path, &cut).unwrap();
    let error = load_err(&path);
    let message = error.to_string();
    match error.problem() {
        Some(FormatProblem::Truncated { what, .. }) => {
            assert!(what.contains("block"), "{message}")
        }
        _ => panic!("expected a truncated block: {message}"),
    }
}

/// One synthetic file of each format and storage variant, for truncation sweeps.
pub fn variants(dir: &Path, v: &Synthetic) -> Vec<(PathBuf, Option<PathBuf>)> {
    let little = Endian::Little;
    let big = Endian::Big;
    let mut files = Vec::new();
    let mut detached = |header: PathBuf, data: &str| {
        let data = dir.join(data);
        files.push((header, Some(data)));
    };
    detached(write_vhdr(dir, "raw", v, big, 17), "data/raw.bin");
    for (name, compressed, local, compressed_size) in
        [("meta_plain", false, false, false), ("meta_zlib", true, false, true)]
    {
        let options = MetaOptions { endian: big, compressed, local, compressed_size, alternative_keys: false };
        detached(write_metaimage(dir, name, v, options), &format!("{name}.raw"));
    }
    for (name, encoding) in [("nrrd_raw", NrrdEncoding::Raw), ("nrrd_gzip", NrrdEncoding::Gzip)] {
        let options = NrrdOptions { endian: little, encoding, detached: true, nhdr: true, directions: false };
        detached(write_nrrd(dir, name, v, options), &format!("{name}.data"));
    }
    let mut single = Vec::new();
    for (name, compressed, compressed_size) in
        [("mha_plain", false, false), ("mha_zlib", true, false), ("mha_zlib_sized", true, true)]
    {
        let options = MetaOptions { endian: little, compressed, local: true, compressed_size, alternative_keys: false };
        single.push(write_metaimage(dir, name, v, options));
    }
    for (name, encoding) in [("attached_raw", NrrdEncoding::Raw), ("attached_gzip", NrrdEncoding::Gzip)] {
        let options = NrrdOptions { endian: big, encoding, detached: false, nhdr: false, directions: true };
        single.push(write_nrrd(dir, name, v, options));
    }
    for (name, gzip) in [("nifti", false), ("nifti_gz", true)] {
        let options = NiftiOptions { endian: big, gzip, scaling: (1.0, 0.0), four_dims: false };
        single.push(write_nifti(dir, name, v, options));
    }
    for (name, storage, block_size, header_u64) in [
        ("vti_raw", VtiStorage::AppendedRaw, None, false),
        ("vti_raw_zlib", VtiStorage::AppendedRaw, Some(64), true),
        ("vti_base64_zlib", VtiStorage::AppendedBase64, Some(64), false),
        ("vti_inline", VtiStorage::InlineBinary, None, true),
        ("vti_inline_zlib", VtiStorage::InlineBinary, Some(64), false),
    ] {
        let options = VtiOptions { endian: big, storage, block_size, header_u64 };
        single.push(write_vti(dir, name, v, options));
    }
    files.extend(single.into_iter().map(|path| (path, None)));
    files
}

#[test]
fn synthetic_files_truncated_anywhere_fail() {
    let scratch = Scratch::new("synthetic_truncated");
    for type_name in ["uint16", "float32"] {
        let v = synthetic(type_name, 70);
        for (header, data) in variants(scratch.path(), &v) {
            assert_every_truncation_fails(&header, &header);
            if let Some(data) = data {
                assert_every_truncation_fails(&data, &header);
            }
        }
    }
}

/// Writes `path` to `target` with every `from` replaced by `to` (which must occur).
fn edit(path: &Path, target: &Path, from: &[u8], to: &[u8]) {
    let bytes = std::fs::read(path).unwrap();
    let mut edited = Vec::new();
    let mut rest = bytes.as_slice();
    let mut found = false;
    while let Some(at) = rest.windows(from.len()).position(|w| w == from) {
        edited.extend_from_slice(&rest[..at]);
        edited.extend_from_slice(to);
        rest = &rest[at + from.len()..];
        found = true;
    }
    assert!(found, "{} lacks {:?}", path.display(), String::from_utf8_lossy(from));
    edited.extend_from_slice(rest);
    std::fs::write(target, edited).unwrap();
}

/// (replace this, with this, expected error kinds) applied to a good file.
type Case<'a> = (&'a str, &'a str, &'a [&'a str]);

fn check_cases(good: &Path, cases: &[Case]) {
    let extension = good.file_name().unwrap().to_string_lossy().split_once('.').unwrap().1.to_string();
    for (i, (from, to, expected)) in cases.iter().enumerate() {
        let bad = good.with_file_name(format!("bad{i}.{extension}"));
        edit(good, &bad, from.as_bytes(), to.as_bytes());
        assert_kind(&bad, expected, &format!("{from:?} -> {to:?}"));
    }
}

const HOSTILE_DIMS: &[&str] = &["BadDims", "BadField"];

#[test]
fn bad_raw_headers_fail() {
    let scratch = Scratch::new("bad_raw_headers");
    let v = synthetic("uint16", 80);
    let good = write_vhdr(scratch.path(), "good", &v, Endian::Little, 0);
    check_cases(
        &good,
        &[
            ("dims = 5 4 3", "dims = 0 4 3", &["BadDims"]),
            ("dims = 5 4 3", "dims = 5 -4 3", &["BadDims"]),
            ("dims = 5 4 3", "dims = 5 4", &["BadField"]),
            ("dims = 5 4 3", "dims = 40000 4 3", &["BadDims"]),
            ("dims = 5 4 3", "dims = 30000 30000 30000", &["BadDims"]),
            ("dims = 5 4 3", "dims = 4294967296 4294967296 4294967296", HOSTILE_DIMS),
            ("dims = 5 4 3", "dims = 99999999999999999999 1 1", HOSTILE_DIMS),
            // Plausible but far more voxels than the data file holds.
            ("dims = 5 4 3", "dims = 30000 30000 4", &["Truncated"]),
            ("dims = 5 4 3", "dims = 5 4 2", &["TooLong"]),
            ("spacing = 0.5", "spacing = -0.5", &["BadSpacing"]),
            ("spacing = 0.5", "spacing = 0", &["BadSpacing"]),
            ("spacing = 0.5", "spacing = nan", &["BadSpacing"]),
            ("spacing = 0.5", "spacing = inf", &["BadSpacing"]),
            ("type = uint16", "type = float64", &["BadField"]),
            ("endian = little", "endian = middle", &["BadField"]),
            ("endian = little\n", "", &["MissingField"]),
            ("data = data/good.bin", "data = data/missing.bin", &["DataFile"]),
            ("offset = 0", "offset = -3", &["BadField"]),
            ("offset = 0", "colour = red", &["Syntax"]),
            ("# synthetic", "this line has no equals sign", &["Syntax"]),
        ],
    );
}

#[test]
fn bad_metaimage_headers_fail() {
    let scratch = Scratch::new("bad_metaimage");
    let v = synthetic("int16", 81);
    let options = MetaOptions {
        endian: Endian::Little,
        compressed: false,
        local: false,
        compressed_size: false,
        alternative_keys: false,
    };
    let good = write_metaimage(scratch.path(), "good", &v, options);
    check_cases(
        &good,
        &[
            ("NDims = 3", "NDims = 2", &["Unsupported"]),
            ("DimSize = 5 4 3", "DimSize = 5 0 3", &["BadDims"]),
            ("DimSize = 5 4 3", "DimSize = 5 4 -3", &["BadDims"]),
            ("DimSize = 5 4 3", "DimSize = 32769 4 3", &["BadDims"]),
            ("DimSize = 5 4 3", "DimSize = 30000 30000 30000", &["BadDims"]),
            ("DimSize = 5 4 3", "DimSize = 30000 30000 4", &["Truncated"]),
            ("ElementSpacing = 0.5", "ElementSpacing = -0.5", &["BadSpacing"]),
            ("ElementSpacing = 0.5", "ElementSpacing = 0", &["BadSpacing"]),
            ("MET_SHORT", "MET_DOUBLE", &["Unsupported"]),
            ("MET_SHORT", "SHORT", &["BadField"]),
            ("ElementDataFile = good.raw", "ElementDataFile = missing.raw", &["DataFile"]),
            ("ElementDataFile = good.raw", "ElementDataFile = LIST", &["Unsupported"]),
            ("ElementDataFile = good.raw\n", "", &["MissingField"]),
            ("NDims = 3", "NDims = 3\nElementNumberOfChannels = 3", &["Unsupported"]),
            ("BinaryDataByteOrderMSB = False", "BinaryDataByteOrderMSB = Maybe", &["BadField"]),
            ("BinaryData = True", "BinaryData = False", &["Unsupported"]),
            ("ObjectType = Image", "ObjectType = Mesh", &["BadField"]),
        ],
    );

    let compressed = MetaOptions { compressed: true, local: true, compressed_size: true, ..options };
    let good = write_metaimage(scratch.path(), "zipped", &v, compressed);
    let bytes = std::fs::read(&good).unwrap();
    let size_line = format!("CompressedDataSize = {}", bytes.len() - header_len(&bytes));
    check_cases(
        &good,
        &[
            (&size_line, "CompressedDataSize = 5", &["TooLong"]),
            (&size_line, "CompressedDataSize = 99999", &["Truncated"]),
            // Far more voxels than the compressed bytes can hold: refused before
            // inflating or allocating.
            ("DimSize = 5 4 3", "DimSize = 30000 30000 4", &["InflatedTooShort"]),
        ],
    );
    // A corrupt zlib stream: flip bytes in the middle of the compressed data.
    let mut corrupt = bytes.clone();
    let middle = header_len(&bytes) + (bytes.len() - header_len(&bytes)) / 2;
    for b in &mut corrupt[middle - 4..middle + 4] {
        *b ^= 0x5A;
    }
    let bad = scratch.path().join("corrupt.mha");
    std::fs::write(&bad, corrupt).unwrap();
    assert_kind(&bad, &["Decompress", "InflatedTooShort"], "corrupt zlib stream");
}

/// Bytes up to the end of the `ElementDataFile` line.
fn header_len(bytes: &[u8]) -> usize {
    let key = b"ElementDataFile = LOCAL\n";
    bytes.windows(key.len()).position(|w| w == key).unwrap() + key.len()
}

#[test]
fn bad_nrrd_headers_fail() {
    let scratch = Scratch::new("bad_nrrd");
    let v = synthetic("float32", 82);
    let options = NrrdOptions {
        endian: Endian::Little,
        encoding: NrrdEncoding::Raw,
        detached: true,
        nhdr: false,
        directions: false,
    };
    let good = write_nrrd(scratch.path(), "good", &v, options);
    check_cases(
        &good,
        &[
            ("NRRD0004", "NRRD0009", &["Syntax"]),
            ("dimension: 3", "dimension: 4", &["Unsupported"]),
            ("sizes: 5 4 3", "sizes: 5 4 0", &["BadDims"]),
            ("sizes: 5 4 3", "sizes: -5 4 3", &["BadDims"]),
            ("sizes: 5 4 3", "sizes: 30000 30000 30000", &["BadDims"]),
            ("sizes: 5 4 3", "sizes: 4294967296 4294967296 4294967296", HOSTILE_DIMS),
            ("sizes: 5 4 3", "sizes: 30000 30000 4", &["Truncated"]),
            ("spacings: 0.5", "spacings: -0.5", &["BadSpacing"]),
            ("spacings: 0.5", "spacings: nan", &["BadSpacing"]),
            ("type: float", "type: double", &["Unsupported"]),
            ("encoding: raw", "encoding: bzip2", &["Unsupported"]),
            ("endian: little\n", "", &["MissingField"]),
            ("data file: good.data", "data file: missing.data", &["DataFile"]),
            ("data file: good.data", "data file: slice%03d.raw 1 3 1", &["Unsupported"]),
            ("data file: good.data\n", "", &["Syntax"]),
            ("sizes: 5 4 3\n", "sizes: 5 4 3\nsizes: 5 4 3\n", &["Syntax"]),
        ],
    );
    // Attached gzip data that is not a gzip stream.
    let gz = NrrdOptions { encoding: NrrdEncoding::Gzip, detached: false, ..options };
    let good = write_nrrd(scratch.path(), "zipped", &v, gz);
    let bytes = std::fs::read(&good).unwrap();
    let data_at = bytes.windows(2).position(|w| w == b"\n\n").unwrap() + 2;
    let mut corrupt = bytes.clone();
    corrupt[data_at..data_at + 2].copy_from_slice(b"PK");
    let bad = scratch.path().join("not_gzip.nrrd");
    std::fs::write(&bad, corrupt).unwrap();
    assert_kind(&bad, &["Decompress"], "zip data labelled gzip");
    check_cases(&good, &[("sizes: 5 4 3", "sizes: 30000 30000 4", &["InflatedTooShort"])]);
}

#[test]
fn bad_nifti_headers_fail() {
    let scratch = Scratch::new("bad_nifti");
    let v = synthetic("uint16", 83);
    let options = NiftiOptions { endian: Endian::Little, gzip: false, scaling: (0.0, 0.0), four_dims: false };
    let good = nifti_bytes(&v, options);
    let put = |at: usize, value: &[u8]| {
        let mut bytes = good.clone();
        bytes[at..at + value.len()].copy_from_slice(value);
        bytes
    };
    let cases: Vec<(&str, Vec<u8>, &[&str])> = vec![
        ("sizeof_hdr 540", put(0, &540i32.to_le_bytes()), &["Unsupported"]),
        ("sizeof_hdr 12", put(0, &12i32.to_le_bytes()), &["Syntax"]),
        ("dim[0] 2", put(40, &2i16.to_le_bytes()), &["Unsupported"]),
        ("dim[0] 9", put(40, &9i16.to_le_bytes()), &["Syntax"]),
        ("dim[1] 0", put(42, &0i16.to_le_bytes()), &["BadDims"]),
        ("dim[2] -4", put(44, &(-4i16).to_le_bytes()), &["BadDims"]),
        ("dim[3] 32767", put(46, &32767i16.to_le_bytes()), &["Truncated"]),
        (
            "dim 32767 32767 32767",
            [42, 44, 46].iter().fold(good.clone(), |mut b, &at| {
                b[at..at + 2].copy_from_slice(&32767i16.to_le_bytes());
                b
            }),
            &["BadDims"],
        ),
        (
            "dim[0] 4 with dim[4] 2",
            {
                let mut b = put(40, &4i16.to_le_bytes());
                b[48..50].copy_from_slice(&2i16.to_le_bytes());
                b
            },
            &["Unsupported"],
        ),
        ("datatype 64", put(70, &64i16.to_le_bytes()), &["Unsupported"]),
        ("bitpix 8 for uint16", put(72, &8i16.to_le_bytes()), &["Syntax"]),
        ("pixdim[1] -1", put(80, &(-1f32).to_le_bytes()), &["BadSpacing"]),
        ("pixdim[2] 0", put(84, &0f32.to_le_bytes()), &["BadSpacing"]),
        ("pixdim[3] NaN", put(88, &f32::NAN.to_le_bytes()), &["BadSpacing"]),
        ("vox_offset 10", put(108, &10f32.to_le_bytes()), &["Syntax"]),
        ("vox_offset 352.5", put(108, &352.5f32.to_le_bytes()), &["Syntax"]),
        ("vox_offset 1e12", put(108, &1e12f32.to_le_bytes()), &["Syntax"]),
        ("scl_slope -1", put(112, &(-1f32).to_le_bytes()), &["Unsupported"]),
        ("magic ni1", put(344, b"ni1\0"), &["Unsupported"]),
        ("magic junk", put(344, b"abc\0"), &["Syntax"]),
        ("extra byte", [good.as_slice(), &[0]].concat(), &["TooLong"]),
    ];
    for (what, bytes, expected) in cases {
        for gzip in [false, true] {
            let path = if gzip {
                let path = scratch.path().join("bad.nii.gz");
                std::fs::write(&path, super::writers::gzip(&bytes)).unwrap();
                path
            } else {
                let path = scratch.path().join("bad.nii");
                std::fs::write(&path, &bytes).unwrap();
                path
            };
            // Through gzip, a short stream reads as inflating too little.
            let expected: Vec<&str> = if gzip && expected == ["Truncated"] {
                vec!["InflatedTooShort"]
            } else if gzip && expected == ["TooLong"] {
                vec!["InflatedTooLong"]
            } else {
                expected.to_vec()
            };
            assert_kind(&path, &expected, &format!("{what} (gzip: {gzip})"));
        }
    }
    // Not gzip at all.
    let path = scratch.path().join("plain.nii.gz");
    std::fs::write(&path, &good).unwrap();
    assert_kind(&path, &["Decompress"], "uncompressed .nii.gz");
}

#[test]
fn bad_vti_files_fail() {
    let scratch = Scratch::new("bad_vti");
    let v = synthetic("uint8", 84);
    let options = VtiOptions {
        endian: Endian::Little,
        storage: VtiStorage::AppendedRaw,
        block_size: Some(16),
        header_u64: false,
    };
    let good = write_vti(scratch.path(), "good", &v, options);
    check_cases(
        &good,
        &[
            ("type=\"ImageData\"", "type=\"PolyData\"", &["Unsupported"]),
            ("WholeExtent=\"0 4", "WholeExtent=\"0 -1", &["BadDims"]),
            ("WholeExtent=\"0 4", "WholeExtent=\"0 40000", &["BadDims"]),
            ("WholeExtent=\"0 4 0 3 0 2\"", "WholeExtent=\"0 30000 0 30000 0 30000\"", &["BadDims"]),
            ("WholeExtent=\"0 4", "WholeExtent=\"-9223372036854775808 9223372036854775807", &["BadField"]),
            // Both extents grow: more voxels than the arrays hold.
            ("Extent=\"0 4 0 3 0 2\"", "Extent=\"0 4 0 3 0 3\"", &["Syntax"]),
            ("<Piece Extent=\"0 4", "<Piece Extent=\"1 4", &["Unsupported"]),
            ("</Piece>", "</Piece><Piece Extent=\"0 4 0 3 3 3\"></Piece>", &["Unsupported"]),
            ("Spacing=\"0.5", "Spacing=\"-0.5", &["BadSpacing"]),
            ("Spacing=\"0.5", "Spacing=\"nan", &["BadSpacing"]),
            ("type=\"UInt8\" Name=\"Density\"", "type=\"Float64\" Name=\"Density\"", &["Unsupported"]),
            ("vtkZLibDataCompressor", "vtkLZ4DataCompressor", &["Unsupported"]),
            ("header_type=\"UInt32\"", "header_type=\"UInt16\"", &["BadField"]),
            ("Scalars=\"Density\"", "Scalars=\"Missing\"", &["Syntax"]),
            ("Name=\"Density\"", "Name=\"Density\" NumberOfComponents=\"3\"", &["Unsupported"]),
            ("<CellData>", "<CellData><Oops>", &["Syntax"]),
            ("<AppendedData encoding=\"raw\">\n   _", "<AppendedData encoding=\"raw\">\n   ", &["Syntax"]),
            ("</VTKFile>", "</VTKFil>", &["Syntax"]),
        ],
    );

    // Binary header words of the Density array: claim an absurd number of
    // blocks or wrong sizes.
    let bytes = std::fs::read(&good).unwrap();
    let text = String::from_utf8_lossy(&bytes).into_owned();
    let offset_key = "Name=\"Density\" format=\"appended\" offset=\"";
    let offset_text: String =
        text[text.find(offset_key).unwrap() + offset_key.len()..].chars().take_while(char::is_ascii_digit).collect();
    let underscore = bytes.windows(4).position(|w| w == b"   _").unwrap() + 4;
    let start = underscore + offset_text.parse::<usize>().unwrap();
    let blocks = v.values.len().div_ceil(16);
    let word = |index: usize| u32::from_le_bytes(bytes[start + 4 * index..][..4].try_into().unwrap());
    assert_eq!((word(0), word(1)), (blocks as u32, 16), "test file layout");
    let set_word = |index: usize, value: u32| {
        let mut b = bytes.clone();
        let at = start + 4 * index;
        b[at..at + 4].copy_from_slice(&value.to_le_bytes());
        b
    };
    let mut corrupt = bytes.clone();
    let first_block = start + 4 * (3 + blocks);
    for b in &mut corrupt[first_block..first_block + 6] {
        *b ^= 0xFF;
    }
    let past_end = {
        let from = format!("{offset_key}{offset_text}\"");
        let to = format!("{offset_key}99999\"");
        text.replacen(&from, &to, 1).into_bytes()
    };
    let cases: Vec<(&str, Vec<u8>, &[&str])> = vec![
        ("4 billion blocks", set_word(0, u32::MAX), &["Truncated"]),
        ("block size 1", set_word(1, 1), &["Syntax"]),
        ("compressed block size huge", set_word(3, u32::MAX), &["Truncated"]),
        ("compressed block size 2", set_word(3, 2), &["Decompress", "InflatedTooShort"]),
        ("corrupt zlib block", corrupt, &["Decompress", "InflatedTooShort"]),
        ("offset past the end", past_end, &["Truncated"]),
    ];
    for (what, bytes, expected) in cases {
        let path = scratch.path().join("words.vti");
        std::fs::write(&path, bytes).unwrap();
        assert_kind(&path, expected, what);
    }
}

#[test]
fn unreadable_files_name_the_file() {
    let scratch = Scratch::new("unreadable");
    let missing = scratch.path().join("absent.nrrd");
    assert_kind(&missing, &["Io"], "missing file");
    let unknown = scratch.path().join("volume.dcm");
    std::fs::write(&unknown, b"DICM").unwrap();
    assert_kind(&unknown, &["UnknownExtension"], "unknown extension");
    // A binary file with a volume extension.
    let garbage = scratch.path().join("garbage.mhd");
    std::fs::write(&garbage, [0xFFu8, 0xFE, 0x00, 0x10, 0x80]).unwrap();
    assert_kind(&garbage, &["Syntax"], "binary .mhd");
}

#[test]
fn randomly_corrupted_files_never_panic() {
    let scratch = Scratch::new("random_corruption");
    let v = synthetic("int16", 90);
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        // xorshift64: cheap, deterministic byte positions and values.
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    for (header, data) in variants(scratch.path(), &v) {
        for target in std::iter::once(&header).chain(data.as_ref()) {
            let original = std::fs::read(target).unwrap();
            for _ in 0..60 {
                let mut bytes = original.clone();
                for _ in 0..1 + next() % 4 {
                    let at = (next() % bytes.len() as u64) as usize;
                    bytes[at] = next() as u8;
                }
                std::fs::write(target, &bytes).unwrap();
                // Either outcome is fine (a flipped voxel is still a volume);
                // a panic fails the test, and errors must name the header.
                if let Err(error) = sweeplab::scene::loaders::load_volume(&header) {
                    let name = header.file_name().unwrap().to_string_lossy().into_owned();
                    assert!(error.to_string().contains(&name), "{error}");
                }
            }
            std::fs::write(target, &original).unwrap();
        }
    }
}
