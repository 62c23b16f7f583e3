#version 460
#extension GL_GOOGLE_include_directive : require
// Baseline ray caster, front to back, one dispatch per chunk of view samples
// (view_chunk.glsl; one chunk at ordinary steps): unshaded
// emission-absorption DVR (SHADING = 0), gradient Blinn-Phong (SHADING = 1), or
// the emission term alone (SHADING = 2: what the illumination techniques render
// for a scene without lights).

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const uint SHADING = 0;

#include "volume.glsl"
#include "lights.glsl"
#include "phong.glsl"
#include "view_ray.glsl"
#include "view_chunk.glsl"

// The chunks ping-pong (src/render/view_chunks.rs): each writes one image and
// reads the march so far from the other, so a missing barrier shows.
layout(set = 0, binding = 4, rgba32f) writeonly uniform image2D out_image;
layout(set = 0, binding = 5, rgba32f) readonly uniform image2D state_in;

vec3 blinn_phong(vec3 p, vec3 rgb, vec3 d) {
    vec3 g = gradient(to_uvw(p));
    if (length(g) < 1e-6 || frame.light_count == 0) return rgb * (frame.ambient + frame.diffuse);
    vec3 n = -normalize(g);
    if (dot(n, -d) < 0.0) n = -n;
    return blinn_phong_lights(rgb * frame.ambient, p, n, rgb, d);
}

void main() {
    load_frame();
    uvec2 px = gl_GlobalInvocationID.xy;
    if (px.x >= frame.image_size.x || px.y >= frame.image_size.y) return;
    ViewMarch v = pixel_march(px, frame.view_step);
    vec4 acc = chunk.is_first != 0 ? vec4(0.0, 0.0, 0.0, 1.0) : imageLoad(state_in, ivec2(px));
    vec3 C = acc.rgb;
    float T = acc.a;
    for (int i = int(chunk.first_sample); i < chunk_end(v.samples); ++i) {
        // Checked before a sample rather than after: the same stop, and a
        // chunk that starts on an opaque ray does nothing.
        if (view_ray_opaque(T)) break;
        vec3 p = sample_point(v, i);
        vec4 m = medium(p);
        float alpha = 1.0 - exp(-m.a * v.hv);
        if (alpha > 0.0) {
            vec3 S = SHADING == 1 ? blinn_phong(p, m.rgb, v.ray.dir) : SHADING == 2 ? m.rgb * frame.emission : m.rgb;
            C += T * alpha * S;
            T *= 1.0 - alpha;
        }
    }
    if (chunk.is_last != 0) C += T * frame.background;
    imageStore(out_image, ivec2(px), vec4(C, T));
}
