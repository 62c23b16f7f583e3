// IPSVI: the illumination cache's geometry (a plane fitted to the volume as seen
// from the light), the sweep-line planes the cache fronts advance to, and light
// segments integrated toward the light. Mirrors src/ipsvi/gpu_params.rs.
#ifndef IPSVI_COMMON_GLSL
#define IPSVI_COMMON_GLSL
#include "volume.glsl"
#include "lights.glsl"
#include "light_path.glsl"

struct SweepParams {
    vec4 cache_origin;  // xyz: light position, or a point behind the volume for directional; w: projection
    vec4 cache_axis;    // xyz: light travel direction (directional) or frustum axis; w: texel size
    vec4 cache_u;       // xyz: first plane axis; w: a0 (start of the cache along u)
    vec4 cache_v;       // xyz: second plane axis; w: b0
    vec4 anchor;        // xy: light anchor in pixels; z: zone blend width (px); w: light scale (cache stores E / scale)
    uvec4 cache_size;   // x: N (cache is N x N); y: light index; z: flags; w: max piecewise steps
    vec4 scatter;       // x: albedo (multiple-scattering share); y: tan(cone half-angle); z: pre-pass scale
};

// One record per light, found by index: on lavapipe a descriptor-set bind costs
// about ten dispatches (tools/dispatch_probe.rs), so sets are bound per sweep
// at most and dispatches pick their parameters from buffers.
layout(std430, set = 0, binding = 4) readonly buffer Sweeps { SweepParams sweeps[]; };

SweepParams sweep;

// One plane per sweep line: rows 0..H-1, then columns 0..W-1: n.x + d = 0.
layout(std430, set = 0, binding = 5) readonly buffer Planes { vec4 planes[]; };

const float PROJ_ORTHOGRAPHIC = 0.0;
const float PROJ_PERSPECTIVE = 1.0;
const float PROJ_OCTAHEDRAL = 2.0;

const uint FLAG_FIRST_LIGHT = 1u;   // adds emission and background
const uint FLAG_PIECEWISE = 2u;     // piecewise integration toward the cache front
const uint FLAG_EARLY_TERMINATION = 4u;
const uint FLAG_EXIT_POINTS = 8u;       // rays go on to l_max of the exit-point sweep

// Front codes of the position image: a plane index, or the ray's box entry/exit.
const uint FRONT_ENTRY = 0xFFFEu;
const uint FRONT_EXIT = 0xFFFFu;

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

// The light ray of cache texel `t`: origin and unit direction of light travel.
Ray cache_ray(uvec2 t) {
    float n = float(sweep.cache_size.x);
    float s = sweep.cache_axis.w;
    vec2 ab = vec2(sweep.cache_u.w, sweep.cache_v.w) + (vec2(t) + 0.5) * s;
    Ray r;
    if (sweep.cache_origin.w == PROJ_ORTHOGRAPHIC) {
        r.origin = sweep.cache_origin.xyz + sweep.cache_u.xyz * ab.x + sweep.cache_v.xyz * ab.y;
        r.dir = sweep.cache_axis.xyz;
    } else if (sweep.cache_origin.w == PROJ_PERSPECTIVE) {
        r.origin = sweep.cache_origin.xyz;
        r.dir = normalize(sweep.cache_axis.xyz + sweep.cache_u.xyz * ab.x + sweep.cache_v.xyz * ab.y);
    } else {
        r.origin = sweep.cache_origin.xyz;
        r.dir = oct_decode((vec2(t) + 0.5) / n * 2.0 - 1.0);
    }
    return r;
}

// Continuous cache coordinates (texel centres at i + 0.5) of world point p, and
// p's distance along its light ray (z).
vec3 cache_coord(vec3 p) {
    vec3 q = p - sweep.cache_origin.xyz;
    float s = sweep.cache_axis.w;
    if (sweep.cache_origin.w == PROJ_ORTHOGRAPHIC) {
        return vec3((dot(q, sweep.cache_u.xyz) - sweep.cache_u.w) / s, (dot(q, sweep.cache_v.xyz) - sweep.cache_v.w) / s, dot(q, sweep.cache_axis.xyz));
    }
    float len = length(q);
    if (sweep.cache_origin.w == PROJ_PERSPECTIVE) {
        float z = max(dot(q, sweep.cache_axis.xyz), 1e-12);
        return vec3((dot(q, sweep.cache_u.xyz) / z - sweep.cache_u.w) / s, (dot(q, sweep.cache_v.xyz) / z - sweep.cache_v.w) / s, len);
    }
    vec2 e = len > 0.0 ? oct_encode(q / len) : vec2(0.0);
    return vec3((e * 0.5 + 0.5) * float(sweep.cache_size.x), len);
}

// Unit vector from p toward the light.
vec3 to_light(vec3 p) {
    if (sweep.cache_origin.w == PROJ_ORTHOGRAPHIC) return -sweep.cache_axis.xyz;
    vec3 q = sweep.cache_origin.xyz - p;
    float len = length(q);
    return len > 0.0 ? q / len : vec3(0.0, 1.0, 0.0);
}

// Parameter where light ray r meets sweep plane `index` (or `fallback` if parallel).
float plane_hit(Ray r, uint index, float fallback) {
    vec4 pl = planes[index];
    float denom = dot(pl.xyz, r.dir);
    if (abs(denom) < 1e-12) return fallback;
    return -(dot(pl.xyz, r.origin) + pl.w) / denom;
}

// Where the cache front of ray r sits, from the position image's code.
float front_param(Ray r, uint code, vec2 enter_exit) {
    if (code == FRONT_ENTRY) return enter_exit.x;
    if (code == FRONT_EXIT) return enter_exit.y;
    return clamp(plane_hit(r, code, enter_exit.x), enter_exit.x, enter_exit.y);
}

// Extent of light ray r inside the box: (enter, exit); enter > exit on a miss.
// Rays of point lights start at the light.
vec2 ray_in_box(Ray r) {
    vec2 t = intersect_box(r.origin, r.dir);
    if (t.x >= t.y) return vec2(1.0, 0.0);
    return t;
}

// Integrates `len` world units from x toward the light with at most `max_steps`
// midpoint samples: (emission arriving at x / light scale: rgb, optical depth).
vec4 light_segment(vec3 x, vec3 dir, float len, uint max_steps, bool gather_emission) {
    vec4 path = integrate_light_path(x, dir, len, float(max_steps), gather_emission);
    return vec4(path.rgb * (frame.background.w / sweep.anchor.w), path.a);
}

#endif
