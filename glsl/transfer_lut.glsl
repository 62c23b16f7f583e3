// The baked transfer LUT (binding 2): rgb + sigma (optical depth per voxel),
// interpolated exactly like TransferLut::sample on the CPU. `lut_size`: its
// texel count.
#ifndef TRANSFER_LUT_GLSL
#define TRANSFER_LUT_GLSL

layout(std430, set = 0, binding = 2) readonly buffer TransferLut { vec4 lut[]; };

vec4 transfer_lut(float s, float lut_size) {
    float n = lut_size;
    float t = clamp(s * n - 0.5, 0.0, n - 1.0);
    int i0 = int(floor(t));
    int i1 = min(i0 + 1, int(n) - 1);
    return mix(lut[i0], lut[i1], t - float(i0));
}

#endif
