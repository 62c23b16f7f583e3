// Front-to-back compositing of stretches of view samples: the over operator,
// associative, so a ray's samples may be composited in pieces and the pieces
// combined in depth order. No bindings: glsl/ipsvi_segment_scan_probe.comp
// tests the combines with it.
#ifndef IPSVI_OVER_GLSL
#define IPSVI_OVER_GLSL

// Radiance toward the eye (C) and transmittance (T) of a stretch of samples.
struct Composite {
    vec3 C;
    float T;
};

Composite no_samples() { return Composite(vec3(0.0), 1.0); }

// `back` seen through `front`.
Composite over(Composite front, Composite back) { return Composite(front.C + front.T * back.C, front.T * back.T); }

// Sample of opacity alpha and radiance S behind what `c` holds.
void composite_sample(inout Composite c, float alpha, vec3 S) {
    c.C += c.T * alpha * S;
    c.T *= 1.0 - alpha;
}

#endif
