#version 460
#extension GL_GOOGLE_include_directive : require
// Starts a sweep: every light ray of the cache carries the unattenuated light
// (transmittance 1, no emission yet) with its front at its box entry. Both
// images of the ping-pong pair are written, so whichever the first line reads
// holds the start state.

layout(local_size_x = 8, local_size_y = 8) in;

#include "ipsvi_common.glsl"

layout(set = 0, binding = 6, rgba16f) writeonly uniform image2D cache_a;
layout(set = 0, binding = 7, r16ui) writeonly uniform uimage2D front_a;
layout(set = 0, binding = 8, rgba16f) writeonly uniform image2D cache_b;
layout(set = 0, binding = 9, r16ui) writeonly uniform uimage2D front_b;
layout(push_constant) uniform Push { uint light; } push;

void main() {
    sweep = sweeps[push.light];
    uvec2 k = gl_GlobalInvocationID.xy;
    if (k.x >= sweep.cache_size || k.y >= sweep.cache_size) return;
    vec4 start = vec4(0.0, 0.0, 0.0, 1.0);
    uvec4 code = uvec4(FRONT_ENTRY);
    imageStore(cache_a, ivec2(k), start);
    imageStore(front_a, ivec2(k), code);
    imageStore(cache_b, ivec2(k), start);
    imageStore(front_b, ivec2(k), code);
}
