// IPSVI line kernels: marches toward the light (section 4.4's piecewise
// integration and the light segments of cache writes), each step counted in
// this invocation's serial chain (glsl/ipsvi_line_interface.glsl, Shape).
#ifndef IPSVI_PIECEWISE_GLSL
#define IPSVI_PIECEWISE_GLSL

// A texel invocation's share of its texel's marches toward the light: the
// segmented kernel gives a texel TEXEL_LANES consecutive lanes of a subgroup
// (march_lanes, while they march together), each marching a part of the
// steps; one lane marches them all otherwise. Lane 0 stores the texel.
uint march_lanes = 1u;
uint march_lane = 0u;

#ifdef SPLIT_TEXEL_MARCHES
// Parts (E, optical depth) of one march combined in order, the part nearer
// its start in front (as light_path.glsl's parts do): every lane ends with
// the whole march's.
vec4 march_parts_combined(vec4 part) {
    for (uint d = 1u; d < march_lanes; d <<= 1) {
        vec4 other = subgroupShuffleXor(part, d);
        vec4 a = (march_lane & d) == 0u ? part : other;
        vec4 b = (march_lane & d) == 0u ? other : part;
        part = vec4(a.rgb + exp(-a.a) * b.rgb, a.a + b.a);
    }
    return part;
}
#endif

// light_segment (glsl/ipsvi_common.glsl), its steps counted: the same step
// count as integrate_light_path takes (this lane's part of them where the
// march is split; a texel's lanes arrive together, its state deciding for all).
vec4 march_to_light(vec3 x, vec3 dir, float len, uint max_steps) {
#ifdef SPLIT_TEXEL_MARCHES
    if (march_lanes > 1u) {
        if (len <= 0.0) return vec4(0.0);
        int m = light_path_steps(len, float(max_steps));
        int per = (m + int(march_lanes) - 1) / int(march_lanes);
        int first = min(int(march_lane) * per, m);
        int last = min(first + per, m);
        chain += uint(last - first);
        return cached_light_path(march_parts_combined(integrate_light_path_part(x, dir, len, m, first, last, EMISSIVE)));
    }
#endif
    if (len > 0.0) chain += uint(light_path_steps(len, float(max_steps)));
    return light_segment(x, dir, len, max_steps, EMISSIVE);
}

// The four cache texels around continuous coordinates c and their bilinear weights.
struct Footprint {
    ivec2 texel[4];
    float weight[4];
};

Footprint bilinear_footprint(vec2 c) {
    ivec2 n = ivec2(sweep.cache_size);
    vec2 t = c - 0.5;
    ivec2 i0 = ivec2(floor(t));
    vec2 f = t - vec2(i0);
    Footprint fp;
    for (int j = 0; j < 4; ++j) {
        ivec2 o = ivec2(j & 1, j >> 1);
        fp.texel[j] = clamp(i0 + o, ivec2(0), n - 1);
        fp.weight[j] = (o.x != 0 ? f.x : 1.0 - f.x) * (o.y != 0 ? f.y : 1.0 - f.y);
    }
    return fp;
}

// Fronts within a voxel (or a light step, if longer) of each other lie on one
// cache plane, apart by the plane's tilt across a texel: a read's texels on
// one plane share their blended depth, which is where the sample's own light
// ray crosses that plane (the paper's one lookup; carrying each value from
// its own depth would put it off the plane, measured far worse in a stiff
// medium). Texels whose fronts lie lines apart keep their group's own depth.
vec4 grouped_back(Footprint fp, vec4 back) {
    float near = max(frame.shadow_step, 1.0) * frame.voxel_length;
    vec4 grouped;
    for (int j = 0; j < 4; ++j) {
        float sum = 0.0;
        float weight = 0.0;
        for (int k = 0; k < 4; ++k) {
            if (abs(back[k] - back[j]) <= near) {
                sum += fp.weight[k] * back[k];
                weight += fp.weight[k];
            }
        }
        grouped[j] = max(weight > 0.0 ? sum / weight : back[j], 0.0);
    }
    return grouped;
}

// The light arriving at p from four texels of footprint fp, texel j's value
// `value[j]` lying `to_front[j]` from p toward the light: the texels grouped
// by plane (grouped_back), each value carried to p over its group's stretch,
// then blended. One midpoint march as long as the longest stretch; each step
// counts for each texel as far as its stretch reaches. With all four on one
// plane it is the blend carried over one stretch (light_segment's march,
// step for step).
vec4 through_fronts(vec3 p, Footprint fp, vec4 value[4], vec4 to_front) {
    vec4 back = grouped_back(fp, to_front);
    float longest = max(max(back.x, back.y), max(back.z, back.w));
    vec4 tau = vec4(0.0);
    vec3 emitted[4] = vec3[4](vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0));
    if (longest > 0.0) {
        float vl = frame.voxel_length;
        float m = clamp(ceil(longest / (frame.shadow_step * vl)), 1.0, float(sweep.max_piecewise_steps));
        float g = longest / m;
        vec3 dir = to_light(p);
        chain += uint(m);
        for (int i = 0; i < int(m); ++i) {
            vec4 med = medium(p + dir * ((float(i) + 0.5) * g));
            vec4 depth = med.a * clamp(back - float(i) * g, 0.0, g) / vl;
            if (EMISSIVE)
                for (int j = 0; j < 4; ++j) emitted[j] += exp(-tau[j]) * (1.0 - exp(-depth[j])) * med.rgb;
            tau += depth;
        }
    }
    float scale = frame.emission / sweep.light_scale;
    vec4 sum = vec4(0.0);
    for (int j = 0; j < 4; ++j) {
        float tr = exp(-tau[j]);
        sum += fp.weight[j] * vec4(value[j].rgb * tr + emitted[j] * scale, value[j].a * tr);
    }
    return sum;
}

#endif
