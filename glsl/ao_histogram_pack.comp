#version 460
#extension GL_GOOGLE_include_directive : require
// AO space sweep, step 3 of a batch, one dispatch per part: normalizes the
// part's unpacked histograms by 1/N_r (in registers: the CPU, reading them back for the final codebook,
// applies the same f32 product) and packs them (section 3.2): packing is
// linear, the packing matrix applied as its sparse rows (bin k -> (packed bin,
// share) pairs), in the CPU's order (PackingScheme::pack), into packed
// histograms zero-padded to a multiple of 8.

layout(local_size_x = 64) in;

#include "ao_histogram_common.glsl"

struct Share {
    uint packed_bin;
    float share;
};

// The part's window of the batch's unpacked histograms, from unpacked_first.
layout(std430, set = 1, binding = 0) readonly buffer Unpacked { float unpacked[]; };
// Row k of the packing matrix: shares[share_starts[k] .. share_starts[k + 1]).
layout(std430, set = 0, binding = 0) readonly buffer ShareStarts { uint share_starts[]; };
layout(std430, set = 0, binding = 1) readonly buffer Shares { Share shares[]; };
layout(std430, set = 0, binding = 2) buffer Packed { float packed[]; };

// 1 / N_r, rounded once from the exact value.
layout(constant_id = 0) const float NORMALIZATION = 1.0;

void main() {
    int part_voxels = sweep.rows * DIMS.x;
    int v = int(gl_GlobalInvocationID.x);
    if (v >= part_voxels) return;
    int voxel = sweep.part_voxel + v;
    for (int side = 0; side < 2; ++side) {
        int histogram = sweep.unpacked_first + v * unpacked_stride() + side * (BINS + 1);
        int out_base = (2 * voxel + side) * PACKED_STRIDE;
        // Built in place (packed_dim is not bounded by a register array).
        for (int j = 0; j < PACKED_STRIDE; ++j) packed[out_base + j] = 0.0;
        for (int k = 0; k < BINS; ++k) {
            precise float h = unpacked[histogram + k] * NORMALIZATION;
            if (h != 0.0) {
                for (uint s = share_starts[k]; s < share_starts[k + 1]; ++s) {
                    precise float add = h * shares[s].share;
                    precise float sum = packed[out_base + int(shares[s].packed_bin)] + add;
                    packed[out_base + int(shares[s].packed_bin)] = sum;
                }
            }
        }
    }
}
