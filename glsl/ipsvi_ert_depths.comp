#version 460
#extension GL_GOOGLE_include_directive : require
// Early ray termination pre-pass (IPSVI paper, section 5.1): at a lower image
// resolution and sampling rate, unshaded, each ray records s_f, where its
// transmittance falls below the termination threshold (or its exit), and s_b,
// where the farthest structure along it lies (distances from the ray origin).

layout(local_size_x = 8, local_size_y = 8) in;

#include "volume.glsl"

layout(set = 0, binding = 3, rg32f) writeonly uniform image2D depths;
layout(push_constant) uniform Push {
    uint scale;       // full-resolution pixels per low-resolution pixel, per axis
    uint width;       // low-resolution size
    uint height;
} push;

const float EARLY_TERMINATION_TRANSMITTANCE = 1e-4;

void main() {
    uvec2 q = gl_GlobalInvocationID.xy;
    if (q.x >= push.width || q.y >= push.height) return;
    Ray r = camera_ray_at((vec2(q) + 0.5) * float(push.scale));
    vec2 t = intersect_box(r.origin, r.dir);
    float s_f = t.y;
    float s_b = t.x;
    if (t.x < t.y) {
        float vl = frame.box_half.w;
        float L = t.y - t.x;
        // Half the sampling rate of the main pass.
        float N = max(1.0, ceil(L / (2.0 * frame.march.x * vl)));
        float h = L / N;
        float hv = h / vl;
        float T = 1.0;
        for (int i = 0; i < int(N); ++i) {
            float ti = t.x + (float(i) + 0.5) * h;
            float sigma = medium(r.origin + r.dir * ti).a;
            if (sigma > 0.0) s_b = ti + 0.5 * h;
            T *= exp(-sigma * hv);
            if (T < EARLY_TERMINATION_TRANSMITTANCE && s_f == t.y) s_f = ti + 0.5 * h;
        }
    }
    imageStore(depths, ivec2(q), vec4(s_f, s_b, 0.0, 0.0));
}
