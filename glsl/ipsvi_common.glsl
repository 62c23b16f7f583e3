// IPSVI: the illumination cache's geometry (a plane fitted to the volume as seen
// from the light), the sweep-line planes the cache fronts advance to, and light
// segments integrated toward the light. Mirrors src/techniques/ipsvi/gpu_params.rs.
#ifndef IPSVI_COMMON_GLSL
#define IPSVI_COMMON_GLSL
#include "volume.glsl"
#include "lights.glsl"
#include "light_path.glsl"
#include "light_space.glsl"

struct SweepParams {
    vec4 cache_origin;  // xyz: light position, or a point behind the volume for directional; w: projection
    vec4 cache_axis;    // xyz: light travel direction (directional) or frustum axis; w: texel size
    vec4 cache_u;       // xyz: first plane axis; w: a0 (start of the cache along u)
    vec4 cache_v;       // xyz: second plane axis; w: b0
    vec2 anchor;        // light anchor in pixels
    float blend_px;     // width of the blend between zones (pixels)
    float light_scale;  // the cache stores E / light_scale
    uint cache_size;    // N: the cache is N x N
    uint light_index;   // into lights[]
    uint flags;         // FLAG_*
    uint max_piecewise_steps;
    float albedo;       // multiple-scattering share
    float cone_tan;     // tan(cone half-angle)
    float ert_scale;    // full-resolution pixels per pre-pass pixel
    float pad;
    vec4 lit_min;       // xyz: the box light rays are clipped to (the volume box,
    vec4 lit_max;       // or with fit_to_visible the box of the cells that can be visible)
};

// One record per light, found by index: on lavapipe a descriptor-set bind costs
// about ten dispatches (tools/dispatch_probe.rs), so sets are bound per sweep
// at most and dispatches pick their parameters from buffers.
layout(std430, set = 0, binding = 4) readonly buffer Sweeps { SweepParams sweeps[]; };

SweepParams sweep;

// One plane per sweep line: rows 0..H-1, then columns 0..W-1: n.x + d = 0.
layout(std430, set = 0, binding = 5) readonly buffer Planes { vec4 planes[]; };

// Per light; what is fixed per renderer is a specialization constant of ipsvi_line.
const uint FLAG_FIRST_LIGHT = 1u;   // adds emission and background

// Front codes of the position image: a plane index, or the ray's box entry/exit.
const uint FRONT_ENTRY = 0xFFFEu;
const uint FRONT_EXIT = 0xFFFFu;

// The cache as a light space (glsl/light_space.glsl).
LightSpace cache_space() {
    return LightSpace(sweep.cache_origin, sweep.cache_axis, sweep.cache_u, sweep.cache_v, sweep.cache_size, 0u, 0u, 0u);
}

// The light ray of cache texel `t`: origin and unit direction of light travel.
Ray cache_ray(uvec2 t) { return light_space_ray(cache_space(), t); }

// Continuous cache coordinates of world point p, and its distance along its light ray (z).
vec3 cache_coord(vec3 p) { return light_space_coord(cache_space(), p); }

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

// Extent of light ray r inside the lit box (the volume box, or with
// fit_to_visible the box of the cells that can be visible): (enter, exit);
// enter > exit on a miss. Rays of point lights start at the light.
vec2 ray_in_box(Ray r) {
    vec2 t = intersect_aabb(r.origin, r.dir, sweep.lit_min.xyz, sweep.lit_max.xyz);
    if (t.x >= t.y) return vec2(1.0, 0.0);
    return t;
}

// A light path's integral (light_path.glsl) as a cache holds it: (emission
// arriving at x / light scale: rgb, optical depth).
vec4 cached_light_path(vec4 path) { return vec4(path.rgb * (frame.emission / sweep.light_scale), path.a); }

// Integrates `len` world units from x toward the light with at most `max_steps`
// midpoint samples: (emission arriving at x / light scale: rgb, optical depth).
vec4 light_segment(vec3 x, vec3 dir, float len, uint max_steps, bool gather_emission) {
    return cached_light_path(integrate_light_path(x, dir, len, float(max_steps), gather_emission));
}

// `light` (emission / scale: rgb, transmittance: a) after it crossed a
// segment `seg` of light_segment: attenuated by it, the segment's own
// emission added in front.
vec4 through_segment(vec4 light, vec4 seg) {
    float tr = exp(-seg.a);
    return vec4(light.rgb * tr + seg.rgb, light.a * tr);
}

#endif
