#version 460
// visibility_raster_tris.comp - the compute rasterizer's first step (visibility_raster.glsl): one
// invocation per triangle clips and sets it up; a triangle whose pixel box holds at most
// PG_RASTER_SMALL pixels is rasterized here, a larger one becomes jobs of PG_RASTER_JOB_BLOCKS 8x8
// blocks for visibility_raster_jobs.comp (an indirect dispatch of one workgroup per job). When the
// job list is full, the invocation rasterizes the triangle itself (the same pixels, slower).
#include "visibility_raster.glsl"
layout(local_size_x = 64) in;

void pg_raster_serial(PgRasterTri r, uint id, bool masked)
{
    for (int y = r.box.y; y <= r.box.w; y++)
        for (int x = r.box.x; x <= r.box.z; x++) pg_raster_pixel(r, ivec2(x, y), id, masked);
}

void main()
{
    uint t = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u + gl_LocalInvocationID.x;
    if (t >= rp.n_tris) return;
    vec4 c[3];
    uint id;
    bool two_sided, masked, mirrored;
    pg_raster_fetch(t, c, id, two_sided, masked, mirrored);
    vec4 poly[8];
    int n = 3;
    if (pg_raster_needs_clip(c)) n = pg_raster_clip(c, poly);
    else poly[0] = c[0], poly[1] = c[1], poly[2] = c[2];
    for (int k = 0; k + 2 < n; k++) { // the polygon as a fan
        PgRasterTri r;
        if (!pg_raster_setup(poly[0], poly[k + 1], poly[k + 2], !two_sided, mirrored, r)) continue;
        uint w = uint(r.box.z - r.box.x + 1), h = uint(r.box.w - r.box.y + 1);
        if (w * h <= PG_RASTER_SMALL) {
            pg_raster_serial(r, id, masked);
            continue;
        }
        uint bw = (w + 7u) / 8u, blocks = bw * ((h + 7u) / 8u);
        uint nj = (blocks + PG_RASTER_JOB_BLOCKS - 1u) / PG_RASTER_JOB_BLOCKS;
        uint s = atomicAdd(raster_job_next, nj);
        if (s + nj > rp.job_cap) { // no room: every later reservation fails too
            pg_raster_serial(r, id, masked);
            continue;
        }
        for (uint j = 0u; j < nj; j++) {
            PgRasterJob job;
            job.a = ivec4(r.p0, r.p1);
            job.b = uvec4(uint(r.p2.x), uint(r.p2.y), id, j * PG_RASTER_JOB_BLOCKS | (masked ? 0x80000000u : 0u));
            job.z = vec4(r.z, 0.0);
            raster_jobs[s + j] = job;
        }
        // both grow with the end, so a maximum keeps them: min(end, X) columns, ceil(end / X) rows
        atomicMax(raster_job_end, s + nj);
        atomicMax(raster_groups_x, min(s + nj, PG_RASTER_GROUPS_X));
        atomicMax(raster_groups_y, (s + nj + PG_RASTER_GROUPS_X - 1u) / PG_RASTER_GROUPS_X);
    }
}
