// IPSVI line kernels: which pixels a block's invocations march and where a
// view ray stops.
#ifndef IPSVI_MARCH_GLSL
#define IPSVI_MARCH_GLSL

float zone_weight(BlockParams line_block, vec2 c) {
    if (line_block.zone == 0u) return 1.0;
    vec2 d = c - sweep.anchor;
    float b = max(sweep.blend_px, 1e-3);
    vec4 m = vec4(d.x - abs(d.y), -d.x - abs(d.y), d.y - abs(d.x), -d.y - abs(d.x));
    vec4 w = clamp(0.5 + m / (2.0 * b), 0.0, 1.0);
    return w[line_block.zone - 1u] / max(w.x + w.y + w.z + w.w, 1e-6);
}

uvec2 block_pixel(BlockParams b, uint index) {
    uint along = b.line_first + index / b.span_len;
    uint across = b.span_start + index % b.span_len;
    return b.columns != 0u ? uvec2(along, across) : uvec2(across, along);
}

// Whether pixel `index` of block b is marched at all: inside the image, and
// inside its zone or the zone's blend.
bool pixel_in_block(BlockParams b, uint index, out uvec2 px, out float w) {
    px = block_pixel(b, index);
    w = 0.0;
    if (px.x >= frame.image_size.x || px.y >= frame.image_size.y) return false;
    w = zone_weight(b, vec2(px) + 0.5);
    return w > 0.0;
}

#include "ipsvi_view_stop.glsl"

// Where the exit-point sweep lets a ray stop (0: wherever it is opaque).
float stop_distance(uvec2 px) { return exit_point_distance(px, sweep.ert_scale); }

#endif
