// cluster.glsl - the numerical core of clustered shading: exponential depth slices, cluster
// coordinates and indices, the view-space AABB of a cluster, and the sphere-vs-AABB light test.
// No #version; include after common.glsl. renderer/common/cluster_math.c is the C twin: same formulas, same
// operation order, float32, and tests/test_numeric.c proves them against double-precision
// references (monotonic slices clamped at both ends, conservative AABBs, no false negatives in the
// sphere test). Change both files together.
//
// Conventions (core/scene/scene.h): view space right-handed, camera looks down -Z, so the positive view
// depth of a point is -view.z. Vulkan NDC: x -1 = left, y -1 = TOP, z 0 = near, 1 = far (standard
// Z, not reversed). Tile (0,0) is the top-left one, like gl_FragCoord's origin.
//
// Valid clip parameters: near_z a normal float (>= 2^-126) and near_z < far_z <= FLT_MAX. Other
// parameters (0, negative, NaN, Inf, far <= near) make every depth fall in slice 0.
#ifndef PG_CLUSTER_GLSL
#define PG_CLUSTER_GLSL

const float PG_FLT_MIN_NORMAL = 1.17549435e-38;  // 2^-126
const float PG_FLT_MAX = 3.40282347e+38;
// far/near above 2^100 (far * 2^-100 > near): log2(far/near) is taken as log2(far) - log2(near)
// so the ratio itself never overflows. Below it the ratio form is used (more precise).
const float PG_CLUSTER_POW2_M100 = 7.88860905e-31; // 2^-100, exact
// Relative padding of a cluster's AABB (2^-14, about 6e-5 of the largest coordinate of the box).
// It covers the float rounding of the slice index (log2 on a GPU: up to 3 ulp / 2^-21 absolute),
// of the tile index (frag_xy * grid / viewport) and of the box corners, so a fragment assigned
// to a cluster always lies inside that cluster's box. Negligible against the size of a cluster.
const float PG_CLUSTER_AABB_PAD = 6.103515625e-05;

// Exponential depth slice of a positive view depth: slice k of grid_z covers view depths
// [near*(far/near)^(k/Z), near*(far/near)^((k+1)/Z)), computed as
//   t = log2(depth/near) / log2(far/near),  k = floor(t * Z)
// (log2 of the ratio, never the power, so near/far ratios of 1e9 and far more are fine).
// Clamped at both ends: depth <= near (0, negative, -Inf, NaN) -> 0; depth >= far (+Inf) -> Z-1;
// invalid clip parameters -> 0; grid_z 0 or 1 -> 0. Never returns >= grid_z (for grid_z >= 1).
// Monotonic non-decreasing in depth (log2, division and scaling are monotonic).
uint pg_cluster_slice(float view_depth, float near_z, float far_z, uint grid_z)
{
    if (grid_z <= 1u) return 0u;
    if (!(near_z >= PG_FLT_MIN_NORMAL && far_z > near_z && far_z <= PG_FLT_MAX)) return 0u;
    if (!(view_depth > near_z)) return 0u;            // also NaN
    if (view_depth >= far_z) return grid_z - 1u;      // also +Inf
    float num;
    float lr;
    if (far_z * PG_CLUSTER_POW2_M100 <= near_z) {
        num = log2(view_depth / near_z);
        lr = log2(far_z / near_z);
    } else {
        float ln = log2(near_z);
        num = log2(view_depth) - ln;
        lr = log2(far_z) - ln;
    }
    float s = num / lr * float(grid_z);
    s = s > 0.0 ? s : 0.0;                            // GPU log2 error near 1, NaN: slice 0
    float top = float(grid_z - 1u);
    s = s < top ? s : top;
    return min(uint(s), grid_z - 1u);
}

// View depth of slice boundary k: near*(far/near)^(k/Z) = near * exp2(log2(far/near) * (k/Z)).
// k = 0 -> near exactly, k >= Z -> far exactly; the result is clamped to [near, far].
// Invalid clip parameters -> near_z for k < Z.
float pg_slice_depth(uint k, float near_z, float far_z, uint grid_z)
{
    if (k >= grid_z) return far_z;
    if (k == 0u || !(near_z >= PG_FLT_MIN_NORMAL && far_z > near_z && far_z <= PG_FLT_MAX))
        return near_z;
    float r;
    if (far_z * PG_CLUSTER_POW2_M100 <= near_z) {
        float a = log2(far_z / near_z) * (float(k) / float(grid_z));
        r = near_z * exp2(a);
    } else {
        float a = (log2(far_z) - log2(near_z)) * (float(k) / float(grid_z));
        float h = 0.5 * a;                            // 2^a alone may overflow: two halves
        r = (near_z * exp2(h)) * exp2(a - h);
    }
    r = r < far_z ? r : far_z;
    return r > near_z ? r : near_z;
}

// Linear cluster index: x fastest, then y, then z (the layout of the cluster buffers).
uint pg_cluster_index(uvec3 c, uvec3 grid)
{
    return c.x + grid.x * (c.y + grid.y * c.z);
}

// Cluster of a fragment. frag_xy = gl_FragCoord.xy (pixel centres at +0.5, origin top-left);
// x = clamp(uint(frag_xy.x * grid.x / viewport.x), 0, grid.x-1) (negative and NaN -> 0), the same
// for y, z = pg_cluster_slice(view_depth). A grid dimension of 0 yields 0 on that axis.
uvec3 pg_cluster_coord(vec2 frag_xy, vec2 viewport_size, float view_depth, float near_z,
                       float far_z, uvec3 grid)
{
    uvec3 c = uvec3(0u, 0u, pg_cluster_slice(view_depth, near_z, far_z, grid.z));
    for (int i = 0; i < 2; i++) {
        uint g = grid[i];
        if (g == 0u) continue;
        float s = frag_xy[i] * float(g) / viewport_size[i];
        s = s > 0.0 ? s : 0.0;
        float top = float(g - 1u);
        s = s < top ? s : top;
        c[i] = min(uint(s), g - 1u);
    }
    return c;
}

// View-space AABB of cluster c: the cluster is the piece of the view frustum between the tile's
// four corner rays and the view depths pg_slice_depth(c.z) .. pg_slice_depth(c.z + 1). Each corner
// (NDC x = 2*cx/gx - 1, y likewise, y -1 = top) is unprojected at NDC z = 0 through inv_proj and
// scaled to view depth 1 (ray = p.xyz / -p.z, so ray.z = -1 whatever p.w is); the box is the AABB
// of the 8 points ray * z_near_k and ray * z_far_k. For a perspective projection the piece is the
// convex hull of those 8 points, so the box contains it. The box is then grown by
// PG_CLUSTER_AABB_PAD times its largest coordinate magnitude (see above).
void pg_cluster_aabb(uvec3 c, uvec3 grid, mat4 inv_proj, float near_z, float far_z, bool ortho,
                     out vec3 aabb_min, out vec3 aabb_max)
{
    float zn = pg_slice_depth(c.z, near_z, far_z, grid.z);
    float zf = pg_slice_depth(c.z + 1u, near_z, far_z, grid.z);
    float x0 = float(c.x) * 2.0 / float(grid.x) - 1.0;
    float x1 = float(c.x + 1u) * 2.0 / float(grid.x) - 1.0;
    float y0 = float(c.y) * 2.0 / float(grid.y) - 1.0;
    float y1 = float(c.y + 1u) * 2.0 / float(grid.y) - 1.0;
    vec3 mn = vec3(PG_FLT_MAX);
    vec3 mx = vec3(-PG_FLT_MAX);
    for (int i = 0; i < 4; i++) {
        vec4 p = inv_proj * vec4((i & 1) != 0 ? x1 : x0, (i & 2) != 0 ? y1 : y0, 0.0, 1.0);
        vec3 ray = p.xyz / -p.z;
        vec3 a = ortho ? vec3(p.xy, -zn) : ray * zn;   // orthographic: parallel view rays
        vec3 b = ortho ? vec3(p.xy, -zf) : ray * zf;
        mn = min(mn, min(a, b));
        mx = max(mx, max(a, b));
    }
    vec3 m = max(abs(mn), abs(mx));
    float pad = max(max(m.x, m.y), m.z) * PG_CLUSTER_AABB_PAD;
    aabb_min = mn - vec3(pad);
    aabb_max = mx + vec3(pad);
}

// Does the sphere (center, radius) reach the box? Squared distance from the center to the box
// <= radius^2 * (1 + 1e-5) + 1e-12: the tiny pad keeps float rounding from ever dropping a light
// that reaches the cluster (conservative; costs a false positive only for spheres within ~5e-6
// radii of the box). radius <= 0 or NaN -> false (such a light contributes exactly 0).
bool pg_sphere_intersects_aabb(vec3 center, float radius, vec3 aabb_min, vec3 aabb_max)
{
    if (!(radius > 0.0)) return false;
    vec3 q = clamp(center, aabb_min, aabb_max);
    vec3 d = center - q;
    float d2 = dot(d, d);
    return d2 <= radius * radius * (1.0 + 1e-5) + 1e-12;
}

#endif // PG_CLUSTER_GLSL
