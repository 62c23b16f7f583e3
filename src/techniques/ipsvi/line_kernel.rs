//! Which kernel marches a line block's pixels (`ipsvi.line_kernel`): the
//! serial kernel (glsl/ipsvi_line.comp, one invocation per pixel, its whole
//! view ray) or the segmented kernel (glsl/ipsvi_line_segmented.comp, a
//! cluster of `segments` invocations per pixel, one depth segment each,
//! combined by subgroup shuffles, and through shared memory where the
//! cluster spans subgroups). Both run the same dispatch and barrier per
//! line block; docs/ipsvi.md "The segmented line kernel" compares them.

use super::cache_update::{parse_name, CacheUpdate, WritePass};
use super::merged_steps::Lanes;
use super::settings::IpsviSettings;
use crate::vk::subgroups::SubgroupSupport;
use std::str::FromStr;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LineKernel {
    /// Per device type (see [`default_kernel`]): serial on a CPU device,
    /// segmented on a GPU where the frame's modes and the device allow it.
    Auto,
    Serial,
    Segmented,
}

impl LineKernel {
    pub const ALL: [LineKernel; 3] = [LineKernel::Auto, LineKernel::Serial, LineKernel::Segmented];
    pub fn name(self) -> &'static str {
        match self {
            LineKernel::Auto => "auto",
            LineKernel::Serial => "serial",
            LineKernel::Segmented => "segmented",
        }
    }
}

impl FromStr for LineKernel {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        parse_name(s, &LineKernel::ALL, LineKernel::name)
    }
}

/// Segments per pixel a GPU gets by default: at 512 pixels per line 16,384
/// invocations per line dispatch (the H200 keeps about 270,000 in flight,
/// `../shared/records/nvidia-h200-2026-12-04/`), and a line's longest serial
/// chain 1/22.5 and 1/30.3 of the serial kernel's on the paper's Table 1
/// scene at 256 and 512 (counted on lavapipe: docs/ipsvi.md, "The line
/// shape"); one subgroup of a 32-lane GPU, so no workgroup barrier. Capped by
/// the device's smallest subgroup; not yet chosen by a GPU measurement.
pub const GPU_SEGMENTS: u32 = 32;

/// Segments per pixel on a CPU device when the segmented kernel is asked for
/// without a count: lavapipe's subgroup (its SIMD width, 8 lanes).
pub const CPU_SEGMENTS: u32 = 8;

/// Rounds a ray's samples are dealt to its segments in (`segment_rounds`).
pub const DEFAULT_ROUNDS: u32 = 16;

/// Subgroups one pixel's segments may span (glsl/ipsvi_segment_scan.glsl's
/// MAX_CLUSTER_SUBGROUPS).
pub const MAX_CLUSTER_SUBGROUPS: u32 = 32;

/// The kernel a renderer runs: `segments` invocations per pixel (1: the serial kernel).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct KernelChoice {
    /// The segmented kernel, one segment per pixel included (`segments = 1`
    /// is the segmented kernel reproducing the serial one: tested).
    pub segmented: bool,
    pub segments: u32,
    /// Rounds of the segmented kernel (unused by the serial one).
    pub rounds: u32,
    /// A pixel's segments span several subgroups (more segments than the
    /// smallest subgroup): its workgroup is the pixel's `segments`
    /// invocations, their parts combined through shared memory between
    /// workgroup barriers.
    pub cross_subgroups: bool,
    /// Invocations per cache texel, its marches toward the light split over
    /// them (1: one invocation marches them whole).
    pub texel_lanes: u32,
}

impl KernelChoice {
    pub const SERIAL: KernelChoice =
        KernelChoice { segmented: false, segments: 1, rounds: 1, cross_subgroups: false, texel_lanes: 1 };

    /// How `render` and bench rows name it: `serial`, `segmented x32`,
    /// `segmented x32, texels x4`.
    pub fn label(&self) -> String {
        match (self.segmented, self.texel_lanes) {
            (false, _) => "serial".to_string(),
            (true, 1) => format!("segmented x{}", self.segments),
            (true, t) => format!("segmented x{}, texels x{t}", self.segments),
        }
    }

    /// Invocations per pixel and per texel of its line dispatches.
    pub fn lanes(&self) -> Lanes {
        Lanes { segments: self.segments, texels: self.texel_lanes }
    }
}

/// `texel_segments = 0`: a texel's lanes for `segments` per pixel. A texel's
/// march carries the light from where the texel was last written, one plane
/// spacing or more along the light: on the paper's Table 1 scene its chain
/// was 1/16 to 1/28 of a pixel's in the serial kernel, and at 32 segments
/// with 2 lanes it still bounded many lines (a line's median chain 23, 15
/// with 4: docs/ipsvi.md, "The line shape"), so an eighth of the segments;
/// none below 16 segments, at most 16. At 128 segments 16 lanes took that
/// scene's median line chain at 256x256 from 7 to 5 (the texels' from 4 to
/// 3, the pixels' 5 then binding); at 64, where the pixels' 8 binds, 16
/// lanes changed nothing. Where texels do not bind (the CT engine's scene
/// defaults) 16 lanes add only invocations (1.8x): not yet weighed on a GPU.
pub fn auto_texel_lanes(segments: u32) -> u32 {
    (segments / 8).clamp(1, 16)
}

/// Why the segmented kernel cannot run `s`'s modes (None: it can). It runs
/// only where a pixel's march reads and never writes: light rays, or view
/// samples with the texel write pass.
pub fn segmented_refusal(s: &IpsviSettings) -> Option<String> {
    if s.cache_update == CacheUpdate::ViewSamples && s.write_pass_run() == Some(WritePass::Sample) {
        let why = match s.write_pass {
            WritePass::Sample => "ipsvi.write_pass = \"sample\"".to_string(),
            _ => format!(
                "ipsvi.write_pass = \"auto\" takes the sample pass here: the texel pass needs ipsvi.{}",
                s.texel_pass_needs().unwrap_or("?")
            ),
        };
        return Some(format!(
            "ipsvi.line_kernel = \"segmented\" cannot run the sample write pass ({why}): there the view samples \
             store into the cache inside their march, and a run's writing sample and its light may lie in \
             another invocation's segment; use ipsvi.line_kernel = \"serial\", or the texel pass"
        ));
    }
    None
}

/// The kernel for `s` on a device of type `device_type` (DeviceInfo) with
/// `subgroups`: an error naming the setting where it asks for what cannot run.
pub fn choose(s: &IpsviSettings, device_type: &str, subgroups: &SubgroupSupport) -> Result<KernelChoice, String> {
    let segmented = |segments: u32| {
        let texel_lanes = match s.texel_segments {
            0 => auto_texel_lanes(segments).min(subgroups.min_size.max(1)),
            t => t,
        };
        KernelChoice {
            segmented: true,
            segments,
            rounds: s.segment_rounds,
            cross_subgroups: segments > subgroups.min_size,
            texel_lanes,
        }
    };
    match s.line_kernel {
        LineKernel::Serial => Ok(KernelChoice::SERIAL),
        LineKernel::Segmented => {
            if let Some(why) = segmented_refusal(s) {
                return Err(why);
            }
            if let Some(missing) = subgroups.missing_shuffles() {
                return Err(format!(
                    "ipsvi.line_kernel = \"segmented\" combines a pixel's segments with {missing}, which this \
                     device lacks; use ipsvi.line_kernel = \"serial\""
                ));
            }
            let segments = if s.segments == 0 { default_segments(device_type, subgroups) } else { s.segments };
            if segments > subgroups.min_size.max(1) * MAX_CLUSTER_SUBGROUPS {
                return Err(format!(
                    "ipsvi.segments = {segments}: a pixel's segments may span at most {MAX_CLUSTER_SUBGROUPS} \
                     subgroups, and this device's subgroups may be as small as {}",
                    subgroups.min_size
                ));
            }
            let texels = s.texel_segments;
            if texels > segments || texels > subgroups.min_size {
                return Err(format!(
                    "ipsvi.texel_segments = {texels}: a texel's lanes lie in one subgroup among a pixel's \
                     segments, so no more than ipsvi.segments ({segments}) nor this device's smallest \
                     subgroup ({})",
                    subgroups.min_size
                ));
            }
            Ok(segmented(segments))
        }
        LineKernel::Auto => Ok(match default_kernel(s, device_type, subgroups) {
            LineKernel::Segmented => segmented(default_segments(device_type, subgroups)),
            _ => KernelChoice::SERIAL,
        }),
    }
}

/// `line_kernel = "auto"`: serial on a CPU device (lavapipe: measured no faster
/// segmented, docs/ipsvi.md), segmented on a GPU wherever `s`'s modes and the
/// device's subgroups allow it (reasoned from the shape report; not yet
/// measured on a GPU).
pub fn default_kernel(s: &IpsviSettings, device_type: &str, subgroups: &SubgroupSupport) -> LineKernel {
    let cpu = device_type == "CPU";
    if cpu || segmented_refusal(s).is_some() || subgroups.missing_shuffles().is_some() || subgroups.min_size < 2 {
        LineKernel::Serial
    } else {
        LineKernel::Segmented
    }
}

/// `s` with `line_kernel = "auto"` resolved for the device (`serial` or
/// `segmented`, its segments left to the device): what a bench names.
pub fn resolved(s: &IpsviSettings, device_type: &str, subgroups: &SubgroupSupport) -> IpsviSettings {
    let line_kernel = match s.line_kernel {
        LineKernel::Auto => default_kernel(s, device_type, subgroups),
        k => k,
    };
    IpsviSettings { line_kernel, ..s.clone() }
}

/// The same modes with the other kernel, where both can run them (the
/// segmented one runs only where a pixel's march writes nothing); None for
/// `auto`, whose kernel depends on the device.
pub fn other_kernel(s: &IpsviSettings) -> Option<IpsviSettings> {
    let line_kernel = match s.line_kernel {
        LineKernel::Serial if segmented_refusal(s).is_none() => LineKernel::Segmented,
        LineKernel::Segmented => LineKernel::Serial,
        _ => return None,
    };
    Some(IpsviSettings { line_kernel, segments: 0, ..s.clone() })
}

/// Segments per pixel where none are asked for: [`GPU_SEGMENTS`] or
/// [`CPU_SEGMENTS`], no more than the smallest subgroup.
pub fn default_segments(device_type: &str, subgroups: &SubgroupSupport) -> u32 {
    let wanted = if device_type == "CPU" { CPU_SEGMENTS } else { GPU_SEGMENTS };
    wanted.min(subgroups.min_size).max(1)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn device(min_size: u32) -> SubgroupSupport {
        SubgroupSupport { size: min_size, min_size, compute: true, shuffle: true, shuffle_relative: true }
    }

    #[test]
    fn auto_is_serial_on_a_cpu_and_segmented_by_the_subgroup_on_a_gpu() {
        let s = IpsviSettings::default();
        assert_eq!(choose(&s, "CPU", &device(8)), Ok(KernelChoice::SERIAL));
        let gpu = choose(&s, "discrete GPU", &device(32)).unwrap();
        let label = "segmented x32, texels x4".to_string();
        assert_eq!((gpu.segments, gpu.rounds, gpu.label()), (32, DEFAULT_ROUNDS, label));
        assert_eq!(choose(&s, "integrated GPU", &device(8)).unwrap().segments, 8, "capped by the subgroup");
        let no_shuffles = SubgroupSupport { shuffle_relative: false, ..device(32) };
        assert_eq!(choose(&s, "discrete GPU", &no_shuffles), Ok(KernelChoice::SERIAL));
    }

    #[test]
    fn asked_for_where_it_cannot_run_it_is_an_error_naming_why() {
        let asked = IpsviSettings { line_kernel: LineKernel::Segmented, ..IpsviSettings::default() };
        assert_eq!(choose(&asked, "CPU", &device(8)).unwrap().segments, CPU_SEGMENTS);
        let sample = IpsviSettings { write_pass: WritePass::Sample, ..asked.clone() };
        let e = choose(&sample, "CPU", &device(8)).unwrap_err();
        assert!(e.contains("write_pass = \"sample\"") && e.contains("line_kernel = \"serial\""), "{e}");
        // Auto takes the sample pass where the texel pass cannot run: named too.
        let racy = IpsviSettings { cache_write: super::super::CacheWrite::Racy, ..asked.clone() };
        let e = choose(&racy, "CPU", &device(8)).unwrap_err();
        assert!(e.contains("cache_write"), "{e}");
        // Each of the texel pass's other needs, named where it is missing.
        let sample_value = IpsviSettings { write_value: super::super::WriteValue::Sample, ..asked.clone() };
        let no_piecewise = IpsviSettings { piecewise: false, ..asked.clone() };
        let moved = IpsviSettings { empty_runs_move_depth: true, ..asked.clone() };
        for (s, named) in [
            (sample_value, "write_value = \"texel-ray\""),
            (no_piecewise, "piecewise = true"),
            (moved, "empty_runs_move_depth = false"),
        ] {
            let e = choose(&s, "CPU", &device(8)).unwrap_err();
            assert!(e.contains(named) && e.contains("line_kernel = \"serial\""), "{e}");
        }
        // Light rays never write from the march.
        let rays = IpsviSettings { cache_update: CacheUpdate::LightRays, ..racy.clone() };
        assert!(choose(&rays, "CPU", &device(8)).is_ok());
        // More segments than a subgroup: the workgroup is the pixel's, up to 32 subgroups.
        let wide = choose(&IpsviSettings { segments: 16, ..asked.clone() }, "CPU", &device(8)).unwrap();
        assert!(wide.cross_subgroups && !choose(&asked, "CPU", &device(8)).unwrap().cross_subgroups);
        // A texel's lanes: an eighth of the segments by default, or as asked within them.
        let lanes = |segments, texel_segments| {
            choose(&IpsviSettings { segments, texel_segments, ..asked.clone() }, "CPU", &device(8))
                .map(|k| k.texel_lanes)
        };
        assert_eq!((lanes(8, 0), lanes(16, 0), lanes(32, 0), lanes(8, 4)), (Ok(1), Ok(2), Ok(4), Ok(4)));
        assert_eq!(lanes(128, 0), Ok(8), "capped by the smallest subgroup");
        let e = lanes(4, 8).unwrap_err();
        assert!(e.contains("ipsvi.texel_segments = 8") && e.contains("(4)"), "{e}");
        assert!(lanes(32, 16).unwrap_err().contains("smallest subgroup (8)"));
        // Within a 32-lane subgroup a texel may have 16 lanes.
        let gpu_lanes = |segments, texel_segments| {
            choose(&IpsviSettings { segments, texel_segments, ..asked.clone() }, "discrete GPU", &device(32))
                .map(|k| k.texel_lanes)
        };
        assert_eq!((gpu_lanes(128, 16), gpu_lanes(16, 16)), (Ok(16), Ok(16)));
        assert_eq!((gpu_lanes(64, 0), gpu_lanes(128, 0)), (Ok(8), Ok(16)), "an eighth, at most 16");
        assert!(gpu_lanes(8, 16).unwrap_err().contains("ipsvi.segments (8)"));
        let e = choose(&IpsviSettings { segments: 128, ..asked.clone() }, "CPU", &device(2)).unwrap_err();
        assert!(e.contains("ipsvi.segments = 128") && e.contains("as small as 2"), "{e}");
        let e = choose(&asked, "CPU", &SubgroupSupport { shuffle: false, ..device(8) }).unwrap_err();
        assert!(e.contains("subgroup shuffles"), "{e}");
        // Auto falls back to serial for such modes instead.
        let auto_racy = IpsviSettings { line_kernel: LineKernel::Auto, ..racy };
        assert_eq!(choose(&auto_racy, "discrete GPU", &device(32)), Ok(KernelChoice::SERIAL));
    }

    #[test]
    fn benches_name_the_resolved_kernel_and_measure_the_other_where_it_runs() {
        let s = IpsviSettings::default();
        let cpu = resolved(&s, "CPU", &device(8));
        assert_eq!(cpu.line_kernel, LineKernel::Serial);
        assert_eq!(other_kernel(&cpu).map(|o| o.line_kernel), Some(LineKernel::Segmented));
        let gpu = resolved(&s, "discrete GPU", &device(32));
        assert_eq!(other_kernel(&gpu).map(|o| o.line_kernel), Some(LineKernel::Serial));
        assert_eq!(other_kernel(&s), None, "auto has no other");
        let sample = IpsviSettings { write_pass: WritePass::Sample, ..cpu };
        assert_eq!(other_kernel(&sample), None, "the sample pass runs serial only");
    }

    #[test]
    fn names_round_trip() {
        for k in LineKernel::ALL {
            assert_eq!(k.name().parse::<LineKernel>().unwrap(), k);
        }
        assert!("segment".parse::<LineKernel>().unwrap_err().contains("`segmented`"));
    }
}
