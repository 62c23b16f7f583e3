//! The workgroup size of the line dispatches (a specialization constant of
//! glsl/ipsvi_line.comp). On a CPU device (lavapipe) a workgroup runs on one
//! thread: a block's pixels in too few groups leave threads idle, and the
//! costly pixels (those that cross the volume) sit together in the middle of a
//! line, so a block should give every thread a few groups. Below the SIMD width
//! lanes go unused, so groups stay at least that wide. A GPU keeps 64.

/// The workgroup size on a GPU, and the largest on a CPU.
pub const WIDEST: u32 = 64;

/// Lanes of one lavapipe SIMD batch (256-bit AVX2, 32-bit lanes): narrower
/// groups leave lanes empty.
pub const NARROWEST: u32 = 8;

/// Groups per CPU thread that a typical block should offer, so that a thread
/// that drew the cheap pixels at the ends of a line takes another group.
const GROUPS_PER_THREAD: u32 = 2;

/// Workgroup size for blocks of `pixels_per_block` pixels (the median block of
/// the frame) on a device of type `device_type` (`DeviceInfo::device_type`)
/// running on `cpu_threads` threads: the widest power of two from
/// [`NARROWEST`] to [`WIDEST`] that still gives every thread
/// [`GROUPS_PER_THREAD`] groups; [`WIDEST`] on a GPU.
pub fn line_group_size(device_type: &str, cpu_threads: u32, pixels_per_block: u32) -> u32 {
    if device_type != "CPU" {
        return WIDEST;
    }
    let wanted_groups = cpu_threads.max(1) * GROUPS_PER_THREAD;
    let mut size = WIDEST;
    while size > NARROWEST && pixels_per_block / size < wanted_groups {
        size /= 2;
    }
    size
}

/// The threads lavapipe runs shaders on: `LP_NUM_THREADS` where set, else one
/// per CPU (its default).
pub fn lavapipe_threads() -> u32 {
    std::env::var("LP_NUM_THREADS")
        .ok()
        .and_then(|v| v.trim().parse::<u32>().ok())
        .filter(|&n| n > 0)
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get() as u32))
}

/// Median of the blocks' pixel counts (0 for none).
pub fn median_pixels(pixel_counts: impl Iterator<Item = u32>) -> u32 {
    let mut counts: Vec<u32> = pixel_counts.filter(|&c| c > 0).collect();
    counts.sort_unstable();
    counts.get(counts.len() / 2).copied().unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gpus_keep_64_and_cpus_narrow_short_lines_down_to_the_simd_width() {
        assert_eq!(line_group_size("discrete GPU", 16, 64), WIDEST);
        // 2 threads: 512 pixels give 8 groups of 64, enough.
        assert_eq!(line_group_size("CPU", 2, 512), 64);
        // 2 threads, a 200-pixel line: 64 would give 3 groups; 32 gives 6.
        assert_eq!(line_group_size("CPU", 2, 200), 32);
        // 16 threads, a 64-pixel line: as narrow as the SIMD width allows.
        assert_eq!(line_group_size("CPU", 16, 64), NARROWEST);
        assert_eq!(line_group_size("CPU", 0, 0), NARROWEST);
    }

    #[test]
    fn median_skips_empty_blocks() {
        assert_eq!(median_pixels([0, 5, 1, 9].into_iter()), 5);
        assert_eq!(median_pixels([0, 0].into_iter()), 0);
    }
}
