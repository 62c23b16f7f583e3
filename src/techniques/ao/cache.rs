//! The preprocessing result on disk, keyed by the volume's content and every
//! parameter that changes the result, so a second run loads it instead of
//! preprocessing again. A file is trusted only when everything checks out;
//! anything else is a miss with its reason, and the caller rebuilds it.
//!
//! File layout (little-endian):
//!
//! | bytes | what |
//! |---|---|
//! | 8 | magic `SWLAOC\r\n` |
//! | 4 | format version ([`FORMAT_VERSION`]) |
//! | 4 + P | parameter block length P, parameter block ([`CacheKey`]) |
//! | 8 + L | payload length L, payload ([`AoPreprocessed`]) |
//! | 16 | XXH3-128 of everything above |
//!
//! The file name is a 64-bit hash of the parameter block; the stored block is
//! compared byte for byte, so a name collision reads as stale, never as a hit.
//! Writes go to a temporary file renamed into place, so a crash mid-write
//! leaves no half file under the real name.

use std::io::ErrorKind;
use std::path::PathBuf;

use xxhash_rust::xxh3::{xxh3_128, xxh3_64, Xxh3};

use super::error::AoError;
use super::settings::{AoSettings, Backend, Metric, TrainingSet};
use super::{AoPreprocessed, PreprocessStats, StepTimings};
use crate::scene::{Volume, VoxelData};

const MAGIC: &[u8; 8] = b"SWLAOC\r\n";
/// Bump whenever the layout *or the algorithm* changes, so old results read as
/// stale.
pub const FORMAT_VERSION: u32 = 2;

/// Why a cache file was not used.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CacheMiss {
    Absent,
    /// Unreadable as a cache file (truncated, bit errors, not ours).
    Corrupt(String),
    /// A sound file for other parameters or an older format.
    Stale(String),
}

/// XXH3-128 of the voxel data with its type, dims and spacing.
pub fn volume_content_hash(volume: &Volume) -> u128 {
    let mut h = Xxh3::new();
    for d in volume.dims.to_array() {
        h.update(&d.to_le_bytes());
    }
    for s in volume.spacing.to_array() {
        h.update(&s.to_bits().to_le_bytes());
    }
    match &volume.data {
        VoxelData::U8(v) => {
            h.update(b"u8");
            h.update(v);
        }
        VoxelData::U16(v) => {
            h.update(b"u16");
            for chunk in v.chunks(4096) {
                let bytes: Vec<u8> = chunk.iter().flat_map(|x| x.to_le_bytes()).collect();
                h.update(&bytes);
            }
        }
        VoxelData::F32(v) => {
            h.update(b"f32");
            for chunk in v.chunks(4096) {
                let bytes: Vec<u8> = chunk.iter().flat_map(|x| x.to_bits().to_le_bytes()).collect();
                h.update(&bytes);
            }
        }
    }
    h.digest128()
}

/// The parameter block: content hash and every setting that changes the result.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CacheKey {
    pub block: Vec<u8>,
}

impl CacheKey {
    pub fn new(volume: &Volume, s: &AoSettings) -> CacheKey {
        let mut w = Writer::default();
        w.u128(volume_content_hash(volume));
        for v in [s.radius, s.bits, s.packed_dim, s.clusters] {
            w.u32(v);
        }
        w.u32(Metric::ALL.iter().position(|&m| m == s.metric).unwrap_or(0) as u32);
        match s.training {
            TrainingSet::Random { count, seed } => {
                w.u32(0);
                w.u32(count);
                w.u64(seed);
                w.u32(0);
            }
            TrainingSet::Gradient { eps, count, seed } => {
                w.u32(1);
                w.u32(count);
                w.u64(seed);
                w.u32(eps.to_bits());
            }
        }
        w.u32(s.lbg_iterations);
        w.u64(s.lbg_threshold.to_bits());
        CacheKey { block: w.bytes }
    }

    /// [`Self::new`] for results computed by `backend`: the CPU's key is
    /// unchanged (its files stay valid), the GPU's carries a tag.
    pub fn for_backend(volume: &Volume, s: &AoSettings, backend: Backend) -> CacheKey {
        let mut key = CacheKey::new(volume, s);
        if backend == Backend::Gpu {
            key.block.extend_from_slice(b"backend gpu");
        }
        key
    }

    pub fn file_name(&self) -> String {
        format!("ao-{:016x}.bin", xxh3_64(&self.block))
    }
}

/// `$XDG_CACHE_HOME/sweeplab/ao`, else `$HOME/.cache/sweeplab/ao`, else
/// `target/ao-cache` (relative to the working directory).
pub fn default_cache_dir() -> PathBuf {
    let non_empty = |var: &str| std::env::var_os(var).filter(|v| !v.is_empty()).map(PathBuf::from);
    if let Some(xdg) = non_empty("XDG_CACHE_HOME") {
        return xdg.join("sweeplab").join("ao");
    }
    if let Some(home) = non_empty("HOME") {
        return home.join(".cache").join("sweeplab").join("ao");
    }
    PathBuf::from("target").join("ao-cache")
}

/// A cache directory.
#[derive(Clone, Debug)]
pub struct AoCache {
    pub dir: PathBuf,
}

impl AoCache {
    pub fn new(dir: impl Into<PathBuf>) -> AoCache {
        AoCache { dir: dir.into() }
    }

    /// `ao.cache_dir` or the default.
    pub fn for_settings(settings: &AoSettings) -> AoCache {
        AoCache::new(settings.cache_dir.as_ref().map_or_else(default_cache_dir, PathBuf::from))
    }

    pub fn path(&self, key: &CacheKey) -> PathBuf {
        self.dir.join(key.file_name())
    }

    /// The cached result for `key`, or why there is none. I/O errors other
    /// than a missing file are errors.
    pub fn load(&self, key: &CacheKey) -> Result<Result<AoPreprocessed, CacheMiss>, AoError> {
        let path = self.path(key);
        match std::fs::read(&path) {
            Ok(bytes) => Ok(decode(key, &bytes)),
            Err(e) if e.kind() == ErrorKind::NotFound => Ok(Err(CacheMiss::Absent)),
            Err(source) => Err(AoError::CacheIo { path, source }),
        }
    }

    /// Writes `result` under `key` (replacing any file there).
    pub fn store(&self, key: &CacheKey, result: &AoPreprocessed) -> Result<PathBuf, AoError> {
        let path = self.path(key);
        match crate::atomic_file::write_atomically(&path, &encode(key, result)) {
            Ok(()) => Ok(path),
            Err(source) => Err(AoError::CacheIo { path, source }),
        }
    }
}

/// The whole file for `result` under `key`.
pub fn encode(key: &CacheKey, r: &AoPreprocessed) -> Vec<u8> {
    let mut payload = Writer::default();
    for v in r.dims.to_array() {
        payload.u32(v);
    }
    for v in [r.bins, r.packed_dim, r.clusters] {
        payload.u32(v);
    }
    payload.f32s(&r.codebook);
    payload.f32s(&r.packed_codebook);
    payload.f32s(&r.packing_matrix);
    payload.u64s(&r.cluster_sizes);
    payload.u32s(&r.cluster_ids);
    let s = &r.stats;
    payload.u64(s.training_vectors);
    payload.u32(s.lloyd_iterations);
    payload.u64(s.training_distortion.to_bits());
    payload.u64(s.assignment_distortion.to_bits());
    let t = &s.timings;
    for v in [t.packing, t.training_histograms, t.training, t.assignment] {
        payload.u64(v.to_bits());
    }

    let mut file = Writer::default();
    file.bytes.extend_from_slice(MAGIC);
    file.u32(FORMAT_VERSION);
    file.u32(key.block.len() as u32);
    file.bytes.extend_from_slice(&key.block);
    file.u64(payload.bytes.len() as u64);
    file.bytes.extend_from_slice(&payload.bytes);
    let checksum = xxh3_128(&file.bytes);
    file.u128(checksum);
    file.bytes
}

/// Reads a file written by [`encode`], trusting nothing.
pub fn decode(key: &CacheKey, bytes: &[u8]) -> Result<AoPreprocessed, CacheMiss> {
    let corrupt = |why: &str| CacheMiss::Corrupt(why.to_string());
    if bytes.len() < MAGIC.len() + 4 + 16 || &bytes[..MAGIC.len()] != MAGIC {
        return Err(corrupt("not an AO cache file (magic)"));
    }
    let (body, checksum) = bytes.split_at(bytes.len() - 16);
    if xxh3_128(body) != u128::from_le_bytes(checksum.try_into().map_err(|_| corrupt("checksum"))?) {
        return Err(corrupt("checksum mismatch (truncated or damaged)"));
    }
    let mut r = Reader { bytes: &body[MAGIC.len()..] };
    let version = r.u32()?;
    if version != FORMAT_VERSION {
        return Err(CacheMiss::Stale(format!("format version {version}, this build writes {FORMAT_VERSION}")));
    }
    let block_len = r.u32()? as usize;
    if r.take(block_len)? != key.block.as_slice() {
        return Err(CacheMiss::Stale("written for other parameters or another volume".into()));
    }
    let payload_len = r.u64()?;
    if payload_len != r.bytes.len() as u64 {
        return Err(corrupt("payload length does not match the file"));
    }
    let dims = glam::UVec3::new(r.u32()?, r.u32()?, r.u32()?);
    let (bins, packed_dim, clusters) = (r.u32()?, r.u32()?, r.u32()?);
    let voxels = dims.x as usize * dims.y as usize * dims.z as usize;
    let result = AoPreprocessed {
        dims,
        bins,
        packed_dim,
        clusters,
        codebook: r.f32s(clusters as usize * bins as usize)?,
        packed_codebook: r.f32s(clusters as usize * packed_dim as usize)?,
        packing_matrix: r.f32s(bins as usize * packed_dim as usize)?,
        cluster_sizes: r.u64s(clusters as usize)?,
        cluster_ids: r.u32s(voxels)?,
        stats: PreprocessStats {
            training_vectors: r.u64()?,
            lloyd_iterations: r.u32()?,
            training_distortion: f64::from_bits(r.u64()?),
            assignment_distortion: f64::from_bits(r.u64()?),
            timings: StepTimings {
                packing: f64::from_bits(r.u64()?),
                training_histograms: f64::from_bits(r.u64()?),
                training: f64::from_bits(r.u64()?),
                assignment: f64::from_bits(r.u64()?),
            },
        },
    };
    if !r.bytes.is_empty() {
        return Err(corrupt("bytes after the payload"));
    }
    Ok(result)
}

#[derive(Default)]
struct Writer {
    bytes: Vec<u8>,
}

impl Writer {
    fn u32(&mut self, v: u32) {
        self.bytes.extend_from_slice(&v.to_le_bytes());
    }
    fn u64(&mut self, v: u64) {
        self.bytes.extend_from_slice(&v.to_le_bytes());
    }
    fn u128(&mut self, v: u128) {
        self.bytes.extend_from_slice(&v.to_le_bytes());
    }
    fn f32s(&mut self, v: &[f32]) {
        self.bytes.extend(v.iter().flat_map(|x| x.to_bits().to_le_bytes()));
    }
    fn u32s(&mut self, v: &[u32]) {
        self.bytes.extend(v.iter().flat_map(|x| x.to_le_bytes()));
    }
    fn u64s(&mut self, v: &[u64]) {
        self.bytes.extend(v.iter().flat_map(|x| x.to_le_bytes()));
    }
}

struct Reader<'a> {
    bytes: &'a [u8],
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize) -> Result<&'a [u8], CacheMiss> {
        if self.bytes.len() < n {
            return Err(CacheMiss::Corrupt("ends early".into()));
        }
        let (head, tail) = self.bytes.split_at(n);
        self.bytes = tail;
        Ok(head)
    }
    fn u32(&mut self) -> Result<u32, CacheMiss> {
        Ok(u32::from_le_bytes(self.take(4)?.try_into().unwrap_or_default()))
    }
    fn u64(&mut self) -> Result<u64, CacheMiss> {
        Ok(u64::from_le_bytes(self.take(8)?.try_into().unwrap_or_default()))
    }
    fn f32s(&mut self, n: usize) -> Result<Vec<f32>, CacheMiss> {
        let b = self.take(n.checked_mul(4).ok_or_else(|| CacheMiss::Corrupt("size".into()))?)?;
        Ok(b.chunks_exact(4).map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect())
    }
    fn u32s(&mut self, n: usize) -> Result<Vec<u32>, CacheMiss> {
        let b = self.take(n.checked_mul(4).ok_or_else(|| CacheMiss::Corrupt("size".into()))?)?;
        Ok(b.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect())
    }
    fn u64s(&mut self, n: usize) -> Result<Vec<u64>, CacheMiss> {
        let b = self.take(n.checked_mul(8).ok_or_else(|| CacheMiss::Corrupt("size".into()))?)?;
        Ok(b.chunks_exact(8).map(|c| u64::from_le_bytes(c.try_into().unwrap_or_default())).collect())
    }
}
