#version 460
#extension GL_GOOGLE_include_directive : require
// Dispatch probe, today's ping-pong (src/bench/experiments/dispatch_probe.rs):
// both images in set 0 with the line pass's resources, one build per parity
// (build.rs BINDING_VARIANTS), a block switches sides by binding the other
// pipeline.
layout(local_size_x = 1) in;
#include "probe_common.glsl"
#ifndef PARITY
#error "compiled with PARITY=0 or PARITY=1 by build.rs"
#endif
#if PARITY == 0
layout(set = 0, binding = 4, rgba32f) readonly uniform image2D a_read;
layout(set = 0, binding = 7, rgba32f) writeonly uniform image2D b_write;
#define image_in a_read
#define image_out b_write
#else
layout(set = 0, binding = 5, rgba32f) readonly uniform image2D b_read;
layout(set = 0, binding = 6, rgba32f) writeonly uniform image2D a_write;
#define image_in b_read
#define image_out a_write
#endif

void main() { load_frame(); imageStore(image_out, ivec2(0), probe_block(imageLoad(image_in, ivec2(0)))); }
