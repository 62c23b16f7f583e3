//! Volume file loaders: VTK XML ImageData, MetaImage, NRRD, NIfTI-1 and our own
//! raw-with-text-header format, all normalized the same way (see [`decode`] and
//! docs/volume-formats.md).
//!
//! Loaders never trust a header: sizes are validated and compared with the bytes
//! really present before anything is allocated, decompression stops at the size
//! the header promises, and every error names the file.

mod base64;
mod data_file;
mod decode;
mod error;
mod fields;
mod inflate;
mod metaimage;
mod nifti;
mod nrrd;
mod raw_header;
mod vti;

use std::path::{Path, PathBuf};

pub use error::{FormatProblem, LoadError};

use crate::scene::volume::Volume;

/// File name endings [`load_volume`] understands, for messages and file pickers.
pub const SUPPORTED_EXTENSIONS: [&str; 8] = [".vti", ".mhd", ".mha", ".nrrd", ".nhdr", ".nii", ".nii.gz", ".vhdr"];

/// The volume file formats, as told by the file name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VolumeFormat {
    /// VTK XML ImageData (`.vti`).
    Vti,
    /// MetaImage (`.mhd` with a data file, `.mha` single file).
    MetaImage,
    /// NRRD (`.nrrd`, `.nhdr`).
    Nrrd,
    /// NIfTI-1 single file (`.nii`).
    Nifti,
    /// NIfTI-1 single file, gzip-compressed (`.nii.gz`).
    NiftiGzip,
    /// sweeplab raw-volume header (`.vhdr`).
    RawHeader,
}

impl VolumeFormat {
    /// Recognizes the format from the file name's ending, ignoring case.
    pub fn from_path(path: &Path) -> Option<VolumeFormat> {
        let name = path.file_name()?.to_string_lossy().to_ascii_lowercase();
        if name.ends_with(".nii.gz") {
            return Some(VolumeFormat::NiftiGzip);
        }
        let extension = name.rsplit_once('.')?.1;
        match extension {
            "vti" => Some(VolumeFormat::Vti),
            "mhd" | "mha" => Some(VolumeFormat::MetaImage),
            "nrrd" | "nhdr" => Some(VolumeFormat::Nrrd),
            "nii" => Some(VolumeFormat::Nifti),
            "vhdr" => Some(VolumeFormat::RawHeader),
            _ => None,
        }
    }
}

/// Loads a volume file, choosing the format by the file name's ending.
pub fn load_volume(path: &Path) -> Result<Volume, LoadError> {
    let format =
        VolumeFormat::from_path(path).ok_or_else(|| LoadError::UnknownExtension { file: path.to_path_buf() })?;
    let bytes = std::fs::read(path).map_err(|source| LoadError::Io { file: path.to_path_buf(), source })?;
    let name = volume_name(path);
    let loaded = match format {
        VolumeFormat::Vti => vti::load(&bytes, name),
        VolumeFormat::MetaImage => metaimage::load(path, &bytes, name),
        VolumeFormat::Nrrd => nrrd::load(path, &bytes, name),
        VolumeFormat::Nifti => nifti::load(&bytes, name),
        VolumeFormat::NiftiGzip => nifti::load_gzip(&bytes, name),
        VolumeFormat::RawHeader => raw_header::load(path, &bytes, name),
    };
    loaded.map_err(|problem| problem.in_file(path))
}

/// The file name without its format ending (`engine.vti` -> `engine`).
fn volume_name(path: &Path) -> String {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let lower = name.to_ascii_lowercase();
    let cut =
        if lower.ends_with(".nii.gz") { name.len() - ".nii.gz".len() } else { name.rfind('.').unwrap_or(name.len()) };
    name[..cut].to_string()
}

/// The repository's `data/` folder, where the real data sets live
/// (data/README.md): the checkout this build was made from, so that tests and
/// the binary find it from any working directory.
pub const DEFAULT_DATA_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/data");

/// Folder of the real data sets: `$SWEEPLAB_DATA`, else [`DEFAULT_DATA_DIR`].
pub fn data_dir() -> PathBuf {
    match std::env::var_os("SWEEPLAB_DATA") {
        Some(dir) if !dir.is_empty() => PathBuf::from(dir),
        _ => PathBuf::from(DEFAULT_DATA_DIR),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_by_file_name() {
        let cases = [
            ("a/engine.vti", Some(VolumeFormat::Vti)),
            ("x.MHD", Some(VolumeFormat::MetaImage)),
            ("x.mha", Some(VolumeFormat::MetaImage)),
            ("x.nrrd", Some(VolumeFormat::Nrrd)),
            ("x.NHDR", Some(VolumeFormat::Nrrd)),
            ("brain.nii", Some(VolumeFormat::Nifti)),
            ("brain.NII.GZ", Some(VolumeFormat::NiftiGzip)),
            ("scan.vhdr", Some(VolumeFormat::RawHeader)),
            ("scan.raw", None),
            ("archive.gz", None),
            ("noextension", None),
        ];
        for (path, format) in cases {
            assert_eq!(VolumeFormat::from_path(Path::new(path)), format, "{path}");
        }
    }

    #[test]
    fn names_drop_the_format_ending() {
        assert_eq!(volume_name(Path::new("d/engine.vti")), "engine");
        assert_eq!(volume_name(Path::new("brain.T1.nii.gz")), "brain.T1");
        assert_eq!(volume_name(Path::new("scan.VHDR")), "scan");
    }

    #[test]
    fn unknown_extension_lists_the_supported_ones() {
        let error = load_volume(Path::new("/nowhere/scan.dcm")).unwrap_err();
        let message = error.to_string();
        assert!(message.starts_with("/nowhere/scan.dcm: "), "{message}");
        for extension in SUPPORTED_EXTENSIONS {
            assert!(message.contains(extension), "{message}");
        }
    }
}
