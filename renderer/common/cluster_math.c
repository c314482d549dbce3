/* cluster_math.c - float32 C twins of shaders/cluster.glsl, shaders/octahedral.glsl and
 * shaders/depth_reconstruct.glsl. Keep every formula and its operation order identical to the
 * shader (the comments there are the documentation); tests/test_numeric.c checks these against
 * double-precision references. Built with -std=c11 (no FP contraction into FMA, SSE float math). */
#include "cluster_math.h"

#include <math.h>

#define PG_FLT_MIN_NORMAL 1.17549435e-38f
#define PG_FLT_MAX_F 3.40282347e+38f
#define PG_CLUSTER_POW2_M100 7.88860905e-31f /* 2^-100: above far/near = 2^100, log2 difference */

static bool clip_valid(float near_z, float far_z)
{
    return near_z >= PG_FLT_MIN_NORMAL && far_z > near_z && far_z <= PG_FLT_MAX_F;
}

/* ---------------------------------------------------------------------------------------- */
/* cluster.glsl                                                                              */

uint32_t pg_cluster_slice(float view_depth, float near_z, float far_z, uint32_t grid_z)
{
    if (grid_z <= 1u) return 0u;
    if (!clip_valid(near_z, far_z)) return 0u;
    if (!(view_depth > near_z)) return 0u;
    if (view_depth >= far_z) return grid_z - 1u;
    float num, lr;
    if (far_z * PG_CLUSTER_POW2_M100 <= near_z) {
        num = log2f(view_depth / near_z);
        lr = log2f(far_z / near_z);
    } else {
        float ln = log2f(near_z);
        num = log2f(view_depth) - ln;
        lr = log2f(far_z) - ln;
    }
    float s = num / lr * (float)grid_z;
    s = s > 0.0f ? s : 0.0f;
    float top = (float)(grid_z - 1u);
    s = s < top ? s : top;
    uint32_t k = (uint32_t)s;
    return k < grid_z - 1u ? k : grid_z - 1u;
}

float pg_slice_depth(uint32_t k, float near_z, float far_z, uint32_t grid_z)
{
    if (k >= grid_z) return far_z;
    if (k == 0u || !clip_valid(near_z, far_z)) return near_z;
    float r;
    if (far_z * PG_CLUSTER_POW2_M100 <= near_z) {
        float a = log2f(far_z / near_z) * ((float)k / (float)grid_z);
        r = near_z * exp2f(a);
    } else {
        float a = (log2f(far_z) - log2f(near_z)) * ((float)k / (float)grid_z);
        float h = 0.5f * a;
        r = (near_z * exp2f(h)) * exp2f(a - h);
    }
    r = r < far_z ? r : far_z;
    return r > near_z ? r : near_z;
}

uint32_t pg_cluster_index(pg_uvec3 c, pg_uvec3 grid)
{
    return c.x + grid.x * (c.y + grid.y * c.z);
}

static uint32_t cluster_tile(float frag, float viewport, uint32_t g)
{
    if (g == 0u) return 0u;
    float s = frag * (float)g / viewport;
    s = s > 0.0f ? s : 0.0f;
    float top = (float)(g - 1u);
    s = s < top ? s : top;
    uint32_t k = (uint32_t)s;
    return k < g - 1u ? k : g - 1u;
}

pg_uvec3 pg_cluster_coord(pg_vec2 frag_xy, pg_vec2 viewport_size, float view_depth, float near_z,
                          float far_z, pg_uvec3 grid)
{
    pg_uvec3 c;
    c.x = cluster_tile(frag_xy.x, viewport_size.x, grid.x);
    c.y = cluster_tile(frag_xy.y, viewport_size.y, grid.y);
    c.z = pg_cluster_slice(view_depth, near_z, far_z, grid.z);
    return c;
}

void pg_cluster_aabb(pg_uvec3 c, pg_uvec3 grid, const float m[16], float near_z, float far_z,
                     pg_vec3 *aabb_min, pg_vec3 *aabb_max)
{
    float zn = pg_slice_depth(c.z, near_z, far_z, grid.z);
    float zf = pg_slice_depth(c.z + 1u, near_z, far_z, grid.z);
    float x0 = (float)c.x * 2.0f / (float)grid.x - 1.0f;
    float x1 = (float)(c.x + 1u) * 2.0f / (float)grid.x - 1.0f;
    float y0 = (float)c.y * 2.0f / (float)grid.y - 1.0f;
    float y1 = (float)(c.y + 1u) * 2.0f / (float)grid.y - 1.0f;
    float mn[3] = {PG_FLT_MAX_F, PG_FLT_MAX_F, PG_FLT_MAX_F};
    float mx[3] = {-PG_FLT_MAX_F, -PG_FLT_MAX_F, -PG_FLT_MAX_F};
    for (int i = 0; i < 4; i++) {
        float x = (i & 1) ? x1 : x0, y = (i & 2) ? y1 : y0;
        /* inv_proj * (x, y, 0, 1) */
        float p[3];
        for (int r = 0; r < 3; r++) p[r] = m[r] * x + m[4 + r] * y + m[8 + r] * 0.0f + m[12 + r] * 1.0f;
        float nz = -p[2];
        for (int r = 0; r < 3; r++) {
            float ray = p[r] / nz;
            float a = ray * zn, b = ray * zf;
            mn[r] = fminf(mn[r], fminf(a, b));
            mx[r] = fmaxf(mx[r], fmaxf(a, b));
        }
    }
    float e[3];
    for (int r = 0; r < 3; r++) e[r] = fmaxf(fabsf(mn[r]), fabsf(mx[r]));
    float pad = fmaxf(fmaxf(e[0], e[1]), e[2]) * PG_CLUSTER_AABB_PAD;
    aabb_min->x = mn[0] - pad;
    aabb_min->y = mn[1] - pad;
    aabb_min->z = mn[2] - pad;
    aabb_max->x = mx[0] + pad;
    aabb_max->y = mx[1] + pad;
    aabb_max->z = mx[2] + pad;
}

bool pg_sphere_intersects_aabb(pg_vec3 center, float radius, pg_vec3 aabb_min, pg_vec3 aabb_max)
{
    if (!(radius > 0.0f)) return false;
    float dx = center.x - fminf(fmaxf(center.x, aabb_min.x), aabb_max.x);
    float dy = center.y - fminf(fmaxf(center.y, aabb_min.y), aabb_max.y);
    float dz = center.z - fminf(fmaxf(center.z, aabb_min.z), aabb_max.z);
    float d2 = dx * dx + dy * dy + dz * dz;
    return d2 <= radius * radius * (1.0f + PG_SPHERE_REL_PAD) + PG_SPHERE_ABS_PAD;
}

uint64_t pg_cluster_count(pg_uvec3 grid)
{
    uint64_t xy = (uint64_t)grid.x * grid.y; /* < 2^64 */
    if (grid.z && xy > UINT64_MAX / grid.z) return UINT64_MAX;
    return xy * grid.z;
}

/* ---------------------------------------------------------------------------------------- */
/* octahedral.glsl                                                                           */

pg_vec2 pg_oct_encode(pg_vec3 n)
{
    pg_vec2 p = {0.0f, 0.0f};
    float s = fabsf(n.x) + fabsf(n.y) + fabsf(n.z);
    if (!(s > 0.0f && s <= PG_FLT_MAX_F)) return p;
    p.x = n.x / s;
    p.y = n.y / s;
    if (n.z < 0.0f) {
        float sx = p.x >= 0.0f ? 1.0f : -1.0f, sy = p.y >= 0.0f ? 1.0f : -1.0f;
        float ex = (1.0f - fabsf(p.y)) * sx;
        float ey = (1.0f - fabsf(p.x)) * sy;
        p.x = ex;
        p.y = ey;
    }
    return p;
}

static float clamp_unit_nan0(float v)
{
    return v > -1.0f ? (v < 1.0f ? v : 1.0f) : (v <= -1.0f ? -1.0f : 0.0f);
}

pg_vec3 pg_oct_decode(pg_vec2 e)
{
    float ex = clamp_unit_nan0(e.x), ey = clamp_unit_nan0(e.y);
    pg_vec3 v = {ex, ey, 1.0f - fabsf(ex) - fabsf(ey)};
    float t = fmaxf(-v.z, 0.0f);
    v.x += v.x >= 0.0f ? -t : t;
    v.y += v.y >= 0.0f ? -t : t;
    float len = sqrtf(v.x * v.x + v.y * v.y + v.z * v.z);
    v.x /= len;
    v.y /= len;
    v.z /= len;
    return v;
}

uint32_t pg_pack_unorm2x16(float x, float y)
{
    float cx = x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f;
    float cy = y > 0.0f ? (y < 1.0f ? y : 1.0f) : 0.0f;
    uint32_t ux = (uint32_t)roundf(cx * 65535.0f), uy = (uint32_t)roundf(cy * 65535.0f);
    return ux | (uy << 16);
}

void pg_unpack_unorm2x16(uint32_t p, float *x, float *y)
{
    *x = (float)(p & 0xffffu) / 65535.0f;
    *y = (float)(p >> 16) / 65535.0f;
}

uint32_t pg_oct_pack_unorm16(pg_vec3 n)
{
    pg_vec2 e = pg_oct_encode(n);
    return pg_pack_unorm2x16(e.x * 0.5f + 0.5f, e.y * 0.5f + 0.5f);
}

pg_vec3 pg_oct_unpack_unorm16(uint32_t p)
{
    pg_vec2 e;
    pg_unpack_unorm2x16(p, &e.x, &e.y);
    e.x = e.x * 2.0f - 1.0f;
    e.y = e.y * 2.0f - 1.0f;
    return pg_oct_decode(e);
}

/* ---------------------------------------------------------------------------------------- */
/* depth_reconstruct.glsl                                                                    */

float pg_view_depth_from_depth(float depth, float near_z, float far_z)
{
    float d = depth < 1.0f ? (depth > 0.0f ? depth : 0.0f) : 1.0f;
    float ratio = fminf(far_z / near_z, PG_FLT_MAX_F);
    return far_z / (d + (1.0f - d) * ratio);
}

pg_vec3 pg_view_pos_from_depth(pg_vec2 uv, float depth, const float m[16])
{
    float nx = uv.x * 2.0f - 1.0f, ny = uv.y * 2.0f - 1.0f;
    float p[4];
    for (int r = 0; r < 4; r++) p[r] = m[r] * nx + m[4 + r] * ny + m[8 + r] * depth + m[12 + r] * 1.0f;
    pg_vec3 v = {p[0] / p[3], p[1] / p[3], p[2] / p[3]};
    return v;
}

pg_vec3 pg_view_pos_from_view_depth(pg_vec2 uv, float view_depth, const float proj[16])
{
    float nx = uv.x * 2.0f - 1.0f, ny = uv.y * 2.0f - 1.0f;
    pg_vec3 v = {(nx / proj[0]) * view_depth, (ny / proj[5]) * view_depth, -view_depth};
    return v;
}
