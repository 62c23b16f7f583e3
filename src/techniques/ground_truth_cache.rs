//! The ground truth of a comparison kept on disk (`sweeplab compare
//! --reference-cache DIR`), so that techniques approximating the same model on
//! the same scene (dvr, phong, ao and the light volume all compare with single
//! scattering) render the brute-force reference once between them: on
//! lavapipe it is nearly all of a comparison's time.
//!
//! The key holds everything the reference reads: the volume's content hash,
//! the transfer function, camera, lights, render and reference settings (the
//! model and colour a technique's comparison switched to included), the image
//! size, where it was rendered (GPU or CPU), the volume's texel format, the
//! device and driver, and this build's version. A file is used only when its
//! stored key equals it byte for byte and its checksum holds; anything else
//! is a miss and the reference is rendered (and stored) again.
//!
//! File layout (little-endian): magic `SWLGTC\r\n`, key length (u32) and key,
//! width and height (u32), the reference's GPU ms and CPU s (f64, NaN for
//! none), the pixels (f32 RGB, row-major), XXH3-128 of everything before it.

use crate::linear_image::LinearImage;
use crate::render::VolumeTexels;
use crate::scene::Scene;
use crate::techniques::ao::cache::volume_content_hash;
use crate::vk::device_info::DeviceInfo;
use std::io::ErrorKind;
use std::path::PathBuf;
use xxhash_rust::xxh3::{xxh3_128, xxh3_64};

const MAGIC: &[u8; 8] = b"SWLGTC\r\n";

/// A ground truth as the comparison reports it.
#[derive(Clone, Debug, PartialEq)]
pub struct GroundTruth {
    pub image: LinearImage,
    pub gpu_ms: Option<f64>,
    pub cpu_s: Option<f64>,
}

/// What one ground truth depends on, as bytes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GroundTruthKey(Vec<u8>);

impl GroundTruthKey {
    /// The key of `scene`'s reference (the comparison scene: its reference
    /// already switched to the technique's model) rendered on `source`.
    pub fn new(scene: &Scene, source: &str, texels: VolumeTexels, device: &DeviceInfo) -> GroundTruthKey {
        let text = format!(
            "sweeplab {} at {} | {source} | {texels:?} | {} {} {} {} | volume {:032x} {:?} {:?} | {:?} | {:?} | {:?} | {:?} | {:?}",
            env!("CARGO_PKG_VERSION"),
            // The commit, not only the version: a reference changed between two
            // builds of one version must not be read back (a build from an
            // uncommitted tree shares its commit's entries: clear the folder).
            env!("SWEEPLAB_GIT_COMMIT"),
            device.name,
            device.vendor_id,
            device.device_id,
            device.driver_version,
            volume_content_hash(&scene.volume),
            scene.volume.dims,
            scene.volume.spacing,
            scene.transfer,
            scene.camera,
            scene.lights,
            scene.render,
            scene.reference,
        );
        GroundTruthKey(text.into_bytes())
    }

    fn file_name(&self) -> String {
        format!("ground-truth-{:016x}.bin", xxh3_64(&self.0))
    }
}

/// Why the cache could not be read or written (a file that is not a sound
/// entry for the key is a miss, not an error).
#[derive(Debug, thiserror::Error)]
#[error("ground-truth cache {path}: {source}")]
pub struct GroundTruthCacheError {
    pub path: PathBuf,
    pub source: std::io::Error,
}

/// A folder of ground truths.
#[derive(Clone, Debug)]
pub struct GroundTruthCache {
    pub dir: PathBuf,
}

impl GroundTruthCache {
    pub fn new(dir: impl Into<PathBuf>) -> GroundTruthCache {
        GroundTruthCache { dir: dir.into() }
    }

    /// The stored ground truth of `key`, or `None` (absent, damaged, or
    /// written for another key).
    pub fn load(&self, key: &GroundTruthKey) -> Result<Option<GroundTruth>, GroundTruthCacheError> {
        let path = self.dir.join(key.file_name());
        match std::fs::read(&path) {
            Ok(bytes) => Ok(decode(key, &bytes)),
            Err(e) if e.kind() == ErrorKind::NotFound => Ok(None),
            Err(source) => Err(GroundTruthCacheError { path, source }),
        }
    }

    /// Stores `truth` under `key` (through a temporary file renamed into
    /// place, so a crash leaves no half entry).
    pub fn store(&self, key: &GroundTruthKey, truth: &GroundTruth) -> Result<(), GroundTruthCacheError> {
        let path = self.dir.join(key.file_name());
        crate::atomic_file::write_atomically(&path, &encode(key, truth))
            .map_err(|source| GroundTruthCacheError { path, source })
    }
}

fn encode(key: &GroundTruthKey, t: &GroundTruth) -> Vec<u8> {
    let mut b = MAGIC.to_vec();
    b.extend_from_slice(&(key.0.len() as u32).to_le_bytes());
    b.extend_from_slice(&key.0);
    b.extend_from_slice(&t.image.width.to_le_bytes());
    b.extend_from_slice(&t.image.height.to_le_bytes());
    for v in [t.gpu_ms, t.cpu_s] {
        b.extend_from_slice(&v.unwrap_or(f64::NAN).to_le_bytes());
    }
    for c in t.image.pixels.iter().flatten() {
        b.extend_from_slice(&c.to_le_bytes());
    }
    let checksum = xxh3_128(&b);
    b.extend_from_slice(&checksum.to_le_bytes());
    b
}

fn decode(key: &GroundTruthKey, bytes: &[u8]) -> Option<GroundTruth> {
    let (body, checksum) = bytes.split_at_checked(bytes.len().checked_sub(16)?)?;
    if xxh3_128(body).to_le_bytes() != checksum {
        return None;
    }
    let mut r = body.strip_prefix(MAGIC.as_slice())?;
    let mut take = |n: usize| {
        let (head, rest) = r.split_at_checked(n)?;
        r = rest;
        Some(head)
    };
    let key_len = u32::from_le_bytes(take(4)?.try_into().ok()?) as usize;
    if take(key_len)? != key.0.as_slice() {
        return None;
    }
    let width = u32::from_le_bytes(take(4)?.try_into().ok()?);
    let height = u32::from_le_bytes(take(4)?.try_into().ok()?);
    let mut time = || Some(f64::from_le_bytes(take(8)?.try_into().ok()?)).map(|v| (!v.is_nan()).then_some(v));
    let (gpu_ms, cpu_s) = (time()?, time()?);
    let count = width as usize * height as usize;
    let data = take(count.checked_mul(12)?)?;
    if !r.is_empty() {
        return None;
    }
    let f = |c: &[u8]| f32::from_le_bytes(c.try_into().expect("4-byte chunks"));
    let pixels = data.chunks_exact(12).map(|p| [f(&p[0..4]), f(&p[4..8]), f(&p[8..12])]).collect();
    Some(GroundTruth { image: LinearImage { width, height, pixels }, gpu_ms, cpu_s })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn truth() -> GroundTruth {
        let mut image = LinearImage::new(3, 2);
        image.set(2, 1, [0.25, 1.5, -0.0]);
        image.set(0, 0, [1e-30, 7.0, 0.5]);
        GroundTruth { image, gpu_ms: Some(123.5), cpu_s: None }
    }

    #[test]
    fn an_entry_is_read_back_only_for_its_own_key_and_intact() {
        let dir = std::env::temp_dir().join(format!("sweeplab-ground-truth-cache-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let cache = GroundTruthCache::new(&dir);
        let key = GroundTruthKey(b"scene a, single scattering".to_vec());
        let other = GroundTruthKey(b"scene a, emissive scattering".to_vec());
        assert_eq!(cache.load(&key).unwrap(), None, "absent");
        cache.store(&key, &truth()).unwrap();
        assert_eq!(cache.load(&key).unwrap(), Some(truth()));
        assert_eq!(cache.load(&other).unwrap(), None, "another key");

        // Same file name, other key (a name collision): a miss.
        let bytes = encode(&other, &truth());
        assert_eq!(decode(&key, &bytes), None);
        // Any flipped bit or a truncation: a miss.
        let good = encode(&key, &truth());
        for at in [0, 9, 20, good.len() / 2, good.len() - 1] {
            let mut bad = good.clone();
            bad[at] ^= 0x10;
            assert_eq!(decode(&key, &bad), None, "bit flipped at {at}");
        }
        assert_eq!(decode(&key, &good[..good.len() - 5]), None);
        assert_eq!(decode(&key, &[]), None);
        std::fs::remove_dir_all(&dir).ok();
    }
}
