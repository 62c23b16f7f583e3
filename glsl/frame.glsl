// Frame parameters shared by the ray casters (binding 0), camera rays and the
// volume box. Mirrors `FrameParams` in src/render/frame_params.rs (std140).
#ifndef FRAME_GLSL
#define FRAME_GLSL

layout(std140, set = 0, binding = 0) uniform Frame {
    vec4 cam_origin;   // xyz; w = 1 for orthographic
    vec4 cam_forward;  // unit
    vec4 cam_right;    // scaled by half width (ortho) or tan(fov/2)*aspect
    vec4 cam_up;       // scaled by half height (ortho) or tan(fov/2)
    vec4 box_half;     // xyz half extents; w = voxel length (world)
    vec4 dims;         // xyz voxel counts; w = transfer LUT size
    vec4 background;   // rgb; w = emission scale
    vec4 march;        // x view step (voxels), y shadow step (voxels), z min transmittance, w light count
    vec4 phong;        // ambient, diffuse, specular, shininess
    uvec4 image_size;  // width, height
} frame;

struct Ray { vec3 origin; vec3 dir; };

// Ray through continuous pixel position `pos` (pixel (x, y) spans [x, x+1)).
Ray camera_ray_at(vec2 pos) {
    vec2 ndc = vec2(pos.x / float(frame.image_size.x) * 2.0 - 1.0, 1.0 - pos.y / float(frame.image_size.y) * 2.0);
    Ray r;
    if (frame.cam_origin.w > 0.5) {
        r.origin = frame.cam_origin.xyz + frame.cam_right.xyz * ndc.x + frame.cam_up.xyz * ndc.y;
        r.dir = frame.cam_forward.xyz;
    } else {
        r.origin = frame.cam_origin.xyz;
        r.dir = normalize(frame.cam_forward.xyz + frame.cam_right.xyz * ndc.x + frame.cam_up.xyz * ndc.y);
    }
    return r;
}

Ray camera_ray(uvec2 pixel) { return camera_ray_at(vec2(pixel) + 0.5); }

// Slab test against [-half, half]; zero direction components never divide.
// Returns (t_near, t_far) with t_near >= 0; t_near >= t_far means a miss.
vec2 intersect_box(vec3 o, vec3 d) {
    vec3 h = frame.box_half.xyz;
    float t0 = 0.0;
    float t1 = 3.0e38;
    for (int a = 0; a < 3; ++a) {
        if (abs(d[a]) < 1e-30) {
            if (o[a] < -h[a] || o[a] > h[a]) return vec2(1.0, 0.0);
            continue;
        }
        float inv = 1.0 / d[a];
        float ta = (-h[a] - o[a]) * inv;
        float tb = (h[a] - o[a]) * inv;
        t0 = max(t0, min(ta, tb));
        t1 = min(t1, max(ta, tb));
    }
    return vec2(t0, t1);
}

vec3 to_uvw(vec3 p) { return (p + frame.box_half.xyz) / (2.0 * frame.box_half.xyz); }

#endif
