// Gradient Blinn-Phong pieces shared by the ray casters (raycast.comp,
// ao_render.comp): the central-difference gradient of the volume and one
// light's diffuse and specular factors at a point.
#ifndef PHONG_GLSL
#define PHONG_GLSL
#include "volume.glsl"
#include "lights.glsl"

vec3 gradient(vec3 uvw) {
    vec3 e = 1.0 / frame.dims;
    return vec3(
        volume_smooth_at_uvw(uvw + vec3(e.x, 0, 0)) - volume_smooth_at_uvw(uvw - vec3(e.x, 0, 0)),
        volume_smooth_at_uvw(uvw + vec3(0, e.y, 0)) - volume_smooth_at_uvw(uvw - vec3(0, e.y, 0)),
        volume_smooth_at_uvw(uvw + vec3(0, 0, e.z)) - volume_smooth_at_uvw(uvw - vec3(0, 0, e.z))) * 0.5;
}

// Light i at p, shading normal n, view direction d: its radiance with falloff
// and cone (rgb), the Lambert factor max(n.w, 0) and the Blinn-Phong
// highlight, and the unit vector w toward the light.
struct LightTerm { vec3 lit; float lambert; float spec; vec3 w; };

LightTerm light_term(int i, vec3 p, vec3 n, vec3 d) {
    vec4 w = toward_light(lights[i], p);
    vec3 lit = lights[i].radiance.rgb * light_shape(lights[i], w);
    // A light straight behind the view ray has no half vector: no highlight.
    vec3 hw = w.xyz - d;
    float spec = length(hw) > 1e-6 ? pow(max(dot(n, normalize(hw)), 0.0), frame.shininess) : 0.0;
    return LightTerm(lit, max(dot(n, w.xyz), 0.0), spec, w.xyz);
}

// `ambient` plus every light's Blinn-Phong diffuse and specular for colour rgb.
vec3 blinn_phong_lights(vec3 ambient, vec3 p, vec3 n, vec3 rgb, vec3 d) {
    vec3 s = ambient;
    for (int i = 0; i < int(frame.light_count); ++i) {
        LightTerm t = light_term(i, p, n, d);
        s += t.lit * (rgb * frame.diffuse * t.lambert + frame.specular * t.spec);
    }
    return s;
}

#endif
