#version 460
#extension GL_GOOGLE_include_directive : require
// Ground truth on the GPU: view rays with a brute-force shadow ray per sample
// (docs/optical-model.md, models (i) and (ii)). llvmpipe stops an invocation after
// 65,535 loop iterations, so each dispatch marches only samples
// [first_sample, first_sample + sample_count) of every ray; the partial result
// (colour, transmittance) is carried from dispatch to dispatch through a
// ping-pong pair of images.

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const uint MODEL = 0; // 0: single scattering, 1: emissive scattering
// Coloured extinction along shadow rays (`reference.chromatic`, model (i) only).
layout(constant_id = 1) const bool CHROMATIC = false;

// Shadow rays step over the volume's empty cells (empty_cells.glsl): the same sums.
#define LIGHT_PATH_SKIPS_EMPTY_CELLS
#include "empty_cells.glsl"
#include "shadow.glsl"
#include "view_ray.glsl"

layout(set = 0, binding = 4, rgba32f) readonly uniform image2D accum_in;
layout(set = 0, binding = 5, rgba32f) writeonly uniform image2D accum_out;

layout(push_constant) uniform Chunk {
    uint first_sample;
    uint sample_count;
    uint is_first;  // start from (0, 0, 0, T = 1) instead of reading accum_in
    uint is_last;   // add the background behind the ray
} chunk;

void main() {
    load_frame();
    uvec2 px = gl_GlobalInvocationID.xy;
    if (px.x >= frame.image_size.x || px.y >= frame.image_size.y) return;
    vec4 acc = chunk.is_first != 0 ? vec4(0.0, 0.0, 0.0, 1.0) : imageLoad(accum_in, ivec2(px));
    ViewMarch v = pixel_march(px, frame.view_step);
    // The ground truth stops at its own threshold, `reference.min_transmittance`.
    uint end = min(chunk.first_sample + chunk.sample_count, uint(v.samples));
    int count = int(frame.light_count);
    for (uint i = chunk.first_sample; i < end; ++i) {
        if (acc.a < frame.min_transmittance) break;
        vec3 p = sample_point(v, int(i));
        vec4 m = medium(p);
        float alpha = 1.0 - exp(-m.a * v.hv);
        if (alpha > 0.0) {
            vec3 light = vec3(frame.emission);
            for (int l = 0; l < count; ++l) {
                vec4 w = toward_light(lights[l], p);
                // Chromatic: model (i) only (one shadow march either way).
                vec4 sh = CHROMATIC ? vec4(0.0, 0.0, 0.0, 1.0) : shadow_ray(lights[l], p, w, MODEL == 1);
                vec3 T = CHROMATIC ? chromatic_shadow_ray(lights[l], p, w) : vec3(sh.a);
                light += lights[l].radiance.rgb * light_shape(lights[l], w) * T + sh.rgb;
            }
            acc.rgb += acc.a * alpha * m.rgb * light;
            acc.a *= 1.0 - alpha;
        }
    }
    if (chunk.is_last != 0) acc.rgb += acc.a * frame.background;
    imageStore(accum_out, ivec2(px), acc);
}
