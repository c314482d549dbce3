/* cluster_math.h - C11 twins of the numerical shader code of clustered shading:
 *   shaders/cluster.glsl           exponential depth slices, cluster coordinates/index/AABB,
 *                                  sphere-vs-AABB light test
 *   shaders/octahedral.glsl        octahedral normal encoding (+ unorm16 packing)
 *   shaders/depth_reconstruct.glsl view depth / position from depth or from a linear view depth
 * Each function computes the same formula in the same operation order in float32 as its GLSL
 * namesake (read the shader comments for the exact semantics, clamping and precision), so the CPU
 * tests (tests/test_numeric.c, double-precision references) prove what the GPU computes up to the
 * GPU's own float precision (log2/exp2/division/normalize are not correctly rounded there).
 * Change a function here and in its shader together.
 *
 * Conventions (core/scene/scene.h): matrices are float[16] column-major (row r, column c at m[c*4+r];
 * GLSL m[c][r]); view space right-handed looking down -Z (view depth = -view.z > 0 in front);
 * Vulkan NDC with y -1 at the TOP and z 0 at near, 1 at far (standard Z; reversed Z is not
 * offered). Pure functions, no allocation, no global state.
 */
#ifndef PG_CLUSTER_MATH_H
#define PG_CLUSTER_MATH_H

#include <stdbool.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pg_vec2 { float x, y; } pg_vec2;
typedef struct pg_vec3 { float x, y, z; } pg_vec3;
typedef struct pg_uvec3 { uint32_t x, y, z; } pg_uvec3;

/* The default cluster grid (parameters grid_x/y/z, the count of cluster_counts in
 * pipelines/fragments/clusters.json): 16x9 screen tiles x 32 exponential depth slices (32, not 24,
 * for shorter lists in the tiled light loop; measured in docs/performance.md). */
#define PG_CLUSTER_GRID_DEFAULT_X 16
#define PG_CLUSTER_GRID_DEFAULT_Y 9
#define PG_CLUSTER_GRID_DEFAULT_Z 32

/* Relative padding of a cluster AABB (2^-14 of its largest coordinate magnitude); see
 * shaders/cluster.glsl. */
#define PG_CLUSTER_AABB_PAD 6.103515625e-05f
/* Sphere test slack: d^2 <= r^2 * (1 + PG_SPHERE_REL_PAD) + PG_SPHERE_ABS_PAD. */
#define PG_SPHERE_REL_PAD 1e-5f
#define PG_SPHERE_ABS_PAD 1e-12f

/* ---- cluster.glsl ---- */

/* Exponential slice of a positive view depth in [0, grid_z-1]: t = log2(d/near)/log2(far/near),
 * k = floor(t*Z). depth <= near (0, negative, -Inf, NaN) -> 0; depth >= far (+Inf) -> Z-1;
 * invalid clip (near < 2^-126, far <= near, non-finite) -> 0; grid_z <= 1 -> 0. Monotonic. */
uint32_t pg_cluster_slice(float view_depth, float near_z, float far_z, uint32_t grid_z);
/* Boundary view depth of slice k: near*(far/near)^(k/Z); k = 0 -> near, k >= Z -> far exactly;
 * clamped to [near, far]; invalid clip -> near for k < Z. */
float pg_slice_depth(uint32_t k, float near_z, float far_z, uint32_t grid_z);
/* c.x + grid.x * (c.y + grid.y * c.z) (uint32 arithmetic, wraps like GLSL). */
uint32_t pg_cluster_index(pg_uvec3 c, pg_uvec3 grid);
/* Cluster of a fragment: frag_xy = gl_FragCoord.xy (pixel centres at +0.5, origin top-left);
 * x = clamp(uint(frag.x * grid.x / viewport.x), 0, grid.x-1) (negative / NaN -> 0), same for y;
 * z = pg_cluster_slice. A zero grid dimension gives 0 on that axis. */
pg_uvec3 pg_cluster_coord(pg_vec2 frag_xy, pg_vec2 viewport_size, float view_depth, float near_z,
                          float far_z, pg_uvec3 grid);
/* View-space AABB of cluster c (conservative; grown by PG_CLUSTER_AABB_PAD). inv_proj is the
 * inverse of the projection (pg_mat4_invert(pg_camera_proj)). c must be inside grid. */
void pg_cluster_aabb(pg_uvec3 c, pg_uvec3 grid, const float inv_proj[16], float near_z,
                     float far_z, pg_vec3 *aabb_min, pg_vec3 *aabb_max);
/* Squared distance from center to the box <= r^2 * (1 + 1e-5) + 1e-12; radius <= 0 / NaN ->
 * false. */
bool pg_sphere_intersects_aabb(pg_vec3 center, float radius, pg_vec3 aabb_min, pg_vec3 aabb_max);

/* Number of clusters (grid.x * grid.y * grid.z, in 64 bits). */
uint64_t pg_cluster_count(pg_uvec3 grid);

/* ---- octahedral.glsl ---- */

/* n (normally unit) -> [-1,1]^2; zero / NaN / Inf -> (0,0) (decodes to +Z). */
pg_vec2 pg_oct_encode(pg_vec3 n);
/* [-1,1]^2 (clamped; NaN -> 0) -> finite unit vector. */
pg_vec3 pg_oct_decode(pg_vec2 e);
/* pg_pack_unorm2x16 of encode(n) * 0.5 + 0.5, and back. */
uint32_t pg_oct_pack_unorm16(pg_vec3 n);
pg_vec3 pg_oct_unpack_unorm16(uint32_t p);

/* GLSL packUnorm2x16 / unpackUnorm2x16: round(clamp(v, 0, 1) * 65535) (NaN -> 0; exact halves
 * round away from zero here, a GPU may round them to even), x in the low 16 bits; unpack is
 * bits / 65535. */
uint32_t pg_pack_unorm2x16(float x, float y);
void pg_unpack_unorm2x16(uint32_t p, float *x, float *y);

/* ---- depth_reconstruct.glsl ---- */

/* Depth-buffer value (clamped to [0,1], NaN -> 1) -> positive view depth,
 * far / (d + (1 - d) * (far / near)); d = 1 -> far exactly. */
float pg_view_depth_from_depth(float depth, float near_z, float far_z);
/* inv_proj * (uv*2-1, depth, 1), divided by w. */
pg_vec3 pg_view_pos_from_depth(pg_vec2 uv, float depth, const float inv_proj[16]);
/* ((ndc.x / proj[0]) * z, (ndc.y / proj[5]) * z, -z), ndc = uv*2-1. */
pg_vec3 pg_view_pos_from_view_depth(pg_vec2 uv, float view_depth, const float proj[16]);

#ifdef __cplusplus
}
#endif
#endif
