#version 460
#extension GL_GOOGLE_include_directive : require
// Half-angle slicing (Kniss et al. 2003), one dispatch per slice: slices are
// planes perpendicular to the half-angle vector h between the view and light
// directions, taken in order from the light's side. Invocations below
// `pixel_count` composite the slice into the eye buffer, lit by the light buffer
// as it stands after the previous slices; the rest attenuate the light buffer by
// this slice, writing the other image of the ping-pong pair (the texels whose
// rays cross this slice's or the previous slice's slab inside the box). The pair is a
// small set 1, {in = a, out = b} or {in = b, out = a}, bound per slice (cheap
// on lavapipe, unlike set 0: tools/dispatch_probe.rs); reads and writes are
// separate bindings, so validation sees what a slice touches.

layout(local_size_x = 64) in;

#include "volume.glsl"
#include "lights.glsl"
#include "light_space.glsl"
#include "view_ray.glsl"

layout(std430, set = 0, binding = 4) readonly buffer LightBuffers { LightSpace light_buffer; };

layout(set = 1, binding = 0, r32f) readonly uniform image2D light_in;
layout(set = 1, binding = 1, r32f) writeonly uniform image2D light_out;
// Eye buffer: front to back rgb = colour, a = transmittance; back to front rgb
// = colour composited over what lies behind.
layout(set = 0, binding = 9, rgba32f) uniform image2D eye;

layout(push_constant) uniform Slice {
    vec4 half_vector;   // xyz h; w plane offset s (points x with dot(x, h) = s)
    vec4 spacing;       // x slice spacing (world); y 1 = front to back; z unused; w 1 = add the background (last slice, front to back)
    uvec4 rect;         // pixels x0, y0, w, h
    uvec4 light_rect;   // light buffer texels x0, y0, w, h this slice updates
    uint pixel_count;
} slice;

float light_bilinear(vec2 c) {
    ivec2 n = ivec2(light_buffer.size);
    vec2 t = c - 0.5;
    ivec2 i0 = ivec2(floor(t));
    vec2 f = t - vec2(i0);
    ivec2 a = clamp(i0, ivec2(0), n - 1);
    ivec2 b = clamp(i0 + 1, ivec2(0), n - 1);
    float v00 = imageLoad(light_in, a).r, v10 = imageLoad(light_in, ivec2(b.x, a.y)).r;
    float v01 = imageLoad(light_in, ivec2(a.x, b.y)).r, v11 = imageLoad(light_in, b).r;
    return mix(mix(v00, v10, f.x), mix(v01, v11, f.x), f.y);
}

bool inside_box(vec3 p) { return all(lessThanEqual(abs(p), frame.box_half)); }

// The slice's sample on the view ray through `px`: (source, alpha); alpha 0
// where the slice misses the ray or the medium is clear. The sample lies at
// the pixel's phase within the slice's slab (view_ray.glsl: the midpoint, or
// with render.jitter the pixel's own), so that the slice planes, which every
// pixel would otherwise sample at the same depths, do not draw rings on
// surfaces; the light buffer is attenuated at the slab's middle plane.
vec4 slice_sample(uvec2 px) {
    Ray r = camera_ray(px);
    vec3 h = slice.half_vector.xyz;
    float dh = dot(r.dir, h);
    if (abs(dh) < 1e-6) return vec4(0.0);
    float phase = ray_start_phase(px);
    float t = (slice.half_vector.w + (phase - 0.5) * slice.spacing.x - dot(r.origin, h)) / dh;
    vec3 p = r.origin + r.dir * t;
    if (t <= 0.0 || !inside_box(p)) return vec4(0.0);
    vec4 m = medium(p);
    float alpha = 1.0 - exp(-m.a * (slice.spacing.x / abs(dh)) / frame.voxel_length);
    if (alpha <= 0.0) return vec4(0.0);
    Light l = lights[light_buffer.light];
    vec4 w = toward_light(l, p);
    // The light buffer holds what passed the slices before this one; the sample
    // lies `phase` of the way through its slab from the light's side (slices
    // run along +h, away from the light), so that share of the slab's own
    // extinction along the light applies too (at midpoints, half: the midpoint
    // rule of the reference's shadow rays).
    float dl = abs(dot(-w.xyz, h));
    float lit = light_bilinear(light_space_coord(light_buffer, p).xy) * exp(-m.a * phase * (slice.spacing.x / max(dl, 1e-6)) / frame.voxel_length);
    vec3 S = m.rgb * (frame.emission + l.radiance.rgb * light_shape(l, w) * lit);
    return vec4(S, alpha);
}

void shade(uint index) {
    uvec2 px = slice.rect.xy + uvec2(index % slice.rect.z, index / slice.rect.z);
    vec4 s = slice_sample(px);
    // Front to back, the last slice (its rect the whole image) adds what shows
    // through the volume: the background times the transmittance left.
    bool background = slice.spacing.w > 0.5;
    if (s.a <= 0.0 && !background) return;
    ivec2 ip = ivec2(px);
    vec4 acc = imageLoad(eye, ip);
    if (s.a > 0.0) {
        float alpha = s.a;
        vec3 S = s.rgb;
        if (slice.spacing.y > 0.5) {
            acc.rgb += acc.a * alpha * S;
            acc.a *= 1.0 - alpha;
        } else {
            acc.rgb = alpha * S + (1.0 - alpha) * acc.rgb;
        }
    }
    if (background) acc.rgb += acc.a * frame.background;
    imageStore(eye, ip, acc);
}

// A texel of `light_rect`: the slab's and the previous slab's region
// (src/render/light_region.rs); every other texel of light_out already holds
// its value as of this slice, written two slices ago and not changed since.
void attenuate(uint index) {
    uvec2 k = slice.light_rect.xy + uvec2(index % slice.light_rect.z, index / slice.light_rect.z);
    float T = imageLoad(light_in, ivec2(k)).r;
    Ray r = light_space_ray(light_buffer, k);
    vec3 h = slice.half_vector.xyz;
    float dh = dot(r.dir, h);
    if (abs(dh) > 1e-6) {
        // The slab's extinction taken at the texel's own phase within it, as the
        // eye samples take theirs: at one plane for every texel, a surface's
        // shadow would show the planes as rings.
        float t = (slice.half_vector.w + (ray_start_phase(k) - 0.5) * slice.spacing.x - dot(r.origin, h)) / dh;
        vec3 q = r.origin + r.dir * t;
        if (t > 0.0 && inside_box(q)) T *= exp(-medium(q).a * (slice.spacing.x / abs(dh)) / frame.voxel_length);
    }
    imageStore(light_out, ivec2(k), vec4(T));
}

void main() {
    load_frame();
    uint id = gl_GlobalInvocationID.x;
    if (id < slice.pixel_count) {
        shade(id);
    } else if (id - slice.pixel_count < slice.light_rect.z * slice.light_rect.w) {
        attenuate(id - slice.pixel_count);
    }
}
