// A cluster: the SEGMENTS invocations that split one view ray into depth
// segments (the segmented line kernel, glsl/ipsvi_line_segmented.comp, and
// the view-stops pass, glsl/ipsvi_view_stops.comp), and how they combine.
// Within a subgroup by shuffles (the cluster's lanes there are consecutive
// and aligned; only shuffles within them: the other lanes may be elsewhere in
// the code). With CROSS_SUBGROUPS the cluster is the whole workgroup, over
// several subgroups: each subgroup's part is combined by shuffles, and the
// parts through shared memory, between two workgroup barriers (every
// invocation of the workgroup is then the same pixel's, so each reaches the
// same barriers). The including file defines SEGMENTS and CROSS_SUBGROUPS, and
// includes ipsvi_optical_depth.glsl.
#ifndef IPSVI_CLUSTER_GLSL
#define IPSVI_CLUSTER_GLSL

// Subgroups a cluster may span (src/techniques/ipsvi/line_kernel.rs keeps
// SEGMENTS / the smallest subgroup within it).
const uint MAX_CLUSTER_SUBGROUPS = 32u;
// One value of each subgroup of the cluster, up to five words.
shared uint cluster_parts[5][MAX_CLUSTER_SUBGROUPS];

// The cluster's lanes in this subgroup (sizes are powers of two).
uint cluster_lanes() { return min(SEGMENTS, gl_SubgroupSize); }
// This invocation's lane among them, and their first and last lane.
uint cluster_lane() { return gl_SubgroupInvocationID & (cluster_lanes() - 1u); }
uint cluster_first_lane() { return gl_SubgroupInvocationID & ~(cluster_lanes() - 1u); }
uint cluster_last_lane() { return gl_SubgroupInvocationID | (cluster_lanes() - 1u); }

// CROSS_SUBGROUPS: each subgroup's lane 0 publishes its part's words; after
// this every invocation may read all parts (cluster_parts[w][0..gl_NumSubgroups)),
// until it calls parts_read().
void publish_part(uint w0, uint w1, uint w2, uint w3, uint w4) {
    if (gl_SubgroupInvocationID == 0u) {
        cluster_parts[0][gl_SubgroupID] = w0;
        cluster_parts[1][gl_SubgroupID] = w1;
        cluster_parts[2][gl_SubgroupID] = w2;
        cluster_parts[3][gl_SubgroupID] = w3;
        cluster_parts[4][gl_SubgroupID] = w4;
    }
    barrier();
}

// Every invocation has read the parts: the next combine may publish.
void parts_read() { barrier(); }

// The optical depth (tau_add, glsl/ipsvi_optical_depth.glsl) of the segments before
// this one, and in `total` of all of them.
uint cluster_tau_before(uint x, out uint total) {
    uint inclusive = x;
    for (uint d = 1u; d < cluster_lanes(); d <<= 1) {
        uint y = subgroupShuffleUp(inclusive, d);
        if (cluster_lane() >= d) inclusive = tau_add(y, inclusive);
    }
    total = subgroupShuffle(inclusive, cluster_last_lane());
    uint up = subgroupShuffleUp(inclusive, 1u);
    uint before = cluster_lane() == 0u ? 0u : up;
    if (CROSS_SUBGROUPS) {
        publish_part(total, 0u, 0u, 0u, 0u);
        uint earlier = 0u;
        total = 0u;
        for (uint s = 0u; s < gl_NumSubgroups; ++s) {
            if (s == gl_SubgroupID) earlier = total;
            total = tau_add(total, cluster_parts[0][s]);
        }
        parts_read();
        before = tau_add(earlier, before);
    }
    return before;
}

// Invocations are numbered by subgroup and lane, so that a pixel's cluster is
// always SEGMENTS aligned lanes of one subgroup, or with CROSS_SUBGROUPS the
// whole workgroup's.
uint cluster_local_index() { return gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID; }

// Whether this workgroup's subgroups hold whole clusters: full subgroups, and
// clusters that fit one (or, CROSS_SUBGROUPS, the workgroup is one cluster).
// Uniform over the workgroup.
bool clusters_fit() {
    bool fit = CROSS_SUBGROUPS ? gl_WorkGroupSize.x == SEGMENTS && gl_NumSubgroups <= MAX_CLUSTER_SUBGROUPS
                               : gl_SubgroupSize % SEGMENTS == 0u;
    return gl_NumSubgroups * gl_SubgroupSize == gl_WorkGroupSize.x && fit;
}

// The largest of x over the subgroup, every lane active.
uint subgroup_largest(uint x) {
    for (uint d = 1u; d < gl_SubgroupSize; d <<= 1) x = max(x, subgroupShuffleXor(x, d));
    return x;
}

#endif
