//! The driver's pipeline cache (`VkPipelineCache`), kept on disk between runs:
//! a pipeline compiled once (shader to device code, the hitch of a GPU
//! driver's first frame) is taken from the file by the next process.
//!
//! One file per device, `pipelines-<vendorID>-<deviceID>.bin` in
//! [`PipelineCacheDir`]. The file is the driver's data behind a small frame of
//! ours (magic, length, xxh3 of the data), so a truncated or corrupt file is
//! told apart from a valid one before the driver sees it. The driver's data
//! starts with `VkPipelineCacheHeaderVersionOne` (Vulkan spec, "Pipeline Cache
//! Header"; all fields least significant byte first, 32 bytes): headerSize
//! (u32), headerVersion (u32, 1), vendorID (u32), deviceID (u32),
//! pipelineCacheUUID (16 bytes). A file whose header names another device or
//! driver build is ignored with a note, never an error: the cache starts empty
//! and the next save replaces the file. Saves write a temporary file beside
//! the cache and rename it over, so a reader never sees half a file.

use super::error::{VkError, VkResultExt};
use ash::vk;
use std::path::PathBuf;
use xxhash_rust::xxh3::xxh3_64;

/// Environment variable naming the directory of the cache files; an empty
/// value turns the cache off.
pub const PIPELINE_CACHE_ENV: &str = "SWEEPLAB_PIPELINE_CACHE";

/// The frame of our file: magic, then the data's length and xxh3 (u64 each, LE).
const MAGIC: &[u8; 8] = b"SWLPCv01";
const FRAME_BYTES: usize = 8 + 8 + 8;
/// `VkPipelineCacheHeaderVersionOne`: 4 + 4 + 4 + 4 + 16 bytes.
const HEADER_ONE_BYTES: usize = 32;

/// Where the cache files live.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum PipelineCacheDir {
    /// `$SWEEPLAB_PIPELINE_CACHE` if set (empty: off), else
    /// `$XDG_CACHE_HOME/sweeplab`, else `$HOME/.cache/sweeplab`, else off.
    #[default]
    FromEnvironment,
    At(PathBuf),
    Off,
}

impl PipelineCacheDir {
    /// The directory, or `None` where the cache is off.
    pub fn resolve(&self) -> Option<PathBuf> {
        match self {
            PipelineCacheDir::At(dir) => Some(dir.clone()),
            PipelineCacheDir::Off => None,
            PipelineCacheDir::FromEnvironment => {
                if let Some(value) = std::env::var_os(PIPELINE_CACHE_ENV) {
                    return (!value.is_empty()).then(|| PathBuf::from(value));
                }
                let non_empty = |var: &str| std::env::var_os(var).filter(|v| !v.is_empty()).map(PathBuf::from);
                non_empty("XDG_CACHE_HOME")
                    .map(|xdg| xdg.join("sweeplab"))
                    .or_else(|| non_empty("HOME").map(|home| home.join(".cache").join("sweeplab")))
            }
        }
    }
}

/// What a cache header names: the device and the driver build whose data it holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CacheDevice {
    pub vendor_id: u32,
    pub device_id: u32,
    pub uuid: [u8; vk::UUID_SIZE],
}

impl CacheDevice {
    pub fn of(props: &vk::PhysicalDeviceProperties) -> CacheDevice {
        CacheDevice { vendor_id: props.vendor_id, device_id: props.device_id, uuid: props.pipeline_cache_uuid }
    }

    /// The device's file; a new driver build keeps the name and replaces the contents.
    pub fn file_name(&self) -> String {
        format!("pipelines-{:04x}-{:04x}.bin", self.vendor_id, self.device_id)
    }
}

/// Why a cache file was not given to the driver.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum Rejected {
    #[error("not a sweeplab pipeline cache (no magic)")]
    NoMagic,
    #[error("truncated or corrupt ({0})")]
    Corrupt(&'static str),
    #[error("its header is {0}: unknown")]
    Header(String),
    #[error("written for device {vendor:04x}:{device:04x}, driver cache {uuid}; this is {want}")]
    OtherDevice { vendor: u32, device: u32, uuid: String, want: String },
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

fn le_u32(bytes: &[u8], at: usize) -> u32 {
    u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]])
}

fn le_u64(bytes: &[u8], at: usize) -> u64 {
    let mut b = [0u8; 8];
    b.copy_from_slice(&bytes[at..at + 8]);
    u64::from_le_bytes(b)
}

/// The file's bytes for the driver's `data`.
pub fn encode(data: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(FRAME_BYTES + data.len());
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&(data.len() as u64).to_le_bytes());
    out.extend_from_slice(&xxh3_64(data).to_le_bytes());
    out.extend_from_slice(data);
    out
}

/// The driver's data in `file`, if the frame is intact and the header names `device`.
pub fn decode<'a>(file: &'a [u8], device: &CacheDevice) -> Result<&'a [u8], Rejected> {
    if file.len() < MAGIC.len() || &file[..MAGIC.len()] != MAGIC {
        return Err(Rejected::NoMagic);
    }
    if file.len() < FRAME_BYTES {
        return Err(Rejected::Corrupt("shorter than its frame"));
    }
    let (len, hash) = (le_u64(file, 8), le_u64(file, 16));
    let data = &file[FRAME_BYTES..];
    if data.len() as u64 != len {
        return Err(Rejected::Corrupt("length differs from the recorded one"));
    }
    if xxh3_64(data) != hash {
        return Err(Rejected::Corrupt("checksum differs"));
    }
    check_header(data, device)?;
    Ok(data)
}

/// `data` starts with a version-one header naming `device`.
pub fn check_header(data: &[u8], device: &CacheDevice) -> Result<(), Rejected> {
    if data.len() < HEADER_ONE_BYTES {
        return Err(Rejected::Header(format!("{} bytes, shorter than version one's {HEADER_ONE_BYTES}", data.len())));
    }
    let (size, version) = (le_u32(data, 0), le_u32(data, 4));
    if (size as usize) < HEADER_ONE_BYTES || size as usize > data.len() {
        return Err(Rejected::Header(format!("headerSize {size}")));
    }
    if version != vk::PipelineCacheHeaderVersion::ONE.as_raw() as u32 {
        return Err(Rejected::Header(format!("headerVersion {version}")));
    }
    let mut uuid = [0u8; vk::UUID_SIZE];
    uuid.copy_from_slice(&data[16..32]);
    let found = CacheDevice { vendor_id: le_u32(data, 8), device_id: le_u32(data, 12), uuid };
    if found != *device {
        return Err(Rejected::OtherDevice {
            vendor: found.vendor_id,
            device: found.device_id,
            uuid: hex(&found.uuid),
            want: format!("{:04x}:{:04x}, driver cache {}", device.vendor_id, device.device_id, hex(&device.uuid)),
        });
    }
    Ok(())
}

/// The context's `VkPipelineCache`, from its file where one was valid.
pub struct PipelineCache {
    pub raw: vk::PipelineCache,
    /// The device's file; `None`: the cache is off (kept in memory only).
    pub path: Option<PathBuf>,
    /// Bytes of driver data taken from the file (0: it started empty).
    pub loaded_bytes: usize,
    /// Why an existing file was ignored.
    pub note: Option<String>,
}

impl PipelineCache {
    /// Creates the cache, filled from `dir`'s file for `cache_device` where it is valid.
    pub fn open(device: &ash::Device, cache_device: &CacheDevice, dir: Option<PathBuf>) -> Result<Self, VkError> {
        let path = dir.map(|d| d.join(cache_device.file_name()));
        let file = path.as_ref().and_then(|p| std::fs::read(p).ok());
        let mut note = None;
        let initial: &[u8] = match &file {
            Some(bytes) => match decode(bytes, cache_device) {
                Ok(data) => data,
                Err(why) => {
                    note = path.as_ref().map(|p| format!("pipeline cache {}: ignored, {why}", p.display()));
                    &[]
                }
            },
            None => &[],
        };
        let info = vk::PipelineCacheCreateInfo::default().initial_data(initial);
        // SAFETY: valid device; the initial data is empty or a header-checked
        // blob this driver build wrote (the spec lets a driver refuse it quietly).
        let raw = unsafe { device.create_pipeline_cache(&info, None) }.call("vkCreatePipelineCache")?;
        Ok(PipelineCache { raw, path, loaded_bytes: initial.len(), note })
    }

    /// Writes the driver's current data to the file; the bytes written, or
    /// `None` where the cache is off.
    pub fn save(&self, device: &ash::Device) -> Result<Option<usize>, VkError> {
        let Some(path) = &self.path else { return Ok(None) };
        // SAFETY: the cache belongs to this device; reading its data is
        // internally synchronized with pipeline creation.
        let data = unsafe { device.get_pipeline_cache_data(self.raw) }.call("vkGetPipelineCacheData")?;
        crate::atomic_file::write_atomically(path, &encode(&data))
            .map_err(|e| VkError::PipelineCache { path: path.display().to_string(), message: e.to_string() })?;
        Ok(Some(data.len()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const DEVICE: CacheDevice = CacheDevice { vendor_id: 0x10005, device_id: 0, uuid: [7; 16] };

    fn header(device: &CacheDevice) -> Vec<u8> {
        let mut h = Vec::new();
        h.extend_from_slice(&32u32.to_le_bytes());
        h.extend_from_slice(&1u32.to_le_bytes());
        h.extend_from_slice(&device.vendor_id.to_le_bytes());
        h.extend_from_slice(&device.device_id.to_le_bytes());
        h.extend_from_slice(&device.uuid);
        h.extend_from_slice(b"driver payload");
        h
    }

    #[test]
    fn a_file_round_trips_and_each_kind_of_damage_is_told_apart() {
        let data = header(&DEVICE);
        let file = encode(&data);
        assert_eq!(decode(&file, &DEVICE), Ok(&data[..]));
        assert_eq!(decode(b"garbage!", &DEVICE), Err(Rejected::NoMagic));
        assert!(matches!(decode(&file[..file.len() - 1], &DEVICE), Err(Rejected::Corrupt(_))));
        let mut flipped = file.clone();
        *flipped.last_mut().unwrap() ^= 1;
        assert_eq!(decode(&flipped, &DEVICE), Err(Rejected::Corrupt("checksum differs")));
    }

    #[test]
    fn a_header_of_another_device_or_driver_build_or_version_is_refused() {
        let other = CacheDevice { device_id: 1, ..DEVICE };
        let e = decode(&encode(&header(&other)), &DEVICE).unwrap_err();
        assert!(matches!(e, Rejected::OtherDevice { device: 1, .. }), "{e}");
        let rebuilt = CacheDevice { uuid: [8; 16], ..DEVICE };
        assert!(matches!(check_header(&header(&rebuilt), &DEVICE), Err(Rejected::OtherDevice { .. })));
        let mut v2 = header(&DEVICE);
        v2[4] = 2;
        assert_eq!(check_header(&v2, &DEVICE), Err(Rejected::Header("headerVersion 2".into())));
        let mut huge = header(&DEVICE);
        huge[0..4].copy_from_slice(&4096u32.to_le_bytes());
        assert_eq!(check_header(&huge, &DEVICE), Err(Rejected::Header("headerSize 4096".into())));
        assert!(matches!(check_header(&header(&DEVICE)[..20], &DEVICE), Err(Rejected::Header(_))));
    }

    #[test]
    fn the_environment_names_the_directory_and_an_empty_value_turns_it_off() {
        assert_eq!(PipelineCacheDir::Off.resolve(), None);
        assert_eq!(PipelineCacheDir::At("/x".into()).resolve(), Some(PathBuf::from("/x")));
        assert_eq!(DEVICE.file_name(), "pipelines-10005-0000.bin");
    }
}
