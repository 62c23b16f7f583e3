#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
// One IPSVI line block (one dispatch; src/ipsvi/): invocations below
// `pixel_count` ray-cast the block's pixels, reading the illumination cache as
// it stands at the previous line. The next invocations keep the history pair
// (cache/front) whole: with cache_update = "light-rays" they advance the light
// rays of the block's cache region to this block's last line; with
// "view-samples" they merge the previous block's sample writes into it. With
// "view-samples" the view samples themselves write the light leaving them
// (Listing 4.1) into the sample pair; with cache_write = "farthest" the last
// invocations claim, for the next block's pixels, which sample writes each
// texel. Reads and writes go to different images, so a block races only where
// the paper does (cache_write = "racy": many samples, one texel).

// Invocations per workgroup, chosen per renderer (src/ipsvi/line_group.rs): on
// lavapipe a workgroup runs on one thread, so a short line in one wide group
// leaves the other cores idle.
layout(local_size_x_id = 8) in;
layout(constant_id = 0) const bool EMISSIVE = true;  // model (ii): light carries emission
layout(constant_id = 1) const bool SCATTER = false;  // albedo-blended forward-cone scattering
layout(constant_id = 2) const bool VIEW_SAMPLES = false;  // cache_update = "view-samples"
layout(constant_id = 3) const bool CLAIMS = false;        // cache_write = "farthest" or "nearest": one writer per texel
layout(constant_id = 4) const bool NEAREST = false;       // "nearest": the sample closest to the light wins
// Cost breakdown (src/ipsvi/breakdown.rs), cumulative: 0 ray casting only,
// 1 + cache reads, 2 + piecewise integration, 3 + the history carry (light
// rays: the texel advance), 4 + racy sample stores of the read light, 5 + the
// claim pass, 6 + the claim check, 7 + the writer's own light segment, 8 + the
// texel-ray march = IPSVI; 9 nothing at all (the sync study's empty workload:
// the sweep's dispatches and barriers alone).
layout(constant_id = 5) const uint STEP = 8u;
const uint STEP_READS = 1u;
const uint STEP_PIECEWISE = 2u;
const uint STEP_CARRY = 3u;
const uint STEP_STORES = 4u;
const uint STEP_CLAIM_PASS = 5u;
const uint STEP_CLAIM_CHECK = 6u;
const uint STEP_OWN_SEGMENT = 7u;
const uint STEP_FULL = 8u;
const uint STEP_EMPTY = 9u;
// Fixed per renderer, so the compiler drops what a frame never runs.
layout(constant_id = 6) const bool PIECEWISE = true;  // piecewise integration (section 4.4)
// When view rays stop: 0 never, 1 once opaque ("plain"), 2 once opaque and past
// l_max of the exit-point sweep ("exit-points", section 5.1).
layout(constant_id = 7) const uint TERMINATION = 1u;
// ipsvi.merge_sweeps (src/ipsvi/merged_steps.rs): a dispatch is step k of every
// independent sweep, its push constant the step index; each workgroup finds its
// sweep's block in the step table. Each sweep has its own cache (rows of the
// cache images) and its own output accumulation (rows of out_image).
layout(constant_id = 9) const bool MERGED = false;
// ipsvi.write_value = "texel-ray" (view samples with piecewise integration): a
// write stores the light on the written texel's own ray at the sample's depth,
// not the light the sample read bilinearly at its own position.
layout(constant_id = 10) const bool WRITE_TEXEL_RAY = true;
// ipsvi.write_rule = "every-sample" (view samples): every sample, empty ones
// included, takes part in runs and every run end stores (Listing 4.1); else
// only samples with non-zero opacity ("non-empty").
layout(constant_id = 11) const bool EVERY_SAMPLE = false;
// ipsvi.empty_runs_move_depth (texel-ray writes): a run whose samples were all
// empty stores its texel's light as it is at the new depth, without the
// texel-ray march (which would cross the medium on the texel's own ray).
layout(constant_id = 12) const bool EMPTY_RUNS_MOVE_DEPTH = false;
// ipsvi.packed_store: each pair is one rgba32ui image, value (four halves,
// packHalf2x16) and depth code / stamp in one texel: one store and one load
// per texel instead of two (bindings 8-11; else 0-7, the others 1x1, unused).
layout(constant_id = 13) const bool PACKED = false;
// ipsvi.write_pass = "texel" (texel-ray writes): the claim march names the
// texels where this block's runs end; its texel invocations march and store
// them (write_claimed_texel), the pixels' sample loop stores nothing.
layout(constant_id = 14) const bool TEXEL_PASS = false;
// ipsvi.read_fronts = "per-texel" (piecewise integration): a read groups its
// four texels by the cache plane their fronts lie on and carries each value
// from its group's blended depth to the sample (one march, the medium fetched
// once per step for all four), not all four from one blended depth (the
// paper's one `res` lookup). Texels written lines apart then no longer
// average a fresh and a stale depth into one that fits neither (see
// through_fronts).
layout(constant_id = 15) const bool PER_TEXEL_FRONTS = false;
const uint TERMINATION_OFF = 0u;
const uint TERMINATION_PLAIN = 1u;
const uint TERMINATION_EXIT_POINTS = 2u;

#include "ipsvi_common.glsl"
#include "view_ray.glsl"

// The ping-pong pairs in a small set 1, {in = a, out = b} or {in = b, out = a},
// bound per block; set 0 stays bound for the sweep (rebinding it costs as
// much as fifty dispatches on lavapipe, a small set about nothing:
// tools/dispatch_probe.rs). Reads and writes are separate bindings, so
// synchronization validation sees exactly what a block reads and writes, and
// reports a missing barrier.
layout(set = 1, binding = 0, rgba16f) readonly uniform image2D cache_in;
layout(set = 1, binding = 1, r16ui) readonly uniform uimage2D front_in;
layout(set = 1, binding = 2, rgba16f) writeonly uniform image2D cache_out;
layout(set = 1, binding = 3, r16ui) writeonly uniform uimage2D front_out;
layout(set = 1, binding = 4, rgba16f) readonly uniform image2D samples_in;
layout(set = 1, binding = 5, r32ui) readonly uniform uimage2D stamps_in;
layout(set = 1, binding = 6, rgba16f) writeonly uniform image2D samples_out;
layout(set = 1, binding = 7, r32ui) writeonly uniform uimage2D stamps_out;
layout(set = 1, binding = 8, rgba32ui) readonly uniform uimage2D history_in;
layout(set = 1, binding = 9, rgba32ui) writeonly uniform uimage2D history_out;
layout(set = 1, binding = 10, rgba32ui) readonly uniform uimage2D packed_samples_in;
layout(set = 1, binding = 11, rgba32ui) writeonly uniform uimage2D packed_samples_out;
#define KEY_HALF_IN (block.parity)        // keys this block's pixels claimed
#define KEY_HALF_NEXT (1u - block.parity) // keys the next block's pixels claim

layout(set = 0, binding = 14, rgba32f) uniform image2D out_image;

struct BlockParams {
    uint line_first;
    uint line_width;
    uint span_start;
    uint span_len;
    uint columns;     // 1: lines are columns
    uint zone;        // 0 all, 1 right, 2 left, 3 down, 4 up
    uint plane;       // plane index of the block's last line
    uint pixel_count; // line_width * span_len
    uvec4 region;     // cache texels to advance: x0, y0, w, h
    uint parity;      // which side of the pairs this block reads (its set 1)
    uint light;       // index into sweeps[]
    uint stamp;       // view-samples: 1 + the block's index in its sweep (stamps of sample writes)
    uint claim_count; // farthest: pixels of the next block to claim for (0: none)
    uint cache_row;   // first row of the block's sweep's cache in the cache images (merged; else 0)
    uint out_row;     // first row of its sweep's accumulation in out_image (merged; else 0)
    uvec2 pad;        // to the struct's 16-byte std430 size
};

// Every block of the frame, planned on the host; a dispatch gets its index as
// its only push constant. (vkCmdDispatchBase would carry it for free, but the
// validation layer we test with does not check synchronization of that command.)
layout(std430, set = 0, binding = 15) readonly buffer Blocks { BlockParams blocks[]; };
layout(push_constant) uniform Push { uint block_index; } push;

// MERGED: per step, one (block record, first workgroup) per sweep, in sweep
// order; a sweep with no such step has block NO_BLOCK.
layout(std430, set = 0, binding = 26) readonly buffer Steps { uint step_sweeps; uint steps_pad; uvec2 step_entries[]; };
const uint NO_BLOCK = 0xFFFFFFFFu;

// The frame-wide index of this invocation's block (push.block_index unless MERGED).
uint block_index;

// l_max of the exit-point sweep (section 5.1), at the pre-pass resolution; a 1x1
// placeholder when that mode is off.
layout(set = 0, binding = 16, r32f) readonly uniform image2D lmax;

// cache_write = "farthest"/"nearest": per texel, the claim of the sample that
// stores into it, two halves (this block's claims, the next block's), cleared
// every frame: 20 bits record number + 1 | 27 bits depth along the light ray
// (inverted for "nearest") | 17 bits pixel; the largest key wins.
layout(std430, set = 0, binding = 25) buffer Keys { uint64_t keys[]; };

BlockParams block;

// Texel k of the block's sweep's cache in the cache images.
ivec2 slot_texel(ivec2 k) { return k + ivec2(0, int(block.cache_row)); }

// Packed texels: the value's halves rounded as the rgba16f images round them
// (toward zero on lavapipe; packHalf2x16 rounds to nearest, which changes the
// image), then the code.
uint half_bits(float f) {
    uint u = floatBitsToUint(f);
    uint sign = (u >> 16) & 0x8000u;
    int e = int((u >> 23) & 0xFFu) - 112;
    uint m = u & 0x7FFFFFu;
    if (e == 143) return sign | 0x7C00u | (m != 0u ? 0x200u : 0u); // inf, NaN
    if (e >= 31) return sign | 0x7BFFu;                            // largest finite
    if (e <= 0) return e < -10 ? sign : sign | ((m | 0x800000u) >> uint(14 - e));
    return sign | (uint(e) << 10) | (m >> 13);
}
uint pack_halves(vec2 v) { return half_bits(v.x) | (half_bits(v.y) << 16); }
uvec4 pack_texel(vec4 v, uint code) { return uvec4(pack_halves(v.rg), pack_halves(v.ba), code, 0u); }
vec4 unpack_value(uvec4 t) { return vec4(unpackHalf2x16(t.x), unpackHalf2x16(t.y)); }

vec4 cache_load(ivec2 k) {
    if (PACKED) return unpack_value(imageLoad(history_in, slot_texel(k)));
    return imageLoad(cache_in, slot_texel(k));
}
uint front_load(ivec2 k) {
    if (PACKED) return imageLoad(history_in, slot_texel(k)).z;
    return imageLoad(front_in, slot_texel(k)).r;
}
// Texel k of the history pair: value and front code in one load when packed.
vec4 history_load(ivec2 k, out uint code) {
    if (PACKED) {
        uvec4 t = imageLoad(history_in, slot_texel(k));
        code = t.z;
        return unpack_value(t);
    }
    code = front_load(k);
    return cache_load(k);
}

void cache_store(ivec2 k, vec4 v, uint code) {
    // r16ui keeps the low 16 bits; the packed code keeps the same.
    if (PACKED) {
        imageStore(history_out, slot_texel(k), pack_texel(v, code & 0xFFFFu));
        return;
    }
    imageStore(cache_out, slot_texel(k), v);
    imageStore(front_out, slot_texel(k), uvec4(code));
}

// The sample pair's texel k: (value, stamp << 16 | depth code).
vec4 sample_load(ivec2 k, out uint stamped) {
    if (PACKED) {
        uvec4 t = imageLoad(packed_samples_in, slot_texel(k));
        stamped = t.z;
        return unpack_value(t);
    }
    stamped = imageLoad(stamps_in, slot_texel(k)).r;
    return imageLoad(samples_in, slot_texel(k));
}
uint stamp_load(ivec2 k) {
    if (PACKED) return imageLoad(packed_samples_in, slot_texel(k)).z;
    return imageLoad(stamps_in, slot_texel(k)).r;
}
void sample_store(ivec2 k, vec4 v, uint stamped) {
    if (PACKED) {
        imageStore(packed_samples_out, slot_texel(k), pack_texel(v, stamped));
        return;
    }
    imageStore(samples_out, slot_texel(k), v);
    imageStore(stamps_out, slot_texel(k), uvec4(stamped));
}

float zone_weight(BlockParams line_block, vec2 c) {
    if (line_block.zone == 0u) return 1.0;
    vec2 d = c - sweep.anchor;
    float b = max(sweep.blend_px, 1e-3);
    vec4 m = vec4(d.x - abs(d.y), -d.x - abs(d.y), d.y - abs(d.x), -d.y - abs(d.x));
    vec4 w = clamp(0.5 + m / (2.0 * b), 0.0, 1.0);
    return w[line_block.zone - 1u] / max(w.x + w.y + w.z + w.w, 1e-6);
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
    return through_segment(cached, light_segment(p, to_light(p), max(c.z - front, 0.0), sweep.max_piecewise_steps, EMISSIVE));
}

// ---- cache_update = "view-samples" -------------------------------------------
// The cache is then two ping-pong pairs: the sample pair (samples/stamps) holds
// what the previous block's view samples wrote, stamped with its block number;
// the history pair (cache/front) holds every texel as of the block before. A
// texel's state after the previous block is its sample write if stamped so,
// else its history. Depths along the light ray are 16-bit fractions of the
// texel ray's extent in the box (the paper's `res` image, section 4.4).

const float DEPTH_STEPS = 65533.0; // codes 0..65533; FRONT_ENTRY/EXIT above

float depth_of(uint code, vec2 io) {
    if (code == FRONT_ENTRY) return io.x;
    if (code == FRONT_EXIT) return io.y;
    return io.x + (io.y - io.x) * (float(code) / DEPTH_STEPS);
}

uint depth_code(float z, vec2 io) {
    return uint(round(clamp((z - io.x) / max(io.y - io.x, 1e-20), 0.0, 1.0) * DEPTH_STEPS));
}

// Texel k as the previous block left it: (value, depth code).
vec4 state_load(ivec2 k, out uint code) {
    uint previous = block.stamp - 1u;
    if (PACKED) {
        // One load when the texel was written by the previous block.
        uint stamped;
        vec4 v = sample_load(k, stamped);
        if (previous != 0u && (stamped >> 16) == previous) {
            code = stamped & 0xFFFFu;
            return v;
        }
        return history_load(k, code);
    }
    uint stamped = stamp_load(k);
    if (previous != 0u && (stamped >> 16) == previous) {
        code = stamped & 0xFFFFu;
        return imageLoad(samples_in, slot_texel(k));
    }
    return history_load(k, code);
}

// The texel a sample at cache coordinates c writes.
ivec2 sample_texel(vec3 c) { return clamp(ivec2(floor(c.xy)), ivec2(0), ivec2(sweep.cache_size) - 1); }

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
    return through_segment(sum, light_segment(p, to_light(p), max(c.z - front, 0.0), sweep.max_piecewise_steps, EMISSIVE));
}

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
    return through_segment(v, light_segment(q, -r.dir, max(at - depth_of(code, io), 0.0), sweep.max_piecewise_steps, EMISSIVE));
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
    if (STEP >= STEP_OWN_SEGMENT) l = through_segment(l, light_segment(p - back * s, back, s, 4u, EMISSIVE));
    uint code = io.x <= io.y ? depth_code(depth + s, io) : FRONT_ENTRY;
    sample_store(k, l, (block.stamp << 16) | code);
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

uvec2 block_pixel(BlockParams b, uint index) {
    uint along = b.line_first + index / b.span_len;
    uint across = b.span_start + index % b.span_len;
    return b.columns != 0u ? uvec2(along, across) : uvec2(across, along);
}

// Where the exit-point sweep lets a ray stop (0: wherever it is opaque).
float stop_distance(uvec2 px) {
    return TERMINATION == TERMINATION_EXIT_POINTS ? imageLoad(lmax, ivec2(vec2(px) / sweep.ert_scale)).r : 0.0;
}

bool may_stop() { return TERMINATION != TERMINATION_OFF; }

// cache_write = "farthest"/"nearest", one dispatch ahead: marches pixel `index`
// of the next block exactly as shade_pixel will (same samples, same stop) and
// claims each texel where one of its runs ends, for the run's writing sample.
void claim_pixel(BlockParams next, uint index) {
    uvec2 px = block_pixel(next, index);
    if (px.x >= frame.image_size.x || px.y >= frame.image_size.y) return;
    if (zone_weight(next, vec2(px) + 0.5) <= 0.0) return;
    ViewMarch v = pixel_march(px, frame.view_step);
    float keep_going = stop_distance(px);
    bool ert = may_stop();
    float T = 1.0;
    ivec2 run = ivec2(-1);
    float run_depth = 0.0;
    for (int i = 0; i < v.samples; ++i) {
        vec3 p = sample_point(v, i);
        vec4 m = medium(p);
        float alpha = 1.0 - exp(-m.a * v.hv);
        if (alpha > 0.0 || EVERY_SAMPLE) {
            vec3 c = cache_coord(p);
            ivec2 k = sample_texel(c);
            if (run.x >= 0 && k != run) atomicMax(keys[key_index(KEY_HALF_NEXT, run)], claim_key(block_index + 1u, run_depth, index));
            if (k != run || !run_keeps_nearest() || c.z < run_depth) run_depth = c.z;
            run = k;
            T *= 1.0 - alpha;
        }
        if (ert && view_ray_opaque(T) && v.t_enter + (float(i) + 1.0) * v.h >= keep_going) break;
    }
    if (run.x >= 0) atomicMax(keys[key_index(KEY_HALF_NEXT, run)], claim_key(block_index + 1u, run_depth, index));
}

void shade_pixel(uint index) {
    uvec2 px = block_pixel(block, index);
    if (px.x >= frame.image_size.x || px.y >= frame.image_size.y) return;
    float w = zone_weight(block, vec2(px) + 0.5);
    if (w <= 0.0) return;
    bool first_light = (sweep.flags & FLAG_FIRST_LIGHT) != 0u;
    Light light = lights[sweep.light_index];
    ViewMarch v = pixel_march(px, frame.view_step);
    vec3 C = vec3(0.0);
    float T = 1.0;
    // view-samples: the run of samples in one texel, written when it ends.
    ivec2 run = ivec2(-1);
    vec3 run_p = vec3(0.0);
    float run_depth = 0.0;
    vec4 run_light = vec4(0.0);
    bool run_empty = true; // every sample of the run had zero opacity
    if (v.samples > 0) {
        bool ert = may_stop();
        float keep_going = stop_distance(px);
        for (int i = 0; i < v.samples; ++i) {
            vec3 p = sample_point(v, i);
            vec4 m = medium(p);
            float alpha = 1.0 - exp(-m.a * v.hv);
            bool shaded = alpha > 0.0;
            vec4 l = vec4(0.0, 0.0, 0.0, 1.0);
            if (shaded || (VIEW_SAMPLES && EVERY_SAMPLE && !TEXEL_PASS && STEP >= STEP_READS)) {
                if (STEP == 0u) {
                } else if (VIEW_SAMPLES && TEXEL_PASS) {
                    // The texel invocations store (write_claimed_texel): no runs here.
                    l = light_from_samples(p, cache_coord(p));
                } else if (VIEW_SAMPLES) {
                    vec3 c = cache_coord(p);
                    ivec2 k = sample_texel(c);
                    if (run.x >= 0 && k != run) store_sample(run, run_p, run_depth, run_light, index, run_empty);
                    run_empty = (run_empty || k != run) && !shaded;
                    bool writer = k != run || !run_keeps_nearest() || c.z < run_depth;
                    // An empty sample (every-sample) needs its light only where it
                    // may write it as it is (texel-ray writes march their own).
                    if (shaded || (writer && !(WRITE_TEXEL_RAY && PIECEWISE)))
                        l = light_from_samples(p, c);
                    if (writer) {
                        run_p = p;
                        run_depth = c.z;
                        run_light = l;
                    }
                    run = k;
                } else {
                    l = light_at(p);
                }
            }
            if (shaded) {
                vec3 direct = light.radiance.rgb * light_shape(light, toward_light(light, p)) * l.a;
                vec3 S = m.rgb * (direct + l.rgb * sweep.light_scale + (first_light ? vec3(frame.emission) : vec3(0.0)));
                C += T * alpha * S;
                T *= 1.0 - alpha;
            }
            if (ert && view_ray_opaque(T) && v.t_enter + (float(i) + 1.0) * v.h >= keep_going) break;
        }
    }
    if (VIEW_SAMPLES && run.x >= 0) store_sample(run, run_p, run_depth, run_light, index, run_empty);
    // Cleared to the background: the first light replaces it by what shows through.
    if (first_light) C += (T - 1.0) * frame.background;
    ivec2 ip = ivec2(px) + ivec2(0, int(block.out_row));
    imageStore(out_image, ip, imageLoad(out_image, ip) + vec4(w * C, 0.0));
}

// view-samples: the history pair takes the previous block's state of texel k.
ivec2 region_texel(uint index) { return ivec2(block.region.xy + uvec2(index % block.region.z, index / block.region.z)); }

void carry_texel(uint index) {
    ivec2 k = region_texel(index);
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
            vec4 seg = light_segment(x, -r.dir, new_front - old_front, 4096u, EMISSIVE);
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
    cache_store(ivec2(k), cached, code);
}

void main() {
    if (STEP == STEP_EMPTY) return;
    uint id = gl_GlobalInvocationID.x;
    block_index = push.block_index;
    if (MERGED) {
        // The step's sweeps own consecutive workgroup ranges: the last entry
        // starting at or before this workgroup is this invocation's block.
        uint group = gl_WorkGroupID.x;
        uint first_group = 0u;
        block_index = NO_BLOCK;
        for (uint s = 0u; s < step_sweeps; ++s) {
            uvec2 e = step_entries[push.block_index * step_sweeps + s];
            if (e.x != NO_BLOCK && e.y <= group) {
                block_index = e.x;
                first_group = e.y;
            }
        }
        if (block_index == NO_BLOCK) return;
        id = (group - first_group) * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
    }
    block = blocks[block_index];
    sweep = sweeps[block.light];
    uint texels = block.region.z * block.region.w;
    if (id < block.pixel_count) {
        shade_pixel(id);
    } else if (STEP < STEP_CARRY) {
        return;
    } else if (id < block.pixel_count + texels) {
        uint texel = id - block.pixel_count;
        if (VIEW_SAMPLES) {
            carry_texel(texel);
            if (TEXEL_PASS && STEP >= STEP_STORES) write_claimed_texel(region_texel(texel));
        } else {
            advance_texel(texel);
        }
    } else if (CLAIMS && STEP >= STEP_CLAIM_PASS) {
        uint claim = id - block.pixel_count - texels;
        if (claim < block.claim_count) claim_pixel(blocks[block_index + 1u], claim);
    }
}
