// IPSVI line kernels: what a view sample reads from the cache as the previous
// line block left it (never anything its own line writes), with piecewise
// integration back to where the light was stored.
#ifndef IPSVI_CACHE_READ_GLSL
#define IPSVI_CACHE_READ_GLSL

// Light at sample p: (direct transmittance, emission arriving / scale): the
// four texels bilinearly (E / scale: rgb, transmittance: a), and with piecewise
// integration the path from p back to their fronts, weighted as their values.
// (Each texel's front lies on its own light ray; the nearest texel's front
// alone is off by the front plane's tilt across a texel, which a stiff medium
// turns into stripes: docs/stability.md.)
vec4 light_at(vec3 p) {
    vec3 c = cache_coord(p);
    Footprint fp = bilinear_footprint(c.xy);
    bool piecewise = PIECEWISE && STEP >= STEP_PIECEWISE;
    vec4 cached = vec4(0.0);
    float front = 0.0;
    vec4 value[4];
    vec4 back;
    for (int j = 0; j < 4; ++j) {
        uint code;
        value[j] = history_load(fp.texel[j], code);
        cached += fp.weight[j] * value[j];
        if (piecewise) {
            Ray r = cache_ray(uvec2(fp.texel[j]));
            vec2 io = ray_in_box(r);
            float d = io.x <= io.y ? front_param(r, code, io) : c.z;
            front += fp.weight[j] * d;
            back[j] = c.z - d;
        }
    }
    if (!piecewise) return cached;
    if (PER_TEXEL_FRONTS) return through_fronts(p, fp, value, back);
    // Piecewise integration: march from p toward the light back to the cache front.
    return through_segment(cached, march_to_light(p, to_light(p), max(c.z - front, 0.0), sweep.max_piecewise_steps));
}

// Light at p from the view-sample cache: the four texels bilinearly, and with
// piecewise integration the path from p back to their (equally weighted) depth.
vec4 light_from_samples(vec3 p, vec3 c) {
    Footprint fp = bilinear_footprint(c.xy);
    bool piecewise = PIECEWISE && STEP >= STEP_PIECEWISE;
    vec4 sum = vec4(0.0);
    float front = 0.0;
    vec4 value[4];
    vec4 back;
    for (int j = 0; j < 4; ++j) {
        uint code;
        value[j] = state_load(fp.texel[j], code);
        sum += fp.weight[j] * value[j];
        if (piecewise) {
            vec2 io = ray_in_box(cache_ray(uvec2(fp.texel[j])));
            float d = io.x <= io.y ? depth_of(code, io) : c.z;
            front += fp.weight[j] * d;
            back[j] = c.z - d;
        }
    }
    if (!piecewise) return sum;
    if (PER_TEXEL_FRONTS) return through_fronts(p, fp, value, back);
    return through_segment(sum, march_to_light(p, to_light(p), max(c.z - front, 0.0), sweep.max_piecewise_steps));
}

// The light a shaded sample at p receives where its pixel's march only reads
// (light rays, or view samples whose writes the texel pass stores): nothing
// but the previous block's images, so no sample depends on another sample of
// its own line. Breakdown step 0 reads nothing (unshadowed light).
vec4 read_light(vec3 p) {
    if (STEP == 0u) return vec4(0.0, 0.0, 0.0, 1.0);
    if (VIEW_SAMPLES) return light_from_samples(p, cache_coord(p));
    return light_at(p);
}

#endif
