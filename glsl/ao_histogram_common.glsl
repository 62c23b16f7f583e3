// Shared by the AO local-histogram sweep (docs/ao.md, "GPU space sweep"):
// the sweep's push constants and the addressing of the ring of binned slices.
//
// The ring holds the intensity bins of the 2 e_z + 1 slices the centre slice's
// stencil reads, padded by the stencil extent in x and y with the "outside"
// bin (= bins), so the stencil loop has no bounds checks. It is doubled: slice
// s (-e_z <= s < n_z + e_z) lives at slots (s + e_z) mod R and that + R
// (R = 2 e_z + 1), so the window z - e_z .. z + e_z is R consecutive slots
// from z mod R and every stencil entry is one constant linear offset.

layout(push_constant) uniform Sweep {
    vec3 gradient_scale; // 0.5 d_min / spacing per axis, rounded once on the host (src/ao/gradient.rs)
    float pad_scale;
    ivec3 dims;          // volume size
    int bins;            // 2^b; bin `bins` is "outside the volume"
    ivec3 extent;        // stencil extent e per axis
    int ring_slices;     // R = 2 e_z + 1
    int slice;           // centre slice z (bin pass: the entering slice)
    int first_row;       // first row y of this part of the slice
    int rows;            // rows in this part
    int first_entry;     // stencil chunk: entries [first_entry, first_entry + entry_count)
    int entry_count;
    int part_voxel;      // first voxel of this part in the batch's buffers
    int packed_stride;   // floats per packed histogram (packed_dim rounded up to 8)
    int pad;
} sweep;

int padded_width() { return sweep.dims.x + 2 * sweep.extent.x; }
int padded_height() { return sweep.dims.y + 2 * sweep.extent.y; }

// Ring index of padded texel (x, y) (-e <= x < n + e) of ring slot `slot`.
int ring_index(int slot, int x, int y) {
    return (slot * padded_height() + y + sweep.extent.y) * padded_width() + x + sweep.extent.x;
}

// Floats per voxel in the unpacked buffer: forward bins, a discard slot, the
// backward bins, a discard slot (the "outside" bin lands in the discard slot).
int unpacked_stride() { return 2 * (sweep.bins + 1); }
