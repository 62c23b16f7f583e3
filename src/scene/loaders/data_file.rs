//! Reading voxel bytes from a detached data file or from the tail of the header
//! file, always checking the sizes against the bytes really there before
//! allocating anything the header asks for.

use std::fs::File;
use std::io::{Read, Seek, SeekFrom};
use std::path::{Path, PathBuf};

use super::decode::try_vec_with_capacity;
use super::error::FormatProblem;

/// Where the voxels start inside the data.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Skip {
    /// After this many header bytes.
    Bytes(u64),
    /// The voxels are the last bytes of the data (NRRD `byte skip: -1`,
    /// MetaImage `HeaderSize = -1`).
    ToTail,
}

/// Resolves a data file name from a header: relative names are relative to the
/// header's folder.
pub fn resolve(header: &Path, name: &str) -> PathBuf {
    let name = Path::new(name);
    if name.is_absolute() {
        return name.to_path_buf();
    }
    header.parent().map(|dir| dir.join(name)).unwrap_or_else(|| name.to_path_buf())
}

fn io_error(path: &Path) -> impl FnOnce(std::io::Error) -> FormatProblem + '_ {
    move |source| FormatProblem::DataFile { path: path.to_path_buf(), source }
}

/// Reads exactly `len` uncompressed voxel bytes from the file at `path`.
pub fn read_exact(path: &Path, skip: Skip, len: usize) -> Result<Vec<u8>, FormatProblem> {
    let what = format!("data file {}", path.display());
    let mut file = File::open(path).map_err(io_error(path))?;
    let size = file.metadata().map_err(io_error(path))?.len();
    let start = checked_start(size, skip, len as u64, &what)?;
    file.seek(SeekFrom::Start(start)).map_err(io_error(path))?;
    let mut bytes = try_vec_with_capacity(len, &what)?;
    file.take(len as u64).read_to_end(&mut bytes).map_err(io_error(path))?;
    if bytes.len() != len {
        // The file shrank while we read it.
        return Err(FormatProblem::Truncated { what, expected: start + len as u64, found: start + bytes.len() as u64 });
    }
    Ok(bytes)
}

/// Reads the file at `path` from byte `skip` to its end (compressed data, whose
/// size is only known once inflated; the file's own size bounds the allocation).
pub fn read_rest(path: &Path, skip: u64) -> Result<Vec<u8>, FormatProblem> {
    let what = format!("data file {}", path.display());
    let mut file = File::open(path).map_err(io_error(path))?;
    let size = file.metadata().map_err(io_error(path))?.len();
    if size < skip {
        return Err(FormatProblem::Truncated { what, expected: skip, found: size });
    }
    file.seek(SeekFrom::Start(skip)).map_err(io_error(path))?;
    let mut bytes = try_vec_with_capacity((size - skip) as usize, &what)?;
    file.read_to_end(&mut bytes).map_err(io_error(path))?;
    Ok(bytes)
}

/// Exactly `len` voxel bytes of `data` (which holds only voxels after `skip`).
pub fn exact_slice<'a>(data: &'a [u8], skip: Skip, len: usize, what: &str) -> Result<&'a [u8], FormatProblem> {
    let start = checked_start(data.len() as u64, skip, len as u64, what)? as usize;
    Ok(&data[start..start + len])
}

/// Offset of the voxels in data of `size` bytes; the size must match exactly.
fn checked_start(size: u64, skip: Skip, len: u64, what: &str) -> Result<u64, FormatProblem> {
    let start = match skip {
        Skip::Bytes(n) => n,
        Skip::ToTail => size.saturating_sub(len),
    };
    let expected = start.saturating_add(len);
    if size < expected {
        return Err(FormatProblem::Truncated { what: what.to_string(), expected, found: size });
    }
    if size > expected {
        return Err(FormatProblem::TooLong { what: what.to_string(), expected, found: size });
    }
    Ok(start)
}

/// Skips `count` lines (NRRD `line skip`) at the start of `data`.
pub fn skip_lines(data: &[u8], count: u64, what: &str) -> Result<usize, FormatProblem> {
    let mut position = 0;
    for skipped in 0..count {
        match data[position..].iter().position(|&b| b == b'\n') {
            Some(i) => position += i + 1,
            None => {
                return Err(FormatProblem::syntax(format!("{what} ends after {skipped} of the {count} lines to skip")))
            }
        }
    }
    Ok(position)
}
