#version 460
#extension GL_GOOGLE_include_directive : require
// Light volume propagation (selective light updates, section 4), one dispatch
// per slice of one propagation group: every invocation owns one texel of the
// slice, i.e. one voxel of the illumination volume, and handles every light of
// the group (so the read-modify-write of the illumination voxel is race free).
// Per light it takes the transmittance arriving at the previous slice along the
// light's direction, attenuates it by the medium between the two slices, writes
// it to its slice buffer and adds factor * light into the illumination volume
// (a negative factor subtracts a light's old state: selective updates).
// Compiled twice by build.rs (PARITY 0 reads slice side a and writes b, 1 the
// opposite), each variant referencing only its sides, so synchronization
// validation sees what a slice really reads and writes.

layout(local_size_x = 8, local_size_y = 8) in;

// Compensated (two-float) sums: the illumination volume is hi + lo, so a
// subtraction cancels the earlier addition of the same contribution to about
// u^2 of the running sum instead of u (selective updates do not drift).
layout(constant_id = 0) const bool COMPENSATED = true;

#include "volume.glsl"
#include "lights.glsl"

// One light of the group: which light, its contribution factor (equations 5a
// and 5b) and its layer of the slice buffers.
struct GroupEntry {
    uint light;
    float factor;
    uint slot;
    uint pad;
};
layout(std430, set = 0, binding = 4) readonly buffer GroupEntries { GroupEntry entries[]; };

// Slice buffers: x, y = texel of the slice, z = slot of the light in its group;
// rgb = light arriving at the voxel centre, a = its transmittance.
// Each binding has one name in both builds (the Rust side binds by name).
#if PARITY == 0
layout(set = 0, binding = 5, rgba32f) readonly uniform image3D slice_a_read;
layout(set = 0, binding = 8, rgba32f) writeonly uniform image3D slice_b_write;
#define slice_in slice_a_read
#define slice_out slice_b_write
#else
layout(set = 0, binding = 6, rgba32f) readonly uniform image3D slice_b_read;
layout(set = 0, binding = 7, rgba32f) writeonly uniform image3D slice_a_write;
#define slice_in slice_b_read
#define slice_out slice_a_write
#endif
layout(set = 0, binding = 9, rgba32f) uniform image3D illumination;
// Low words of the compensated sums (a one-voxel placeholder when not compensated).
layout(set = 0, binding = 10, rgba32f) uniform image3D illumination_low;

layout(push_constant) uniform Pass {
    int axis;         // propagation axis
    int travel;       // direction the light travels along it (+1/-1)
    int slice;        // slice index k
    int entry_count;  // lights of the group
    ivec3 grid;       // illumination volume size
    int first_entry;  // the group's first entry in entries[]
} pass;

// Sub-steps of the medium integration between two slices, in data voxels: fine
// enough for transfer functions whose opaque band is narrow (a single midpoint
// per voxel lands between voxel centres and steps over thin shells). At most
// MAX_SUBSTEPS per slice (scale 4 straight along the axis needs 16; grazing
// paths take longer sub-steps), far below llvmpipe's loop limit.
// The sub-step length in data voxels: `lightvolume.substep` illumination voxels.
layout(constant_id = 1) const float SUBSTEP_VOXELS = 0.25;
// Shared medium (`lightvolume.shared_medium`, the paper's propagation): the
// medium between two slices is integrated once per voxel, along the axis, and
// every light of the pass scales that optical depth by its own path length
// (1/c), so per light only the previous slice's lookup and an exp remain.
// Otherwise each light integrates along its own direction (more accurate for
// oblique light through thin structures, and as costly per light as a pass).
layout(constant_id = 2) const bool SHARED_MEDIUM = false;
const int MAX_SUBSTEPS = 64;
// Lights whose travel direction is this close to perpendicular to the axis (a
// cosine, not a transmittance) do not propagate along it: 1/c would blow up.
const float MIN_AXIS_COSINE = 1e-4;

vec3 voxel_centre(ivec3 g) {
    return ((vec3(g) + 0.5) / vec3(pass.grid) * 2.0 - 1.0) * frame.box_half;
}

// Optical depth (sigma per voxel times voxels) of `len` world units from p along dir.
float optical_depth(vec3 p, vec3 dir, float len) {
    if (len <= 0.0) return 0.0;
    float vl = frame.voxel_length;
    int n = int(clamp(ceil(len / (SUBSTEP_VOXELS * vl)), 1.0, float(MAX_SUBSTEPS)));
    float g = len / float(n);
    float tau = 0.0;
    for (int j = 0; j < n; ++j) tau += medium(p + dir * ((float(j) + 0.5) * g)).a;
    return tau * g / vl;
}

// Transmittance stored in the previous slice at lateral texel position c
// (continuous, texel centres at i + 0.5; callers only ask for points inside the
// volume), bilinear between texel centres. Between the outermost texel centre
// and a face the light enters through (`enters`: per lateral axis, -1 low face,
// +1 high face, 0 neither) it blends toward 1, the transmittance at that face;
// elsewhere it clamps to the edge.
float previous_transmittance(vec2 c, ivec2 size, int slot, ivec2 enters) {
    vec2 cc = clamp(c, vec2(0.5), vec2(size) - 0.5);
    vec2 t = cc - 0.5;
    ivec2 i0 = ivec2(floor(t));
    vec2 f = t - vec2(i0);
    float v[4];
    for (int k = 0; k < 4; ++k) {
        ivec2 i = min(i0 + ivec2(k & 1, k >> 1), size - 1);
        v[k] = imageLoad(slice_in, ivec3(i, slot)).a;
    }
    float T = mix(mix(v[0], v[1], f.x), mix(v[2], v[3], f.x), f.y);
    // How far past the outermost texel centre, in half texels, toward an entry face.
    vec2 excess = (c - cc) * vec2(enters) * 2.0;
    return mix(T, 1.0, clamp(max(excess.x, excess.y), 0.0, 1.0));
}

// (s, e) with s + e == a + b exactly (TwoSum; `precise` keeps the compiler
// from reassociating the error terms away).
void two_sum(vec3 a, vec3 b, out vec3 s, out vec3 e) {
    precise vec3 sum = a + b;
    precise vec3 bv = sum - a;
    precise vec3 err = (a - (sum - bv)) + (b - bv);
    s = sum;
    e = err;
}

// hi + lo += x, renormalised so that hi is the rounded sum.
void compensated_add(inout vec3 hi, inout vec3 lo, vec3 x) {
    vec3 s, e, h, l;
    two_sum(hi, x, s, e);
    precise vec3 low = lo + e;
    two_sum(s, low, h, l);
    hi = h;
    lo = l;
}

void main() {
    int a = pass.axis;
    int u = (a + 1) % 3;
    int v = (a + 2) % 3;
    ivec2 size = ivec2(pass.grid[u], pass.grid[v]);
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (t.x >= size.x || t.y >= size.y) return;
    int k = pass.slice;
    float travel = float(pass.travel);
    ivec3 g;
    g[a] = pass.travel > 0 ? k : pass.grid[a] - 1 - k;
    g[u] = t.x;
    g[v] = t.y;
    vec3 p = voxel_centre(g);
    // Distance between slice centres along the axis, world units.
    float dstep = 2.0 * frame.box_half[a] / float(pass.grid[a]);
    // The first slice takes the light at the volume face, half a slice away.
    float segment = (k == 0 ? 0.5 : 1.0) * dstep;
    vec3 back_along_axis = vec3(0.0);
    back_along_axis[a] = -travel;
    float axis_depth = SHARED_MEDIUM ? optical_depth(p, back_along_axis, segment) : 0.0;
    vec4 hi = imageLoad(illumination, g);
    vec3 lo = COMPENSATED ? imageLoad(illumination_low, g).rgb : vec3(0.0);
    for (int e = 0; e < pass.entry_count; ++e) {
        GroupEntry entry = entries[pass.first_entry + e];
        Light l = lights[entry.light];
        vec4 w = toward_light(l, p);
        // Cosine between the light's travel direction and the propagation axis.
        float c = -w[a] * travel;
        vec4 result = vec4(0.0);
        // Light travelling against this group's direction (possible for the
        // second group of a point light) cannot arrive from the previous slice.
        if (c > MIN_AXIS_COSINE) {
            float along = segment / c;
            // Where the light enters the volume (through any face) or leaves the
            // light itself before the previous slice, nothing attenuates it
            // beyond: the path ends there with transmittance 1.
            float reach = min(intersect_box(p, w.xyz).y, w.w);
            float len = min(along, reach);
            float T = 1.0;
            if (k > 0 && along < reach) {
                vec3 q = p + w.xyz * along;
                vec2 cq = vec2((q[u] / (2.0 * frame.box_half[u]) + 0.5) * float(size.x),
                               (q[v] / (2.0 * frame.box_half[v]) + 0.5) * float(size.y));
                // The light enters through a lateral face where it travels inward:
                // toward the light (w) points out of the face.
                ivec2 enters = ivec2(w[u] > 0.0 ? 1 : (w[u] < 0.0 ? -1 : 0), w[v] > 0.0 ? 1 : (w[v] < 0.0 ? -1 : 0));
                T = previous_transmittance(cq, size, int(entry.slot), enters);
            }
            T *= exp(-(SHARED_MEDIUM ? axis_depth * (len / segment) : optical_depth(p, w.xyz, len)));
            vec3 light = l.radiance.rgb * light_shape(l, w) * T;
            result = vec4(light, T);
            // Each entry on its own: a contribution's value does not depend on
            // which other lights share the pass.
            vec3 x = entry.factor * light;
            if (COMPENSATED) {
                compensated_add(hi.rgb, lo, x);
            } else {
                hi.rgb += x;
            }
        }
        imageStore(slice_out, ivec3(t, int(entry.slot)), result);
    }
    imageStore(illumination, g, vec4(hi.rgb, 1.0));
    if (COMPENSATED) imageStore(illumination_low, g, vec4(lo, 0.0));
}
