// Lights (binding 3): mirrors `GpuLight` in src/render/frame_params.rs.
#ifndef LIGHTS_GLSL
#define LIGHTS_GLSL
#include "frame.glsl"

struct Light {
    vec4 pos_type;        // xyz position (point/spot) or travel direction (directional); w type
    vec4 spot_dir;        // xyz spot axis (unit); w cos(inner)
    vec4 radiance;        // rgb colour * intensity; w cos(outer)
    vec4 params;          // x 1 = inverse-square falloff
};
layout(std430, set = 0, binding = 3) readonly buffer Lights { Light lights[]; };

const float LIGHT_DIRECTIONAL = 0.0;
const float LIGHT_POINT = 1.0;
const float LIGHT_SPOT = 2.0;

// toward_light for a directional light (the same everywhere).
vec4 toward_directional_light(Light l) {
    return vec4(-normalize(l.pos_type.xyz), 3.0e38);
}

// Unit vector toward the light and the distance to it (3e38 for directional).
vec4 toward_light(Light l, vec3 p) {
    if (l.pos_type.w == LIGHT_DIRECTIONAL) return toward_directional_light(l);
    vec3 d = l.pos_type.xyz - p;
    float len = length(d);
    return vec4(len > 0.0 ? d / len : vec3(0.0, 1.0, 0.0), len);
}

// Falloff and spot cone at p, given (w, dist) from toward_light.
float light_shape(Light l, vec4 w_dist) {
    float f = 1.0;
    if (l.pos_type.w != LIGHT_DIRECTIONAL && l.params.x > 0.5) {
        float d = max(w_dist.w, frame.voxel_length);
        f = 1.0 / (d * d);
    }
    if (l.pos_type.w == LIGHT_SPOT) {
        float c = dot(-w_dist.xyz, l.spot_dir.xyz);
        float ci = l.spot_dir.w;
        float co = l.radiance.w;
        if (ci <= co) {
            f *= c >= co ? 1.0 : 0.0;
        } else {
            float t = clamp((c - co) / (ci - co), 0.0, 1.0);
            f *= t * t * (3.0 - 2.0 * t);
        }
    }
    return f;
}

#endif
