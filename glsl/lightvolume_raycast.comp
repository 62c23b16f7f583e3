#version 460
#extension GL_GOOGLE_include_directive : require
// Light volume ray cast, one dispatch per frame, front to back with the
// discretization of raycast.comp: the source term is
// rgb * (emission + illumination(p)), the illumination read trilinearly from
// the propagated illumination volume (storage image, so filtered by hand).

layout(local_size_x = 8, local_size_y = 8) in;

#include "volume.glsl"

layout(set = 0, binding = 3, rgba32f) readonly uniform image3D illumination;
layout(set = 0, binding = 4, rgba32f) writeonly uniform image2D out_image;

const float EARLY_TERMINATION_TRANSMITTANCE = 1e-4;

// Trilinear, clamp to edge, texel centres at (i + 0.5) / n like the sampler.
vec3 illumination_at(vec3 p) {
    ivec3 n = imageSize(illumination);
    vec3 c = clamp(to_uvw(p) * vec3(n) - 0.5, vec3(0.0), vec3(n - 1));
    ivec3 i0 = ivec3(floor(c));
    ivec3 i1 = min(i0 + 1, n - 1);
    vec3 f = c - vec3(i0);
    vec3 x00 = mix(imageLoad(illumination, i0).rgb, imageLoad(illumination, ivec3(i1.x, i0.y, i0.z)).rgb, f.x);
    vec3 x10 = mix(imageLoad(illumination, ivec3(i0.x, i1.y, i0.z)).rgb, imageLoad(illumination, ivec3(i1.x, i1.y, i0.z)).rgb, f.x);
    vec3 x01 = mix(imageLoad(illumination, ivec3(i0.x, i0.y, i1.z)).rgb, imageLoad(illumination, ivec3(i1.x, i0.y, i1.z)).rgb, f.x);
    vec3 x11 = mix(imageLoad(illumination, ivec3(i0.x, i1.y, i1.z)).rgb, imageLoad(illumination, i1).rgb, f.x);
    return mix(mix(x00, x10, f.y), mix(x01, x11, f.y), f.z);
}

void main() {
    uvec2 px = gl_GlobalInvocationID.xy;
    if (px.x >= frame.image_size.x || px.y >= frame.image_size.y) return;
    Ray r = camera_ray(px);
    vec2 t = intersect_box(r.origin, r.dir);
    vec3 C = vec3(0.0);
    float T = 1.0;
    if (t.x < t.y) {
        float vl = frame.box_half.w;
        float L = t.y - t.x;
        float N = max(1.0, ceil(L / (frame.march.x * vl)));
        float h = L / N;
        float hv = h / vl;
        int n = int(N);
        for (int i = 0; i < n; ++i) {
            vec3 p = r.origin + r.dir * (t.x + (float(i) + 0.5) * h);
            vec4 m = medium(p);
            float alpha = 1.0 - exp(-m.a * hv);
            if (alpha > 0.0) {
                C += T * alpha * m.rgb * (frame.background.w + illumination_at(p));
                T *= 1.0 - alpha;
            }
            if (T < EARLY_TERMINATION_TRANSMITTANCE) break;
        }
    }
    C += T * frame.background.rgb;
    imageStore(out_image, ivec2(px), vec4(C, T));
}
