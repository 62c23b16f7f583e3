// The volume (binding 1, linear sampler) and the baked transfer LUT (binding 2):
// rgb + sigma (optical depth per voxel), interpolated exactly like
// TransferLut::sample on the CPU.
#ifndef VOLUME_GLSL
#define VOLUME_GLSL
#include "frame.glsl"

layout(set = 0, binding = 1) uniform sampler3D volume_tex;
layout(std430, set = 0, binding = 2) readonly buffer TransferLut { vec4 lut[]; };

float sample_scalar(vec3 p) { return textureLod(volume_tex, to_uvw(p), 0.0).r; }

vec4 transfer(float s) {
    float n = frame.lut_size;
    float t = clamp(s * n - 0.5, 0.0, n - 1.0);
    int i0 = int(floor(t));
    int i1 = min(i0 + 1, int(n) - 1);
    return mix(lut[i0], lut[i1], t - float(i0));
}

// (rgb, sigma) of the medium at world position p.
vec4 medium(vec3 p) { return transfer(sample_scalar(p)); }

#endif
