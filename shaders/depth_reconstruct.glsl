// depth_reconstruct.glsl - view depth and view-space position from a depth-buffer value or from
// a stored linear view depth. No #version. renderer/common/cluster_math.c is the C twin (same formulas and
// order, float32); tests/test_numeric.c measures the errors against a double-precision reference.
//
// Standard Z only (core/scene/scene.h pg_camera_proj: z_ndc 0 at near, 1 at far; cleared depth 1.0).
// Reversed Z is not offered. uv = (pixel + 0.5) / size, ndc.xy = uv * 2 - 1 (y -1 = top).
//
// Precision (measured by test_numeric): the reconstruction arithmetic itself costs a few ulp, but
// a D32 depth value d carries up to half an ulp of rounding (<= 2^-25), and 1/z is linear in d:
// 1/z = 1/near - d * (1/near - 1/far). So the relative view-depth error from the stored depth is
//   eps = 2^-25 * z * (1/near - 1/far),  rel. error <= eps / (1 - eps) + a few ulp
// i.e. it grows linearly with z/near: about 3e-8 * z/near (measured: 1e-3 is reached at
// z/near ~ 3.4e4, whatever far is). With near 0.1 that is 3e-4 at z = 1e3
// and useless (>= 1) beyond z ~ 3e7*near. Storing a float32 view depth instead (the 'packed'
// G-buffer variant, pg_view_pos_from_view_depth) costs < 1e-6 relative at every depth.
#ifndef PG_DEPTH_RECONSTRUCT_GLSL
#define PG_DEPTH_RECONSTRUCT_GLSL

// Depth-buffer value (0..1; NaN and > 1 -> 1, < 0 -> 0) -> positive view depth:
//   z = near*far / (far - d*(far - near))   written as   z = far / (d + (1 - d) * (far / near))
// which has no cancellation (both terms of the denominator are >= 0; 1 - d is exact for
// d >= 0.5), never overflows n*f, gives exactly far for d = 1 and stays in [~near, far].
// Needs 0 < near < far (far/near is clamped to FLT_MAX, so d = 1 gives far even past that).
float pg_view_depth_from_depth(float depth, float near_z, float far_z)
{
    float d = depth < 1.0 ? (depth > 0.0 ? depth : 0.0) : 1.0;
    float ratio = min(far_z / near_z, 3.40282347e+38);  // no 0 * Inf at d = 1
    return far_z / (d + (1.0 - d) * ratio);
}

// View-space position: unproject (ndc.xy, depth) through inv_proj and divide by w. Exact in
// exact arithmetic for any projection; in float, w = (d + proj[10]) / proj[14] cancels when d is
// close to 1, adding an error of the same order as the depth quantization (eps above, measured
// about 2-3x it). Where far/near > 2^24 the float projection's proj[10] rounds to -1, so depth 1
// unprojects to w = 0 (an infinite position): prefer
// pg_view_pos_from_view_depth(uv, pg_view_depth_from_depth(...), proj) there.
vec3 pg_view_pos_from_depth(vec2 uv, float depth, mat4 inv_proj)
{
    vec2 ndc = uv * 2.0 - 1.0;
    vec4 p = inv_proj * vec4(ndc, depth, 1.0);
    return p.xyz / p.w;
}

// View-space position from a positive linear view depth (e.g. a stored float32 view depth):
//   x = (ndc.x / proj[0][0]) * z, y = (ndc.y / proj[1][1]) * z, view z = -z.
// Exact for a symmetric perspective projection (pg_camera_proj); proj[1][1] is negative (Vulkan
// y-down), which maps ndc.y = -1 (top) to view +Y.
vec3 pg_view_pos_from_view_depth(vec2 uv, float view_depth, mat4 proj)
{
    vec2 ndc = uv * 2.0 - 1.0;
    return vec3((ndc.x / proj[0][0]) * view_depth, (ndc.y / proj[1][1]) * view_depth, -view_depth);
}

// Orthographic twins (pg_camera.ortho_height > 0): depth is linear in view depth,
//   z = near + d * (far - near),
// and the view-space x, y of a pixel do not depend on its depth: x = ndc.x / proj[0][0].
float pg_ortho_view_depth_from_depth(float depth, float near_z, float far_z)
{
    float d = depth < 1.0 ? (depth > 0.0 ? depth : 0.0) : 1.0;
    return d < 1.0 ? near_z + d * (far_z - near_z) : far_z;
}

vec3 pg_ortho_view_pos_from_view_depth(vec2 uv, float view_depth, mat4 proj)
{
    vec2 ndc = uv * 2.0 - 1.0;
    return vec3(ndc.x / proj[0][0], ndc.y / proj[1][1], -view_depth);
}

#endif // PG_DEPTH_RECONSTRUCT_GLSL
