#version 460
#extension GL_GOOGLE_include_directive : require
// Light volume propagation (selective light updates, section 4), one dispatch
// per slice of one propagation group: every invocation owns one texel of the
// slice, i.e. one voxel of the illumination volume, and handles every light of
// the group (so the read-modify-write of the illumination voxel is race free).
// Per light it takes the transmittance arriving at the previous slice along the
// light's direction, attenuates it by the medium between the two slices and
// writes it to its slice buffer; the lights' factor * light are summed in
// registers (a two-float sum) and added into the illumination volume once per
// voxel (a negative factor subtracts a light's old state: selective updates).
// The slice buffers ping-pong through a small set 1, {in = a, out = b} or
// {in = b, out = a}, bound per slice (cheap on lavapipe, unlike set 0:
// tools/dispatch_probe.rs); reads and writes are separate bindings, so
// synchronization validation sees what a slice really reads and writes.

layout(local_size_x = 8, local_size_y = 8) in;

// Compensated (two-float) sums: the illumination volume is hi + lo, so a
// subtraction cancels the earlier addition of the same contribution to about
// u^2 of the running sum instead of u (selective updates do not drift).
layout(constant_id = 0) const bool COMPENSATED = true;
// Coloured propagation (`lightvolume.chromatic`, the paper's
// l_i = (1 - alpha) l_{i-1} + alpha c l_{i-1} in the limit of small steps): each
// channel's optical depth is sigma * (1 - rgb), so the medium passes its own
// colour on (docs/optical-model.md, "chromatic"). Off: one transmittance, model (i).
layout(constant_id = 3) const bool CHROMATIC = true;

#include "volume.glsl"
#include "lights.glsl"

// One light of the group: which light, its contribution factor (equations 5a
// and 5b), its layer of the slice buffers, and whether the factor is further
// weighted per voxel by the squared cosine between the light's travel and the
// axis (a light inside the volume: six groups whose weights sum to one).
// A directional light's step is the same at every voxel of a slice, so the
// host computes it once (src/techniques/lightvolume/directional_step.rs) and the shader
// does no per-voxel direction, path length, box exit or lookup position
// arithmetic for it (llvmpipe runs that arithmetic on every voxel).
struct GroupEntry {
    uint light;
    float factor;
    uint slot;
    uint per_voxel;
    // Directional lights: rgb factor * radiance (times cos^2 when per_voxel);
    // w the path length per unit of axis length (1 / cos), 0: not carried.
    vec4 radiance_path;
    // Directional lights: xy how far the previous-slice lookup lies beside the
    // voxel's texel over one slice, in texels (u, v); zw their reciprocals
    // (infinite where zero).
    vec4 lateral_step;
};
// A uniform block, not a storage buffer: llvmpipe loads a uniform block at a
// dynamically uniform index once for all lanes, but a storage buffer inside
// control flow (the loop over the entries) once per lane. Its size bounds the
// entries of one update (propagation.rs, MAX_ENTRIES; 48 KiB, within the 64 KiB
// maxUniformBufferRange of lavapipe and most GPUs).
layout(std140, set = 0, binding = 4) uniform GroupEntries { GroupEntry entries[1024]; };

// Slice buffers: x, y = texel of the slice, z = slot of the light in its group;
// rgb = the light's transmittance to the voxel centre, per channel.
layout(set = 1, binding = 0, rgba32f) readonly uniform image3D slice_in;
layout(set = 1, binding = 1, rgba32f) writeonly uniform image3D slice_out;
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
// Whether a light of the pass can come within NEAR_LIGHT_SLICES of a slice
// (a point or spot light inside or close to the entry face; chosen per pass by
// propagation.rs). Off, the near-light integration is compiled out: llvmpipe
// runs both sides of a divergent branch, and that per-light loop of medium
// samples cost about a fifth of the whole propagation even where no light was
// near. The far lights' arithmetic is the same in both builds (bit-equal
// values: selective updates rely on it, tests/lightvolume_updates.rs).
layout(constant_id = 4) const bool NEAR_LIGHTS = true;
// Whether every light of the pass is directional (chosen per pass by
// propagation.rs): with the shared medium the per-voxel path
// (`step_at_voxel`) is compiled out (llvmpipe runs every branch under a
// mask, so it would cost every light of every voxel) and the lights are not
// read: a directional light's step comes with its entry. Without it, the
// per-voxel direction, falloff and cone are. A directional light's arithmetic
// is the same in every build (bit-equal).
layout(constant_id = 5) const bool DIRECTIONAL_ONLY = false;
// Lights whose travel direction is this close to perpendicular to the axis (a
// cosine, not a transmittance) do not propagate along it: 1/c would blow up.
// Set from propagation.rs, whose host-computed directional step uses it too.
layout(constant_id = 6) const float MIN_AXIS_COSINE = 1e-4;
// Within this many slices of a point or spot light (along the axis) the path is
// integrated all the way to the light instead of read from the previous slice:
// the distance to a light has a cusp there that bilinear resampling between
// texel centres cannot follow (it lengthened the path by a third of a voxel next
// to the light, a deficit every slice beyond then carried on). Set from
// propagation.rs, which also chooses the pass's build by it.
layout(constant_id = 7) const float NEAR_LIGHT_SLICES = 4.0;

vec3 voxel_centre(ivec3 g) {
    return ((vec3(g) + 0.5) / vec3(pass.grid) * 2.0 - 1.0) * frame.box_half;
}

// Optical depth per channel of the medium sample m: sigma, times the share of
// each channel the medium does not pass on when chromatic.
vec3 extinction(vec4 m) {
    return CHROMATIC ? m.a * max(vec3(1.0) - m.rgb, vec3(0.0)) : vec3(m.a);
}

// Optical depth (sigma per voxel times voxels, per channel) of `len` world units
// from p along dir.
vec3 optical_depth(vec3 p, vec3 dir, float len) {
    if (len <= 0.0) return vec3(0.0);
    float vl = frame.voxel_length;
    int n = int(clamp(ceil(len / (SUBSTEP_VOXELS * vl)), 1.0, float(MAX_SUBSTEPS)));
    float g = len / float(n);
    vec3 tau = vec3(0.0);
    for (int j = 0; j < n; ++j) tau += extinction(medium(p + dir * ((float(j) + 0.5) * g)));
    return tau * g / vl;
}

// Optical depth of the cell's column between p and the previous slice (`len`
// world units back along the axis), shared by every light of the pass: the
// sub-steps are spread over the cell's lateral cross-section (a 2D
// low-discrepancy pattern, one lateral point per sub-step) instead of all on
// the axis line through the centre. An oblique light crosses the cell up to
// half a cell beside that line, through medium the line never sees; at scale 4
// (a cell four data voxels wide) the line alone misjudged thin structures most.
// The points spread over the data voxel centres the cell covers (the
// trilinear filter already spans one data voxel): none at scale 1, where a
// spread over the whole cell blurred the medium (DR*1 error 1.4x the line's).
// Same number of samples as the line.
vec3 cell_column_depth(vec3 p, int a, int u, int v, float back, float len) {
    if (len <= 0.0) return vec3(0.0);
    float vl = frame.voxel_length;
    int n = int(clamp(ceil(len / (SUBSTEP_VOXELS * vl)), 1.0, float(MAX_SUBSTEPS)));
    float g = len / float(n);
    vec2 cell = vec2(2.0 * frame.box_half[u] / float(pass.grid[u]), 2.0 * frame.box_half[v] / float(pass.grid[v]));
    vec2 spread = max(cell - vl, vec2(0.0));
    // R2 sequence (plastic number): evenly spread for every n.
    const vec2 R2 = vec2(0.7548776662, 0.5698402910);
    vec3 tau = vec3(0.0);
    for (int j = 0; j < n; ++j) {
        vec2 o = (fract(vec2(0.5) + R2 * float(j + 1)) - 0.5) * spread;
        vec3 q = p;
        q[a] += back * ((float(j) + 0.5) * g);
        q[u] += o.x;
        q[v] += o.y;
        tau += extinction(medium(q));
    }
    return tau * g / vl;
}

// Transmittance stored in the previous slice at lateral texel position c
// (continuous, texel centres at i + 0.5; callers only ask for points inside the
// volume), bilinear between texel centres. Between the outermost texel centre
// and a face the light enters through (`enters`: per lateral axis, -1 low face,
// +1 high face, 0 neither) it blends toward 1, the transmittance at that face;
// elsewhere it clamps to the edge.
vec3 previous_transmittance(vec2 c, ivec2 size, int slot, ivec2 enters) {
    vec2 cc = clamp(c, vec2(0.5), vec2(size) - 0.5);
    vec2 t = cc - 0.5;
    ivec2 i0 = ivec2(floor(t));
    precise vec2 f = t - vec2(i0);
    vec3 v[4];
    for (int k = 0; k < 4; ++k) {
        ivec2 i = min(i0 + ivec2(k & 1, k >> 1), size - 1);
        v[k] = imageLoad(slice_in, ivec3(i, slot)).rgb;
    }
    precise vec3 T = mix(mix(v[0], v[1], f.x), mix(v[2], v[3], f.x), f.y);
    // How far past the outermost texel centre, in half texels, toward an entry face.
    vec2 excess = (c - cc) * vec2(enters) * 2.0;
    return mix(T, vec3(1.0), clamp(max(excess.x, excess.y), 0.0, 1.0));
}

// Distance from p (inside the box) along the unit vector w to where it leaves
// the box: intersect_box(p, w).y with the same arithmetic per axis (the face
// ahead, times 1/w; axes w does not move along skipped), so bit-equal to it,
// without the entry side and the outside tests that a point inside never
// needs (a fifth of a light's cost per voxel on llvmpipe, which runs them all).
float box_exit(vec3 p, vec3 w) {
    vec3 h = frame.box_half;
    float t1 = 3.0e38;
    for (int a = 0; a < 3; ++a) {
        float face = w[a] > 0.0 ? h[a] : -h[a];
        float t = (face - p[a]) * (1.0 / w[a]);
        t1 = abs(w[a]) < 1e-30 ? t1 : min(t1, t);
    }
    return t1;
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

// One light's step at one voxel, what the shared part below needs: where to
// read the previous slice (if at all), the optical depth of the path to it,
// and what scales the transmittance into the contribution. Two ways to get
// it (from the host, or computed at the voxel) and one way to use it, so
// llvmpipe, which runs both sides of a branch, runs the taps, the exp and
// the sum once per light in a pass that mixes directional and other lights.
struct LightStep {
    bool carried;  // false: travelling against the group, adds nothing here
    bool lookup;   // read the previous slice at cq (else transmittance 1)
    vec2 cq;       // lateral texel position in the previous slice
    ivec2 enters;  // per lateral axis, the face the light enters through
    vec3 depth;    // optical depth from there to the voxel, per channel
    vec3 scale;    // factor * radiance (* falloff, cone and cos^2)
};

// A directional light's step with the shared medium, from the entry's
// host-computed constants: the lookup point in the previous slice is the
// texel centre t shifted by lateral_step, and where that point lies beyond a
// lateral face the path ends at the face (the share of the slice's path that
// lies inside), with transmittance 1 beyond. The same arithmetic in every
// build (bit-equal values: selective updates rely on it).
LightStep step_from_host(GroupEntry entry, ivec2 t, ivec2 size, int k, vec3 axis_depth) {
    LightStep s;
    // The first slice takes the light at the volume face, half a slice away.
    float part = k == 0 ? 0.5 : 1.0;
    precise vec2 shift = entry.lateral_step.xy * part;
    precise vec2 inverse_shift = entry.lateral_step.zw * (1.0 / part);
    precise vec2 from = vec2(t) + 0.5;
    precise vec2 cq = from + shift;
    // The lateral face the path leaves through toward the light, per axis
    // (the high one where it does not move: its distance is then infinite).
    vec2 face = vec2(shift.x < 0.0 ? 0.0 : float(size.x), shift.y < 0.0 ? 0.0 : float(size.y));
    precise vec2 to_face = (face - from) * inverse_shift;
    precise float share = min(min(to_face.x, to_face.y), 1.0);
    precise vec3 depth = axis_depth * (entry.radiance_path.w * share);
    s.carried = entry.radiance_path.w > 0.0;
    s.lookup = k > 0 && share >= 1.0;
    s.cq = cq;
    // The light enters through a lateral face where it travels inward.
    s.enters = ivec2(sign(entry.lateral_step.xy));
    s.depth = depth;
    s.scale = entry.radiance_path.rgb;
    return s;
}

// A light's step computed at the voxel p: a point or spot light's direction,
// path, falloff and cone differ from voxel to voxel, and without the shared
// medium a directional light too is integrated along its own direction here.
LightStep step_at_voxel(GroupEntry entry, Light l, vec3 p, ivec2 size, int k, float segment, float dstep,
                        vec3 axis_depth) {
    LightStep s = LightStep(false, false, vec2(0.0), ivec2(0), vec3(0.0), vec3(0.0));
    int a = pass.axis;
    int u = (a + 1) % 3;
    int v = (a + 2) % 3;
    float travel = float(pass.travel);
    vec4 w = DIRECTIONAL_ONLY ? toward_directional_light(l) : toward_light(l, p);
    // Cosine between the light's travel direction and the propagation axis.
    float c = -w[a] * travel;
    // Light travelling against this group's direction is carried by the
    // group of the opposite direction (lights inside or beside the volume
    // have both), so it adds nothing here.
    s.carried = c > MIN_AXIS_COSINE;
    if (!s.carried) return s;
    // `precise` (no fusing or reassociation) from here to the contribution:
    // both NEAR_LIGHTS builds must give a far light bit-equal values.
    precise float along = segment / c;
    precise vec3 q = p + w.xyz * along;
    bool near_light = NEAR_LIGHTS && w.w * c <= NEAR_LIGHT_SLICES * dstep;
    // Where the light enters the volume (through any face) or leaves the
    // light itself before the previous slice, nothing attenuates it
    // beyond: the path ends there with transmittance 1. The box is only
    // intersected where the path may leave it before the previous slice
    // (q outside the box laterally, or near the light).
    bool inside = abs(q[u]) <= frame.box_half[u] && abs(q[v]) <= frame.box_half[v];
    precise float reach = inside && !near_light ? w.w : min(box_exit(p, w.xyz), w.w);
    precise float len = near_light ? reach : min(along, reach);
    s.lookup = k > 0 && along < reach && !near_light;
    precise vec2 cq = vec2((q[u] / (2.0 * frame.box_half[u]) + 0.5) * float(size.x),
                           (q[v] / (2.0 * frame.box_half[v]) + 0.5) * float(size.y));
    s.cq = cq;
    // The light enters through a lateral face where it travels inward:
    // toward the light (w) points out of the face.
    s.enters = ivec2(w[u] > 0.0 ? 1 : (w[u] < 0.0 ? -1 : 0), w[v] > 0.0 ? 1 : (w[v] < 0.0 ? -1 : 0));
    bool shared_path = SHARED_MEDIUM && !near_light;
    precise vec3 depth = shared_path ? axis_depth * (len / segment) : optical_depth(p, w.xyz, len);
    s.depth = depth;
    precise float weight = entry.factor * (entry.per_voxel != 0u ? c * c : 1.0);
    float shape = DIRECTIONAL_ONLY ? 1.0 : light_shape(l, w);
    precise vec3 scale = weight * l.radiance.rgb * shape;
    s.scale = scale;
    return s;
}

void main() {
    load_frame();
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
    // Shared medium: sampled once per voxel for every light of the pass.
    vec3 axis_depth = SHARED_MEDIUM ? cell_column_depth(p, a, u, v, -travel, segment) : vec3(0.0);
    // This pass's light at the voxel, summed in registers (two-float when
    // compensated) and added into the volume once below.
    vec3 sum_hi = vec3(0.0);
    vec3 sum_lo = vec3(0.0);
    for (int e = 0; e < pass.entry_count; ++e) {
        GroupEntry entry = entries[pass.first_entry + e];
        // With the shared medium the directional build never reads the light itself.
        Light l;
        if (!(DIRECTIONAL_ONLY && SHARED_MEDIUM)) l = lights[entry.light];
        LightStep s;
        if (SHARED_MEDIUM && (DIRECTIONAL_ONLY || l.pos_type.w == LIGHT_DIRECTIONAL)) {
            s = step_from_host(entry, t, size, k, axis_depth);
        } else {
            s = step_at_voxel(entry, l, p, size, k, segment, dstep, axis_depth);
        }
        vec4 result = vec4(0.0);
        if (s.carried) {
            precise vec3 T = vec3(1.0);
            if (s.lookup) T = previous_transmittance(s.cq, size, int(entry.slot), s.enters);
            T *= exp(-s.depth);
            result = vec4(T, 0.0);
            precise vec3 x = s.scale * T;
            if (COMPENSATED) {
                compensated_add(sum_hi, sum_lo, x);
            } else {
                sum_hi += x;
            }
        }
        imageStore(slice_out, ivec3(t, int(entry.slot)), result);
    }
    vec3 hi = imageLoad(illumination, g).rgb;
    if (COMPENSATED) {
        // (hi + lo) += (sum_hi + sum_lo): the high word exactly, then the low words.
        vec3 lo = imageLoad(illumination_low, g).rgb;
        compensated_add(hi, lo, sum_hi);
        compensated_add(hi, lo, sum_lo);
        imageStore(illumination_low, g, vec4(lo, 0.0));
    } else {
        hi += sum_hi;
    }
    imageStore(illumination, g, vec4(hi, 1.0));
}
