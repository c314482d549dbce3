/* visibility_raster.h - the visibility pass's compute rasterizer (its option raster "compute"):
 * writes the same triangle ids and depth as the hardware path, with compute shaders that use the
 * whole GPU rather than its raster units (shaders/visibility_raster.glsl says how it decides
 * coverage, depth and ties). Three dispatches and a copy a frame: one invocation per triangle
 * (small triangles drawn there, large ones cut into jobs), one workgroup per job (an indirect
 * dispatch), then one invocation per pixel turns the 64-bit (depth, id) minimum into the id image
 * and a depth buffer, copied into the depth image. The opaque and alpha-mask draws: with the
 * latter the shaders are compiled with the surface variant of the scene (the alpha test rebuilds
 * the surface at the pixel, as the shading pass does). Needs 64-bit buffer atomics
 * (pg_gpu.int64_atomics). */
#ifndef PG_VISIBILITY_RASTER_H
#define PG_VISIBILITY_RASTER_H

#include "visibility_common.h"

typedef struct pg_vis_raster {
    pg_vis_geometry vis;          /* vertices, indices, the draw table */
    pg_buffer keys, jobs, args, tri_start, depth;
    pg_phys_resource res[5];      /* descriptors of those buffers */
    pg_pass_set set;
    VkPipelineLayout layout;
    VkPipeline tris, job, resolve;
    uint32_t n_tris, n_draws, job_cap;
    bool masked;                  /* alpha-mask draws: PG_RASTER_ALPHA_MASK, the scene's set bound */
    uint32_t width, height;
    pg_slot depth_slot;           /* the depth image the record copies into */
} pg_vis_raster;

/* f: the pass's features (the geometry slot, the surface variant); vis_id / depth: its write slots (storage image,
 * transfer destination). */
pg_result pg_vis_raster_create(const pg_pass_create_ctx *ctx, const pg_scene_draw_features *f, pg_slot vis_id,
                               pg_slot depth, pg_vis_raster *r, pg_error *err);
void pg_vis_raster_record(const pg_vis_raster *r, const pg_pass_record_ctx *ctx);
void pg_vis_raster_destroy(pg_gpu *gpu, pg_vis_raster *r);

#endif
