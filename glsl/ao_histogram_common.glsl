// Shared by the AO local-histogram sweep (docs/ao.md, "GPU space sweep"):
// the sweep's push constants and the addressing of the binned slices.
//
// The binned slices hold the intensity bins of every slice a batch's stencils
// read (its centre slices and e_z more on each side), padded by the stencil
// extent in x and y with the "outside" bin (= bins), so the stencil loop has
// no bounds checks. Slice s (-e_z <= s < n_z + e_z) lives at slot
// s - first_binned, so the window z - e_z .. z + e_z is 2 e_z + 1 consecutive
// slots and every stencil entry is one constant linear offset.

// What stays the same for a whole sweep is specialized (constant_id 0 is
// the pack pass's own), so the push constants stay within AMD's recommended
// layout size.
layout(constant_id = 1) const float GRADIENT_SCALE_X = 0.0;  // 0.5 d_min / spacing per axis,
layout(constant_id = 2) const float GRADIENT_SCALE_Y = 0.0;  // rounded once on the host
layout(constant_id = 3) const float GRADIENT_SCALE_Z = 0.0;  // (src/techniques/ao/gradient.rs)
layout(constant_id = 4) const int DIMS_X = 1;                // volume size
layout(constant_id = 5) const int DIMS_Y = 1;
layout(constant_id = 6) const int DIMS_Z = 1;
layout(constant_id = 7) const int BINS = 2;                  // 2^b; bin BINS is "outside the volume"
layout(constant_id = 8) const int EXTENT_X = 0;              // stencil extent e per axis
layout(constant_id = 9) const int EXTENT_Y = 0;
layout(constant_id = 10) const int EXTENT_Z = 0;
layout(constant_id = 11) const int PACKED_STRIDE = 8;        // floats per packed histogram (packed_dim rounded up to 8)
const vec3 GRADIENT_SCALE = vec3(GRADIENT_SCALE_X, GRADIENT_SCALE_Y, GRADIENT_SCALE_Z);
const ivec3 DIMS = ivec3(DIMS_X, DIMS_Y, DIMS_Z);
const ivec3 EXTENT = ivec3(EXTENT_X, EXTENT_Y, EXTENT_Z);

layout(push_constant) uniform Sweep {
    int first_binned;    // the slice at slot 0 of the binned slices
    int slice;           // centre slice z (bin pass: the first slice it bins)
    int first_row;       // first row y of this part of the slice (bin pass: of the batch)
    int rows;            // rows in this part (bin pass: in the batch)
    int first_entry;     // stencil chunk: entries [first_entry, first_entry + entry_count)
    int entry_count;
    int part_voxel;      // first voxel of this part in the batch's buffers
    int unpacked_first;  // its first float in the unpacked histograms' window (set 1)
} sweep;

int padded_width() { return DIMS.x + 2 * EXTENT.x; }
int padded_height() { return DIMS.y + 2 * EXTENT.y; }

// Index of padded texel (x, y) (-e <= x < n + e) of binned slot `slot`.
int binned_index(int slot, int x, int y) {
    return (slot * padded_height() + y + EXTENT.y) * padded_width() + x + EXTENT.x;
}

// Floats per voxel in the unpacked buffer: forward bins, a discard slot, the
// backward bins, a discard slot (the "outside" bin lands in the discard slot).
int unpacked_stride() { return 2 * (BINS + 1); }
