// IPSVI line kernels: which invocation of a block's dispatch does what, and the
// shape report. A block's invocations (ids within its share of the dispatch):
//   [0, P * SEGMENTS)        its P pixels, SEGMENTS invocations each (shade_pixel)
//   [.., + T * TEXEL_LANES)  the T texels of its cache region, TEXEL_LANES each
//                            (carry or advance; texel pass: the stores its claims
//                            name), their marches toward the light split over them
//   [aligned up to SEGMENTS, + C * SEGMENTS)
//                            the C pixels of the next block, claimed for (claim_pixel)
// The including kernel defines SEGMENTS, TEXEL_LANES, `segment` (this invocation's index
// among its pixel's), line_local_index(), line_kernel_ready(), shade_pixel,
// claim_pixel and report_chain (this invocation's chain into Shape), then
// includes this file for main(). No workgroup barrier: on lavapipe a shader
// with one runs as coroutines, measured 1.12-1.20x the serial kernel's CPU
// time at 256 (docs/bench/lavapipe-engine/ipsvi_line_kernels_256_alternating.*).
#ifndef IPSVI_LINE_MAIN_GLSL
#define IPSVI_LINE_MAIN_GLSL

// Invocations a block needs before its claim invocations (src/techniques/ipsvi/merged_steps.rs mirrors it).
uint claims_first(uint pixel_and_texel_invocations) {
    return (pixel_and_texel_invocations + SEGMENTS - 1u) / SEGMENTS * SEGMENTS;
}

void line_invocation(uint id) {
    uint texels = block.region.z * block.region.w;
    uint pixel_invocations = block.pixel_count * SEGMENTS;
    if (id < pixel_invocations) {
        shade_pixel(id / SEGMENTS);
        return;
    }
    if (STEP < STEP_CARRY) return;
    chain_role = CHAIN_TEXELS;
    if (id < pixel_invocations + texels * TEXEL_LANES) {
        uint texel = (id - pixel_invocations) / TEXEL_LANES;
        march_lanes = TEXEL_LANES;
        march_lane = (id - pixel_invocations) % TEXEL_LANES;
        if (VIEW_SAMPLES) {
            carry_texel(texel);
            if (TEXEL_PASS && STEP >= STEP_STORES) write_claimed_texel(region_texel(texel));
        } else {
            advance_texel(texel);
        }
        return;
    }
    chain_role = CHAIN_CLAIMS;
    uint first = claims_first(pixel_invocations + texels * TEXEL_LANES);
    if (CLAIMS && STEP >= STEP_CLAIM_PASS && id >= first) {
        uint claim = (id - first) / SEGMENTS;
        if (claim < block.claim_count) claim_pixel(blocks[block_index + 1u], claim);
    }
}

// The block's loads are unconditional and unmerged ids are the dispatch's own
// (gl_GlobalInvocationID): with the loads, the work and the report behind one
// `has_block` branch, lavapipe ran the serial kernel at 1.12x the line time of
// the build before the kernels shared this file (engine 256, median of 8
// rotated rounds), 1.01x in this shape (docs/ipsvi.md, "The line kernels").
void main() {
    load_frame();
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
    // Both returns are uniform over the workgroup: no subgroup operation
    // below runs short of lanes.
    if (!line_kernel_ready()) return;
    block = blocks[block_index];
    sweep = sweeps[block.light];
    // The kernel's own order of a workgroup's invocations (the segmented one's
    // by subgroup lane; the serial one's is the local index: id itself).
    line_invocation(id - gl_LocalInvocationID.x + line_local_index());
    report_chain();
}

#endif
