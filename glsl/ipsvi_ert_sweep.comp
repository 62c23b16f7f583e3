#version 460
#extension GL_GOOGLE_include_directive : require
// Exit-point sweep (IPSVI paper, section 5.1), one dispatch per low-resolution
// line, toward the light: for pixel p and its predecessor p' on the line
// processed before (farther from the light),
//     l_max(p) = min(s_b(p), max(s_f(p'), l_max(p'))),
// the distance up to which p's ray must go on past its own termination point
// so that what lies behind it can still light the rays farther from the light.

layout(local_size_x = 64) in;

layout(set = 0, binding = 0, rg32f) readonly uniform image2D depths;
// Ping-pong pair: this line reads the previous line's l_max from one side and
// writes its own to the other; `lmax` keeps every line's result. Compiled twice
// by build.rs (PARITY 0 reads a and writes b, 1 the opposite), each variant
// referencing only its own sides, so validation sees what each line touches.
// Each binding has one name in both builds (the Rust side binds by name).
#if PARITY == 0
layout(set = 0, binding = 1, r32f) readonly uniform image2D lmax_a_read;
layout(set = 0, binding = 4, r32f) writeonly uniform image2D lmax_b_write;
#define lmax_in lmax_a_read
#define lmax_out lmax_b_write
#else
layout(set = 0, binding = 2, r32f) readonly uniform image2D lmax_b_read;
layout(set = 0, binding = 3, r32f) writeonly uniform image2D lmax_a_write;
#define lmax_in lmax_b_read
#define lmax_out lmax_a_write
#endif
layout(set = 0, binding = 5, r32f) writeonly uniform image2D lmax;

layout(push_constant) uniform Push {
    vec2 anchor;      // light anchor in low-resolution pixels (zones only)
    uint line;        // this line's index (row or column)
    int previous;     // the line processed before, or -1
    uint span_start;
    uint span_len;
    uint columns;     // 1: lines are columns
    uint zone;        // 0: parallel lines; else a zone around the anchor
} push;

float load_prev(ivec2 p) { return imageLoad(lmax_in, p).r; }

void store(ivec2 p, float v) {
    imageStore(lmax_out, p, vec4(v));
    imageStore(lmax, p, vec4(v));
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= push.span_len) return;
    uint across = push.span_start + i;
    ivec2 p = push.columns != 0u ? ivec2(push.line, across) : ivec2(across, push.line);
    vec2 d = imageLoad(depths, p).rg;
    float l = 0.0;
    if (push.previous >= 0) {
        // The predecessor lies on the line through p and the anchor (zones), or
        // straight across (parallel lines).
        float a = float(across) + 0.5;
        if (push.zone != 0u) {
            vec2 anchor = push.columns != 0u ? push.anchor : push.anchor.yx;
            float along = float(push.line) + 0.5 - anchor.x;
            float along_prev = float(push.previous) + 0.5 - anchor.x;
            a = anchor.y + (a - anchor.y) * (abs(along) > 1e-3 ? along_prev / along : 1.0);
        }
        ivec2 size = imageSize(depths);
        int ai = clamp(int(floor(a)), 0, (push.columns != 0u ? size.y : size.x) - 1);
        ivec2 q = push.columns != 0u ? ivec2(push.previous, ai) : ivec2(ai, push.previous);
        l = max(imageLoad(depths, q).r, load_prev(q));
    }
    store(p, min(d.g, l));
}
