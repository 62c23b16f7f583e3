// Integration along a path toward a light, shared by the ground truth's shadow
// rays and IPSVI's cache updates and piecewise integration (docs/optical-model.md).
#ifndef LIGHT_PATH_GLSL
#define LIGHT_PATH_GLSL
#include "volume.glsl"

// Midpoint rule over `len` world units from x along `dir`, in steps of
// frame.shadow_step voxels, at most `max_steps` of them (longer steps beyond that).
// A shader that defines LIGHT_PATH_SKIPS_EMPTY_CELLS (and includes
// empty_cells.glsl first) steps over empty cells: the same sums.
// Returns (sum of T_before * alpha * rgb over the samples, optical depth): the
// medium's emission arriving at x is rgb * emission scale. The march is
// integrate_light_path; its parts are integrate_light_path_part.

// Steps of the march over `len`: at least one, at most max_steps.
int light_path_steps(float len, float max_steps) {
    return int(clamp(ceil(len / (frame.shadow_step * frame.voxel_length)), 1.0, max_steps));
}

// Steps [first, last) of the march over `len` in m steps (the same samples as
// the whole march): (sum over them of T_before * alpha * rgb, T_before from
// step `first` on; their optical depth). Consecutive parts of one march
// combine in order as stretches of samples do (the over operator).
vec4 integrate_light_path_part(vec3 x, vec3 dir, float len, int m, int first, int last, bool gather_emission) {
    float vl = frame.voxel_length;
    float g = len / float(m);
    float gv = g / vl;
    float tau = 0.0;
    vec3 E = vec3(0.0);
#ifdef LIGHT_PATH_SKIPS_EMPTY_CELLS
    // empty_cells.glsl: a cell is looked up once per crossing; the samples in
    // an empty one are skipped (each would add exactly 0).
    CellWalk walk = cell_walk(dir);
    int cell_end = 0;
#endif
    for (int j = first; j < last; ++j) {
        vec3 q = x + dir * ((float(j) + 0.5) * g);
#ifdef LIGHT_PATH_SKIPS_EMPTY_CELLS
        if (j >= cell_end) {
            bool empty;
            cell_end = cell_exit(walk, q, g, j, empty);
            if (empty) {
                j = cell_end - 1;
                continue;
            }
        }
#endif
        vec4 med = medium(q);
        if (gather_emission) E += exp(-tau) * (1.0 - exp(-med.a * gv)) * med.rgb;
        tau += med.a * gv;
    }
    return vec4(E, tau);
}

vec4 integrate_light_path(vec3 x, vec3 dir, float len, float max_steps, bool gather_emission) {
    if (len <= 0.0) return vec4(0.0);
    int m = light_path_steps(len, max_steps);
    return integrate_light_path_part(x, dir, len, m, 0, m, gather_emission);
}

#endif
