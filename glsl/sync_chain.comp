#version 460
// The sync study's calibration workload (src/bench/experiments/sync/chain.rs):
// per line, every invocation runs a dependent chain of `trips` x STEPS_PER_TRIP
// fused multiply-adds, each waiting for the one before, seeded by what the
// previous line wrote, and writes its end for the next line. A line's time
// then grows linearly with `trips`, with no memory traffic inside the chain.
//
// The steps add 1 each (scale and offset are 1, pushed so that no compiler
// can fold the chain); the chain starts from the previous line's value minus
// its own length plus one, so each line adds exactly 1: after N lines an
// invocation holds its seed plus N, whatever the chain's length (exact in
// float below 2^24), which the host checks. A chain cut short (lavapipe ends
// an invocation after 65,535 loop iterations; one trip is one iteration) or
// a line that read a stale value would leave a different number.
layout(local_size_x = 64) in;

// Kept in step with src/bench/experiments/sync/chain.rs STEPS_PER_TRIP.
#define STEPS_PER_TRIP 64

layout(set = 0, binding = 0) readonly buffer Seeds { float seed[]; } seeds;
layout(set = 1, binding = 0) readonly buffer ValuesIn { float value[]; } values_in;
layout(set = 1, binding = 1) writeonly buffer ValuesOut { float value[]; } values_out;

layout(push_constant) uniform Chain {
    uint trips;
    uint invocations;
    // 1 on a frame's first line: it starts from the seeds.
    uint first_line;
    float scale;
    float offset;
} chain;

#define STEP x = fma(x, a, b);
#define STEP4 STEP STEP STEP STEP
#define STEP16 STEP4 STEP4 STEP4 STEP4
#define STEP64 STEP16 STEP16 STEP16 STEP16

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= chain.invocations) {
        return;
    }
    float previous = chain.first_line != 0u ? seeds.seed[i] : values_in.value[i];
    float x = previous - float(chain.trips * STEPS_PER_TRIP) + 1.0;
    float a = chain.scale;
    float b = chain.offset;
    for (uint t = 0u; t < chain.trips; ++t) {
        STEP64
    }
    values_out.value[i] = x;
}
