#version 460
#extension GL_GOOGLE_include_directive : require
// AO space sweep, step 1 of a slice: bins the slice entering the stencil's
// window (z + e_z) into both of its slots of the doubled ring, with the
// "outside" bin in the padding and for slices outside the volume. Each voxel
// is binned once here instead of once per stencil voxel that reads it.

layout(local_size_x = 8, local_size_y = 8) in;

#include "ao_histogram_common.glsl"

// Normalized intensity of every voxel (x fastest), as the CPU reads it.
layout(std430, set = 0, binding = 0) readonly buffer Values { float values[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Ring { uint ring[]; };

void main() {
    int px = int(gl_GlobalInvocationID.x), py = int(gl_GlobalInvocationID.y);
    if (px >= padded_width() || py >= padded_height()) return;
    // z: the first slice primes the ring with the whole window (depth 2 e_z + 1).
    int x = px - sweep.extent.x, y = py - sweep.extent.y, z = sweep.slice + int(gl_GlobalInvocationID.z);
    uint bin = uint(sweep.bins);
    if (x >= 0 && y >= 0 && z >= 0 && x < sweep.dims.x && y < sweep.dims.y && z < sweep.dims.z) {
        float s = clamp(values[(z * sweep.dims.y + y) * sweep.dims.x + x], 0.0, 1.0);
        // k = min(floor(s 2^b), 2^b - 1): exact, 2^b is a power of two.
        bin = min(uint(floor(s * float(sweep.bins))), uint(sweep.bins - 1));
    }
    // z >= -e_z, so the slot index is not negative.
    int slot = (z + sweep.extent.z) % sweep.ring_slices;
    ring[ring_index(slot, x, y)] = bin;
    ring[ring_index(slot + sweep.ring_slices, x, y)] = bin;
}
