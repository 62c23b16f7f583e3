#version 460
#extension GL_GOOGLE_include_directive : require
// One IPSVI line block (one dispatch; src/ipsvi/): invocations below
// `pixel_count` ray-cast the block's pixels, reading the illumination cache as
// it stands at the previous line; the rest advance the light rays of the
// block's cache region to this block's last line and carry the previous block's
// region forward into the other image of the ping-pong pair. Reads and writes go
// to different images, so the block has no race inside it.

layout(local_size_x = 64) in;
layout(constant_id = 0) const bool EMISSIVE = true;  // model (ii): light carries emission
layout(constant_id = 1) const bool SCATTER = false;  // albedo-blended forward-cone scattering

#include "ipsvi_common.glsl"
#include "view_ray.glsl"

// The ping-pong pair, all four images in one descriptor set bound once per
// sweep (on lavapipe a set bind costs as much as twenty dispatches; a pipeline
// bind about nothing, tools/dispatch_probe.rs). build.rs compiles this file twice:
// PARITY 0 reads the a side and writes b, PARITY 1 the opposite, and each
// variant references only those bindings, so synchronization validation sees
// exactly what a block reads and writes, and reports a missing barrier.
#ifndef PARITY
#error "compiled with PARITY=0 or PARITY=1 by build.rs"
#endif
// Each binding has one name in both builds (the Rust side binds by name); the
// code reads cache_in/front_in and writes cache_out/front_out.
#if PARITY == 0
layout(set = 0, binding = 6, rgba16f) readonly uniform image2D cache_a_read;
layout(set = 0, binding = 7, r16ui) readonly uniform uimage2D front_a_read;
layout(set = 0, binding = 12, rgba16f) writeonly uniform image2D cache_b_write;
layout(set = 0, binding = 13, r16ui) writeonly uniform uimage2D front_b_write;
#define cache_in cache_a_read
#define front_in front_a_read
#define cache_out cache_b_write
#define front_out front_b_write
#else
layout(set = 0, binding = 8, rgba16f) readonly uniform image2D cache_b_read;
layout(set = 0, binding = 9, r16ui) readonly uniform uimage2D front_b_read;
layout(set = 0, binding = 10, rgba16f) writeonly uniform image2D cache_a_write;
layout(set = 0, binding = 11, r16ui) writeonly uniform uimage2D front_a_write;
#define cache_in cache_b_read
#define front_in front_b_read
#define cache_out cache_a_write
#define front_out front_a_write
#endif
layout(set = 0, binding = 14, rgba32f) uniform image2D out_image;

struct BlockParams {
    uint line_first;
    uint line_width;
    uint span_start;
    uint span_len;
    uint columns;     // 1: lines are columns
    uint zone;        // 0 all, 1 right, 2 left, 3 down, 4 up
    uint plane;       // plane index of the block's last line
    uint pixel_count; // line_width * span_len
    uvec4 region;     // cache texels to advance: x0, y0, w, h
    uint parity;      // which of the two pipelines runs this block (PARITY)
    uint light;       // index into sweeps[]
    uint pad0;
    uint pad1;
};

// Every block of the frame, planned on the host; a dispatch gets its index as
// its only push constant. (vkCmdDispatchBase would carry it for free, but the
// validation layer we test with does not check synchronization of that command.)
layout(std430, set = 0, binding = 15) readonly buffer Blocks { BlockParams blocks[]; };
layout(push_constant) uniform Push { uint block_index; } push;

// l_max of the exit-point sweep (section 5.1), at the pre-pass resolution; a 1x1
// placeholder when that mode is off.
layout(set = 0, binding = 16, r32f) readonly uniform image2D lmax;

BlockParams block;

vec4 cache_load(ivec2 k) { return imageLoad(cache_in, k); }
uint front_load(ivec2 k) { return imageLoad(front_in, k).r; }

void cache_store(ivec2 k, vec4 v, uint code) {
    imageStore(cache_out, k, v);
    imageStore(front_out, k, uvec4(code));
}

float zone_weight(vec2 c) {
    if (block.zone == 0u) return 1.0;
    vec2 d = c - sweep.anchor;
    float b = max(sweep.blend_px, 1e-3);
    vec4 m = vec4(d.x - abs(d.y), -d.x - abs(d.y), d.y - abs(d.x), -d.y - abs(d.x));
    vec4 w = clamp(0.5 + m / (2.0 * b), 0.0, 1.0);
    return w[block.zone - 1u] / max(w.x + w.y + w.z + w.w, 1e-6);
}

// Cache value (E / scale: rgb, transmittance: a) interpolated at continuous
// coordinates c, and the front parameter of the nearest texel's ray.
vec4 cache_bilinear(vec2 c) {
    ivec2 n = ivec2(sweep.cache_size);
    vec2 t = c - 0.5;
    ivec2 i0 = ivec2(floor(t));
    vec2 f = t - vec2(i0);
    ivec2 a = clamp(i0, ivec2(0), n - 1);
    ivec2 b = clamp(i0 + 1, ivec2(0), n - 1);
    vec4 v00 = cache_load(ivec2(a.x, a.y));
    vec4 v10 = cache_load(ivec2(b.x, a.y));
    vec4 v01 = cache_load(ivec2(a.x, b.y));
    vec4 v11 = cache_load(ivec2(b.x, b.y));
    return mix(mix(v00, v10, f.x), mix(v01, v11, f.x), f.y);
}

// Light at sample p: (direct transmittance, emission arriving / scale).
vec4 light_at(vec3 p) {
    vec3 c = cache_coord(p);
    vec4 cached = cache_bilinear(c.xy);
    if ((sweep.flags & FLAG_PIECEWISE) == 0u) return vec4(cached.rgb, cached.a);
    uvec2 k = uvec2(clamp(ivec2(floor(c.xy)), ivec2(0), ivec2(sweep.cache_size) - 1));
    Ray r = cache_ray(k);
    vec2 io = ray_in_box(r);
    if (io.x > io.y) return cached;
    float front = front_param(r, front_load(ivec2(k)), io);
    // Piecewise integration: march from p toward the light back to the cache front.
    vec4 seg = light_segment(p, to_light(p), c.z - front, sweep.max_piecewise_steps, EMISSIVE);
    float tr = exp(-seg.a);
    return vec4(cached.rgb * tr + seg.rgb, cached.a * tr);
}

void shade_pixel(uint index) {
    uint along = block.line_first + index / block.span_len;
    uint across = block.span_start + index % block.span_len;
    uvec2 px = block.columns != 0u ? uvec2(along, across) : uvec2(across, along);
    if (px.x >= frame.image_size.x || px.y >= frame.image_size.y) return;
    float w = zone_weight(vec2(px) + 0.5);
    if (w <= 0.0) return;
    bool first_light = (sweep.flags & FLAG_FIRST_LIGHT) != 0u;
    Light light = lights[sweep.light_index];
    ViewMarch v = view_march(camera_ray(px), frame.view_step);
    vec3 C = vec3(0.0);
    float T = 1.0;
    if (v.samples > 0) {
        bool exit_points = (sweep.flags & FLAG_EXIT_POINTS) != 0u;
        bool ert = exit_points || (sweep.flags & FLAG_EARLY_TERMINATION) != 0u;
        float keep_going = exit_points ? imageLoad(lmax, ivec2(vec2(px) / sweep.ert_scale)).r : 0.0;
        for (int i = 0; i < v.samples; ++i) {
            vec3 p = sample_point(v, i);
            vec4 m = medium(p);
            float alpha = 1.0 - exp(-m.a * v.hv);
            if (alpha > 0.0) {
                vec4 l = light_at(p);
                vec3 direct = light.radiance.rgb * light_shape(light, toward_light(light, p)) * l.a;
                vec3 S = m.rgb * (direct + l.rgb * sweep.light_scale + (first_light ? vec3(frame.emission) : vec3(0.0)));
                C += T * alpha * S;
                T *= 1.0 - alpha;
            }
            if (ert && view_ray_opaque(T) && v.t_enter + (float(i) + 1.0) * v.h >= keep_going) break;
        }
    }
    // Cleared to the background: the first light replaces it by what shows through.
    if (first_light) C += (T - 1.0) * frame.background;
    ivec2 ip = ivec2(px);
    imageStore(out_image, ip, imageLoad(out_image, ip) + vec4(w * C, 0.0));
}

vec4 cone_average(uvec2 k, float radius) {
    ivec2 n = ivec2(sweep.cache_size);
    vec4 sum = cache_load(ivec2(k));
    ivec2 r = ivec2(max(1.0, round(radius)));
    sum += cache_load(clamp(ivec2(k) + ivec2(r.x, 0), ivec2(0), n - 1));
    sum += cache_load(clamp(ivec2(k) - ivec2(r.x, 0), ivec2(0), n - 1));
    sum += cache_load(clamp(ivec2(k) + ivec2(0, r.y), ivec2(0), n - 1));
    sum += cache_load(clamp(ivec2(k) - ivec2(0, r.y), ivec2(0), n - 1));
    return sum * 0.2;
}

void advance_texel(uint index) {
    uvec2 k = block.region.xy + uvec2(index % block.region.z, index / block.region.z);
    vec4 cached = cache_load(ivec2(k));
    uint code = front_load(ivec2(k));
    Ray r = cache_ray(k);
    vec2 io = ray_in_box(r);
    if (io.x <= io.y && code != FRONT_EXIT) {
        float old_front = front_param(r, code, io);
        float target = plane_hit(r, block.plane, old_front);
        if (target > old_front) {
            float new_front = min(target, io.y);
            vec3 x = r.origin + r.dir * new_front;
            // The segment from the old front to the new one, integrated from its far
            // end toward the light, composited behind what the cache carried.
            vec4 seg = light_segment(x, -r.dir, new_front - old_front, 4096u, EMISSIVE);
            float tr = exp(-seg.a);
            if (SCATTER) {
                // Forward-cone scattering: the albedo share of the light arrives
                // from a cone around the ray, i.e. from neighbouring texels.
                float radius = sweep.cone_tan * (new_front - old_front) / max(sweep.cache_axis.w, 1e-9);
                cached = mix(cached, cone_average(k, radius), sweep.albedo);
            }
            cached = vec4(cached.rgb * tr + seg.rgb, cached.a * tr);
            code = new_front >= io.y ? FRONT_EXIT : block.plane;
        }
    }
    cache_store(ivec2(k), cached, code);
}

void main() {
    block = blocks[push.block_index];
    sweep = sweeps[block.light];
    uint id = gl_GlobalInvocationID.x;
    if (id < block.pixel_count) {
        shade_pixel(id);
    } else {
        uint texel = id - block.pixel_count;
        if (texel < block.region.z * block.region.w) advance_texel(texel);
    }
}
