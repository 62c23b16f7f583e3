#version 460
#extension GL_GOOGLE_include_directive : require
// Ground truth of the ambient occlusion and environment colour (see
// src/reference/ao.rs): per voxel and hemisphere, what the paper's clustered
// histograms discard: rays from the voxel to the sphere radius r along a fixed
// set of direction pairs (w and -w), the medium attenuating along each ray.
// Per direction: occlusion 1 - T(r), colour sum T alpha rgb. Each direction
// goes to the hemisphere its side of the intensity-gradient plane names
// (forward: dot(w, g) < 0; on the plane, half to each), as the histograms do.
// One invocation per voxel; the direction pairs are split across dispatches
// (llvmpipe's 65,535-iteration cap), each adding its share to the sums; a
// barrier separates the dispatches. The sums ping-pong between two buffers,
// one read (readonly), the other written (writeonly), so that
// synchronization validation sees a missing barrier (it cannot on a buffer
// bound read-write).

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

#include "transfer_lut.glsl"

struct AoReferenceParams {
    uvec4 dims;          // xyz voxels
    vec4 step_scale;     // xyz: d_min / spacing (voxels per d_min); w: sample spacing in d_min
    float radius;        // r, in d_min
    float lut_size;
    uint steps;          // samples per ray
    float inv_pairs;     // 1 / direction pairs: the mean over a hemisphere's directions
};
// A storage buffer read once into registers (load_params), not a uniform block:
// see frame.glsl.
layout(std140, set = 0, binding = 0) readonly buffer AoReferenceBlock { AoReferenceParams p; } params_buffer;
AoReferenceParams params;
void load_params() { params = params_buffer.p; }
#include "volume_fetch.glsl"
// Unit directions (xyz; w unused), one per pair.
layout(std430, set = 0, binding = 3) readonly buffer Directions { vec4 directions[]; };
// Per voxel v: sums[2 v] forward, sums[2 v + 1] backward, (E rgb, O).
layout(std430, set = 0, binding = 4) readonly buffer SumsIn { vec4 sums_in[]; };
layout(std430, set = 0, binding = 5) writeonly buffer SumsOut { vec4 sums_out[]; };

layout(push_constant) uniform Chunk {
    uint first_pair;
    uint pair_count;
    uint is_first;   // start the sums from zero
    uint pad;
} chunk;

float voxel_at(ivec3 v) { return texelFetch(volume_tex, clamp(v, ivec3(0), ivec3(params.dims.xyz) - 1), 0).r; }

// (E rgb, O) of the ray from voxel centre x (voxel coordinates) along w.
vec4 ray(vec3 x, vec3 w) {
    vec3 step = w * params.step_scale.xyz;
    float h = params.step_scale.w;
    vec3 c = vec3(0.0);
    float T = 1.0;
    for (uint i = 0; i < params.steps; ++i) {
        // Midpoints of [0.5, r]: the voxel's own half voxel is left out, as the
        // histograms leave out the centre.
        float t = 0.5 + (float(i) + 0.5) * h;
        vec3 uvw = (x + step * t + 0.5) / vec3(params.dims.xyz);
        // Outside the volume is empty, as for the histograms.
        if (any(lessThan(uvw, vec3(0.0))) || any(greaterThan(uvw, vec3(1.0)))) break;
        vec4 m = transfer_lut(volume_at_uvw(uvw), params.lut_size);
        float alpha = 1.0 - exp(-m.a * h);
        c += T * alpha * m.rgb;
        T *= 1.0 - alpha;
    }
    return vec4(c, 1.0 - T);
}

void main() {
    load_params();
    ivec3 v = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(uvec3(v), params.dims.xyz))) return;
    uint index = uint(v.x) + params.dims.x * (uint(v.y) + params.dims.y * uint(v.z));
    // Central differences, clamped at the border (src/techniques/ao/gradient.rs).
    vec3 g = vec3(voxel_at(v + ivec3(1, 0, 0)) - voxel_at(v - ivec3(1, 0, 0)),
                  voxel_at(v + ivec3(0, 1, 0)) - voxel_at(v - ivec3(0, 1, 0)),
                  voxel_at(v + ivec3(0, 0, 1)) - voxel_at(v - ivec3(0, 0, 1))) * 0.5 * params.step_scale.xyz;
    vec4 forward = chunk.is_first != 0 ? vec4(0.0) : sums_in[2 * index];
    vec4 backward = chunk.is_first != 0 ? vec4(0.0) : sums_in[2 * index + 1];
    vec3 x = vec3(v);
    uint end = min(chunk.first_pair + chunk.pair_count, uint(directions.length()));
    for (uint k = chunk.first_pair; k < end; ++k) {
        vec3 w = directions[k].xyz;
        vec4 plus = ray(x, w) * params.inv_pairs;
        vec4 minus = ray(x, -w) * params.inv_pairs;
        float side = dot(w, g);
        // w forward when side < 0, then -w backward; and the other way round.
        vec2 share = side < 0.0 ? vec2(1.0, 0.0) : side > 0.0 ? vec2(0.0, 1.0) : vec2(0.5);
        forward += share.x * plus + share.y * minus;
        backward += share.y * plus + share.x * minus;
    }
    sums_out[2 * index] = forward;
    sums_out[2 * index + 1] = backward;
}
