#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_shuffle : require
#extension GL_KHR_shader_subgroup_shuffle_relative : require
// One IPSVI line block (one dispatch; src/techniques/ipsvi/), the segmented kernel: the
// same block as glsl/ipsvi_line.comp, but SEGMENTS invocations per pixel (a
// cluster of consecutive lanes of one subgroup, or a workgroup of several),
// each marching one depth segment of the pixel's view ray. A sample's light read depends only on the
// previous block's images, never on another sample of its line, so the only
// dependency along the ray is compositing, which is associative: the
// segments' composites are combined in depth order (ipsvi_segment_scan.glsl).
// The per-line dispatch and its barrier are the serial kernel's.
//
// Early ray termination stops where the serial kernel stops: the view-stops
// pass (glsl/ipsvi_view_stops.comp) found each ray's stop before the sweep,
// with the serial march's rule and sums, so a pixel's segments split only the
// samples up to it, and no invocation marches past it. A run of samples in one
// texel may cross segments: the claim march scans the run state so that each
// run is claimed once, at its end, with its writer's depth: the same keys as
// the serial march, whatever the split. Used only where the pixel's march
// only reads (light rays, or view samples with write_pass = "texel"):
// src/techniques/ipsvi/line_kernel.rs refuses the sample write pass.

layout(local_size_x_id = 8) in;
// Invocations per pixel: a power of two up to 128 (32 subgroups at most).
layout(constant_id = 16) const uint SEGMENTS = 4u;
// Rounds a ray's samples are dealt to its segments in, for shading: a
// sample's own march toward the light makes its cost uneven along the ray,
// and stretches from each round spread an invocation's share along it.
layout(constant_id = 17) const uint SEGMENT_ROUNDS = 4u;
// A pixel's segments span the workgroup's subgroups (SEGMENTS above the
// smallest subgroup): the workgroup is one cluster, combined through shared
// memory between workgroup barriers (glsl/ipsvi_segment_scan.glsl). Off, the
// shader has no barrier (on lavapipe one makes the whole shader run as
// coroutines: see glsl/ipsvi_line_main.glsl).
layout(constant_id = 19) const bool CROSS_SUBGROUPS = false;
// Invocations per cache texel (a power of two, no more than SEGMENTS and the
// smallest subgroup): a texel's marches toward the light split over them.
layout(constant_id = 20) const uint TEXEL_LANES = 1u;
#define SPLIT_TEXEL_MARCHES

#include "ipsvi_line_interface.glsl"
#include "ipsvi_cache_io.glsl"
#include "ipsvi_piecewise.glsl"
#include "ipsvi_cache_read.glsl"
#include "ipsvi_writes.glsl"
#include "ipsvi_march.glsl"
#include "ipsvi_compositing.glsl"

#include "ipsvi_segment_scan.glsl"

// Each pixel's view samples up to its stop (glsl/ipsvi_view_stops.comp).
layout(std430, set = 0, binding = 28) readonly buffer ViewStops { uint view_stops[]; };

// This invocation's index among its pixel's SEGMENTS (its segment of the ray).
uint segment = 0u;

// A workgroup that finds no whole clusters flags the frame, and the host
// refuses it (src/techniques/ipsvi/line_shape.rs).
uint line_local_index() { return cluster_local_index(); }

bool line_kernel_ready() {
    bool fit = clusters_fit();
    if (!fit && gl_LocalInvocationIndex == 0u) atomicOr(shape_flags, SHAPE_PARTIAL_SUBGROUPS);
    segment = line_local_index() % SEGMENTS;
    return fit;
}

// The subgroup's longest chain of each role (butterflies over all its lanes,
// active again after line_invocation), one atomic per role that ran.
void report_chain() {
    for (uint role = 0u; role < CHAIN_ROLES; ++role) {
        uint longest = subgroup_largest(chain_role == role ? chain : 0u);
        if (gl_SubgroupInvocationID == 0u && longest > 0u)
            atomicMax(chains[chain_slot(block_index, role, gl_SubgroupID)], longest);
    }
}

// Pixel px's march, its samples ending where the ray stops.
ViewMarch stopped_march(uvec2 px) {
    ViewMarch v = pixel_march(px, frame.view_step);
    if (may_stop()) v.samples = min(v.samples, int(view_stops[px.y * frame.image_size.x + px.x]));
    return v;
}

// Samples per segment and round for a ray of n samples dealt in `rounds`.
int segment_length(int n, uint rounds) {
    int per_round = int(SEGMENTS * rounds);
    return max(1, (n + per_round - 1) / per_round);
}

// cache_write = "farthest"/"nearest", one dispatch ahead: claims for pixel
// `index` of the next block the texels where its runs end, as the serial
// claim march does, one segment per invocation.
void claim_pixel(BlockParams next, uint index) {
    uvec2 px;
    float w;
    // The whole cluster leaves together (one pixel).
    if (!pixel_in_block(next, index, px, w)) return;
    ViewMarch v = stopped_march(px);
    int len = segment_length(v.samples, 1u);
    int lo = int(segment) * len;
    Runs mine = no_runs();
    for (int i = lo; i < min(lo + len, v.samples); ++i) {
        vec3 p = sample_point(v, i);
        float alpha = 1.0 - exp(-medium(p).a * v.hv);
        chain += 1u;
        if (alpha > 0.0 || EVERY_SAMPLE) {
            vec3 c = cache_coord(p);
            uint k = texel_code(sample_texel(c));
            if (!has_runs(mine)) {
                mine = Runs(RUNS_ANY, k, c.z, k, c.z);
            } else if (k == mine.trail_k) {
                mine.trail_d = run_depth(mine.trail_d, c.z);
                if (!runs_closed(mine)) mine.lead_d = mine.trail_d;
            } else {
                // A run ended: one inside the segment is claimed now; the
                // first may have begun in an earlier segment (below).
                if (runs_closed(mine)) claim_run(code_texel(mine.trail_k), mine.trail_d, index);
                mine.flags |= RUNS_CLOSED;
                mine.trail_k = k;
                mine.trail_d = c.z;
            }
        }
    }
    Runs all_runs;
    Runs before = cluster_runs_before(mine, all_runs);
    uint next_k = cluster_next_texel(mine);
    if (has_runs(mine)) {
        bool joined = has_runs(before) && before.trail_k == mine.lead_k;
        float lead_d = joined ? run_depth(before.trail_d, mine.lead_d) : mine.lead_d;
        if (runs_closed(mine)) claim_run(code_texel(mine.lead_k), lead_d, index);
        float trail_d = runs_closed(mine) ? mine.trail_d : lead_d;
        // The last run ends here if the next sample taking part is in another
        // texel, or there is none.
        if (next_k != mine.trail_k) claim_run(code_texel(mine.trail_k), trail_d, index);
    }
}

// Shading only reads: in each round each segment composites its stretch of
// samples, and the stretches' composites combine in depth order. (The claim
// march above is dealt in one round: its samples cost alike.)
void shade_pixel(uint index) {
    uvec2 px;
    float w;
    if (!pixel_in_block(block, index, px, w)) return;
    bool first_light = (sweep.flags & FLAG_FIRST_LIGHT) != 0u;
    Light light = lights[sweep.light_index];
    ViewMarch v = stopped_march(px);
    int len = segment_length(v.samples, SEGMENT_ROUNDS);
    int round_samples = len * int(SEGMENTS);
    Composite pixel = no_samples();
    for (int base = 0; base < v.samples; base += round_samples) {
        int lo = base + int(segment) * len;
        Composite mine = no_samples();
        for (int i = lo; i < min(lo + len, v.samples); ++i) {
            vec3 p = sample_point(v, i);
            vec4 m = medium(p);
            float alpha = 1.0 - exp(-m.a * v.hv);
            chain += 1u;
            if (alpha > 0.0) composite_sample(mine, alpha, sample_radiance(light, p, m, read_light(p), first_light));
        }
        pixel = over(pixel, cluster_over(mine));
    }
    if (segment == 0u) {
        digest_stop(block_index, index, v.samples);
        finish_pixel(px, w, pixel, first_light);
    }
}

#include "ipsvi_line_main.glsl"
