#version 460
#extension GL_GOOGLE_include_directive : require
// AO nearest-codeword assignment (section 3.2) of one part of a slice's packed
// hemisphere histograms, one invocation per histogram (2 voxel + side). The
// same exact search as the CPU (src/techniques/ao/search.rs): start at a hint codeword h
// (the codeword of the same voxel and hemisphere in the previous slice, the
// sweep's coherence), walk h's list of codewords sorted by distance to h and
// stop where the triangle inequality says no later one can win; ties to the
// lowest index. Every float operation in the CPU's order, without contraction,
// so both searches pick the same codeword for the same vector. The walk is
// split into chunks of list entries over dispatches (llvmpipe's loop cap),
// its state carried in `states`.
//
// A histogram equal to the one `copy_stride` before it (the same hemisphere
// of the previous voxel) is not searched: the nearest codeword depends only
// on the vector (ties to the lowest index), so after the walk a run-copy
// dispatch (`run_copy`) gives it the result of its run's first histogram, as
// the CPU's assignment reuses its previous voxel's codeword. Runs restart
// every RUN_WINDOW voxels, which bounds the copy's walk back to its run's
// start.

layout(local_size_x = 64) in;

layout(constant_id = 0) const uint METRIC = 0;  // 0: L2 (squared), 1: L1, 2: Lmax
// (1 + SLACK) and (1 - SLACK) of search.rs, as the CPU rounds them.
layout(constant_id = 1) const float SLACK_UP = 1.0;
layout(constant_id = 2) const float SLACK_DOWN = 1.0;

layout(push_constant) uniform Assign {
    int first;           // first histogram of the part in the batch buffers
    int count;           // histograms in the part
    int hint_first;      // the part's first hint in `hints_in` (the slice before)
    int hint_out_first;  // ... and where its results go in `hints_out` (this slice)
    int has_hints;       // 0 on the first slice: start at codeword 0
    int first_entry;     // list entries [first_entry, first_entry + entries) this dispatch
    int entries;
    int first_chunk;     // 1: start the search
    int last_chunk;      // 1: leave the result as the next slice's hint
    int clusters;        // n_c
    int packed_stride;   // floats per packed histogram and codeword (multiple of 8)
    int copy_stride;     // histograms from one to the next it may copy (2: voxel after voxel); 0: none
    int run_copy;        // 1: this dispatch gives each copy its run's result (after the walk)
} assign;

const int RUN_WINDOW = 32;  // voxels (histograms / copy_stride) per window of runs

// SearchState.done
const uint SEARCHING = 0u;
const uint FOUND = 1u;
const uint COPY = 2u;  // equal to the histogram copy_stride before: takes its run's result

struct SearchState {
    uint hint;
    float to_hint;    // true distance to the hint
    uint best;
    float best_raw;   // distance in the metric's raw form (L2 squared)
    uint done;
};

layout(std430, set = 0, binding = 0) readonly buffer Packed { float packed[]; };
layout(std430, set = 0, binding = 1) readonly buffer Codewords { float codewords[]; };
// Row h: every codeword by ascending distance to codeword h, and those distances.
layout(std430, set = 0, binding = 2) readonly buffer Order { uint order[]; };
layout(std430, set = 0, binding = 3) readonly buffer OrderDistances { float order_distances[]; };
layout(std430, set = 0, binding = 4) buffer States { SearchState states[]; };
// The run-copy dispatch reads the walk's results through a read-only binding
// of the same buffer, so that synchronization validation sees the read and
// reports a missing `search_state_write_to_run_copy_read`.
layout(std430, set = 0, binding = 7) readonly buffer StatesIn { SearchState states_in[]; };
// The hints ping-pong between the two halves of one buffer (a slice reads the
// half the slice before wrote and writes the other), bound twice so that the
// read and the write are separate bindings: synchronization validation then
// reports a missing `search_hints_write_to_next_slice_read`.
layout(std430, set = 0, binding = 5) readonly buffer HintsIn { uint hints_in[]; };
layout(std430, set = 0, binding = 6) writeonly buffer HintsOut { uint hints_out[]; };

#define MIN_POSITIVE uintBitsToFloat(0x00800000u)  // f32::MIN_POSITIVE
#define INFINITY uintBitsToFloat(0x7f800000u)

float term(float a, float b) {
    precise float d = a - b;
    precise float t = METRIC == 0 ? d * d : abs(d);
    return t;
}

// quantize.rs distance_within: per chunk of 8 components, the chunk's terms
// summed left to right, then added to the total (Lmax: the running maximum);
// returns early once the total exceeds `bound`.
float distance_within(int x, int c, float bound) {
    float sum = 0.0;
    for (int i = 0; i < assign.packed_stride; i += 8) {
        if (METRIC == 2) {
            for (int t = 0; t < 8; ++t) sum = max(sum, abs(packed[x + i + t] - codewords[c + i + t]));
        } else {
            precise float part = term(packed[x + i], codewords[c + i]);
            part += term(packed[x + i + 1], codewords[c + i + 1]);
            part += term(packed[x + i + 2], codewords[c + i + 2]);
            part += term(packed[x + i + 3], codewords[c + i + 3]);
            part += term(packed[x + i + 4], codewords[c + i + 4]);
            part += term(packed[x + i + 5], codewords[c + i + 5]);
            part += term(packed[x + i + 6], codewords[c + i + 6]);
            part += term(packed[x + i + 7], codewords[c + i + 7]);
            precise float total = sum + part;
            sum = total;
        }
        if (sum > bound) return sum;
    }
    return sum;
}

float true_distance(float raw) {
    return METRIC == 0 ? sqrt(raw) : raw;
}

// Whether histogram i of the range equals the one copy_stride before it,
// within its window of runs; compared in chunks of 8 (the loop budget counts
// stride / 8 iterations, as for one distance).
bool same_as_previous(int i, int x) {
    if (assign.copy_stride == 0 || (i / assign.copy_stride) % RUN_WINDOW == 0) return false;
    int y = x - assign.copy_stride * assign.packed_stride;
    for (int c = x; c < x + assign.packed_stride; c += 8) {
        int d = c - x + y;
        bvec4 low = equal(vec4(packed[c], packed[c + 1], packed[c + 2], packed[c + 3]),
                          vec4(packed[d], packed[d + 1], packed[d + 2], packed[d + 3]));
        bvec4 high = equal(vec4(packed[c + 4], packed[c + 5], packed[c + 6], packed[c + 7]),
                           vec4(packed[d + 4], packed[d + 5], packed[d + 6], packed[d + 7]));
        if (!all(low) || !all(high)) return false;
    }
    return true;
}

// The run-copy dispatch: a copy takes the codeword and distance of its run's
// first histogram (searched, within RUN_WINDOW voxels before it). Reads only
// the copies' `done` and the searched histograms' results, writes only the
// copies' results: no invocation reads what another writes.
void copy_run_result(int i, int histogram) {
    if (states_in[histogram].done != COPY) return;
    int first = histogram - assign.copy_stride;
    while (states_in[first].done == COPY) first -= assign.copy_stride;
    uint best = states_in[first].best;
    states[histogram].best = best;
    states[histogram].best_raw = states_in[first].best_raw;
    hints_out[assign.hint_out_first + i] = best;
}

void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i >= assign.count) return;
    int histogram = assign.first + i;
    if (assign.run_copy != 0) {
        copy_run_result(i, histogram);
        return;
    }
    int x = histogram * assign.packed_stride;
    SearchState s;
    if (assign.first_chunk != 0 && same_as_previous(i, x)) {
        s = SearchState(0u, 0.0, 0u, 0.0, COPY);
    } else if (assign.first_chunk != 0) {
        uint h = assign.has_hints != 0 ? min(hints_in[assign.hint_first + i], uint(assign.clusters - 1)) : 0u;
        s.hint = h;
        s.best = h;
        s.best_raw = distance_within(x, int(h) * assign.packed_stride, INFINITY);
        s.to_hint = true_distance(s.best_raw);
        s.done = SEARCHING;
    } else {
        s = states[histogram];
    }
    if (s.done == SEARCHING) {
        int row = int(s.hint) * assign.clusters;
        int end = min(assign.first_entry + assign.entries, assign.clusters);
        for (int k = assign.first_entry; k < end; ++k) {
            float apart = order_distances[row + k];
            float best_true = true_distance(s.best_raw);
            // d(x, c_j) >= |d(c_h, c_j) - d(x, c_h)|: only the shell
            // to_hint - best < apart < to_hint + best can hold a better codeword.
            precise float upper = (best_true + s.to_hint) * SLACK_UP + MIN_POSITIVE;
            if (apart > upper) {
                s.done = FOUND;
                break;
            }
            uint j = order[row + k];
            precise float lower = (s.to_hint - best_true) * SLACK_DOWN - MIN_POSITIVE;
            if (j == s.best || apart < lower) continue;
            float d = distance_within(x, int(j) * assign.packed_stride, s.best_raw);
            if (d < s.best_raw || (d == s.best_raw && j < s.best)) {
                s.best = j;
                s.best_raw = d;
            }
        }
    }
    states[histogram] = s;
    // A copy's hint is written by the run-copy dispatch.
    if (assign.last_chunk != 0 && s.done != COPY) hints_out[assign.hint_out_first + i] = s.best;
}
