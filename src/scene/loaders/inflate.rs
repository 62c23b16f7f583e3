//! zlib and gzip decompression with the output size fixed by the header: never
//! more than the promised bytes are produced (zip bombs), and a stream that ends
//! early or runs long is an error.

use std::io::Read;

use flate2::read::MultiGzDecoder;
use flate2::{Decompress, FlushDecompress, Status};

use super::error::FormatProblem;

/// Deflate cannot expand one input byte into more than 1032 output bytes; a header
/// promising more than that is lying, and we refuse before allocating for it.
const MAX_DEFLATE_RATIO: u64 = 1032;
/// Room for stream headers and trailers in the ratio check.
const RATIO_SLACK: u64 = 1024;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stream {
    /// RFC 1950 (VTK, MetaImage).
    Zlib,
    /// RFC 1952, possibly several members (NRRD, `.nii.gz`).
    Gzip,
}

/// Inflates `compressed` into a new buffer of exactly `len` bytes.
pub fn inflate_exact(compressed: &[u8], stream: Stream, len: usize, what: &str) -> Result<Vec<u8>, FormatProblem> {
    let mut out = Vec::new();
    inflate_append(compressed, stream, len, what, &mut out)?;
    Ok(out)
}

/// Inflates `compressed`, which must hold exactly `len` bytes, onto the end of `out`.
pub fn inflate_append(
    compressed: &[u8],
    stream: Stream,
    len: usize,
    what: &str,
    out: &mut Vec<u8>,
) -> Result<(), FormatProblem> {
    check_ratio(compressed.len() as u64, len as u64, what)?;
    // One spare byte so that a stream running past `len` is noticed.
    out.try_reserve_exact(len + 1)
        .map_err(|_| FormatProblem::OutOfMemory { what: what.to_string(), bytes: len as u64 })?;
    let start = out.len();
    match stream {
        Stream::Zlib => inflate_zlib(compressed, len, what, out)?,
        Stream::Gzip => {
            let mut limited = MultiGzDecoder::new(compressed).take(len as u64 + 1);
            limited
                .read_to_end(out)
                .map_err(|e| FormatProblem::Decompress { what: what.to_string(), reason: e.to_string() })?;
        }
    }
    let produced = out.len() - start;
    if produced > len {
        return Err(FormatProblem::InflatedTooLong { what: what.to_string(), expected: len as u64 });
    }
    if produced < len {
        return Err(FormatProblem::InflatedTooShort {
            what: what.to_string(),
            expected: len as u64,
            found: produced as u64,
        });
    }
    Ok(())
}

/// Refuses sizes no deflate stream of `compressed_len` bytes can produce.
pub fn check_ratio(compressed_len: u64, len: u64, what: &str) -> Result<(), FormatProblem> {
    let most = compressed_len.saturating_mul(MAX_DEFLATE_RATIO).saturating_add(RATIO_SLACK);
    if len > most {
        return Err(FormatProblem::InflatedTooShort { what: what.to_string(), expected: len, found: most });
    }
    Ok(())
}

/// Drives the raw decompressor so that a stream cut short (which the `Read`
/// adapters report as a clean end) is an error, and its checksum is verified.
fn inflate_zlib(compressed: &[u8], len: usize, what: &str, out: &mut Vec<u8>) -> Result<(), FormatProblem> {
    let start = out.len();
    let limit = start + len + 1;
    let mut inflater = Decompress::new(true);
    loop {
        let consumed = inflater.total_in() as usize;
        let before = (consumed, out.len());
        // decompress_vec writes only into spare capacity, which ends at `limit`.
        let status = inflater
            .decompress_vec(&compressed[consumed..], out, FlushDecompress::None)
            .map_err(|e| FormatProblem::Decompress { what: what.to_string(), reason: e.to_string() })?;
        if status == Status::StreamEnd {
            break;
        }
        if out.len() >= limit {
            break; // too long, reported by the caller
        }
        let progressed = (inflater.total_in() as usize, out.len()) != before;
        if !progressed {
            if inflater.total_in() as usize >= compressed.len() {
                let found = out.len() - start;
                if found < len {
                    return Err(FormatProblem::InflatedTooShort {
                        what: what.to_string(),
                        expected: len as u64,
                        found: found as u64,
                    });
                }
                return Err(FormatProblem::Decompress {
                    what: what.to_string(),
                    reason: "stream ends before its checksum".into(),
                });
            }
            return Err(FormatProblem::Decompress {
                what: what.to_string(),
                reason: "decompressor made no progress".into(),
            });
        }
    }
    Ok(())
}
