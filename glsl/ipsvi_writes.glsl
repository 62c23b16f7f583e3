// IPSVI line kernels: the cache writes. View samples: the claim keys that
// pick one writer per texel, the value a write stores (store_sample) and the
// texel invocations of the texel pass; both modes: the invocations that carry
// (view samples) or advance (light rays) the history pair.
#ifndef IPSVI_WRITES_GLSL
#define IPSVI_WRITES_GLSL

// The claim key of a sample write (see Keys); `record` is the block's index in the frame.
uint64_t claim_key(uint record, float depth, uint pixel) {
    uint d27 = floatBitsToUint(max(depth, 0.0)) >> 5;
    uint64_t d = uint64_t(NEAREST ? 0x7FFFFFFu - d27 : d27);
    return (uint64_t(record + 1u) << 44) | (d << 17) | uint64_t(pixel);
}

// Keys of the whole cache images (every sweep's cache when merged), per half.
uint key_index(uint half_index, ivec2 k) {
    uint n = sweep.cache_size;
    uint rows = uint(PACKED ? imageSize(history_in).y : imageSize(cache_in).y);
    return half_index * n * rows + uint(slot_texel(k).y) * n + uint(k.x);
}

// With piecewise integration a run's sample nearest the light writes, without
// it the run's last sample (the paper's choice): readers then use the value as
// it is, and it should have come as far along the light as the run did.
bool run_keeps_nearest() { return PIECEWISE; }

// Claims texel k of the next block's pixel `pixel` for the run that ends there,
// its writer `depth` along the light (see Keys; the largest key wins, so the
// order in which runs end does not matter).
void claim_run(ivec2 k, float depth, uint pixel) {
    uint64_t key = claim_key(block_index + 1u, depth, pixel);
    atomicMax(keys[key_index(KEY_HALF_NEXT, k)], key);
    if (DIGESTS) atomicAdd(claim_digest, digest_hash(key ^ digest_hash(uint64_t(slot_texel(k).x) | (uint64_t(slot_texel(k).y) << 16))));
}

// write_value = "texel-ray": the light on texel k's own ray at distance z,
// carried there along that ray from the texel's state (no lateral filtering),
// and the point it is at. A sample's own light was read from four texels: a
// texel written with it is filtered again at every line that writes it, so
// the light blurs across the sweep (engine.vti 512x512: RMSE 1.44e-2 against
// 7.3e-3 this way; docs/ipsvi.md).
vec4 texel_ray_light(ivec2 k, float z, out vec3 q) {
    Ray r = cache_ray(uvec2(k));
    vec2 io = ray_in_box(r);
    uint code;
    vec4 v = state_load(k, code);
    float at = clamp(z, io.x, io.y);
    q = r.origin + r.dir * at;
    if (io.x > io.y) return v;
    return through_segment(v, march_to_light(q, -r.dir, max(at - depth_of(code, io), 0.0), sweep.max_piecewise_steps));
}

// The sweep plane of the line holding pixel `index` of this block.
uint writer_plane(uint index) {
    uint line = block.line_first + index / block.span_len;
    return block.columns != 0u ? frame.image_size.y + line : line;
}

// A run of samples in texel k ends: its writing sample stores the light
// leaving it: the light l it received (write_value = "sample", the paper's;
// "texel-ray": the light on the texel's ray at its depth), composited back to
// front with its own segment along the light (one light step), stored at the
// segment's far end. (With piecewise integration, storing the run's last sample as the
// paper does: on a surface lit from the camera's side it lies deep inside the
// object, and the next line's surface samples, nearer the light, read its
// attenuated light: measured 1.6e-2 RMSE on the engine at 256x256, 7.6e-3 with
// the nearest sample, 2.7e-3 for light rays. Readers farther along march back
// to the nearest sample exactly.)
void store_sample(ivec2 k, vec3 p, float depth, vec4 l, uint pixel, bool empty) {
    if (STEP < STEP_STORES) return;
    if (CLAIMS && STEP >= STEP_CLAIM_CHECK) {
        // Only the claimed winner stores; compared on record and pixel.
        uint64_t mask = (uint64_t(0xFFFFFu) << 44) | uint64_t(0x1FFFFu);
        uint64_t key = keys[key_index(KEY_HALF_IN, k)];
        if ((key & mask) != (claim_key(block_index, 0.0, pixel) & mask)) return;
    }
    float s = frame.shadow_step * frame.voxel_length;
    vec2 io = ray_in_box(cache_ray(uvec2(k)));
    if (WRITE_TEXEL_RAY && PIECEWISE && io.x <= io.y) {
        // The texel's point is where its ray crosses the writing sample's line
        // plane (the paper's cache plane, section 4.4), not the sample's own
        // depth: that lies up to half a texel off the ray, where the plane's tilt
        // across a texel moves it along the light, so neighbouring texels held
        // points scattered about the plane and a reader's weighted depth missed
        // its own ray's crossing (engine.vti 256x256 RMSE: every-sample 4.61e-3
        // -> 2.86e-3, non-empty 5.26e-3 -> 3.08e-3). Under either write rule the
        // writer's view ray lies in its line plane, and the texel-ray march
        // carries the light from wherever the texel was last written (under
        // non-empty often many lines back) to the crossing, so the rule holds
        // for both. The own segment is the last stretch up to the plane; a write
        // never moves a texel back toward the light. (write_value = "sample"
        // keeps the sample's depth: its value is the light read at the sample's
        // own point, which no march carries to the crossing.)
        uint old_code;
        state_load(k, old_code);
        float old_depth = depth_of(old_code, io);
        float plane_depth = max(clamp(plane_hit(cache_ray(uvec2(k)), writer_plane(pixel), depth), io.x, io.y), old_depth);
        s = min(s, plane_depth - old_depth);
        depth = plane_depth - s;
    }
    if (WRITE_TEXEL_RAY && PIECEWISE) {
        // Breakdown steps before the march store the texel's state as it is.
        uint old_code;
        if (STEP >= STEP_FULL && !(EMPTY_RUNS_MOVE_DEPTH && empty)) l = texel_ray_light(k, depth, p);
        else l = state_load(k, old_code);
    }
    vec3 back = to_light(p);
    if (STEP >= STEP_OWN_SEGMENT) l = through_segment(l, march_to_light(p - back * s, back, s, 4u));
    uint code = io.x <= io.y ? depth_code(depth + s, io) : FRONT_ENTRY;
    if (march_lane == 0u) sample_store(k, l, (block.stamp << 16) | code);
}

// write_pass = "texel": texel k stores here if one of this block's runs ends in
// it (its claim key carries this block's record), as that run's writer would:
// the value and depth depend only on the texel's state and the writer's line
// plane, which the key's pixel names; the key's depth stands in for the
// writer's only where the texel's ray runs parallel to the plane.
void write_claimed_texel(ivec2 k) {
    uint64_t key = keys[key_index(KEY_HALF_IN, k)];
    if (uint(key >> 44) != block_index + 1u) return;
    uint d27 = uint(key >> 17) & 0x7FFFFFFu;
    float depth = uintBitsToFloat((NEAREST ? 0x7FFFFFFu - d27 : d27) << 5);
    store_sample(k, vec3(0.0), depth, vec4(0.0), uint(key) & 0x1FFFFu, false);
}

// view-samples: the history pair takes the previous block's state of texel k.
ivec2 region_texel(uint index) { return ivec2(block.region.xy + uvec2(index % block.region.z, index / block.region.z)); }

void carry_texel(uint index) {
    ivec2 k = region_texel(index);
    if (march_lane != 0u) return;
    uint code;
    vec4 v = state_load(k, code);
    cache_store(k, v, code);
}

vec4 cone_average(uvec2 k, float radius) {
    ivec2 n = ivec2(sweep.cache_size);
    vec4 sum = cache_load(ivec2(k));
    ivec2 r = ivec2(max(1.0, round(radius)));
    sum += cache_load(clamp(ivec2(k) + ivec2(r.x, 0), ivec2(0), n - 1));
    sum += cache_load(clamp(ivec2(k) - ivec2(r.x, 0), ivec2(0), n - 1));
    sum += cache_load(clamp(ivec2(k) + ivec2(0, r.y), ivec2(0), n - 1));
    sum += cache_load(clamp(ivec2(k) - ivec2(0, r.y), ivec2(0), n - 1));
    return sum * 0.2;
}

void advance_texel(uint index) {
    uvec2 k = block.region.xy + uvec2(index % block.region.z, index / block.region.z);
    uint code;
    vec4 cached = history_load(ivec2(k), code);
    Ray r = cache_ray(k);
    vec2 io = ray_in_box(r);
    if (io.x <= io.y && code != FRONT_EXIT) {
        float old_front = front_param(r, code, io);
        float target = plane_hit(r, block.plane, old_front);
        if (target > old_front) {
            float new_front = min(target, io.y);
            vec3 x = r.origin + r.dir * new_front;
            // The segment from the old front to the new one, integrated from its far
            // end toward the light, composited behind what the cache carried.
            vec4 seg = march_to_light(x, -r.dir, new_front - old_front, 4096u);
            if (SCATTER) {
                // Forward-cone scattering: the albedo share of the light arrives
                // from a cone around the ray, i.e. from neighbouring texels.
                float radius = sweep.cone_tan * (new_front - old_front) / max(sweep.cache_axis.w, 1e-9);
                cached = mix(cached, cone_average(k, radius), sweep.albedo);
            }
            cached = through_segment(cached, seg);
            code = new_front >= io.y ? FRONT_EXIT : block.plane;
        }
    }
    if (march_lane == 0u) cache_store(ivec2(k), cached, code);
}

#endif
