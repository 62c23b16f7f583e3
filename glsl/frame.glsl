// Frame parameters shared by the ray casters (binding 0), camera rays and the
// volume box. Mirrors `FrameParams` in src/render/frame_params.rs (std140).
#ifndef FRAME_GLSL
#define FRAME_GLSL

struct FrameParams {
    vec3 cam_origin;
    uint orthographic;        // 1: parallel rays from the image plane
    vec4 cam_forward;         // unit (w unused)
    vec4 cam_right;           // scaled by half width (ortho) or tan(fov/2)*aspect (w unused)
    vec4 cam_up;              // scaled by half height (ortho) or tan(fov/2) (w unused)
    vec3 box_half;            // half extents of the volume box (world)
    float voxel_length;       // world units per voxel
    vec3 dims;                // voxel counts
    float lut_size;           // texels of the transfer LUT
    vec3 background;          // rgb
    float emission;           // emission scale of the medium
    float view_step;          // voxels
    float shadow_step;        // voxels
    float min_transmittance;  // where the ground truth's view rays stop
    uint light_count;
    float ambient;            // Blinn-Phong
    float diffuse;
    float specular;
    float shininess;
    uvec2 image_size;         // width, height
    uint jitter;              // 1: each pixel's view samples start at its own phase (view_ray.glsl)
    uint frame_unused;
};

// A storage buffer, not a uniform block: lavapipe (Mesa 22.3) recompiles a
// shader whose branches and loop bounds read a uniform block, once with the
// block's values folded in and again without them (docs/testing.md).
layout(std140, set = 0, binding = 0) readonly buffer FrameBlock { FrameParams params; } frame_buffer;

// The invocation's copy, read once at the top of main (load_frame), so the
// hot loops read registers rather than the buffer. A shader that reads `frame`
// without calling load_frame has no `frame_buffer` binding in its reflected
// interface, so its Rust code cannot name FRAME_BUFFER: the build fails there.
// (A global initializer instead of the call would make every shader that
// includes this file read the buffer, whether it uses `frame` or not.)
FrameParams frame;
void load_frame() { frame = frame_buffer.params; }

struct Ray { vec3 origin; vec3 dir; };

// Ray through continuous pixel position `pos` (pixel (x, y) spans [x, x+1)).
Ray camera_ray_at(vec2 pos) {
    vec2 ndc = vec2(pos.x / float(frame.image_size.x) * 2.0 - 1.0, 1.0 - pos.y / float(frame.image_size.y) * 2.0);
    Ray r;
    if (frame.orthographic != 0u) {
        r.origin = frame.cam_origin + frame.cam_right.xyz * ndc.x + frame.cam_up.xyz * ndc.y;
        r.dir = frame.cam_forward.xyz;
    } else {
        r.origin = frame.cam_origin;
        r.dir = normalize(frame.cam_forward.xyz + frame.cam_right.xyz * ndc.x + frame.cam_up.xyz * ndc.y);
    }
    return r;
}

Ray camera_ray(uvec2 pixel) { return camera_ray_at(vec2(pixel) + 0.5); }

// Slab test against [lo, hi]; zero direction components never divide.
// Returns (t_near, t_far) with t_near >= 0; t_near >= t_far means a miss.
vec2 intersect_aabb(vec3 o, vec3 d, vec3 lo, vec3 hi) {
    float t0 = 0.0;
    float t1 = 3.0e38;
    for (int a = 0; a < 3; ++a) {
        if (abs(d[a]) < 1e-30) {
            if (o[a] < lo[a] || o[a] > hi[a]) return vec2(1.0, 0.0);
            continue;
        }
        float inv = 1.0 / d[a];
        float ta = (lo[a] - o[a]) * inv;
        float tb = (hi[a] - o[a]) * inv;
        t0 = max(t0, min(ta, tb));
        t1 = min(t1, max(ta, tb));
    }
    return vec2(t0, t1);
}

// The volume box, [-half, half].
vec2 intersect_box(vec3 o, vec3 d) { return intersect_aabb(o, d, -frame.box_half, frame.box_half); }

vec3 to_uvw(vec3 p) { return (p + frame.box_half) / (2.0 * frame.box_half); }

#endif
