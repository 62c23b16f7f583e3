#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_shuffle : require
#extension GL_KHR_shader_subgroup_shuffle_relative : require
// Where every view ray stops (early ray termination), once per frame before
// the sweeps, for the segmented line kernel (src/techniques/ipsvi/view_stops.rs):
// a ray's opacity depends on the volume and the view only, never on the
// light, so its stop does not wait for any line. Each pixel's SEGMENTS
// invocations (a cluster, as in the line kernel) sum their segment's optical
// depth, scan the sums, and the one segment holding the stop marches it
// again up to the sample where the serial march stops (the same rule and
// integer sums: glsl/ipsvi_view_stop.glsl). The line kernel's segments then
// split only the samples before it: no speculative march past the stop, no
// opacity pass before the claims.

layout(local_size_x_id = 8) in;
layout(constant_id = 7) const uint TERMINATION = 1u;
layout(constant_id = 16) const uint SEGMENTS = 4u;
layout(constant_id = 19) const bool CROSS_SUBGROUPS = false;

#include "volume.glsl"
#include "view_ray.glsl"
#include "ipsvi_view_stop.glsl"
#include "ipsvi_cluster.glsl"
#include "ipsvi_shape.glsl"

// Per pixel (row-major), the view samples its ray marches: up to and
// including the one after which it stops, or all of them.
layout(std430, set = 0, binding = 28) writeonly buffer ViewStops { uint view_stops[]; };
layout(push_constant) uniform Push { float ert_scale; } push;

// This invocation's serial chain: samples whose opacity it fetched.
uint chain = 0u;

void stop_of_pixel(uint pixel, uint segment) {
    uvec2 size = frame.image_size;
    // The whole cluster leaves together (one pixel).
    if (pixel >= size.x * size.y) return;
    uvec2 px = uvec2(pixel % size.x, pixel / size.x);
    ViewMarch v = pixel_march(px, frame.view_step);
    float keep_going = exit_point_distance(px, push.ert_scale);
    int len = max(1, (v.samples + int(SEGMENTS) - 1) / int(SEGMENTS));
    int lo = int(segment) * len;
    int hi = min(lo + len, v.samples);
    uint mine = 0u;
    for (int i = lo; i < hi; ++i) mine = tau_add(mine, tau_units(medium(sample_point(v, i)).a * v.hv));
    chain = uint(max(hi - lo, 0));
    uint total;
    uint tau = cluster_tau_before(mine, total);
    // The stop is monotone in depth: at most one segment has not stopped
    // before its first sample and has by its last.
    bool before = lo > 0 && ray_stops(tau, v, lo - 1, keep_going);
    if (hi > lo && !before && ray_stops(tau_add(tau, mine), v, hi - 1, keep_going)) {
        for (int i = lo; i < hi; ++i) {
            tau = tau_add(tau, tau_units(medium(sample_point(v, i)).a * v.hv));
            chain += 1u;
            if (ray_stops(tau, v, i, keep_going)) {
                view_stops[pixel] = uint(i + 1);
                break;
            }
        }
    } else if (segment == 0u && (v.samples == 0 || !ray_stops(total, v, v.samples - 1, keep_going))) {
        view_stops[pixel] = uint(v.samples);
    }
}

void main() {
    load_frame();
    // Uniform over the workgroup: the line kernel's check, which flags the frame.
    if (!clusters_fit()) return;
    uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    uint id = group * gl_WorkGroupSize.x + cluster_local_index();
    stop_of_pixel(id / SEGMENTS, id % SEGMENTS);
    // Every lane active again: one atomic per subgroup, spread over the slots.
    uint longest = subgroup_largest(chain);
    if (gl_SubgroupInvocationID == 0u && longest > 0u)
        atomicMax(stops_chains[group % CHAIN_ROLE_SLOTS], longest);
}
