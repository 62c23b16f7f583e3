#version 460
#extension GL_GOOGLE_include_directive : require
// Environment colour and occlusion of every codebook cluster (equations 4-5 of
// the 2008 paper), recomputed whenever the transfer function changes: each bin
// of the cluster's mean histogram weighted by the TF at that bin
// (ao_env_bins.comp, dispatched just before). One invocation per cluster; its
// loop runs over the 2^b <= 4096 bins, below llvmpipe's 65,535-iteration cap.
// Written: env[c] = (E_env rgb, O_env); with GLOW, also env[clusters + c] =
// (glow colour, glow intensity): the sums of equations 4-5 over the glowing
// intensities only, the normalized (h(j) - 1) / (h_max - 1) of the band
// mapping h (1 in the band, 0 outside). The renderer adds (h_max - 1) times
// the glow colour to E_env: equation 4 with each summand weighted by h(j).
// Normalization: by the stencil's full-hemisphere mass, so that O_env = 1 for a
// fully occupied opaque hemisphere (docs/ao.md).

layout(local_size_x = 64) in;
layout(constant_id = 0) const uint GLOW = 0;

layout(std430, set = 0, binding = 0) readonly buffer Codebook { float codebook[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Environment { vec4 env[]; };
layout(std430, set = 0, binding = 2) readonly buffer BinWeights { vec4 weights[]; };

layout(push_constant) uniform EnvParams {
    uint clusters;
    uint bins;
    float inv_mass;    // 1 / full-hemisphere mass of the stencil
    float glow_low;    // intensities in [glow_low, glow_high] glow
    float glow_high;
    uint pad0;
    uint pad1;
    uint pad2;
} p;

void main() {
    uint c = gl_GlobalInvocationID.x;
    if (c >= p.clusters) return;
    vec4 e = vec4(0.0);
    vec4 glow = vec4(0.0);
    for (uint j = 0; j < p.bins; ++j) {
        vec4 w = codebook[c * p.bins + j] * weights[j];
        e += w;
        if (GLOW != 0) {
            float s = (float(j) + 0.5) / float(p.bins);
            if (s >= p.glow_low && s <= p.glow_high) glow += w;
        }
    }
    env[c] = e * p.inv_mass;
    if (GLOW != 0) env[p.clusters + c] = glow * p.inv_mass;
}
