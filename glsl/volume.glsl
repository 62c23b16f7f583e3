// The volume (binding 1, volume_fetch.glsl) and the baked transfer LUT (binding 2,
// transfer_lut.glsl): rgb + sigma (optical depth per voxel), interpolated
// exactly like TransferLut::sample on the CPU.
#ifndef VOLUME_GLSL
#define VOLUME_GLSL
#include "frame.glsl"
#include "transfer_lut.glsl"
#include "volume_fetch.glsl"

float sample_scalar(vec3 p) { return volume_at_uvw(to_uvw(p)); }

vec4 transfer(float s) { return transfer_lut(s, frame.lut_size); }

// (rgb, sigma) of the medium at world position p.
vec4 medium(vec3 p) { return transfer(sample_scalar(p)); }

#endif
