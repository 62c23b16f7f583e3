#version 460
#extension GL_GOOGLE_include_directive : require
// Ambient occlusion and colour bleeding from clustered local histograms
// (sections 4.2-4.4 of the 2008 paper), front to back, one dispatch per chunk
// of view samples (view_chunk.glsl). Per sample two extra fetches, as the paper
// has them: the voxel's two cluster ids (one u32) and the environment lookup of
// the hemisphere the shading normal points into (and in MODE 2 the other
// hemisphere's too). MODE: 0 isosurface with the ambient term of equation 6,
// 1 DVR with colour bleeding, 2 as 1 plus the Henyey-Greenstein phase function
// on both hemispheres, 3 as 1 plus volumetric glow. SOURCE: 0 the lookup by
// cluster id; 1 a lookup per voxel and hemisphere (the unclustered histograms
// or the ground truth), entry 2 v + hemisphere.

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const uint MODE = 1;
layout(constant_id = 1) const uint SOURCE = 0;

#include "volume.glsl"
#include "lights.glsl"
#include "phong.glsl"
#include "view_ray.glsl"
#include "view_chunk.glsl"

layout(set = 0, binding = 4, rgba32f) writeonly uniform image2D out_image;
layout(set = 0, binding = 5, rgba32f) readonly uniform image2D state_in;
// Per voxel (x fastest): forward cluster | backward cluster << 16.
layout(std430, set = 0, binding = 6) readonly buffer ClusterIds { uint cluster_ids[]; };
// (E_env rgb, O_env) per entry, then in MODE 3 (glow colour, glow intensity).
layout(std430, set = 0, binding = 7) readonly buffer Environment { vec4 env[]; };
struct AoParams {
    uint entries;     // (E_env, O_env) entries before the glow block
    float isovalue;   // MODE 0
    float phase_g;    // MODE 2
    float glow_max;   // MODE 3: h_max
};
// A storage buffer read once into registers (load_ao_params), not a uniform block:
// see frame.glsl.
layout(std140, set = 0, binding = 8) readonly buffer AoBlock { AoParams p; } ao_buffer;
AoParams ao;
void load_ao_params() { ao = ao_buffer.p; }

const float PI = 3.14159265358979;

// Lookup entries of p's voxel: x forward hemisphere (the side n = -grad f
// points into), y backward.
uvec2 lookup_entries(vec3 p) {
    uvec3 d = uvec3(frame.dims);
    uvec3 v = uvec3(clamp(ivec3(floor(to_uvw(p) * frame.dims)), ivec3(0), ivec3(d) - 1));
    uint index = v.x + d.x * (v.y + d.y * v.z);
    if (SOURCE == 1) return uvec2(2 * index, 2 * index + 1);
    uint ids = cluster_ids[index];
    return uvec2(ids & 0xffffu, ids >> 16);
}

// BT.601 YUV.
vec3 rgb_to_yuv(vec3 c) {
    float y = dot(c, vec3(0.299, 0.587, 0.114));
    return vec3(y, 0.492 * (c.b - y), 0.877 * (c.r - y));
}
vec3 yuv_to_rgb(vec3 c) {
    float r = c.x + c.z / 0.877;
    float b = c.x + c.y / 0.492;
    return vec3(r, (c.x - 0.299 * r - 0.114 * b) / 0.587, b);
}

// Henyey-Greenstein, times 4 pi so that the isotropic case is 1.
float henyey_greenstein(float g, float cos_theta) {
    float k = 1.0 + g * g - 2.0 * g * cos_theta;
    return (1.0 - g * g) / (k * sqrt(k));
}

// Section 4.3: hue between tau_rgb and the environment's mean colour E / O by
// O_env (chroma per unit luminance); luminance tau's times the ambient term
// (1 - O_env) of equation 6 plus min(1 - O_env, Lambert) diffuse, plus the
// specular highlight.
vec3 colour_bleeding(vec3 rgb, vec4 e, float lambert, float spec) {
    vec3 own = rgb_to_yuv(rgb);
    vec3 around = rgb_to_yuv(e.rgb / max(e.a, 1e-6));
    float o = clamp(e.a, 0.0, 1.0);
    vec2 chroma = mix(own.yz / max(own.x, 1e-6), around.yz / max(around.x, 1e-6), o);
    float y = own.x * (frame.ambient * (1.0 - o) + frame.diffuse * min(1.0 - o, lambert));
    return max(yuv_to_rgb(vec3(y, chroma * y)), 0.0) + frame.specular * spec;
}

// The shaded colour of sample p (colour rgb) in MODE 1-3 and its environment.
vec3 shade(vec3 p, vec3 rgb, vec3 d, uvec2 entries) {
    vec3 g = gradient(to_uvw(p));
    bool flat_region = length(g) < 1e-6;
    vec3 n = flat_region ? -d : -normalize(g);
    // The side the viewer sees: its hemisphere is the one whose environment
    // shades this sample.
    if (dot(n, -d) < 0.0) {
        n = -n;
        entries = entries.yx;
    }
    vec4 e = env[entries.x];
    // Glow: each summand of equation 4 weighted by h(j), 1 + (h_max - 1) in the band.
    if (MODE == 3) e.rgb += (ao.glow_max - 1.0) * env[ao.entries + entries.x].rgb;
    float lambert = frame.light_count == 0 ? 1.0 : 0.0;
    float spec = 0.0;
    vec3 scattered = vec3(0.0);
    vec4 e_back = MODE == 2 ? env[entries.y] : vec4(0.0);
    for (int i = 0; i < int(frame.light_count); ++i) {
        LightTerm t = light_term(i, p, n, d);
        float luminance = dot(t.lit, vec3(0.299, 0.587, 0.114));
        lambert += luminance * (flat_region ? 1.0 : t.lambert);
        spec += luminance * (flat_region ? 0.0 : t.spec);
        if (MODE == 2) {
            // Light scattered from the environment toward the viewer; in a
            // homogeneous region both hemispheres, at a border the one behind
            // the surface (the subsurface look of figure 7).
            float phase = henyey_greenstein(ao.phase_g, dot(t.w, d));
            vec3 around = flat_region ? 0.5 * (e.rgb + e_back.rgb) : e_back.rgb;
            scattered += t.lit * phase * around;
        }
    }
    return colour_bleeding(rgb, e, lambert, spec) + scattered;
}

void main() {
    load_ao_params();
    load_frame();
    uvec2 px = gl_GlobalInvocationID.xy;
    if (px.x >= frame.image_size.x || px.y >= frame.image_size.y) return;
    ViewMarch v = pixel_march(px, frame.view_step);
    vec4 acc = chunk.is_first != 0 ? vec4(0.0, 0.0, 0.0, 1.0) : imageLoad(state_in, ivec2(px));
    vec3 C = acc.rgb;
    float T = acc.a;
    for (int i = int(chunk.first_sample); i < chunk_end(v.samples); ++i) {
        if (view_ray_opaque(T)) break;
        vec3 p = sample_point(v, i);
        if (MODE == 0) {
            // Isosurface: the first sample at or above the isovalue, opaque,
            // Blinn-Phong with the ambient term (1 - O_env) Col_iso (equation 6).
            if (sample_scalar(p) < ao.isovalue) continue;
            vec3 col = transfer(ao.isovalue).rgb;
            uvec2 entries = lookup_entries(p);
            vec3 g = gradient(to_uvw(p));
            vec3 n = length(g) < 1e-6 ? -v.ray.dir : -normalize(g);
            if (dot(n, -v.ray.dir) < 0.0) {
                n = -n;
                entries = entries.yx;
            }
            vec3 ambient = frame.ambient * (1.0 - clamp(env[entries.x].a, 0.0, 1.0)) * col;
            C += T * blinn_phong_lights(ambient, p, n, col, v.ray.dir);
            T = 0.0;
            break;
        }
        vec4 m = medium(p);
        float alpha = 1.0 - exp(-m.a * v.hv);
        if (MODE == 3 && alpha <= 0.0) {
            // Glow (section 4.4): an otherwise transparent sample takes the
            // environment's normalized glow intensity as its opacity.
            vec4 glow = env[ao.entries + lookup_entries(p).x];
            float a = 1.0 - pow(max(1.0 - glow.a, 0.0), v.hv);
            C += T * a * glow.rgb / max(glow.a, 1e-6);
            T *= 1.0 - a;
            continue;
        }
        if (alpha > 0.0) {
            vec3 S = shade(p, m.rgb, v.ray.dir, lookup_entries(p));
            C += T * alpha * S;
            T *= 1.0 - alpha;
        }
    }
    if (chunk.is_last != 0) C += T * frame.background;
    imageStore(out_image, ivec2(px), vec4(C, T));
}
