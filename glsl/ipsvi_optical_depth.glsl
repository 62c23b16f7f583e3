// IPSVI line kernels: the optical depth early ray termination decides on. No
// bindings (glsl/ipsvi_segment_scan_probe.comp tests its sums).
#ifndef IPSVI_OPTICAL_DEPTH_GLSL
#define IPSVI_OPTICAL_DEPTH_GLSL

// Early ray termination decides on the optical depth marched so far, summed in
// fixed point: integer sums do not depend on the order they are added in, so
// a ray marched in segments (glsl/ipsvi_line_segmented.comp) stops at the very
// sample the serial march stops at, and both claim the same texels. A sample
// adds its optical depth sigma * h in units of 2^-16 (at most 64, where it is
// opaque anyway); sums saturate at TAU_CAP, far above the stop.
const float TAU_UNITS = 65536.0;
const uint TAU_CAP = 0x40000000u;
// The transmittance EARLY_TERMINATION_TRANSMITTANCE as an optical depth.
const uint TAU_STOP = uint(ceil(-log(EARLY_TERMINATION_TRANSMITTANCE) * TAU_UNITS));
uint tau_units(float optical_depth) { return uint(min(optical_depth, 64.0) * TAU_UNITS + 0.5); }
uint tau_add(uint a, uint b) { return min(a + b, TAU_CAP); }

#endif
