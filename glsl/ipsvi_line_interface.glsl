// The interface both IPSVI line kernels share (glsl/ipsvi_line.comp, serial:
// one invocation per pixel; glsl/ipsvi_line_segmented.comp: several per
// pixel): the specialization constants fixed per renderer, the bindings, the
// block records and the per-block globals. src/techniques/ipsvi/ binds the same sets to
// either pipeline.
#ifndef IPSVI_LINE_INTERFACE_GLSL
#define IPSVI_LINE_INTERFACE_GLSL

layout(constant_id = 0) const bool EMISSIVE = true;  // model (ii): light carries emission
layout(constant_id = 1) const bool SCATTER = false;  // albedo-blended forward-cone scattering
layout(constant_id = 2) const bool VIEW_SAMPLES = false;  // cache_update = "view-samples"
layout(constant_id = 3) const bool CLAIMS = false;        // cache_write = "farthest" or "nearest": one writer per texel
layout(constant_id = 4) const bool NEAREST = false;       // "nearest": the sample closest to the light wins
// Cost breakdown (src/techniques/ipsvi/breakdown.rs), cumulative: 0 ray casting only,
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
// ipsvi.merge_sweeps (src/techniques/ipsvi/merged_steps.rs): a dispatch is step k of every
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

// cache_write = "farthest"/"nearest": per texel, the claim of the sample that
// stores into it, two halves (this block's claims, the next block's), cleared
// every frame: 20 bits record number + 1 | 27 bits depth along the light ray
// (inverted for "nearest") | 17 bits pixel; the largest key wins.
layout(std430, set = 0, binding = 25) buffer Keys { uint64_t keys[]; };

#include "ipsvi_shape.glsl"

// This invocation's serial chain so far and its role (see Shape).
uint chain = 0u;
uint chain_role = CHAIN_PIXELS;

BlockParams block;

// Texel k of the block's sweep's cache in the cache images.
ivec2 slot_texel(ivec2 k) { return k + ivec2(0, int(block.cache_row)); }

#endif
