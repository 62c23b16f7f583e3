// The dispatch probe's block (src/bench/experiments/dispatch_probe.rs): the
// set-0 resources of a line pass (frame, volume, LUT, lights, as IPSVI's set
// holds them), read once, added to the ping-pong image's texel.
#ifndef PROBE_COMMON_GLSL
#define PROBE_COMMON_GLSL
#include "volume.glsl"
#include "lights.glsl"

vec4 probe_block(vec4 previous) {
    vec4 m = medium(vec3(0.0));
    float light = frame.light_count > 0 ? lights[0].radiance.x : 0.0;
    return previous + 1e-6 * (m + vec4(light));
}
#endif
