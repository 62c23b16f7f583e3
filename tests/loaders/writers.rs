//! Writers of small test files in each format, written from the format
//! descriptions (VTK file-format docs, MetaIO, NRRD and NIfTI-1 specifications),
//! independently of the loaders.

use std::io::Write;
use std::path::{Path, PathBuf};

use flate2::write::{GzEncoder, ZlibEncoder};
use flate2::Compression;

use super::synthetic::{Endian, Synthetic, Values};

pub fn zlib(data: &[u8]) -> Vec<u8> {
    let mut encoder = ZlibEncoder::new(Vec::new(), Compression::default());
    encoder.write_all(data).unwrap();
    encoder.finish().unwrap()
}

pub fn gzip(data: &[u8]) -> Vec<u8> {
    let mut encoder = GzEncoder::new(Vec::new(), Compression::default());
    encoder.write_all(data).unwrap();
    encoder.finish().unwrap()
}

pub fn base64(data: &[u8]) -> String {
    const ALPHABET: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for chunk in data.chunks(3) {
        let b = [chunk[0], *chunk.get(1).unwrap_or(&0), *chunk.get(2).unwrap_or(&0)];
        let bits = (b[0] as u32) << 16 | (b[1] as u32) << 8 | b[2] as u32;
        for i in 0..4 {
            if i <= chunk.len() {
                out.push(ALPHABET[(bits >> (18 - 6 * i) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

fn write(path: &Path, bytes: &[u8]) -> PathBuf {
    std::fs::write(path, bytes).unwrap();
    path.to_path_buf()
}

fn endian_word(endian: Endian) -> &'static str {
    match endian {
        Endian::Little => "little",
        Endian::Big => "big",
    }
}

// ---------------------------------------------------------------- raw header

pub fn write_vhdr(dir: &Path, name: &str, v: &Synthetic, endian: Endian, offset: usize) -> PathBuf {
    let type_name = match v.values {
        Values::U8(_) => "uint8",
        Values::U16(_) => "uint16",
        Values::I16(_) => "int16",
        Values::F32(_) => "float32",
    };
    let header = format!(
        "# synthetic test volume\n\
         dims = {} {} {}\n\
         spacing = {} {} {}\n\
         type = {type_name}\n\
         endian = {}\n\
         data = data/{name}.bin\n\
         offset = {offset}\n",
        v.dims[0],
        v.dims[1],
        v.dims[2],
        v.spacing[0],
        v.spacing[1],
        v.spacing[2],
        endian_word(endian),
    );
    std::fs::create_dir_all(dir.join("data")).unwrap();
    let mut data = vec![0xAB; offset];
    data.extend(v.values.bytes(endian));
    write(&dir.join(format!("data/{name}.bin")), &data);
    write(&dir.join(format!("{name}.vhdr")), header.as_bytes())
}

// ---------------------------------------------------------------- MetaImage

#[derive(Clone, Copy, Debug)]
pub struct MetaOptions {
    pub endian: Endian,
    pub compressed: bool,
    /// `.mha` with `ElementDataFile = LOCAL`, else `.mhd` + `.raw`.
    pub local: bool,
    /// Write `CompressedDataSize` (only with `compressed`).
    pub compressed_size: bool,
    /// Spell the spacing `ElementSize` instead of `ElementSpacing`, and the byte
    /// order `ElementByteOrderMSB` instead of `BinaryDataByteOrderMSB`.
    pub alternative_keys: bool,
}

pub fn meta_element_type(values: &Values) -> &'static str {
    match values {
        Values::U8(_) => "MET_UCHAR",
        Values::U16(_) => "MET_USHORT",
        Values::I16(_) => "MET_SHORT",
        Values::F32(_) => "MET_FLOAT",
    }
}

pub fn write_metaimage(dir: &Path, name: &str, v: &Synthetic, o: MetaOptions) -> PathBuf {
    let raw = v.values.bytes(o.endian);
    let data = if o.compressed { zlib(&raw) } else { raw };
    let msb = if o.endian == Endian::Big { "True" } else { "False" };
    let (spacing_key, order_key) = if o.alternative_keys {
        ("ElementSize", "ElementByteOrderMSB")
    } else {
        ("ElementSpacing", "BinaryDataByteOrderMSB")
    };
    let mut header = format!(
        "ObjectType = Image\nNDims = 3\nBinaryData = True\n{order_key} = {msb}\n\
         CompressedData = {}\n",
        if o.compressed { "True" } else { "False" }
    );
    if o.compressed && o.compressed_size {
        header += &format!("CompressedDataSize = {}\n", data.len());
    }
    header += &format!(
        "Offset = 0 0 0\n{spacing_key} = {} {} {}\nDimSize = {} {} {}\nElementType = {}\n",
        v.spacing[0],
        v.spacing[1],
        v.spacing[2],
        v.dims[0],
        v.dims[1],
        v.dims[2],
        meta_element_type(&v.values),
    );
    if o.local {
        header += "ElementDataFile = LOCAL\n";
        let mut bytes = header.into_bytes();
        bytes.extend(data);
        write(&dir.join(format!("{name}.mha")), &bytes)
    } else {
        header += &format!("ElementDataFile = {name}.raw\n");
        write(&dir.join(format!("{name}.raw")), &data);
        write(&dir.join(format!("{name}.mhd")), header.as_bytes())
    }
}

// ---------------------------------------------------------------- NRRD

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NrrdEncoding {
    Raw,
    Gzip,
    Ascii,
}

#[derive(Clone, Copy, Debug)]
pub struct NrrdOptions {
    pub endian: Endian,
    pub encoding: NrrdEncoding,
    /// Data in a separate file named by `data file:`.
    pub detached: bool,
    /// Write the header as `.nhdr` (implies detached).
    pub nhdr: bool,
    /// Give the spacing as `space directions` (rotated axes) instead of `spacings`.
    pub directions: bool,
}

pub fn nrrd_type(values: &Values) -> &'static str {
    match values {
        Values::U8(_) => "uchar",
        Values::U16(_) => "unsigned short",
        Values::I16(_) => "int16",
        Values::F32(_) => "float",
    }
}

pub fn write_nrrd(dir: &Path, name: &str, v: &Synthetic, o: NrrdOptions) -> PathBuf {
    let data = match o.encoding {
        NrrdEncoding::Raw => v.values.bytes(o.endian),
        NrrdEncoding::Gzip => gzip(&v.values.bytes(o.endian)),
        NrrdEncoding::Ascii => v.values.ascii().into_bytes(),
    };
    let mut header = format!(
        "NRRD0004\n# synthetic test volume\ntype: {}\ndimension: 3\nsizes: {} {} {}\n",
        nrrd_type(&v.values),
        v.dims[0],
        v.dims[1],
        v.dims[2]
    );
    if o.directions {
        // Axes rotated in the x-y plane; each vector's length is the spacing.
        let [sx, sy, sz] = v.spacing.map(|s| s as f64);
        let (c, s) = (0.6, 0.8);
        header += &format!(
            "space: right-anterior-superior\nspace directions: ({},{},0) ({},{},0) (0,0,{})\n",
            sx * c,
            sx * s,
            -sy * s,
            sy * c,
            sz
        );
    } else {
        header += &format!("spacings: {} {} {}\n", v.spacing[0], v.spacing[1], v.spacing[2]);
    }
    header += "kinds: domain domain domain\n";
    header += &format!("endian: {}\n", endian_word(o.endian));
    header += match o.encoding {
        NrrdEncoding::Raw => "encoding: raw\n",
        NrrdEncoding::Gzip => "encoding: gzip\n",
        NrrdEncoding::Ascii => "encoding: ascii\n",
    };
    header += "comment:=key/value pairs are ignored\n";
    if o.detached || o.nhdr {
        header += &format!("data file: {name}.data\n");
        write(&dir.join(format!("{name}.data")), &data);
        let extension = if o.nhdr { "nhdr" } else { "nrrd" };
        write(&dir.join(format!("{name}.{extension}")), header.as_bytes())
    } else {
        header += "\n";
        let mut bytes = header.into_bytes();
        bytes.extend(data);
        write(&dir.join(format!("{name}.nrrd")), &bytes)
    }
}

// ---------------------------------------------------------------- NIfTI-1

#[derive(Clone, Copy, Debug)]
pub struct NiftiOptions {
    pub endian: Endian,
    pub gzip: bool,
    /// scl_slope and scl_inter.
    pub scaling: (f32, f32),
    /// Write dim[0] = 4 with dim[4] = 1 (a one-frame series).
    pub four_dims: bool,
}

/// The 348-byte NIfTI-1 header, 4 bytes of (empty) extension flag, then the data.
pub fn nifti_bytes(v: &Synthetic, o: NiftiOptions) -> Vec<u8> {
    let big = o.endian == Endian::Big;
    let mut h = vec![0u8; 352];
    let mut put = |at: usize, bytes: &[u8]| h[at..at + bytes.len()].copy_from_slice(bytes);
    let i16b = |x: i16| {
        if big {
            x.to_be_bytes()
        } else {
            x.to_le_bytes()
        }
    };
    let i32b = |x: i32| {
        if big {
            x.to_be_bytes()
        } else {
            x.to_le_bytes()
        }
    };
    let f32b = |x: f32| {
        if big {
            x.to_be_bytes()
        } else {
            x.to_le_bytes()
        }
    };
    put(0, &i32b(348));
    let rank = if o.four_dims { 4 } else { 3 };
    let dim = [rank, v.dims[0] as i16, v.dims[1] as i16, v.dims[2] as i16, 1, 1, 1, 1];
    for (i, d) in dim.iter().enumerate() {
        put(40 + 2 * i, &i16b(*d));
    }
    let (datatype, bitpix) = match v.values {
        Values::U8(_) => (2, 8),
        Values::I16(_) => (4, 16),
        Values::U16(_) => (512, 16),
        Values::F32(_) => (16, 32),
    };
    put(70, &i16b(datatype));
    put(72, &i16b(bitpix));
    let pixdim = [1.0, v.spacing[0], v.spacing[1], v.spacing[2], 1.0, 1.0, 1.0, 1.0];
    for (i, p) in pixdim.iter().enumerate() {
        put(76 + 4 * i, &f32b(*p));
    }
    put(108, &f32b(352.0));
    put(112, &f32b(o.scaling.0));
    put(116, &f32b(o.scaling.1));
    put(344, b"n+1\0");
    h.extend(v.values.bytes(o.endian));
    h
}

pub fn write_nifti(dir: &Path, name: &str, v: &Synthetic, o: NiftiOptions) -> PathBuf {
    let bytes = nifti_bytes(v, o);
    if o.gzip {
        write(&dir.join(format!("{name}.nii.gz")), &gzip(&bytes))
    } else {
        write(&dir.join(format!("{name}.nii")), &bytes)
    }
}

// ---------------------------------------------------------------- VTK XML

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VtiStorage {
    AppendedRaw,
    AppendedBase64,
    InlineBinary,
    InlineAscii,
}

#[derive(Clone, Copy, Debug)]
pub struct VtiOptions {
    pub endian: Endian,
    pub storage: VtiStorage,
    /// zlib blocks of this many uncompressed bytes; `None`: uncompressed.
    pub block_size: Option<usize>,
    pub header_u64: bool,
}

pub fn vtk_type(values: &Values) -> &'static str {
    match values {
        Values::U8(_) => "UInt8",
        Values::U16(_) => "UInt16",
        Values::I16(_) => "Int16",
        Values::F32(_) => "Float32",
    }
}

/// The binary form of one array: its header of size words and its data, kept
/// apart because VTK base64-encodes them separately.
fn vtk_binary(data: &[u8], o: VtiOptions) -> (Vec<u8>, Vec<u8>) {
    let word = |x: usize| -> Vec<u8> {
        match (o.header_u64, o.endian) {
            (true, Endian::Little) => (x as u64).to_le_bytes().to_vec(),
            (true, Endian::Big) => (x as u64).to_be_bytes().to_vec(),
            (false, Endian::Little) => (x as u32).to_le_bytes().to_vec(),
            (false, Endian::Big) => (x as u32).to_be_bytes().to_vec(),
        }
    };
    match o.block_size {
        None => (word(data.len()), data.to_vec()),
        Some(block_size) => {
            let blocks: Vec<Vec<u8>> = data.chunks(block_size).map(zlib).collect();
            let mut header = word(blocks.len());
            header.extend(word(block_size));
            header.extend(word(data.len() % block_size));
            for b in &blocks {
                header.extend(word(b.len()));
            }
            (header, blocks.concat())
        }
    }
}

/// A `.vti` whose point data holds a decoy `Mask` array before the `Density`
/// scalars (named by `Scalars=`), so that array selection and offsets matter.
pub fn vti_bytes(v: &Synthetic, o: VtiOptions) -> Vec<u8> {
    let mask = Values::U8((0..v.values.len()).map(|i| (i % 2) as u8).collect());
    let arrays = [("Mask", &mask), ("Density", &v.values)];
    let byte_order = match o.endian {
        Endian::Little => "LittleEndian",
        Endian::Big => "BigEndian",
    };
    let mut xml = format!(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"{byte_order}\" header_type=\"{}\"{}>\n",
        if o.header_u64 { "UInt64" } else { "UInt32" },
        if o.block_size.is_some() { " compressor=\"vtkZLibDataCompressor\"" } else { "" },
    );
    let extent = format!("0 {} 0 {} 0 {}", v.dims[0] - 1, v.dims[1] - 1, v.dims[2] - 1);
    xml += &format!(
        "  <ImageData WholeExtent=\"{extent}\" Origin=\"0 0 0\" Spacing=\"{} {} {}\">\n    <Piece Extent=\"{extent}\">\n      <PointData Scalars=\"Density\">\n",
        v.spacing[0], v.spacing[1], v.spacing[2]
    );
    let mut appended: Vec<u8> = Vec::new();
    for (name, values) in arrays {
        let kind = vtk_type(values);
        let (header, data) = vtk_binary(&values.bytes(o.endian), o);
        match o.storage {
            VtiStorage::AppendedRaw | VtiStorage::AppendedBase64 => {
                xml += &format!(
                    "        <DataArray type=\"{kind}\" Name=\"{name}\" format=\"appended\" offset=\"{}\"/>\n",
                    appended.len()
                );
                if o.storage == VtiStorage::AppendedRaw {
                    appended.extend(header);
                    appended.extend(data);
                } else {
                    appended.extend(base64(&header).into_bytes());
                    appended.extend(base64(&data).into_bytes());
                }
            }
            VtiStorage::InlineBinary => {
                xml += &format!(
                    "        <DataArray type=\"{kind}\" Name=\"{name}\" format=\"binary\">\n          {}{}\n        </DataArray>\n",
                    base64(&header),
                    base64(&data)
                );
            }
            VtiStorage::InlineAscii => {
                xml += &format!(
                    "        <DataArray type=\"{kind}\" Name=\"{name}\" format=\"ascii\">\n{}\n        </DataArray>\n",
                    values.ascii()
                );
            }
        }
    }
    xml += "      </PointData>\n      <CellData>\n      </CellData>\n    </Piece>\n  </ImageData>\n";
    let mut bytes = xml.into_bytes();
    if matches!(o.storage, VtiStorage::AppendedRaw | VtiStorage::AppendedBase64) {
        let encoding = if o.storage == VtiStorage::AppendedRaw { "raw" } else { "base64" };
        bytes.extend(format!("  <AppendedData encoding=\"{encoding}\">\n   _").into_bytes());
        bytes.extend(appended);
        bytes.extend(b"\n  </AppendedData>\n");
    }
    bytes.extend(b"</VTKFile>\n");
    bytes
}

pub fn write_vti(dir: &Path, name: &str, v: &Synthetic, o: VtiOptions) -> PathBuf {
    write(&dir.join(format!("{name}.vti")), &vti_bytes(v, o))
}
