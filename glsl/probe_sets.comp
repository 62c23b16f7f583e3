#version 460
#extension GL_GOOGLE_include_directive : require
// Dispatch probe, one pipeline (src/bench/experiments/dispatch_probe.rs): the
// line pass's resources in set 0, bound once; the ping-pong pair in a small
// set 1, {in = a, out = b} or {in = b, out = a}, bound (or pushed) per block.
// Reads and writes stay on separate bindings, so synchronization validation
// still sees which image a dispatch reads and which it writes.
layout(local_size_x = 1) in;
#include "probe_common.glsl"
layout(set = 1, binding = 0, rgba32f) readonly uniform image2D image_in;
layout(set = 1, binding = 1, rgba32f) writeonly uniform image2D image_out;

void main() { load_frame(); imageStore(image_out, ivec2(0), probe_block(imageLoad(image_in, ivec2(0)))); }
