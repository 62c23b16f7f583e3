// A 2D buffer of light rays fitted to the volume as seen from the light
// (src/techniques/ipsvi/cache_geometry.rs): IPSVI's illumination cache and half-angle
// slicing's light buffer. Orthographic for directional lights, a perspective
// frustum for lights outside the volume's bounding sphere, an octahedral map
// of all directions for lights inside it.
#ifndef LIGHT_SPACE_GLSL
#define LIGHT_SPACE_GLSL
#include "frame.glsl"

struct LightSpace {
    vec4 origin;  // xyz: light position, or a point behind the volume for directional; w: projection
    vec4 axis;    // xyz: light travel direction (orthographic) or frustum axis; w: texel size
    vec4 u;       // xyz: first plane axis; w: a0 (start along u)
    vec4 v;       // xyz: second plane axis; w: b0
    uint size;    // N: the buffer is N x N
    uint light;   // index of the light (half-angle slicing's light buffer)
    uint pad0;
    uint pad1;
};

const float PROJ_ORTHOGRAPHIC = 0.0;
const float PROJ_PERSPECTIVE = 1.0;
const float PROJ_OCTAHEDRAL = 2.0;

vec2 oct_encode(vec3 d) {
    d /= abs(d.x) + abs(d.y) + abs(d.z);
    vec2 e = d.xy;
    if (d.z < 0.0) e = (1.0 - abs(d.yx)) * vec2(d.x >= 0.0 ? 1.0 : -1.0, d.y >= 0.0 ? 1.0 : -1.0);
    return e;
}

vec3 oct_decode(vec2 e) {
    vec3 d = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (d.z < 0.0) d.xy = (1.0 - abs(d.yx)) * vec2(d.x >= 0.0 ? 1.0 : -1.0, d.y >= 0.0 ? 1.0 : -1.0);
    return normalize(d);
}

// The light ray of texel `t`: origin and unit direction of light travel.
Ray light_space_ray(LightSpace ls, uvec2 t) {
    vec2 ab = vec2(ls.u.w, ls.v.w) + (vec2(t) + 0.5) * ls.axis.w;
    Ray r;
    if (ls.origin.w == PROJ_ORTHOGRAPHIC) {
        r.origin = ls.origin.xyz + ls.u.xyz * ab.x + ls.v.xyz * ab.y;
        r.dir = ls.axis.xyz;
    } else if (ls.origin.w == PROJ_PERSPECTIVE) {
        r.origin = ls.origin.xyz;
        r.dir = normalize(ls.axis.xyz + ls.u.xyz * ab.x + ls.v.xyz * ab.y);
    } else {
        r.origin = ls.origin.xyz;
        r.dir = oct_decode((vec2(t) + 0.5) / float(ls.size) * 2.0 - 1.0);
    }
    return r;
}

// Continuous buffer coordinates (texel centres at i + 0.5) of world point p, and
// p's distance along its light ray (z).
vec3 light_space_coord(LightSpace ls, vec3 p) {
    vec3 q = p - ls.origin.xyz;
    float s = ls.axis.w;
    if (ls.origin.w == PROJ_ORTHOGRAPHIC) {
        return vec3((dot(q, ls.u.xyz) - ls.u.w) / s, (dot(q, ls.v.xyz) - ls.v.w) / s, dot(q, ls.axis.xyz));
    }
    float len = length(q);
    if (ls.origin.w == PROJ_PERSPECTIVE) {
        float z = max(dot(q, ls.axis.xyz), 1e-12);
        return vec3((dot(q, ls.u.xyz) / z - ls.u.w) / s, (dot(q, ls.v.xyz) / z - ls.v.w) / s, len);
    }
    vec2 e = len > 0.0 ? oct_encode(q / len) : vec2(0.0);
    return vec3((e * 0.5 + 0.5) * float(ls.size), len);
}

#endif
