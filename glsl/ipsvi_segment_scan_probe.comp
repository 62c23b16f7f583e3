#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_shuffle : require
#extension GL_KHR_shader_subgroup_shuffle_relative : require
// Tests only (tests/ipsvi_segmented.rs): the segmented line kernel's combines
// (glsl/ipsvi_segment_scan.glsl) on fabricated segments, one cluster of
// SEGMENTS invocations per fabricated ray, numbered as the kernel numbers them.

// 64, or SEGMENTS with CROSS_SUBGROUPS (a cluster over the workgroup's subgroups).
layout(local_size_x_id = 2) in;
layout(constant_id = 0) const uint SEGMENTS = 4u;
layout(constant_id = 1) const bool NEAREST_RUNS = true;
layout(constant_id = 3) const bool CROSS_SUBGROUPS = false;

#include "ipsvi_over.glsl"
#include "ipsvi_optical_depth.glsl"

bool run_keeps_nearest() { return NEAREST_RUNS; }

#include "ipsvi_segment_scan.glsl"

struct ProbeSegment {
    vec4 composite;  // rgb: C, a: T of the segment
    uint tau;        // its optical depth (tau_units)
    uint run_flags;  // its runs (Runs)
    uint lead_k;
    float lead_d;
    uint trail_k;
    float trail_d;
    uvec2 pad;
};

struct ProbeResult {
    vec4 total;           // the ray's composite
    uint tau_before;      // optical depth of the segments before
    uint tau_total;
    uint next_texel;      // cluster_next_texel
    uint before_flags;    // runs of the segments before
    uint before_lead_k;
    float before_lead_d;
    uint before_trail_k;
    float before_trail_d;
    uint total_flags;     // runs of all of them
    uint total_lead_k;
    float total_lead_d;
    uint total_trail_k;
    float total_trail_d;
    uint pad[3];          // to 20 words, a multiple of the vec4 (a uvec3 would align to 16)
};

layout(std430, set = 0, binding = 0) readonly buffer Segments { ProbeSegment segments[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Results { ProbeResult results[]; };
layout(push_constant) uniform Push { uint count; } push;

void main() {
    uint id = gl_WorkGroupID.x * gl_WorkGroupSize.x + gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID;
    // Whole clusters only (count is a multiple of SEGMENTS): with
    // CROSS_SUBGROUPS a workgroup returns whole, before its barriers.
    if (id >= push.count) return;
    ProbeSegment s = segments[id];
    Composite total = cluster_over(Composite(s.composite.rgb, s.composite.a));
    uint tau_total;
    uint tau_before = cluster_tau_before(s.tau, tau_total);
    Runs mine = Runs(s.run_flags, s.lead_k, s.lead_d, s.trail_k, s.trail_d);
    Runs all;
    Runs before = cluster_runs_before(mine, all);
    ProbeResult r;
    r.total = vec4(total.C, total.T);
    r.tau_before = tau_before;
    r.tau_total = tau_total;
    r.next_texel = cluster_next_texel(mine);
    r.before_flags = before.flags;
    r.before_lead_k = before.lead_k;
    r.before_lead_d = before.lead_d;
    r.before_trail_k = before.trail_k;
    r.before_trail_d = before.trail_d;
    r.total_flags = all.flags;
    r.total_lead_k = all.lead_k;
    r.total_lead_d = all.lead_d;
    r.total_trail_k = all.trail_k;
    r.total_trail_d = all.trail_d;
    r.pad = uint[3](0u, 0u, 0u);
    results[id] = r;
}
