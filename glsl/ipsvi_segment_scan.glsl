// The segmented line kernel's combines (glsl/ipsvi_line_segmented.comp): the
// SEGMENTS invocations of one pixel (a cluster: consecutive lanes of one
// subgroup, aligned to SEGMENTS) each march one depth segment of the ray, and
// their results are combined in depth order with subgroup shuffles: a
// Hillis-Steele scan for what a segment needs from the segments before (or
// after) it, a butterfly for what the whole ray needs. Only shuffles within
// the cluster: the other lanes of the subgroup may be elsewhere in the code.
// The including file defines SEGMENTS and `segment`.
#ifndef IPSVI_SEGMENT_SCAN_GLSL
#define IPSVI_SEGMENT_SCAN_GLSL

// The cluster's last lane.
uint cluster_last_lane() { return gl_SubgroupInvocationID | (SEGMENTS - 1u); }

bool cluster_any(bool x) {
    uint v = x ? 1u : 0u;
    for (uint d = 1u; d < SEGMENTS; d <<= 1) v |= subgroupShuffleXor(v, d);
    return v != 0u;
}

// The whole ray's composite, the segments' composites combined in depth
// order: at each step a lane and its partner hold adjacent aligned blocks of
// segments, and both put the nearer one in front, so every lane ends with
// the same total.
Composite cluster_over(Composite x) {
    for (uint d = 1u; d < SEGMENTS; d <<= 1) {
        Composite y = Composite(subgroupShuffleXor(x.C, d), subgroupShuffleXor(x.T, d));
        x = (segment & d) == 0u ? over(x, y) : over(y, x);
    }
    return x;
}

// The optical depth (tau_add, glsl/ipsvi_march.glsl) of the segments before
// this one, and in `total` of all of them.
uint cluster_tau_before(uint x, out uint total) {
    uint inclusive = x;
    for (uint d = 1u; d < SEGMENTS; d <<= 1) {
        uint y = subgroupShuffleUp(inclusive, d);
        if (segment >= d) inclusive = tau_add(y, inclusive);
    }
    total = subgroupShuffle(inclusive, cluster_last_lane());
    uint before = subgroupShuffleUp(inclusive, 1u);
    return segment == 0u ? 0u : before;
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
    for (uint d = 1u; d < SEGMENTS; d <<= 1) {
        Runs y = shuffle_up_runs(inclusive, d);
        if (segment >= d) inclusive = runs_then(y, inclusive);
    }
    uint last = cluster_last_lane();
    total = Runs(subgroupShuffle(inclusive.flags, last), subgroupShuffle(inclusive.lead_k, last),
                 subgroupShuffle(inclusive.lead_d, last), subgroupShuffle(inclusive.trail_k, last),
                 subgroupShuffle(inclusive.trail_d, last));
    Runs before = shuffle_up_runs(inclusive, 1u);
    return segment == 0u ? no_runs() : before;
}

// The texel of the first sample taking part after this segment (NO_TEXEL: none).
uint cluster_next_texel(Runs x) {
    uint inclusive = has_runs(x) ? x.lead_k : NO_TEXEL;
    for (uint d = 1u; d < SEGMENTS; d <<= 1) {
        uint y = subgroupShuffleDown(inclusive, d);
        if (segment + d < SEGMENTS && inclusive == NO_TEXEL) inclusive = y;
    }
    uint after = subgroupShuffleDown(inclusive, 1u);
    return segment + 1u < SEGMENTS ? after : NO_TEXEL;
}

#endif
