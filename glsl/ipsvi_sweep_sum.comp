#version 460
// ipsvi.merge_sweeps: each sweep accumulated its weighted colour into its own
// rows of `accumulation` (sweeps of one step may shade the same pixel in one
// dispatch); this adds them to the output in sweep order, the order in which
// the unmerged frame adds them, so the image is the same bit for bit.

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) readonly uniform image2D accumulation;
layout(set = 0, binding = 1, rgba32f) uniform image2D out_image;

void main() {
    ivec2 size = imageSize(out_image);
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= size.x || p.y >= size.y) return;
    int sweeps = imageSize(accumulation).y / size.y;
    vec4 sum = imageLoad(out_image, p);
    for (int s = 0; s < sweeps; ++s) sum += imageLoad(accumulation, p + ivec2(0, s * size.y));
    imageStore(out_image, p, sum);
}
