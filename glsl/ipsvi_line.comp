#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
// One IPSVI line block (one dispatch; src/techniques/ipsvi/), the serial kernel: one
// invocation per pixel marches its whole view ray, reading the illumination
// cache as it stands at the previous line. The next invocations keep the
// history pair (cache/front) whole: with cache_update = "light-rays" they
// advance the light rays of the block's cache region to this block's last
// line; with "view-samples" they merge the previous block's sample writes into
// it. With "view-samples" the view samples themselves write the light leaving
// them (Listing 4.1) into the sample pair (write_pass = "sample"), or the
// texel invocations store the texels the claim march names (write_pass =
// "texel"); with cache_write = "farthest" the last invocations claim, for the
// next block's pixels, which sample writes each texel. Reads and writes go to
// different images, so a block races only where the paper does
// (cache_write = "racy": many samples, one texel).
//
// The pieces both kernels share (glsl/ipsvi_line_segmented.comp marches each
// ray in segments, several invocations per pixel) are the includes below.

// Invocations per workgroup, chosen per renderer (src/techniques/ipsvi/line_group.rs): on
// lavapipe a workgroup runs on one thread, so a short line in one wide group
// leaves the other cores idle.
layout(local_size_x_id = 8) in;

#include "ipsvi_line_interface.glsl"
#include "ipsvi_cache_io.glsl"
#include "ipsvi_piecewise.glsl"
#include "ipsvi_cache_read.glsl"
#include "ipsvi_writes.glsl"
#include "ipsvi_march.glsl"
#include "ipsvi_compositing.glsl"

// One invocation per pixel.
const uint SEGMENTS = 1u;
const uint TEXEL_LANES = 1u;
uint line_local_index() { return gl_LocalInvocationID.x; }
bool line_kernel_ready() { return true; }
// One atomic per invocation that ran a chain, into one of the block's slots.
void report_chain() {
    if (chain > 0u) atomicMax(chains[chain_slot(block_index, chain_role, gl_LocalInvocationIndex)], chain);
}

// cache_write = "farthest"/"nearest", one dispatch ahead: marches pixel `index`
// of the next block exactly as shade_pixel will (same samples, same stop) and
// claims each texel where one of its runs ends, for the run's writing sample.
void claim_pixel(BlockParams next, uint index) {
    uvec2 px;
    float w;
    if (!pixel_in_block(next, index, px, w)) return;
    ViewMarch v = pixel_march(px, frame.view_step);
    float keep_going = stop_distance(px);
    uint tau = 0u;
    ivec2 run = ivec2(-1);
    float run_depth = 0.0;
    for (int i = 0; i < v.samples; ++i) {
        vec3 p = sample_point(v, i);
        vec4 m = medium(p);
        float alpha = 1.0 - exp(-m.a * v.hv);
        chain += 1u;
        if (alpha > 0.0 || EVERY_SAMPLE) {
            vec3 c = cache_coord(p);
            ivec2 k = sample_texel(c);
            if (run.x >= 0 && k != run) claim_run(run, run_depth, index);
            if (k != run || !run_keeps_nearest() || c.z < run_depth) run_depth = c.z;
            run = k;
        }
        tau = tau_add(tau, tau_units(m.a * v.hv));
        if (ray_stops(tau, v, i, keep_going)) break;
    }
    if (run.x >= 0) claim_run(run, run_depth, index);
}

void shade_pixel(uint index) {
    uvec2 px;
    float w;
    if (!pixel_in_block(block, index, px, w)) return;
    bool first_light = (sweep.flags & FLAG_FIRST_LIGHT) != 0u;
    Light light = lights[sweep.light_index];
    ViewMarch v = pixel_march(px, frame.view_step);
    Composite pixel = no_samples();
    // write_pass = "sample": the run of samples in one texel, written when it ends.
    ivec2 run = ivec2(-1);
    vec3 run_p = vec3(0.0);
    float run_depth = 0.0;
    vec4 run_light = vec4(0.0);
    bool run_empty = true; // every sample of the run had zero opacity
    bool sample_writes = VIEW_SAMPLES && !TEXEL_PASS && STEP >= STEP_READS;
    int marched = 0; // view samples marched before the ray stopped
    if (v.samples > 0) {
        float keep_going = stop_distance(px);
        uint tau = 0u;
        marched = v.samples;
        for (int i = 0; i < v.samples; ++i) {
            vec3 p = sample_point(v, i);
            vec4 m = medium(p);
            float alpha = 1.0 - exp(-m.a * v.hv);
            bool shaded = alpha > 0.0;
            chain += 1u;
            vec4 l = vec4(0.0, 0.0, 0.0, 1.0);
            if (sample_writes && (shaded || EVERY_SAMPLE)) {
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
            } else if (shaded) {
                // Reads only: the texel invocations store (write_claimed_texel), or light rays.
                l = read_light(p);
            }
            if (shaded) composite_sample(pixel, alpha, sample_radiance(light, p, m, l, first_light));
            tau = tau_add(tau, tau_units(m.a * v.hv));
            if (ray_stops(tau, v, i, keep_going)) {
                marched = i + 1;
                break;
            }
        }
    }
    digest_stop(block_index, index, marched);
    // `sample_writes` is what sets `run`; named here, it leaves the store out of
    // the variants whose samples never write (write_pass = "texel", early
    // breakdown steps), which lavapipe's compiler kept behind `run.x >= 0`
    // alone: a fifth of the default variant's LLVM work (docs/testing.md).
    if (sample_writes && run.x >= 0) store_sample(run, run_p, run_depth, run_light, index, run_empty);
    finish_pixel(px, w, pixel, first_light);
}

#include "ipsvi_line_main.glsl"
