#version 460
#extension GL_GOOGLE_include_directive : require
// AO space sweep, step 2 of a batch, one dispatch per part: the local
// histograms (equations 2-3) of the voxels of one part of a centre slice, for
// one chunk of the stencil
// (llvmpipe ends an invocation after 65,535 loop iterations; r = 16 fits in
// one chunk, r = 32 takes three). Reads the binned slices; adds each
// stencil voxel's 1/d^2 weight to its bin in the forward or backward
// hemisphere (half to each on the plane) of the unpacked, not yet normalized
// histograms (cleared by a buffer fill before the batch). Neighbours come in runs of equal bins (stencil rows are rows of
// voxels), summed in registers and added to memory when the bin changes.

layout(local_size_x = 8, local_size_y = 8) in;

#include "ao_histogram_common.glsl"

layout(std430, set = 0, binding = 0) readonly buffer Values { float values[]; };
layout(std430, set = 0, binding = 1) readonly buffer Binned { uint binned[]; };
// Per stencil entry: the offset in units of d_min (xyz) and the weight 1/d^2 (w)...
layout(std430, set = 0, binding = 2) readonly buffer StencilDirections { vec4 stencil_directions[]; };
// ...and its linear offset in the binned slices, from the window's first slot.
layout(std430, set = 0, binding = 3) readonly buffer StencilOffsets { int stencil_offsets[]; };
// The part's window of the batch's unpacked histograms (a batch can exceed
// maxStorageBufferRange; a part cannot): from its first float, unpacked_first.
layout(std430, set = 1, binding = 0) buffer Unpacked { float unpacked[]; };

float value_at(ivec3 p) {
    return values[(p.z * DIMS.y + p.y) * DIMS.x + p.x];
}

// Central differences with clamped neighbours, in the CPU's operation order
// (src/techniques/ao/gradient.rs): the hemisphere test must agree exactly on the plane.
// Only a subtraction and a product by the host's per-axis scale: both are
// correctly rounded on every Vulkan device (a division is not: 2.5 ulp).
vec3 central_gradient(ivec3 p) {
    precise vec3 g;
    for (int axis = 0; axis < 3; ++axis) {
        ivec3 lo = p, hi = p;
        lo[axis] = max(p[axis] - 1, 0);
        hi[axis] = min(p[axis] + 1, DIMS[axis] - 1);
        precise float difference = value_at(hi) - value_at(lo);
        g[axis] = difference * GRADIENT_SCALE[axis];
    }
    return g;
}

void main() {
    int x = int(gl_GlobalInvocationID.x), row = int(gl_GlobalInvocationID.y);
    if (x >= DIMS.x || row >= sweep.rows) return;
    int y = sweep.first_row + row, z = sweep.slice;
    int forward = sweep.unpacked_first + (row * DIMS.x + x) * unpacked_stride();
    int backward = forward + BINS + 1;
    vec3 g = central_gradient(ivec3(x, y, z));
    // The window's first slice z - e_z.
    int base = binned_index(z - EXTENT.z - sweep.first_binned, x, y);
    int run_bin = BINS;  // the discard slot: flushing the empty run is harmless
    float run_forward = 0.0, run_backward = 0.0;
    int end = sweep.first_entry + sweep.entry_count;
    for (int i = sweep.first_entry; i < end; ++i) {
        int k = int(binned[base + stencil_offsets[i]]);
        if (k != run_bin) {
            unpacked[forward + run_bin] += run_forward;
            unpacked[backward + run_bin] += run_backward;
            run_bin = k;
            run_forward = 0.0;
            run_backward = 0.0;
        }
        vec4 o = stencil_directions[i];
        precise float side = g.x * o.x + g.y * o.y + g.z * o.z;
        // Forward: the side the shading normal -g points into; on the plane
        // (and everywhere for a zero gradient) half to each.
        run_forward += side < 0.0 ? o.w : (side > 0.0 ? 0.0 : 0.5 * o.w);
        run_backward += side > 0.0 ? o.w : (side < 0.0 ? 0.0 : 0.5 * o.w);
    }
    unpacked[forward + run_bin] += run_forward;
    unpacked[backward + run_bin] += run_backward;
}
