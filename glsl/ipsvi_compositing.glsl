// IPSVI line kernels: what a shaded view sample sends toward the eye, and a
// pixel's composite added to its accumulation (the over operator itself:
// glsl/ipsvi_over.glsl).
#ifndef IPSVI_COMPOSITING_GLSL
#define IPSVI_COMPOSITING_GLSL

#include "ipsvi_over.glsl"

// What a shaded sample at p with medium m sends toward the eye, given the light
// l it receives (E / scale: rgb, direct transmittance: a).
vec3 sample_radiance(Light light, vec3 p, vec4 m, vec4 l, bool first_light) {
    vec3 direct = light.radiance.rgb * light_shape(light, toward_light(light, p)) * l.a;
    return m.rgb * (direct + l.rgb * sweep.light_scale + (first_light ? vec3(frame.emission) : vec3(0.0)));
}

// Adds the pixel's composite, weighted by its zone weight w, to its
// accumulation. Cleared to the background: the first light replaces it by
// what shows through.
void finish_pixel(uvec2 px, float w, Composite c, bool first_light) {
    vec3 C = c.C;
    if (first_light) C += (c.T - 1.0) * frame.background;
    ivec2 ip = ivec2(px) + ivec2(0, int(block.out_row));
    imageStore(out_image, ip, imageLoad(out_image, ip) + vec4(w * C, 0.0));
}

#endif
