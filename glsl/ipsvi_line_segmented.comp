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
// Early ray termination stops where the serial kernel stops: the ray is
// marched in at most SEGMENT_ROUNDS rounds of SEGMENTS segments, and the
// optical depth is scanned (integer, so the sum does not depend on the
// split); no round starts after the stop. Shading only reads, so a round
// marches its segments in full and then drops what lies past the stop, the
// segment holding it marching again up to it. The claim march writes, so
// each of its rounds first fetches only the opacity of its samples, scans,
// and then marches only the samples up to the stop: a run of samples in one
// texel may cross segments, and the run state is scanned so that each run is
// claimed once, at its end, with its writer's depth: the same keys as the
// serial march, whatever the split. Used only where the pixel's march only
// reads (light rays, or view samples with write_pass = "texel"):
// src/techniques/ipsvi/line_kernel.rs refuses the sample write pass.

layout(local_size_x_id = 8) in;
// Invocations per pixel: a power of two up to 128 (32 subgroups at most).
layout(constant_id = 16) const uint SEGMENTS = 4u;
// Rounds a ray's samples are split into when it may stop early (else one).
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

// This invocation's index among its pixel's SEGMENTS (its segment of the ray).
uint segment = 0u;

// Invocations are numbered by subgroup and lane, so that a pixel's cluster is
// always SEGMENTS aligned lanes of one subgroup, or with CROSS_SUBGROUPS the
// whole workgroup's; that needs full subgroups, checked once per workgroup (a
// workgroup that finds none flags the frame, and the host refuses it:
// src/techniques/ipsvi/line_shape.rs).
uint line_local_index() { return gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID; }

bool line_kernel_ready() {
    bool clusters_fit = CROSS_SUBGROUPS ? gl_WorkGroupSize.x == SEGMENTS && gl_NumSubgroups <= MAX_CLUSTER_SUBGROUPS
                                        : gl_SubgroupSize % SEGMENTS == 0u;
    bool full = gl_NumSubgroups * gl_SubgroupSize == gl_WorkGroupSize.x && clusters_fit;
    if (!full && gl_LocalInvocationIndex == 0u) atomicOr(shape_flags, SHAPE_PARTIAL_SUBGROUPS);
    segment = line_local_index() % SEGMENTS;
    return full;
}

// The subgroup's longest chain of each role (butterflies over all its lanes,
// active again after line_invocation), one atomic per role that ran.
void report_chain() {
    for (uint role = 0u; role < CHAIN_ROLES; ++role) {
        uint longest = chain_role == role ? chain : 0u;
        for (uint d = 1u; d < gl_SubgroupSize; d <<= 1) longest = max(longest, subgroupShuffleXor(longest, d));
        if (gl_SubgroupInvocationID == 0u && longest > 0u)
            atomicMax(chains[chain_slot(block_index, role, gl_SubgroupID)], longest);
    }
}

// Samples per segment and round for a ray of n samples.
int segment_length(int n) {
    int per_round = int(SEGMENTS * (may_stop() ? SEGMENT_ROUNDS : 1u));
    return max(1, (n + per_round - 1) / per_round);
}

// The opacity pass of a round (only where the ray may stop): this segment's
// samples [lo, hi) fetch their medium once each; returns the optical depth up
// to sample lo, and moves `tau_round` (up to the round's first sample) past
// the round.
uint optical_depth_before(ViewMarch v, int lo, int hi, inout uint tau_round) {
    if (!may_stop()) return 0u;
    uint mine = 0u;
    for (int i = lo; i < hi; ++i) mine = tau_add(mine, tau_units(medium(sample_point(v, i)).a * v.hv));
    chain += uint(max(hi - lo, 0));
    uint total;
    uint before = tau_add(tau_round, cluster_tau_before(mine, total));
    tau_round = tau_add(tau_round, total);
    return before;
}

// The end of this segment's samples [lo, hi): lo where the ray stopped at an
// earlier sample (sample lo - 1 or before: the stop is monotone in depth).
int segment_end(ViewMarch v, int lo, int hi, uint tau, float keep_going) {
    return lo > 0 && ray_stops(tau, v, lo - 1, keep_going) ? lo : hi;
}

// cache_write = "farthest"/"nearest", one dispatch ahead: claims for pixel
// `index` of the next block the texels where its runs end, as the serial
// claim march does, one segment per invocation.
void claim_pixel(BlockParams next, uint index) {
    uvec2 px;
    float w;
    // The whole cluster leaves together (one pixel).
    if (!pixel_in_block(next, index, px, w)) return;
    ViewMarch v = pixel_march(px, frame.view_step);
    float keep_going = stop_distance(px);
    int len = segment_length(v.samples);
    int round_samples = len * int(SEGMENTS);
    uint tau_round = 0u;
    Runs carried = no_runs(); // the runs of the rounds before, its last run still open
    for (int base = 0; base < v.samples; base += round_samples) {
        int lo = base + int(segment) * len;
        int hi = min(lo + len, v.samples);
        uint tau = optical_depth_before(v, lo, hi, tau_round);
        hi = segment_end(v, lo, hi, tau, keep_going);
        Runs mine = no_runs();
        bool stops = false;
        for (int i = lo; i < hi; ++i) {
            vec3 p = sample_point(v, i);
            vec4 m = medium(p);
            float alpha = 1.0 - exp(-m.a * v.hv);
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
            tau = tau_add(tau, tau_units(m.a * v.hv));
            if (ray_stops(tau, v, i, keep_going)) {
                stops = true;
                break;
            }
        }
        bool ended = cluster_any(stops) || base + round_samples >= v.samples;
        Runs round_runs;
        Runs before = runs_then(carried, cluster_runs_before(mine, round_runs));
        uint next_k = cluster_next_texel(mine);
        if (has_runs(mine)) {
            bool joined = has_runs(before) && before.trail_k == mine.lead_k;
            float lead_d = joined ? run_depth(before.trail_d, mine.lead_d) : mine.lead_d;
            if (runs_closed(mine)) claim_run(code_texel(mine.lead_k), lead_d, index);
            float trail_d = runs_closed(mine) ? mine.trail_d : lead_d;
            // The last run ends here if the next sample taking part is in
            // another texel, or there is none and the ray ends in this round.
            if (next_k != NO_TEXEL ? next_k != mine.trail_k : ended)
                claim_run(code_texel(mine.trail_k), trail_d, index);
        }
        // A run left open by the rounds before ends at this round's first
        // sample taking part, if that is in another texel, or with the ray.
        if (segment == 0u && has_runs(carried) && (has_runs(round_runs) ? round_runs.lead_k != carried.trail_k : ended))
            claim_run(code_texel(carried.trail_k), carried.trail_d, index);
        carried = runs_then(carried, round_runs);
        if (ended) break;
    }
}

// Marches samples [lo, hi) of this segment and composites them, moving `tau`
// (the optical depth before lo) past them. With `to_stop` it ends at the
// ray's stop and digests it; without, the stop is not known yet (the scan
// after the march finds it): a sample's shading does not depend on it.
Composite march_samples(ViewMarch v, int lo, int hi, Light light, bool first_light, inout uint tau, bool to_stop,
                        float keep_going, uint index) {
    Composite mine = no_samples();
    for (int i = lo; i < hi; ++i) {
        vec3 p = sample_point(v, i);
        vec4 m = medium(p);
        float alpha = 1.0 - exp(-m.a * v.hv);
        chain += 1u;
        if (alpha > 0.0) composite_sample(mine, alpha, sample_radiance(light, p, m, read_light(p), first_light));
        tau = tau_add(tau, tau_units(m.a * v.hv));
        if (to_stop && ray_stops(tau, v, i, keep_going)) {
            digest_stop(block_index, index, i + 1);
            break;
        }
    }
    return mine;
}

// Shading only reads, so each round marches its segments speculatively: the
// optical depths are scanned after the march, a segment past the stop drops
// its composite, and the one segment holding the stop marches again up to
// it. A round's chain is one segment's march; the stop adds one segment's.
void shade_pixel(uint index) {
    uvec2 px;
    float w;
    if (!pixel_in_block(block, index, px, w)) return;
    bool first_light = (sweep.flags & FLAG_FIRST_LIGHT) != 0u;
    Light light = lights[sweep.light_index];
    ViewMarch v = pixel_march(px, frame.view_step);
    float keep_going = stop_distance(px);
    int len = segment_length(v.samples);
    int round_samples = len * int(SEGMENTS);
    Composite pixel = no_samples();
    uint tau_round = 0u;
    bool stopped = false;
    for (int base = 0; base < v.samples; base += round_samples) {
        int lo = base + int(segment) * len;
        int hi = min(lo + len, v.samples);
        uint tau_mine = 0u;
        Composite mine = march_samples(v, lo, hi, light, first_light, tau_mine, false, keep_going, index);
        bool stops = false;
        if (may_stop()) {
            uint total;
            uint tau = tau_add(tau_round, cluster_tau_before(tau_mine, total));
            tau_round = tau_add(tau_round, total);
            if (lo > 0 && ray_stops(tau, v, lo - 1, keep_going)) {
                mine = no_samples(); // the ray stopped in an earlier segment
            } else if (hi > lo && ray_stops(tau_add(tau, tau_mine), v, hi - 1, keep_going)) {
                stops = true; // the stop is monotone in depth: it lies in [lo, hi)
                mine = march_samples(v, lo, hi, light, first_light, tau, true, keep_going, index);
            }
        }
        pixel = over(pixel, cluster_over(mine));
        stopped = cluster_any(stops);
        if (stopped || base + round_samples >= v.samples) break;
    }
    if (segment == 0u) {
        if (!stopped) digest_stop(block_index, index, v.samples);
        finish_pixel(px, w, pixel, first_light);
    }
}

#include "ipsvi_line_main.glsl"
