// Brute-force shadow ray from p toward a light (docs/optical-model.md): returns
// (transmittance, emission gathered along the way: rgb) as vec4(E.rgb, T).
#ifndef SHADOW_GLSL
#define SHADOW_GLSL
#include "volume.glsl"
#include "lights.glsl"

vec4 shadow_ray(Light l, vec3 p, vec4 w_dist, bool gather_emission) {
    vec2 t = intersect_box(p, w_dist.xyz);
    float D = t.x < t.y ? t.y : 0.0;
    if (l.pos_type.w != LIGHT_DIRECTIONAL) D = min(D, w_dist.w);
    if (D <= 0.0) return vec4(0.0, 0.0, 0.0, 1.0);
    float vl = frame.box_half.w;
    float M = max(1.0, ceil(D / (frame.march.y * vl)));
    float g = D / M;
    float gv = g / vl;
    int m = int(M);
    float tau = 0.0;
    vec3 E = vec3(0.0);
    for (int j = 0; j < m; ++j) {
        vec4 med = medium(p + w_dist.xyz * ((float(j) + 0.5) * g));
        if (gather_emission) {
            float a = 1.0 - exp(-med.a * gv);
            E += exp(-tau) * a * frame.background.w * med.rgb;
        }
        tau += med.a * gv;
    }
    return vec4(E, exp(-tau));
}

#endif
