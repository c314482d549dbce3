// visibility_raster.glsl - the visibility pass's compute rasterizer (option raster "compute";
// renderer/passes/visibility_raster.c): what its three shaders share.
//
// Every opaque triangle of the scene is transformed as scene.vert transforms it, clipped against
// the near plane (clip z >= 0) and a guard band of PG_RASTER_GUARD pixels around the viewport
// (in homogeneous clip space: the far side and the viewport's own edges are left to the pixel
// tests), projected and snapped to 1/256 pixel (8 subpixel bits, as the rasterizers of desktop
// GPUs). Coverage is the exact integer edge test at pixel centres with a tie rule for centres on
// an edge (an edge a->b owns them when dy < 0, or dy = 0 and dx > 0: of two triangles that share
// an edge exactly one does, so a closed mesh has neither holes nor double hits). Back faces of
// single-sided materials are culled by the sign of the snapped area (VK_FRONT_FACE_COUNTER_CLOCKWISE
// with the pass's viewport, y down: front when the area below is negative). Depth is z/w
// interpolated with the screen-space barycentrics; a pixel keeps the 64-bit minimum of
// (depth bits << 32) | id (atomicMin), so the nearest triangle wins and a tie goes to the lower id,
// i.e. the draw and then the primitive drawn first, as a LESS depth test does.
//
// PG_RASTER_ALPHA_MASK (a scene with alpha-mask draws): a covered pixel of an alpha-mask draw
// (flags bit 1) is kept only where its material's alpha test keeps it: the surface is rebuilt at the
// pixel centre as the shading pass rebuilds it (visibility_surface.glsl: barycentrics from the
// pixel ray, analytic UV derivatives) and its base alpha tested (surface.glsl
// pg_surface_alpha_kept), after a look at the pixel's key (a point behind it needs no test).
//
// Set 1: 0 the keys (one uint64 per pixel), 1 the job list, 2 the job dispatch's indirect
// arguments, 3 each draw's first global triangle, 4 the id image, 5 the depth values (one float per
// pixel, copied into the depth image), from 6 the scene's vertices, indices and draw table
// (visibility_common.h: uvec4 first index, vertex offset, material, flags with bit 0 double-sided
// and bit 1 alpha mask) and, with PG_RASTER_ALPHA_MASK, COLOR_0 and TEXCOORD_1 where compiled in;
// set 2 the scene's materials and textures (PG_RASTER_ALPHA_MASK).
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#ifdef PG_RASTER_ALPHA_MASK
#extension GL_EXT_nonuniform_qualifier : require
#endif
#include "common.glsl"
FRAME_UNIFORMS_BLOCK

layout(set = 1, binding = 0, std430) buffer RasterKeys { uint64_t raster_keys[]; };
// a job: a triangle too large for one invocation, PG_RASTER_JOB_BLOCKS 8x8 blocks of its box per
// workgroup: (x0, y0, x1, y1) and (x2, y2, id, first block | alpha mask << 31) snapped and
// oriented, (z0, z1, z2)
struct PgRasterJob {
    ivec4 a;
    uvec4 b;
    vec4 z;
};
// raster_job_next: jobs reserved (a failed reservation too); raster_job_end: the end of the last
// successful one (the jobs written are exactly [0, end))
layout(set = 1, binding = 1, std430) buffer RasterJobs {
    uint raster_job_next;
    uint raster_job_end;
    uint raster_job_pad[2];
    PgRasterJob raster_jobs[];
};
// the job dispatch's groups, x <= PG_RASTER_GROUPS_X wide, y rows: x * y >= raster_job_end
layout(set = 1, binding = 2, std430) buffer RasterArgs { uint raster_groups_x; uint raster_groups_y; uint raster_groups_z; };
#ifndef PG_RASTER_GROUPS_X
#define PG_RASTER_GROUPS_X 65535u // a test may set fewer (PASSGRAPH_RASTER_GROUPS_X): more rows
#endif
layout(set = 1, binding = 3, std430) readonly buffer RasterTriStart { uint raster_tri_start[]; };
#define PG_VIS_SET 1
#define PG_VIS_BINDING 6
#ifdef PG_RASTER_ALPHA_MASK
#include "depth_reconstruct.glsl"
#include "surface.glsl"
#include "visibility_surface.glsl"
#else
#include "visibility_streams.glsl"
#endif
layout(push_constant) uniform RasterPush {
    uint n_tris;   // triangles of the rasterized draws
    uint n_draws;  // rasterized draws (the scene's opaque ones)
    uint job_cap;  // entries of raster_jobs
    uint tri_bits; // visibility_common.h
} rp;

const float PG_RASTER_SNAP = 256.0;      // 8 subpixel bits
const float PG_RASTER_GUARD = 1048576.0; // guard band: 2^20 pixels from the viewport's centre
const uint PG_RASTER_JOB_BLOCKS = 16u;   // 8x8 blocks per job
const uint PG_RASTER_SMALL = 64u;        // box pixels one invocation covers itself

ivec2 pg_raster_size() { return ivec2(frame.counts.zw); }

// The draw that global triangle t belongs to (raster_tri_start[d] <= t < raster_tri_start[d + 1]).
uint pg_raster_draw_of(uint t)
{
    uint lo = 0u, hi = rp.n_draws; // raster_tri_start[lo] <= t < raster_tri_start[hi]
    while (hi - lo > 1u) {
        uint mid = (lo + hi) >> 1u;
        if (raster_tri_start[mid] <= t) lo = mid;
        else hi = mid;
    }
    return lo;
}

// Clip-space corners of triangle t (as scene.vert computes gl_Position), its id, whether its
// material is double-sided and alpha-masked, and whether the frame's pose mirrors its draw against
// its indices' winding (visibility_common.h, flag bit 2: clockwise is then its front).
void pg_raster_fetch(uint t, out vec4 c[3], out uint id, out bool two_sided, out bool masked, out bool mirrored)
{
    uint d = pg_raster_draw_of(t);
    uvec4 dr = vis_draws[d];
    uint prim = t - raster_tri_start[d];
    id = (d << rp.tri_bits) | prim;
    two_sided = (dr.w & 1u) != 0u;
    masked = (dr.w & 2u) != 0u;
    mirrored = (dr.w & 4u) != 0u;
    for (int k = 0; k < 3; k++) {
        uint v = vis_indices[dr.x + 3u * prim + uint(k)] + dr.y;
        precise vec4 g = frame.proj * vec4(PG_REL_TO_VIEW(pg_vis_vec3(v, 0u) - frame.camera_pos.xyz), 1.0);
        c[k] = g;
    }
}

// The clip planes: dot(plane, c) >= 0 inside. 0: z >= 0 (near); 1-4: the guard band.
vec4 pg_raster_plane(int i)
{
    vec2 g = PG_RASTER_GUARD / (0.5 * vec2(pg_raster_size()));
    if (i == 0) return vec4(0.0, 0.0, 1.0, 0.0);
    if (i == 1) return vec4(1.0, 0.0, 0.0, g.x);
    if (i == 2) return vec4(-1.0, 0.0, 0.0, g.x);
    if (i == 3) return vec4(0.0, 1.0, 0.0, g.y);
    return vec4(0.0, -1.0, 0.0, g.y);
}

// false when every corner is inside every plane and the viewport's box (most triangles): no clipping
bool pg_raster_needs_clip(vec4 c[3])
{
    for (int k = 0; k < 3; k++)
        if (!(c[k].z >= 0.0 && c[k].z <= c[k].w && abs(c[k].x) <= c[k].w && abs(c[k].y) <= c[k].w)) return true;
    return false;
}

// Where the edge a-b (signed distances da, db to a plane) crosses it, computed from the lesser
// corner (in x, then y, z, w) so that the two triangles sharing an edge get the same point whatever
// their order: their clipped edges stay shared, with no crack along the near plane.
vec4 pg_raster_cut(vec4 a, vec4 b, float da, float db)
{
    bool swap = a.x != b.x ? a.x > b.x : a.y != b.y ? a.y > b.y : a.z != b.z ? a.z > b.z : a.w > b.w;
    return swap ? mix(b, a, db / (db - da)) : mix(a, b, da / (da - db));
}

// The triangle clipped to the planes, as a convex polygon of n <= 8 corners (0: nothing left; a
// triangle wholly outside the viewport on one side or beyond the far plane is dropped here too).
int pg_raster_clip(vec4 c[3], out vec4 poly[8])
{
    for (int k = 0; k < 3; k++) poly[k] = c[k];
    // wholly outside one side of the viewport, or beyond the far plane: nothing to draw
    for (int a = 0; a < 2; a++) {
        if (c[0][a] > c[0].w && c[1][a] > c[1].w && c[2][a] > c[2].w) return 0;
        if (c[0][a] < -c[0].w && c[1][a] < -c[1].w && c[2][a] < -c[2].w) return 0;
    }
    if (c[0].z > c[0].w && c[1].z > c[1].w && c[2].z > c[2].w) return 0;
    int n = 3;
    for (int i = 0; i < 5; i++) {
        vec4 pl = pg_raster_plane(i);
        bool all_in = true;
        for (int k = 0; k < n; k++) all_in = all_in && dot(pl, poly[k]) >= 0.0;
        if (all_in) continue;
        vec4 src[8];
        for (int k = 0; k < 8; k++) src[k] = poly[k];
        int m = 0;
        for (int k = 0; k < n; k++) {
            vec4 a = src[k], b = src[(k + 1) % n];
            float da = dot(pl, a), db = dot(pl, b);
            if (da >= 0.0 && m < 8) poly[m++] = a;
            if ((da >= 0.0) != (db >= 0.0) && m < 8) poly[m++] = pg_raster_cut(a, b, da, db);
        }
        n = m;
        if (n < 3) return 0;
    }
    return n;
}

// A triangle ready for pixel tests: snapped corners (1/256 pixel) ordered so that the area is
// positive, their depths, the pixel box (inclusive, clipped to the viewport) and the area.
struct PgRasterTri {
    ivec2 p0, p1, p2;
    vec3 z;
    ivec4 box;
    int64_t area;
};

ivec2 pg_raster_snap(vec4 c)
{
    vec2 s = vec2(pg_raster_size());
    precise vec2 f = (c.xy / c.w * 0.5 + 0.5) * s;
    return ivec2(round(f * PG_RASTER_SNAP));
}

int64_t pg_raster_edge(ivec2 a, ivec2 b, ivec2 p)
{
    return int64_t(b.x - a.x) * int64_t(p.y - a.y) - int64_t(b.y - a.y) * int64_t(p.x - a.x);
}

void pg_raster_box(inout PgRasterTri t)
{
    ivec2 lo = min(min(t.p0, t.p1), t.p2), hi = max(max(t.p0, t.p1), t.p2);
    // pixel centres px * 256 + 128 within [lo, hi]
    ivec2 a = (lo - 128 + 255) >> 8, b = (hi - 128) >> 8;
    ivec2 s = pg_raster_size();
    t.box = ivec4(max(a, ivec2(0)), min(b, s - 1));
}

// false: nothing to draw (degenerate, a culled back face, or outside the viewport). mirrored: the
// front face is clockwise (a draw the frame's pose mirrors).
bool pg_raster_setup(vec4 a, vec4 b, vec4 c, bool cull_back, bool mirrored, out PgRasterTri t)
{
    t.p0 = pg_raster_snap(a);
    t.p1 = pg_raster_snap(b);
    t.p2 = pg_raster_snap(c);
    t.z = vec3(a.z / a.w, b.z / b.w, c.z / c.w);
    t.area = pg_raster_edge(t.p0, t.p1, t.p2);
    if (t.area == 0l) return false;
    if (cull_back && (t.area > 0l) != mirrored) return false; // clockwise on screen (y down): a back face
    if (t.area < 0l) {
        ivec2 q = t.p1;
        t.p1 = t.p2;
        t.p2 = q;
        t.z = t.z.xzy;
        t.area = -t.area;
    }
    pg_raster_box(t);
    return t.box.x <= t.box.z && t.box.y <= t.box.w;
}

bool pg_raster_owns(ivec2 a, ivec2 b, int64_t e) // the tie rule: e = 0 counts for one side only
{
    int dx = b.x - a.x, dy = b.y - a.y;
    return e > 0l || (e == 0l && (dy < 0 || (dy == 0 && dx > 0)));
}

#ifdef PG_RASTER_ALPHA_MASK
// false where the alpha test of triangle `id`'s material drops the centre of pixel px
bool pg_raster_alpha_kept(uint id, ivec2 px)
{
    SurfaceInput si;
    uint material;
    vec3 P;
    pg_vis_fetch(id, vec2(px) + 0.5, vec2(pg_raster_size()), si, material, P);
    GpuMaterial m = materials[material];
    return pg_surface_alpha_kept(m, pg_surface_base(m, si));
}
#endif

// Tests the centre of pixel px against the triangle and keeps the nearer of it and what the pixel
// holds (masked: an alpha-mask draw's triangle, PG_RASTER_ALPHA_MASK).
void pg_raster_pixel(PgRasterTri t, ivec2 px, uint id, bool masked)
{
    ivec2 p = px * 256 + 128;
    int64_t e0 = pg_raster_edge(t.p1, t.p2, p), e1 = pg_raster_edge(t.p2, t.p0, p), e2 = pg_raster_edge(t.p0, t.p1, p);
    if (!pg_raster_owns(t.p1, t.p2, e0) || !pg_raster_owns(t.p2, t.p0, e1) || !pg_raster_owns(t.p0, t.p1, e2))
        return;
    float inv = 1.0 / float(t.area);
    float z = (float(e0) * t.z.x + float(e1) * t.z.y + float(e2) * t.z.z) * inv;
    z = max(z, 0.0);
    if (!(z < 1.0)) return; // beyond the far plane (a LESS test against the cleared 1.0)
    uint i = uint(px.y) * uint(pg_raster_size().x) + uint(px.x);
    uint64_t key = (uint64_t(floatBitsToUint(z)) << 32) | uint64_t(id);
#ifdef PG_RASTER_ALPHA_MASK
    if (masked && (key >= raster_keys[i] || !pg_raster_alpha_kept(id, px))) return;
#endif
    atomicMin(raster_keys[i], key);
}
