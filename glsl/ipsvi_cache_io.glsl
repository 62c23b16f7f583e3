// IPSVI line kernels: loads and stores of the cache pairs (history: value and
// front; view samples: value and stamp | depth), packed or not, and the
// 16-bit depth codes of view-sample writes.
#ifndef IPSVI_CACHE_IO_GLSL
#define IPSVI_CACHE_IO_GLSL

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

#endif
