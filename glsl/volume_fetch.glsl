// The scalar volume (binding 1) and the one way every shader reads it at a
// continuous position: trilinear filtering with clamp-to-edge, texel centres at
// (i + 0.5) / n. VOLUME_FILTER (render.filter, docs/filtering.md, and the volume's
// interpolation) picks how:
//   0 "exact":    the sampler's linear filter (exact on lavapipe for r32f);
//   1 "gpu-8bit": the eight texels fetched and blended with sub-texel weights
//                 rounded to 1/256, as NVIDIA, AMD and Intel filter every format,
//                 so that lavapipe shows what a desktop GPU's filter gives.
//   2 a labelled volume (Interpolation::Nearest, src/scene/volume.rs): the value
//     of the voxel the position lies in, never a blend of two labels.
// The constant id is src/vk/pipeline.rs's VOLUME_FILTER_CONSTANT_ID: every
// pipeline gets it, the scene's choice.
#ifndef VOLUME_FETCH_GLSL
#define VOLUME_FETCH_GLSL

layout(set = 0, binding = 1) uniform sampler3D volume_tex;
layout(constant_id = 900) const uint VOLUME_FILTER = 0u;

// Sub-texel weights as hardware keeps them: 8 fractional bits.
vec3 quantized_weights(vec3 f) { return floor(f * 256.0 + 0.5) / 256.0; }

float volume_at_uvw(vec3 uvw) {
    if (VOLUME_FILTER == 0u) return textureLod(volume_tex, uvw, 0.0).r;
    ivec3 size = textureSize(volume_tex, 0);
    if (VOLUME_FILTER == 2u) return texelFetch(volume_tex, clamp(ivec3(floor(uvw * vec3(size))), ivec3(0), size - 1), 0).r;
    vec3 t = uvw * vec3(size) - 0.5;
    vec3 base = floor(t);
    vec3 w = quantized_weights(t - base);
    ivec3 lo = clamp(ivec3(base), ivec3(0), size - 1);
    ivec3 hi = clamp(ivec3(base) + 1, ivec3(0), size - 1);
    float c000 = texelFetch(volume_tex, ivec3(lo.x, lo.y, lo.z), 0).r;
    float c100 = texelFetch(volume_tex, ivec3(hi.x, lo.y, lo.z), 0).r;
    float c010 = texelFetch(volume_tex, ivec3(lo.x, hi.y, lo.z), 0).r;
    float c110 = texelFetch(volume_tex, ivec3(hi.x, hi.y, lo.z), 0).r;
    float c001 = texelFetch(volume_tex, ivec3(lo.x, lo.y, hi.z), 0).r;
    float c101 = texelFetch(volume_tex, ivec3(hi.x, lo.y, hi.z), 0).r;
    float c011 = texelFetch(volume_tex, ivec3(lo.x, hi.y, hi.z), 0).r;
    float c111 = texelFetch(volume_tex, ivec3(hi.x, hi.y, hi.z), 0).r;
    float x00 = mix(c000, c100, w.x);
    float x10 = mix(c010, c110, w.x);
    float x01 = mix(c001, c101, w.x);
    float x11 = mix(c011, c111, w.x);
    return mix(mix(x00, x10, w.y), mix(x01, x11, w.y), w.z);
}

// The field a shading normal is taken from (phong.glsl): the volume's own read,
// but trilinear in a labelled volume too. Read nearest, a part's gradient would
// be a slab one voxel deep with a hard inner edge, and whether a view ray's
// second or third sample still lies in it would switch pixel by pixel with the
// ray's phase (dots on every face); the trilinear field's gradient fades out.
float volume_smooth_at_uvw(vec3 uvw) {
    return VOLUME_FILTER == 2u ? textureLod(volume_tex, uvw, 0.0).r : volume_at_uvw(uvw);
}

#endif
