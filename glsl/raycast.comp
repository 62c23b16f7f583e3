#version 460
#extension GL_GOOGLE_include_directive : require
// Baseline ray caster, one dispatch per frame, front to back: unshaded
// emission-absorption DVR (SHADING = 0), gradient Blinn-Phong (SHADING = 1), or
// the emission term alone (SHADING = 2: what the illumination techniques render
// for a scene without lights).

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const uint SHADING = 0;

#include "volume.glsl"
#include "lights.glsl"

layout(set = 0, binding = 4, rgba32f) writeonly uniform image2D out_image;

const float EARLY_TERMINATION_TRANSMITTANCE = 1e-4;

vec3 gradient(vec3 uvw) {
    vec3 e = 1.0 / frame.dims.xyz;
    return vec3(
        textureLod(volume_tex, uvw + vec3(e.x, 0, 0), 0.0).r - textureLod(volume_tex, uvw - vec3(e.x, 0, 0), 0.0).r,
        textureLod(volume_tex, uvw + vec3(0, e.y, 0), 0.0).r - textureLod(volume_tex, uvw - vec3(0, e.y, 0), 0.0).r,
        textureLod(volume_tex, uvw + vec3(0, 0, e.z), 0.0).r - textureLod(volume_tex, uvw - vec3(0, 0, e.z), 0.0).r) * 0.5;
}

vec3 blinn_phong(vec3 p, vec3 rgb, vec3 d) {
    float ambient = frame.phong.x, diffuse = frame.phong.y, specular = frame.phong.z, shininess = frame.phong.w;
    vec3 g = gradient(to_uvw(p));
    int count = int(frame.march.w);
    if (length(g) < 1e-6 || count == 0) return rgb * (ambient + diffuse);
    vec3 n = -normalize(g);
    if (dot(n, -d) < 0.0) n = -n;
    vec3 s = rgb * ambient;
    for (int i = 0; i < count; ++i) {
        vec4 w = toward_light(lights[i], p);
        vec3 lit = lights[i].radiance.rgb * light_shape(lights[i], w);
        // A light straight behind the view ray has no half vector: no highlight.
        vec3 hw = w.xyz - d;
        float spec = length(hw) > 1e-6 ? pow(max(dot(n, normalize(hw)), 0.0), shininess) : 0.0;
        s += lit * (rgb * diffuse * max(dot(n, w.xyz), 0.0) + specular * spec);
    }
    return s;
}

void main() {
    uvec2 px = gl_GlobalInvocationID.xy;
    if (px.x >= frame.image_size.x || px.y >= frame.image_size.y) return;
    Ray r = camera_ray(px);
    vec2 t = intersect_box(r.origin, r.dir);
    vec3 C = vec3(0.0);
    float T = 1.0;
    if (t.x < t.y) {
        float vl = frame.box_half.w;
        float L = t.y - t.x;
        float N = max(1.0, ceil(L / (frame.march.x * vl)));
        float h = L / N;
        float hv = h / vl;
        int n = int(N);
        for (int i = 0; i < n; ++i) {
            vec3 p = r.origin + r.dir * (t.x + (float(i) + 0.5) * h);
            vec4 m = medium(p);
            float alpha = 1.0 - exp(-m.a * hv);
            if (alpha > 0.0) {
                vec3 S = SHADING == 1 ? blinn_phong(p, m.rgb, r.dir) : SHADING == 2 ? m.rgb * frame.background.w : m.rgb;
                C += T * alpha * S;
                T *= 1.0 - alpha;
            }
            if (T < EARLY_TERMINATION_TRANSMITTANCE) break;
        }
    }
    C += T * frame.background.rgb;
    imageStore(out_image, ivec2(px), vec4(C, T));
}
