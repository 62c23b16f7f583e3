// Cells of the volume where every sample has extinction exactly 0
// (src/render/empty_cells.rs, binding 6): a sample there adds exactly
// nothing to a march toward a light, so the ground truth's shadow rays step
// over the cell and give the brute-force march's sums bit for bit.
#ifndef EMPTY_CELLS_GLSL
#define EMPTY_CELLS_GLSL
#include "volume.glsl"

// xyz: cells per axis; w: voxels per cell side. Then 1 per occupied cell, x fastest.
layout(std430, set = 0, binding = 6) readonly buffer EmptyCells {
    uvec4 empty_cells_grid;
    uint cell_occupied[];
};

// What a march along `dir` needs to find cells: computed once per march.
struct CellWalk {
    vec3 dims;  // voxels per axis
    vec3 du;    // voxels per world unit along dir
    float side;
    ivec3 grid;
};

CellWalk cell_walk(vec3 dir) {
    vec3 dims = vec3(textureSize(volume_tex, 0));
    return CellWalk(dims, dir * dims / (2.0 * frame.box_half), float(empty_cells_grid.w), ivec3(empty_cells_grid.xyz));
}

// The march x + dir * ((i + 0.5) * g) at sample j, midpoint q: whether the cell
// holding q is empty, and the first later sample that may lie past that cell's
// exit face. The cells' emptiness covers a voxel beyond each face, far more
// than the rounding between this estimate and the march's own positions.
int cell_exit(CellWalk w, vec3 q, float g, int j, out bool empty) {
    vec3 u = to_uvw(q) * w.dims;
    ivec3 c = clamp(ivec3(floor(u / w.side)), ivec3(0), w.grid - 1);
    empty = cell_occupied[(c.z * w.grid.y + c.y) * w.grid.x + c.x] == 0u;
    vec3 lo = vec3(c) * w.side;
    float t = 3.0e38;
    for (int a = 0; a < 3; ++a) {
        if (w.du[a] > 0.0) t = min(t, (lo[a] + w.side - u[a]) / w.du[a]);
        if (w.du[a] < 0.0) t = min(t, (lo[a] - u[a]) / w.du[a]);
    }
    return j + 1 + int(floor(max(t, 0.0) / g));
}

#endif
