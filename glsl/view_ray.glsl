// The view ray's march, shared by every ray caster: the ray's extent inside the
// volume box and its samples, equally spaced at most `step_voxels` voxels
// apart, one per step at the same phase within each (the midpoint, 0.5, or
// with render.jitter a per-pixel hash in [0, 1), so that sample planes do not
// beat against surfaces as rings; docs/optical-model.md; src/reference/cpu.rs
// marches the same way), and the transmittance at which a view ray stops.
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
    float phase;    // sample i lies at t_enter + (i + phase) * h
};

// lowbias32 (Wellons): an integer hash whose bits are all well mixed; the CPU
// reference computes the same one (src/reference/ray_start.rs).
uint ray_start_hash(uvec2 px) {
    uint h = px.x * 0x8da6b343u ^ px.y * 0xd8163841u;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h;
}

// Where in its step pixel px's samples lie: 24 bits of the hash, exact in f32
// and f64 alike, so the CPU and GPU references sample the same points.
float ray_start_phase(uvec2 px) {
    return frame.jitter != 0u ? float(ray_start_hash(px) >> 8u) * (1.0 / 16777216.0) : 0.5;
}

ViewMarch view_march_at_phase(Ray r, float step_voxels, float phase) {
    vec2 t = intersect_box(r.origin, r.dir);
    ViewMarch m = ViewMarch(r, t.x, t.y, 0.0, 0.0, 0, phase);
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

// Midpoint samples: for marches that are not one pixel's view ray.
ViewMarch view_march(Ray r, float step_voxels) { return view_march_at_phase(r, step_voxels, 0.5); }

// Pixel px's view ray, its samples at the pixel's phase.
ViewMarch pixel_march(uvec2 px, float step_voxels) {
    return view_march_at_phase(camera_ray(px), step_voxels, ray_start_phase(px));
}

// Distance along the ray of sample i, at the march's phase within its step.
float sample_t(ViewMarch m, int i) { return m.t_enter + (float(i) + m.phase) * m.h; }

vec3 sample_point(ViewMarch m, int i) { return m.ray.origin + m.ray.dir * sample_t(m, i); }

// Nothing behind this point of the ray shows.
bool view_ray_opaque(float transmittance) { return transmittance < EARLY_TERMINATION_TRANSMITTANCE; }

#endif
