#version 460
#extension GL_GOOGLE_include_directive : require
// The transfer function at each histogram bin, once per TF change, for the
// environment pass (ao_env.comp) to weight every cluster's histogram with:
// weights[j] = (tau_alpha tau_rgb, tau_alpha) at bin j's centre intensity
// (docs/ao.md, "Bins"); tau_alpha is the opacity of one voxel of optical depth
// sigma. One invocation per bin.

layout(local_size_x = 64) in;

#include "transfer_lut.glsl"

layout(std430, set = 0, binding = 0) writeonly buffer BinWeights { vec4 weights[]; };

layout(push_constant) uniform BinParams {
    uint bins;
    float lut_size;
} p;

void main() {
    uint j = gl_GlobalInvocationID.x;
    if (j >= p.bins) return;
    vec4 t = transfer_lut((float(j) + 0.5) / float(p.bins), p.lut_size);
    float a = 1.0 - exp(-t.a);
    weights[j] = vec4(a * t.rgb, a);
}
