#version 460
#extension GL_GOOGLE_include_directive : require
// Starts a sweep (or, merged, every sweep at once): every light ray of the cache carries the unattenuated light
// (transmittance 1, no emission yet) with its front at its box entry. Both
// images of the ping-pong pair are written, so whichever the first line reads
// holds the start state; the view-sample stamps are cleared.

layout(local_size_x = 8, local_size_y = 8) in;

#include "ipsvi_common.glsl"

layout(set = 0, binding = 6, rgba16f) writeonly uniform image2D cache_a;
layout(set = 0, binding = 7, r16ui) writeonly uniform uimage2D front_a;
layout(set = 0, binding = 8, rgba16f) writeonly uniform image2D cache_b;
layout(set = 0, binding = 9, r16ui) writeonly uniform uimage2D front_b;
// The view-sample pair's stamps (cache_update = "view-samples"; 1x1 otherwise):
// stamp 0 is no block's, so the first block reads the history pair.
layout(set = 0, binding = 10, r32ui) writeonly uniform uimage2D stamps_a;
layout(set = 0, binding = 11, r32ui) writeonly uniform uimage2D stamps_b;
// ipsvi.packed_store: the packed pairs (rgba32ui: value halves, code or
// stamp; glsl/ipsvi_line.comp), 1x1 otherwise, as the unpacked ones are then.
layout(set = 0, binding = 12, rgba32ui) writeonly uniform uimage2D history_a;
layout(set = 0, binding = 13, rgba32ui) writeonly uniform uimage2D history_b;
layout(set = 0, binding = 14, rgba32ui) writeonly uniform uimage2D packed_samples_a;
layout(set = 0, binding = 15, rgba32ui) writeonly uniform uimage2D packed_samples_b;
// `slots` caches stacked in rows (ipsvi.merge_sweeps: one per sweep; else 1).
layout(push_constant) uniform Push { uint light; uint slots; } push;

void main() {
    sweep = sweeps[push.light];
    uvec2 k = gl_GlobalInvocationID.xy;
    if (k.x >= sweep.cache_size || k.y >= sweep.cache_size * push.slots) return;
    vec4 start = vec4(0.0, 0.0, 0.0, 1.0);
    uvec4 code = uvec4(FRONT_ENTRY);
    if (all(lessThan(ivec2(k), imageSize(cache_a)))) {
        imageStore(cache_a, ivec2(k), start);
        imageStore(front_a, ivec2(k), code);
        imageStore(cache_b, ivec2(k), start);
        imageStore(front_b, ivec2(k), code);
    }
    if (all(lessThan(ivec2(k), imageSize(stamps_a)))) {
        imageStore(stamps_a, ivec2(k), uvec4(0u));
        imageStore(stamps_b, ivec2(k), uvec4(0u));
    }
    if (all(lessThan(ivec2(k), imageSize(history_a)))) {
        uvec4 packed_start = uvec4(packHalf2x16(start.rg), packHalf2x16(start.ba), FRONT_ENTRY, 0u);
        imageStore(history_a, ivec2(k), packed_start);
        imageStore(history_b, ivec2(k), packed_start);
    }
    if (all(lessThan(ivec2(k), imageSize(packed_samples_a)))) {
        imageStore(packed_samples_a, ivec2(k), uvec4(0u));
        imageStore(packed_samples_b, ivec2(k), uvec4(0u));
    }
}
