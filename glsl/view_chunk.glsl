// One dispatch's share of a chunked view march. llvmpipe silently ends an
// invocation after 65,535 loop iterations, so a long march is split across
// dispatches (src/render/view_chunks.rs plans them): each marches samples
// [first_sample, first_sample + sample_count) and carries (colour,
// transmittance) to the next through a ping-pong pair (the output and a state
// image, one read, the other written); a barrier separates the dispatches.
#ifndef VIEW_CHUNK_GLSL
#define VIEW_CHUNK_GLSL

layout(push_constant) uniform ViewChunk {
    uint first_sample;
    uint sample_count;
    uint is_first;  // start from (0, 0, 0, T = 1) instead of reading the image
    uint is_last;   // add the background behind the ray
} chunk;

// End (exclusive) of this chunk's samples on a ray of `samples` samples.
int chunk_end(int samples) { return int(min(chunk.first_sample + chunk.sample_count, uint(samples))); }

#endif
