// Shared by the AO local-histogram sweep (docs/ao.md, "GPU space sweep"):
// the sweep's push constants and the addressing of the binned slices.
//
// The binned slices hold the intensity bins of every slice a batch's stencils
// read (its centre slices and e_z more on each side), padded by the stencil
// extent in x and y with the "outside" bin (= bins), so the stencil loop has
// no bounds checks. Slice s (-e_z <= s < n_z + e_z) lives at slot
// s - first_binned, so the window z - e_z .. z + e_z is 2 e_z + 1 consecutive
// slots and every stencil entry is one constant linear offset.

layout(push_constant) uniform Sweep {
    vec3 gradient_scale; // 0.5 d_min / spacing per axis, rounded once on the host (src/ao/gradient.rs)
    float pad_scale;
    ivec3 dims;          // volume size
    int bins;            // 2^b; bin `bins` is "outside the volume"
    ivec3 extent;        // stencil extent e per axis
    int first_binned;    // the slice at slot 0 of the binned slices
    int slice;           // centre slice z (bin pass: the first slice it bins)
    int first_row;       // first row y of this part of the slice (bin pass: of the batch)
    int rows;            // rows in this part (bin pass: in the batch)
    int first_entry;     // stencil chunk: entries [first_entry, first_entry + entry_count)
    int entry_count;
    int part_voxel;      // first voxel of this part in the batch's buffers
    int packed_stride;   // floats per packed histogram (packed_dim rounded up to 8)
    int pad;
} sweep;

int padded_width() { return sweep.dims.x + 2 * sweep.extent.x; }
int padded_height() { return sweep.dims.y + 2 * sweep.extent.y; }

// Index of padded texel (x, y) (-e <= x < n + e) of binned slot `slot`.
int binned_index(int slot, int x, int y) {
    return (slot * padded_height() + y + sweep.extent.y) * padded_width() + x + sweep.extent.x;
}

// Floats per voxel in the unpacked buffer: forward bins, a discard slot, the
// backward bins, a discard slot (the "outside" bin lands in the discard slot).
int unpacked_stride() { return 2 * (sweep.bins + 1); }
