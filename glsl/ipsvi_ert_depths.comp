#version 460
#extension GL_GOOGLE_include_directive : require
// Early ray termination pre-pass (IPSVI paper, section 5.1): at a lower image
// resolution and sampling rate, unshaded, each ray records s_f, where its
// transmittance falls below the termination threshold (or its exit), and s_b,
// where the farthest structure along it lies (distances from the ray origin).

layout(local_size_x = 8, local_size_y = 8) in;

#include "volume.glsl"
#include "view_ray.glsl"

layout(set = 0, binding = 3, rg32f) writeonly uniform image2D depths;
layout(push_constant) uniform Push {
    uint scale;       // full-resolution pixels per low-resolution pixel, per axis
    uint width;       // low-resolution size
    uint height;
} push;

void main() {
    load_frame();
    uvec2 q = gl_GlobalInvocationID.xy;
    if (q.x >= push.width || q.y >= push.height) return;
    // Half the sampling rate of the main pass.
    ViewMarch v = view_march(camera_ray_at((vec2(q) + 0.5) * float(push.scale)), 2.0 * frame.view_step);
    float s_f = v.t_exit;
    float s_b = v.t_enter;
    float T = 1.0;
    for (int i = 0; i < v.samples; ++i) {
        float ti = sample_t(v, i);
        float sigma = medium(v.ray.origin + v.ray.dir * ti).a;
        if (sigma > 0.0) s_b = ti + 0.5 * v.h;
        T *= exp(-sigma * v.hv);
        if (view_ray_opaque(T) && s_f == v.t_exit) s_f = ti + 0.5 * v.h;
    }
    imageStore(depths, ivec2(q), vec4(s_f, s_b, 0.0, 0.0));
}
