#version 460
#extension GL_GOOGLE_include_directive : require
// AO space sweep, step 1 of a batch: bins every slice the batch's stencils
// read (one per invocation z; the rows its parts' stencils read) into its slot
// of the binned slices, with the
// "outside" bin in the padding and for slices outside the volume. Each voxel
// is binned once per batch instead of once per stencil voxel that reads it.

layout(local_size_x = 8, local_size_y = 8) in;

#include "ao_histogram_common.glsl"

// Normalized intensity of every voxel (x fastest), as the CPU reads it.
layout(std430, set = 0, binding = 0) readonly buffer Values { float values[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Binned { uint binned[]; };

void main() {
    // Padded row first_row is row first_row - e_y: the batch's rows and e_y
    // more on each side.
    int px = int(gl_GlobalInvocationID.x), py = int(gl_GlobalInvocationID.y) + sweep.first_row;
    if (px >= padded_width() || py >= min(padded_height(), sweep.first_row + sweep.rows + 2 * EXTENT.y)) return;
    int x = px - EXTENT.x, y = py - EXTENT.y, z = sweep.slice + int(gl_GlobalInvocationID.z);
    uint bin = uint(BINS);
    if (x >= 0 && y >= 0 && z >= 0 && x < DIMS.x && y < DIMS.y && z < DIMS.z) {
        float s = clamp(values[(z * DIMS.y + y) * DIMS.x + x], 0.0, 1.0);
        // k = min(floor(s 2^b), 2^b - 1): exact, 2^b is a power of two.
        bin = min(uint(floor(s * float(BINS))), uint(BINS - 1));
    }
    binned[binned_index(z - sweep.first_binned, x, y)] = bin;
}
