//! The parameters of every line block of an IPSVI frame (glsl/ipsvi_line_interface.glsl
//! `BlockParams`), planned on the host.

use super::cache_update::CacheUpdate;
use super::gpu_params::BlockParams;
use super::settings::IpsviSettings;
use super::study::IpsviStudy;
use super::sweep_plan::{LineAxis, SweepPlan};
use crate::render::light_region::{plane_region, TexelRect};
use crate::render::light_space::LightSpacePlane;
use crate::render::RenderError;

/// A sweep's block records: (first, count).
pub type SweepRecords = (usize, usize);

/// The parameters of every line block of the frame, in dispatch order, and
/// each sweep's (first record, record count). With `cache_update =
/// "view-samples"` a block's region is the texels its samples may write (the
/// union over its lines' planes) and it carries the previous two blocks'
/// regions into the history pair; with "farthest" each sweep starts with a
/// claim-only record for its first block.
pub fn block_params(
    plans: &[SweepPlan],
    geometries: &[LightSpacePlane],
    lit_corners: &[glam::Vec3; 8],
    planes: &[[f32; 4]],
    height: u32,
    settings: &IpsviSettings,
    study: &IpsviStudy,
) -> Result<(Vec<BlockParams>, Vec<SweepRecords>), RenderError> {
    let claims = settings.claims_recorded(study.keep_redundant_claims);
    let breakdown_step = study.breakdown_step;
    let view_samples = settings.cache_update == CacheUpdate::ViewSamples;
    let mut out: Vec<BlockParams> = Vec::new();
    let mut sweeps = Vec::new();
    for (li, plan) in plans.iter().enumerate() {
        for sweep in &plan.sweeps {
            let first_record = out.len();
            let columns = sweep.axis == LineAxis::Columns;
            let plane_of = |line: u32| if columns { height + line } else { line };
            let region_of = |line: u32| plane_region(&geometries[li], lit_corners, planes[plane_of(line) as usize]);
            let mut previous_region = TexelRect::default();
            let mut before_previous = TexelRect::default();
            if claims {
                // Claims for the first block; no pixels, no texels.
                out.push(BlockParams { light: li as u32, zone: sweep.zone as u32, ..BlockParams::default() });
            }
            for block in sweep.blocks.iter() {
                let plane = plane_of(block.last_line);
                let (region, update) = if view_samples {
                    let written = (block.first..block.first + block.width)
                        .fold(TexelRect::default(), |r, l| r.union(&region_of(l)));
                    let carried = previous_region.union(&before_previous);
                    // write_pass = "texel": the block's own texels store in its texel
                    // invocations too (carrying one more texel writes its true state).
                    let texels = if settings.texel_pass() { carried.union(&written) } else { carried };
                    (written, texels)
                } else {
                    let region = region_of(block.last_line);
                    (region, region.union(&previous_region))
                };
                before_previous = previous_region;
                previous_region = region;
                let index = out.len() - first_record;
                out.push(BlockParams {
                    line_first: block.first,
                    line_width: block.width,
                    span_start: block.span_start,
                    span_len: block.span_len,
                    columns: columns as u32,
                    zone: sweep.zone as u32,
                    plane,
                    pixel_count: block.width * block.span_len,
                    region: [update.x0, update.y0, update.w, update.h],
                    parity: (index % 2) as u32,
                    light: li as u32,
                    stamp: index as u32 + 1,
                    claim_count: 0,
                    ..BlockParams::default()
                });
            }
            let count = out.len() - first_record;
            if !breakdown_step.writes_history() {
                // Nothing written: no texel or claim invocations either.
                for r in &mut out[first_record..] {
                    r.region = [0; 4];
                }
            }
            // (write_pass = "texel" stores only the texels the claim keys name: its
            // stores come on with the claim pass, docs/ipsvi.md "Cost breakdown".)
            if claims && breakdown_step.claims() {
                for r in first_record..first_record + count - 1 {
                    out[r].claim_count = out[r + 1].pixel_count;
                }
            }
            // Stamps are 16 bits in the stamp image.
            if view_samples && count >= 0xFFFF {
                return Err(RenderError::Invalid(format!(
                    "a sweep of {count} line blocks; view samples stamp at most 65534"
                )));
            }
            sweeps.push((first_record, count));
        }
    }
    // Claim keys hold the frame-wide block number + 1 in 20 bits.
    if claims && out.len() + 1 >= 1 << 20 {
        return Err(RenderError::Invalid(format!(
            "{} line blocks in a frame; farthest claims count at most 2^20 - 2",
            out.len()
        )));
    }
    Ok((out, sweeps))
}
