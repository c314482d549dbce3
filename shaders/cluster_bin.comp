#version 460
// cluster_bin.comp - light assignment, step 1 of 4 (renderer/passes/cluster_assign.c): each light finds
// the screen tiles and depth slices its sphere can reach and sets its bit in one mask per tile
// and one mask per slice (bit i of word i/32: masks stay in light order). Cost: O(lights x
// (grid_x + grid_y + grid_z)) tests plus one atomicOr per touched tile and slice.
//
// Conservative with respect to the exact test the list shaders apply afterwards
// (pg_sphere_intersects_aabb against pg_cluster_aabb, cluster.glsl): if a light's sphere reaches
// the padded box of cluster (x, y, z), its bit is set in tile (x, y) AND slice z. Why:
//  - the box of cluster (x, y, z) is the AABB of its tile's 4 corner rays times the slice's two
//    depths, grown by PG_CLUSTER_AABB_PAD x its largest coordinate <= PAD * M * zf (M = max(1,
//    largest |ray.x|, |ray.y| over the screen corners; ray.z = -1));
//  - a sphere reaching a box overlaps it on every axis (with the test's 1e-5 relative slack);
//  - slice z is kept when the sphere's depth interval overlaps [zn - 4 PAD M zf, zf + 4 PAD M zf];
//  - tile (x, y) is kept when the sphere's x interval overlaps the x extent of column x's rays
//    (both vertical screen edges, so any x-y coupling of the projection is covered) over the
//    depths of the kept slices, grown by 4 PAD M zf, and the same for y: the x extent of a
//    cluster's box lies inside, since ray * depth is linear in depth.
// The radius is grown by 1e-4 relative plus 1e-5 of the distance: 10x the test's slack and
// float rounding. tests/test_cluster_assign.c checks the lists against the brute-force oracle.
// Every light's sphere is also stored (spheres[]), so the list steps test candidates without
// transforming lights again; with PG_BRUTE_FORCE only that is done. PG_SPOT_LIGHTS: a spot light's
// sphere, the one binned, is the bound of its ball within its cone (pg_cone_bound_sphere; it reaches
// past the ball), and its view-space cone and ball follow it (PG_LIGHT_RECORD_VEC4 = 3 vec4 a
// light): the list steps test all three, so the binned sphere is conservative for them.
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
#include "cluster.glsl"
#include "cluster_light.glsl"

layout(local_size_x = 64) in;
layout(set = 1, binding = 0, std430) readonly buffer Lights { Light lights[]; };
#ifndef PG_BRUTE_FORCE
layout(set = 1, binding = 3, std430) buffer TileMasks { uint tile_masks[]; };   // tile * words + w
layout(set = 1, binding = 4, std430) buffer SliceMasks { uint slice_masks[]; }; // slice * words + w
#endif
layout(set = 1, binding = 6, std430) writeonly buffer Spheres { vec4 spheres[]; }; // per light, for steps 2 and 4
layout(push_constant) uniform Push { uint words; } pc;

shared float s_depth[GRID_Z + 1];                       // slice boundaries
shared float s_col_lo[GRID_X + 1], s_col_hi[GRID_X + 1]; // ray.x at column edges (min/max over y)
shared float s_row_lo[GRID_Y + 1], s_row_hi[GRID_Y + 1]; // ray.y at row edges (min/max over x)
shared float s_m;

vec3 edge_ray(float nx, float ny)
{
    vec4 p = frame.inv_proj * vec4(nx, ny, 0.0, 1.0);
    return PG_ORTHO ? vec3(p.xy, -1.0) : p.xyz / -p.z; // orthographic: the edge's x / y itself
}

// An edge coordinate at view depth z: perspective rays scale with z, orthographic ones do not.
float at_depth(float e, float z) { return PG_ORTHO ? e : e * z; }

void main()
{
    const uvec3 grid = uvec3(GRID_X, GRID_Y, GRID_Z);
    float near_z = frame.clip.x, far_z = frame.clip.y;
    uint lid = gl_LocalInvocationIndex;
    for (uint k = lid; k <= grid.z; k += 64u) s_depth[k] = pg_slice_depth(k, near_z, far_z, grid.z);
    for (uint e = lid; e <= grid.x; e += 64u) {
        float nx = float(e) * 2.0 / float(grid.x) - 1.0;
        float a = edge_ray(nx, -1.0).x, b = edge_ray(nx, 1.0).x;
        s_col_lo[e] = min(a, b);
        s_col_hi[e] = max(a, b);
    }
    for (uint e = lid; e <= grid.y; e += 64u) {
        float ny = float(e) * 2.0 / float(grid.y) - 1.0;
        float a = edge_ray(-1.0, ny).y, b = edge_ray(1.0, ny).y;
        s_row_lo[e] = min(a, b);
        s_row_hi[e] = max(a, b);
    }
    if (lid == 0u) {
        float m = 1.0;
        for (int i = 0; i < 4; i++) {
            vec3 r = edge_ray((i & 1) != 0 ? 1.0 : -1.0, (i & 2) != 0 ? 1.0 : -1.0);
            m = max(m, max(abs(r.x), abs(r.y)));
        }
        s_m = m;
    }
    barrier();

    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u + lid;
    if (i >= frame.counts.x) return;
    vec4 sph = pg_light_view_sphere(lights[i]);
#ifdef PG_SPOT_LIGHTS
    vec4 cone = pg_light_view_cone(lights[frame.counts.x + i].pos_radius);
    spheres[i * PG_LIGHT_RECORD_VEC4 + 1u] = cone;
    spheres[i * PG_LIGHT_RECORD_VEC4 + 2u] = sph;  // the ball: apex and range
    sph = pg_cone_bound_sphere(sph, lights[i].pos_radius.w, cone);
#endif
    spheres[i * PG_LIGHT_RECORD_VEC4] = sph;
#ifndef PG_BRUTE_FORCE                               // the oracle needs only the spheres
    if (!(sph.w > 0.0) || any(isnan(sph.xyz)) || any(isinf(sph.xyz))) return;
    float rr = sph.w * (1.0 + 1e-4) + 1e-5 * length(sph.xyz) + 1e-6;
    float pad_rel = 4.0 * PG_CLUSTER_AABB_PAD * s_m;
    float dmin = -sph.z - rr, dmax = -sph.z + rr;   // positive view depth = -z

    // slices
    int k0 = -1, k1 = -1;
    for (uint k = 0u; k < grid.z; k++) {
        float zn = s_depth[k], zf = s_depth[k + 1u];
        float pad = PG_ORTHO ? 4.0 * PG_CLUSTER_AABB_PAD * max(s_m, zf) : pad_rel * zf;
        if (dmax >= zn - pad && dmin <= zf + pad) {
            if (k0 < 0) k0 = int(k);
            k1 = int(k);
        }
    }
    if (k0 < 0) return;                              // behind the camera, past far, or NaN
    float za = s_depth[k0], zb = s_depth[k1 + 1];
    float pad = PG_ORTHO ? 4.0 * PG_CLUSTER_AABB_PAD * max(s_m, zb) : pad_rel * zb;

    int x0 = -1, x1 = -1;
    for (uint x = 0u; x < grid.x; x++) {
        float lo = min(s_col_lo[x], s_col_lo[x + 1u]), hi = max(s_col_hi[x], s_col_hi[x + 1u]);
        float bmin = min(at_depth(lo, za), at_depth(lo, zb)) - pad, bmax = max(at_depth(hi, za), at_depth(hi, zb)) + pad;
        if (sph.x + rr >= bmin && sph.x - rr <= bmax) {
            if (x0 < 0) x0 = int(x);
            x1 = int(x);
        }
    }
    int y0 = -1, y1 = -1;
    for (uint y = 0u; y < grid.y; y++) {
        // tile row 0 is the top one: NDC y -1 (Vulkan)
        float lo = min(s_row_lo[y], s_row_lo[y + 1u]), hi = max(s_row_hi[y], s_row_hi[y + 1u]);
        float bmin = min(at_depth(lo, za), at_depth(lo, zb)) - pad, bmax = max(at_depth(hi, za), at_depth(hi, zb)) + pad;
        if (sph.y + rr >= bmin && sph.y - rr <= bmax) {
            if (y0 < 0) y0 = int(y);
            y1 = int(y);
        }
    }
    if (x0 < 0 || y0 < 0) return;

    uint w = i >> 5u, bit = 1u << (i & 31u);
    for (int k = k0; k <= k1; k++) atomicOr(slice_masks[uint(k) * pc.words + w], bit);
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++) atomicOr(tile_masks[(uint(y) * grid.x + uint(x)) * pc.words + w], bit);
#endif
}
