// Where a view ray stops under early ray termination: the rule the serial
// line kernel applies as it marches, and the view-stops pass
// (glsl/ipsvi_view_stops.comp) applies ahead of the segmented one. The
// including file declares TERMINATION (specialization constant 7) and
// includes view_ray.glsl.
#ifndef IPSVI_VIEW_STOP_GLSL
#define IPSVI_VIEW_STOP_GLSL

const uint TERMINATION_OFF = 0u;
const uint TERMINATION_PLAIN = 1u;
const uint TERMINATION_EXIT_POINTS = 2u;

// l_max of the exit-point sweep (section 5.1), at the pre-pass resolution; a 1x1
// placeholder when that mode is off.
layout(set = 0, binding = 16, r32f) readonly uniform image2D lmax;

#include "ipsvi_optical_depth.glsl"

bool may_stop() { return TERMINATION != TERMINATION_OFF; }

// Where the exit-point sweep lets pixel px's ray stop (0: wherever it is
// opaque), `ert_scale` full-resolution pixels per pre-pass pixel.
float exit_point_distance(uvec2 px, float ert_scale) {
    return TERMINATION == TERMINATION_EXIT_POINTS ? imageLoad(lmax, ivec2(vec2(px) / ert_scale)).r : 0.0;
}

// Whether the ray stops after sample i, with `tau` the optical depth up to
// and including it: opaque, and (exit points) past where the sweep needs it.
// Monotone in i and tau, so a ray split in segments finds its stop from each
// segment's optical depth and the sums before it.
bool ray_stops(uint tau, ViewMarch v, int i, float keep_going) {
    return may_stop() && tau >= TAU_STOP && v.t_enter + (float(i) + 1.0) * v.h >= keep_going;
}

#endif
