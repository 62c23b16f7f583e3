#version 460
#extension GL_GOOGLE_include_directive : require
// Light volume ray cast, front to back with the discretization of
// raycast.comp, one dispatch per chunk of view samples (view_chunk.glsl): the source term is
// rgb * (emission + illumination(p)), the illumination read trilinearly from
// the propagated illumination volume (storage image, so filtered by hand).

layout(local_size_x = 8, local_size_y = 8) in;

#include "volume.glsl"
#include "view_ray.glsl"
#include "view_chunk.glsl"

layout(set = 0, binding = 3, rgba32f) readonly uniform image3D illumination;
// The chunks ping-pong (src/render/view_chunks.rs): each writes one image and
// reads the march so far from the other, so a missing barrier shows.
layout(set = 0, binding = 4, rgba32f) writeonly uniform image2D out_image;
layout(set = 0, binding = 5, rgba32f) readonly uniform image2D state_in;

const float LOG_FLOOR = 1e-3;

// Trilinear, texel centres at (i + 0.5) / n like the sampler, of the logarithm
// of the light: light decays exponentially through the medium, so
// interpolating log(light) between voxel centres reproduces the decay inside
// an opaque surface where a linear blend of the centres would light the
// surface's first voxel far too brightly. The floor keeps fully shadowed
// corners finite, relative to the brightest corner.
// Between the outermost centres and the box faces (half an illumination voxel)
// log(light) is extrapolated linearly from the two outermost centres instead of
// clamped, so the light rises toward a face it enters through and keeps
// decaying toward one it leaves by: exact for a homogeneous medium (clamping
// was off by the transmittance of half a voxel at each face). The extrapolation
// changes the light by at most MAX_EXTRAPOLATION over the corners' range, so a
// dense layer between the outermost centres cannot blow up a face.
const float MAX_EXTRAPOLATION = 2.0;
vec3 illumination_at(vec3 p) {
    ivec3 n = imageSize(illumination);
    vec3 c = clamp(to_uvw(p) * vec3(n) - 0.5, vec3(-0.5), vec3(n) - 0.5);
    ivec3 i0 = clamp(ivec3(floor(c)), ivec3(0), max(n - 2, ivec3(0)));
    vec3 f = c - vec3(i0);
    vec3 v[8];
    vec3 peak = vec3(0.0);
    vec3 least = vec3(3.0e38);
    for (int k = 0; k < 8; ++k) {
        ivec3 i = min(i0 + ivec3(k & 1, (k >> 1) & 1, k >> 2), n - 1);
        v[k] = imageLoad(illumination, i).rgb;
        peak = max(peak, v[k]);
        least = min(least, v[k]);
    }
    if (all(equal(peak, vec3(0.0)))) return vec3(0.0);
    vec3 floor_value = max(peak * LOG_FLOOR, vec3(1e-37));
    vec3 acc = vec3(0.0);
    for (int k = 0; k < 8; ++k) {
        vec3 w3 = mix(1.0 - f, f, vec3(k & 1, (k >> 1) & 1, k >> 2));
        acc += w3.x * w3.y * w3.z * log(max(v[k], floor_value));
    }
    vec3 r = clamp(exp(acc), max(least, floor_value) / MAX_EXTRAPOLATION, peak * MAX_EXTRAPOLATION);
    return mix(vec3(0.0), r, greaterThan(peak, vec3(0.0)));
}

void main() {
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
        vec4 m = medium(p);
        float alpha = 1.0 - exp(-m.a * v.hv);
        if (alpha > 0.0) {
            C += T * alpha * m.rgb * (frame.emission + illumination_at(p));
            T *= 1.0 - alpha;
        }
    }
    if (chunk.is_last != 0) C += T * frame.background;
    imageStore(out_image, ivec2(px), vec4(C, T));
}
