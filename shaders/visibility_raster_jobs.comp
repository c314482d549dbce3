#version 460
// visibility_raster_jobs.comp - the compute rasterizer's second step (visibility_raster.glsl): one
// workgroup of 8x8 invocations per job (a 2D grid of groups: more jobs than one dimension allows)
// covers up to PG_RASTER_JOB_BLOCKS 8x8 blocks of a large triangle's pixel box, an invocation per
// pixel of the block.
#include "visibility_raster.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

void main()
{
    uint j = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    if (j >= raster_job_end) return; // the last row's tail (uniform: the whole workgroup)
    PgRasterJob job = raster_jobs[j];
    PgRasterTri r;
    r.p0 = job.a.xy;
    r.p1 = job.a.zw;
    r.p2 = ivec2(job.b.xy);
    r.z = job.z.xyz;
    r.area = pg_raster_edge(r.p0, r.p1, r.p2);
    pg_raster_box(r);
    uint bw = uint(r.box.z - r.box.x + 8) / 8u;
    uint blocks = bw * (uint(r.box.w - r.box.y + 8) / 8u);
    uint first = job.b.w & 0x7fffffffu;
    bool masked = (job.b.w & 0x80000000u) != 0u;
    uint end = min(first + PG_RASTER_JOB_BLOCKS, blocks);
    for (uint b = first; b < end; b++) {
        ivec2 px = r.box.xy + ivec2((b % bw) * 8u, (b / bw) * 8u) + ivec2(gl_LocalInvocationID.xy);
        if (px.x <= r.box.z && px.y <= r.box.w) pg_raster_pixel(r, px, job.b.z, masked);
    }
}
