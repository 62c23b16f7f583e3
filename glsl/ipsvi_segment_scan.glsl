// The segmented line kernel's combines (glsl/ipsvi_line_segmented.comp): the
// SEGMENTS invocations of one pixel (a cluster, glsl/ipsvi_cluster.glsl) each
// march one depth segment of the ray, and their results are combined in
// depth order: a Hillis-Steele scan for what a segment needs from the
// segments before (or after) it, a butterfly for what the whole ray needs.
// The including file defines SEGMENTS and CROSS_SUBGROUPS, and includes
// ipsvi_over.glsl.
#ifndef IPSVI_SEGMENT_SCAN_GLSL
#define IPSVI_SEGMENT_SCAN_GLSL

#include "ipsvi_cluster.glsl"

// The whole ray's composite, the segments' composites combined in depth
// order: at each step a lane and its partner hold adjacent aligned blocks of
// segments, and both put the nearer one in front, so every lane ends with
// the same total.
Composite cluster_over(Composite x) {
    for (uint d = 1u; d < cluster_lanes(); d <<= 1) {
        Composite y = Composite(subgroupShuffleXor(x.C, d), subgroupShuffleXor(x.T, d));
        x = (cluster_lane() & d) == 0u ? over(x, y) : over(y, x);
    }
    if (CROSS_SUBGROUPS) {
        // Every invocation folds the subgroups' parts in the same order: one total.
        publish_part(floatBitsToUint(x.C.r), floatBitsToUint(x.C.g), floatBitsToUint(x.C.b), floatBitsToUint(x.T), 0u);
        x = no_samples();
        for (uint s = 0u; s < gl_NumSubgroups; ++s) {
            vec3 C = uintBitsToFloat(uvec3(cluster_parts[0][s], cluster_parts[1][s], cluster_parts[2][s]));
            x = over(x, Composite(C, uintBitsToFloat(cluster_parts[3][s])));
        }
        parts_read();
    }
    return x;
}

// ---- claims: runs of samples in one texel across segments --------------------
// A stretch of samples summarized by its runs (samples that take part in
// writes, consecutive ones in one texel forming a run): the first run (its
// texel and writer depth), whether another run follows it (closed), and the
// last run. Runs strictly inside a stretch need nothing from outside it.
const uint RUNS_ANY = 1u;     // the stretch holds a sample that takes part
const uint RUNS_CLOSED = 2u;  // its first run ends inside it
const uint NO_TEXEL = 0xFFFFFFFFu;

struct Runs {
    uint flags;
    uint lead_k;   // texel of the first run (x | y << 16)
    float lead_d;  // its writer's depth so far
    uint trail_k;  // texel of the last run (the first if not closed)
    float trail_d;
};

Runs no_runs() { return Runs(0u, NO_TEXEL, 0.0, NO_TEXEL, 0.0); }
bool has_runs(Runs r) { return (r.flags & RUNS_ANY) != 0u; }
bool runs_closed(Runs r) { return (r.flags & RUNS_CLOSED) != 0u; }
uint texel_code(ivec2 k) { return uint(k.x) | (uint(k.y) << 16); }
ivec2 code_texel(uint c) { return ivec2(int(c & 0xFFFFu), int(c >> 16)); }

// The writer depth of a run from an earlier and a later part of it: with
// piecewise integration the sample nearest the light, else the last.
float run_depth(float earlier, float later) { return run_keeps_nearest() ? min(earlier, later) : later; }

// Stretch a then stretch b (associative: a run may continue across the seam).
Runs runs_then(Runs a, Runs b) {
    if (!has_runs(b)) return a;
    if (!has_runs(a)) return b;
    bool joined = a.trail_k == b.lead_k;
    Runs r = a;
    if (!runs_closed(a) && joined) r.lead_d = run_depth(a.lead_d, b.lead_d);
    if (!joined || runs_closed(b)) r.flags |= RUNS_CLOSED;
    if (runs_closed(b)) {
        r.trail_k = b.trail_k;
        r.trail_d = b.trail_d;
    } else {
        r.trail_k = b.lead_k;
        r.trail_d = joined ? run_depth(a.trail_d, b.lead_d) : b.lead_d;
    }
    return r;
}

Runs shuffle_up_runs(Runs r, uint d) {
    return Runs(subgroupShuffleUp(r.flags, d), subgroupShuffleUp(r.lead_k, d), subgroupShuffleUp(r.lead_d, d),
                subgroupShuffleUp(r.trail_k, d), subgroupShuffleUp(r.trail_d, d));
}

// The runs of the segments before this one, and in `total` of all of them.
Runs cluster_runs_before(Runs x, out Runs total) {
    Runs inclusive = x;
    for (uint d = 1u; d < cluster_lanes(); d <<= 1) {
        Runs y = shuffle_up_runs(inclusive, d);
        if (cluster_lane() >= d) inclusive = runs_then(y, inclusive);
    }
    uint last = cluster_last_lane();
    total = Runs(subgroupShuffle(inclusive.flags, last), subgroupShuffle(inclusive.lead_k, last),
                 subgroupShuffle(inclusive.lead_d, last), subgroupShuffle(inclusive.trail_k, last),
                 subgroupShuffle(inclusive.trail_d, last));
    Runs up = shuffle_up_runs(inclusive, 1u);
    Runs before = cluster_lane() == 0u ? no_runs() : up;
    if (CROSS_SUBGROUPS) {
        publish_part(total.flags, total.lead_k, floatBitsToUint(total.lead_d), total.trail_k,
                     floatBitsToUint(total.trail_d));
        Runs earlier = no_runs();
        total = no_runs();
        for (uint s = 0u; s < gl_NumSubgroups; ++s) {
            if (s == gl_SubgroupID) earlier = total;
            Runs part = Runs(cluster_parts[0][s], cluster_parts[1][s], uintBitsToFloat(cluster_parts[2][s]),
                             cluster_parts[3][s], uintBitsToFloat(cluster_parts[4][s]));
            total = runs_then(total, part);
        }
        parts_read();
        before = runs_then(earlier, before);
    }
    return before;
}

// The texel of the first sample taking part after this segment (NO_TEXEL: none).
uint cluster_next_texel(Runs x) {
    uint inclusive = has_runs(x) ? x.lead_k : NO_TEXEL;
    for (uint d = 1u; d < cluster_lanes(); d <<= 1) {
        uint y = subgroupShuffleDown(inclusive, d);
        if (cluster_lane() + d < cluster_lanes() && inclusive == NO_TEXEL) inclusive = y;
    }
    uint down = subgroupShuffleDown(inclusive, 1u);
    uint after = cluster_lane() + 1u < cluster_lanes() ? down : NO_TEXEL;
    if (CROSS_SUBGROUPS) {
        // The first texel of the subgroups after this one's, where its own have none.
        publish_part(subgroupShuffle(inclusive, cluster_first_lane()), 0u, 0u, 0u, 0u);
        uint later = NO_TEXEL;
        for (uint s = gl_NumSubgroups; s > gl_SubgroupID + 1u; --s) {
            uint k = cluster_parts[0][s - 1u];
            if (k != NO_TEXEL) later = k; // downward: the nearest one stays
        }
        parts_read();
        if (after == NO_TEXEL) after = later;
    }
    return after;
}

#endif
