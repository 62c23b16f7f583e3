// The shape report of an IPSVI frame, shared by the line kernels and the
// view-stops pass (glsl/ipsvi_view_stops.comp). Needs 64-bit integers and atomics.
#ifndef IPSVI_SHAPE_GLSL
#define IPSVI_SHAPE_GLSL

// The frame's shape (src/techniques/ipsvi/line_shape.rs), cleared every frame:
// flags (SHAPE_*), then per block record CHAIN_SLOTS maxima of the serial
// chains its invocations ran (view samples marched, in every pass, plus the
// steps of every march toward the light), CHAIN_ROLE_SLOTS for each role
// (CHAIN_*: which part of a block the invocation did); the host takes the
// largest of each role's. Spread over slots so that a GPU does not serialize a
// dispatch's atomics on one address. With DIGESTS (tests only) also order-free
// sums of a hash of every claim and of where every view ray stopped, which two
// kernels, or two splits of the rays, must give alike.
layout(constant_id = 18) const bool DIGESTS = false;
layout(std430, set = 0, binding = 27) buffer Shape {
    uint64_t claim_digest;
    uint64_t stop_digest;
    uint shape_flags;
    uint stops_chains[16]; // the view-stops pass's (glsl/ipsvi_view_stops.comp), CHAIN_ROLE_SLOTS of them
    uint chains[];
};
const uint SHAPE_PARTIAL_SUBGROUPS = 1u; // the segmented kernel found a subgroup it cannot split a ray over
const uint CHAIN_PIXELS = 0u; // shade_pixel
const uint CHAIN_TEXELS = 1u; // the cache texels of the block's region
const uint CHAIN_CLAIMS = 2u; // claim_pixel, for the next block
const uint CHAIN_ROLES = 3u;
const uint CHAIN_ROLE_SLOTS = 16u;
const uint CHAIN_SLOTS = CHAIN_ROLES * CHAIN_ROLE_SLOTS;

// Slot `i` (any number: taken modulo) of `role`'s slots of block record `record`.
uint chain_slot(uint record, uint role, uint i) {
    return record * CHAIN_SLOTS + role * CHAIN_ROLE_SLOTS + i % CHAIN_ROLE_SLOTS;
}

// splitmix64's finalizer.
uint64_t digest_hash(uint64_t x) {
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9UL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebUL;
    return x ^ (x >> 31);
}

// Pixel `pixel` of block `record` marched its first `samples` view samples.
void digest_stop(uint record, uint pixel, int samples) {
    if (DIGESTS) atomicAdd(stop_digest, digest_hash((uint64_t(record) << 40) ^ (uint64_t(pixel) << 20) ^ uint64_t(samples)));
}

#endif
