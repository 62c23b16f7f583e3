// Brute-force shadow ray from p toward a light (docs/optical-model.md): returns
// (transmittance, emission gathered along the way: rgb) as vec4(E.rgb, T).
#ifndef SHADOW_GLSL
#define SHADOW_GLSL
#include "volume.glsl"
#include "lights.glsl"
#include "light_path.glsl"

vec4 shadow_ray(Light l, vec3 p, vec4 w_dist, bool gather_emission) {
    vec2 t = intersect_box(p, w_dist.xyz);
    float D = t.x < t.y ? t.y : 0.0;
    if (l.pos_type.w != LIGHT_DIRECTIONAL) D = min(D, w_dist.w);
    if (D <= 0.0) return vec4(0.0, 0.0, 0.0, 1.0);
    vec4 path = integrate_light_path(p, w_dist.xyz, D, 3.0e38, gather_emission);
    return vec4(path.rgb * frame.emission, exp(-path.a));
}

// Per-channel transmittance toward the light under coloured extinction (optical
// depth sigma * max(1 - rgb, 0) per channel), with the steps of shadow_ray.
vec3 chromatic_shadow_ray(Light l, vec3 p, vec4 w_dist) {
    vec2 t = intersect_box(p, w_dist.xyz);
    float D = t.x < t.y ? t.y : 0.0;
    if (l.pos_type.w != LIGHT_DIRECTIONAL) D = min(D, w_dist.w);
    if (D <= 0.0) return vec3(1.0);
    float vl = frame.voxel_length;
    float M = max(ceil(D / (frame.shadow_step * vl)), 1.0);
    float g = D / M;
    float gv = g / vl;
    int m = int(M);
    vec3 tau = vec3(0.0);
    for (int j = 0; j < m; ++j) {
        vec4 med = medium(p + w_dist.xyz * ((float(j) + 0.5) * g));
        tau += med.a * gv * max(vec3(1.0) - med.rgb, vec3(0.0));
    }
    return exp(-tau);
}

#endif
