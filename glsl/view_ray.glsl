// The view ray's march, shared by every ray caster: the ray's extent inside the
// volume box and its midpoint samples, equally spaced at most `step_voxels`
// voxels apart (docs/optical-model.md; src/reference/cpu.rs marches the same
// way), and the transmittance at which a view ray stops.
#ifndef VIEW_RAY_GLSL
#define VIEW_RAY_GLSL
#include "frame.glsl"

// Defined by build.rs from src/reference/early_termination.rs, the constant the
// CPU renderers stop at.
#ifndef EARLY_TERMINATION_TRANSMITTANCE
#error "build.rs defines EARLY_TERMINATION_TRANSMITTANCE"
#endif

struct ViewMarch {
    Ray ray;
    float t_enter;  // box entry and exit along the ray (t_enter >= t_exit: a miss)
    float t_exit;
    float h;        // sample spacing, world units
    float hv;       // sample spacing, voxels: a sample's optical depth is sigma * hv
    int samples;    // 0 on a miss
};

ViewMarch view_march(Ray r, float step_voxels) {
    vec2 t = intersect_box(r.origin, r.dir);
    ViewMarch m = ViewMarch(r, t.x, t.y, 0.0, 0.0, 0);
    if (t.x < t.y) {
        float vl = frame.voxel_length;
        float L = t.y - t.x;
        float N = max(1.0, ceil(L / (step_voxels * vl)));
        m.h = L / N;
        m.hv = m.h / vl;
        m.samples = int(N);
    }
    return m;
}

// Distance along the ray of sample i, the midpoint of its step.
float sample_t(ViewMarch m, int i) { return m.t_enter + (float(i) + 0.5) * m.h; }

vec3 sample_point(ViewMarch m, int i) { return m.ray.origin + m.ray.dir * sample_t(m, i); }

// Nothing behind this point of the ray shows.
bool view_ray_opaque(float transmittance) { return transmittance < EARLY_TERMINATION_TRANSMITTANCE; }

#endif
