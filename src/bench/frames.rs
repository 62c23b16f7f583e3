//! Timed frames of a technique, or of one IPSVI renderer, measured by a [`Harness`].

use super::harness::{Harness, Measurement, Sample};
use crate::ipsvi::renderer::IpsviRenderer;
use crate::ipsvi::{IpsviSettings, SyncStrategy};
use crate::render::technique::FrameResult;
use crate::render::{render, GpuScene, RenderError, RenderOutput, Technique};
use crate::vk::{ProfileReport, Profiler};

/// A frame and the profile resolved right after it.
pub struct ProfiledFrame {
    pub frame: FrameResult,
    pub profile: ProfileReport,
}

/// Frames of `technique`, each a full `render` (set-up included), timed by the
/// GPU time of the whole frame.
pub fn technique_frames(
    harness: &Harness,
    gpu: &GpuScene,
    technique: Technique,
    (width, height): (u32, u32),
    profiler: &mut Profiler,
) -> Result<Measurement<RenderOutput>, RenderError> {
    harness.measure(|| {
        let out = render(gpu, technique, width, height, profiler)?;
        Ok(Sample::timed(out.profile.gpu_ms_total, out))
    })
}

/// Frames of one IPSVI renderer made once for all of them (the secondary
/// strategy replays what it recorded), timed by the GPU time of the frame; the
/// profile's memory is the device-local peak since the caller last reset it.
pub fn ipsvi_frames(
    harness: &Harness,
    gpu: &GpuScene,
    settings: &IpsviSettings,
    (width, height): (u32, u32),
    profiler: &mut Profiler,
    sync: SyncStrategy,
) -> Result<Measurement<ProfiledFrame>, RenderError> {
    let mut renderer = IpsviRenderer::new(gpu, settings, width, height)?;
    harness.measure(|| {
        profiler.reset();
        let frame = renderer.frame(profiler, sync)?;
        let profile = profiler.resolve(gpu.ctx.memory.device_local_peak())?;
        Ok(Sample::timed(profile.gpu_ms_total, ProfiledFrame { frame, profile }))
    })
}
