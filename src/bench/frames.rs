//! One timed frame of a technique, or of an IPSVI renderer: the runs a
//! [`Harness`](super::Harness) repeats.

use super::harness::Sample;
use crate::render::FrameResult;
use crate::render::{GpuScene, RenderError};
use crate::techniques::ipsvi::renderer::IpsviRenderer;
use crate::techniques::ipsvi::SyncStrategy;
use crate::techniques::{render, RenderOutput, Technique};
use crate::vk::{Context, ProfileReport, Profiler};

/// A frame and the profile resolved right after it.
pub struct ProfiledFrame {
    pub frame: FrameResult,
    pub profile: ProfileReport,
}

/// A full `render` of `technique` (its set-up included), timed by the GPU time
/// of the whole frame.
pub fn technique_frame(
    gpu: &GpuScene,
    technique: Technique,
    (width, height): (u32, u32),
    profiler: &mut Profiler,
) -> Result<Sample<RenderOutput>, RenderError> {
    let out = render(gpu, technique, width, height, profiler)?;
    Ok(Sample::timed(out.profile.gpu_ms_total, out))
}

/// A frame of `renderer` (made once for all its frames: the secondary strategy
/// replays what it recorded), timed by the GPU time of the frame; the profile's
/// memory is the device-local peak since the caller last reset it.
pub fn ipsvi_frame(
    ctx: &Context,
    renderer: &mut IpsviRenderer,
    profiler: &mut Profiler,
    sync: SyncStrategy,
) -> Result<Sample<ProfiledFrame>, RenderError> {
    profiler.reset();
    let frame = renderer.frame(profiler, sync)?;
    let profile = profiler.resolve(ctx.memory.device_local_peak())?;
    Ok(Sample::timed(profile.gpu_ms_total, ProfiledFrame { frame, profile }))
}
