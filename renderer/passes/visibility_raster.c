/* visibility_raster.c - the visibility pass's compute rasterizer (visibility_raster.h). */
#include "visibility_raster.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "shader.h"

/* a job covers 16 8x8 blocks (1,024 pixels) of one triangle's box; the list holds one job per 32
 * pixels of the target, at least 65,536 and at most 2^22 (the jobs of a frame: about the pixels
 * covered, times the boxes' waste, over 1,024) */
enum { RASTER_JOB_BYTES = 48, RASTER_JOB_MIN = 65536, RASTER_JOB_MAX = 1 << 22, RASTER_PIXELS_PER_JOB = 32 };

typedef struct raster_push {
    uint32_t n_tris, n_draws, job_cap, tri_bits;
} raster_push;

static pg_result make_buffers(pg_gpu *gpu, const pg_scene_gpu *sc, const char *pass, pg_vis_raster *r, pg_error *err)
{
    const VkDeviceSize pixels = (VkDeviceSize)r->width * r->height;
    if (pixels * 8 > gpu->max_storage_buffer_range)
        return pg_fail(err, PG_ERR_LIMIT,
                       "%s: raster \"compute\" keeps 8 bytes a pixel in one buffer: %ux%u needs %llu bytes, the "
                       "device allows %llu per buffer; use raster \"hardware\"",
                       pass, r->width, r->height, (unsigned long long)(pixels * 8),
                       (unsigned long long)gpu->max_storage_buffer_range);
    const VkBufferUsageFlags st = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    const struct {
        pg_buffer *b;
        VkDeviceSize size;
        VkBufferUsageFlags usage;
        bool host;
        const char *what;
    } k[5] = {
        {&r->keys, pixels * 8, st | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false, "keys"},
        {&r->jobs, 16 + (VkDeviceSize)r->job_cap * RASTER_JOB_BYTES, st | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false, "jobs"},
        {&r->args, 16, st | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false, "args"},
        {&r->tri_start, 4 * ((VkDeviceSize)r->n_draws + 1), st, true, "tri_start"},
        {&r->depth, pixels * 4, st | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, false, "depth"},
    };
    char name[PG_NAME_MAX + 24];
    pg_result res;
    for (int i = 0; i < 5; i++) {
        snprintf(name, sizeof name, "%s.%s", pass, k[i].what);
        if ((res = pg_buffer_create(gpu, k[i].size, k[i].usage, k[i].host, name, k[i].b, err))) return res;
        r->res[i] = (pg_phys_resource){.kind = PG_RES_BUFFER, .buffer = k[i].b->buffer, .size = k[i].b->size};
    }
    uint32_t *start = r->tri_start.mapped;
    uint32_t t = 0;
    for (uint32_t d = 0; d < r->n_draws; d++) {
        start[d] = t;
        t += sc->draws[d].index_count / 3;
    }
    start[r->n_draws] = t;
    return PG_OK;
}

static pg_result make_pipelines(const pg_pass_create_ctx *ctx, pg_vis_raster *r, pg_error *err)
{
    const char *defs[PG_MAX_DEFINES + 16];
    uint32_t nd = 0;
    /* PASSGRAPH_RASTER_GROUPS_X=N (1..65535): the job dispatch's rows N groups wide instead of 65,535,
     * so that a test reaches its second row */
    char gx[40];
    const char *env = getenv("PASSGRAPH_RASTER_GROUPS_X");
    const long n = env ? strtol(env, NULL, 10) : 0;
    if (n >= 1 && n <= 65535) {
        snprintf(gx, sizeof gx, "PG_RASTER_GROUPS_X=%ldu", n);
        defs[nd++] = gx;
    }
    if (r->masked) { /* the surface variant of the alpha test (visibility_surface.glsl, surface.glsl) */
        nd += pg_vis_geometry_define_list(&r->vis, defs + nd);
        defs[nd++] = "PG_RASTER_ALPHA_MASK";
    }
    static const char *const shaders[3] = {"visibility_raster_tris.comp", "visibility_raster_jobs.comp",
                                           "visibility_raster_resolve.comp"};
    VkPipeline *out[3] = {&r->tris, &r->job, &r->resolve};
    pg_result res;
    for (int i = 0; i < 3; i++) {
        VkShaderModule cs;
        if ((res = pg_shader_module(ctx->gpu, shaders[i], VK_SHADER_STAGE_COMPUTE_BIT, defs, nd, &cs, err)))
            return res;
        pg_compute_pipeline_desc pd = {.layout = r->layout, .cs = cs};
        res = pg_compute_pipeline_create_ex(ctx->gpu, &pd, ctx->pass->name, out[i], err);
        vkDestroyShaderModule(ctx->gpu->device, cs, NULL);
        if (res) return res;
    }
    return PG_OK;
}

pg_result pg_vis_raster_create(const pg_pass_create_ctx *ctx, const pg_scene_draw_features *f, pg_slot vis_id,
                               pg_slot depth, pg_vis_raster *r, pg_error *err)
{
    pg_gpu *gpu = ctx->gpu;
    const pg_scene_gpu *sc = PG_SCENE_OF(ctx);
    pg_result res;
    if (!gpu->int64_atomics)
        return pg_fail(err, PG_ERR_NO_DEVICE,
                       "%s: raster \"compute\" needs 64-bit atomics on storage buffers (shaderInt64 and "
                       "shaderBufferInt64Atomics), which the device lacks; use raster \"hardware\"",
                       ctx->pass->name);
    if (!sc) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: needs a scene", ctx->pass->name);
    r->masked = f->alpha_mask;
    pg_scene_draw_features vf = *f;
    if (!r->masked) vf.vertex_colors = vf.uv1 = false; /* positions only */
    if ((res = pg_vis_geometry_create(ctx, &vf, 2, &r->vis, err))) return res;
    const pg_phys_resource *id = pg_ctx_res(ctx, vis_id);
    r->width = id->width;
    r->height = id->height;
    r->n_draws = sc->n_draws - sc->n_blend_draws; /* the opaque, then the alpha-mask draws */
    /* PASSGRAPH_RASTER_JOBS=N (1..2^22): another job list size, e.g. a small one, so that its
     * overflow path (the triangle rasterized by its own invocation) can be tested */
    uint64_t want = (uint64_t)r->width * r->height / RASTER_PIXELS_PER_JOB;
    want = want < RASTER_JOB_MIN ? RASTER_JOB_MIN : want > RASTER_JOB_MAX ? RASTER_JOB_MAX : want;
    const char *jobs = getenv("PASSGRAPH_RASTER_JOBS");
    const long cap = jobs ? strtol(jobs, NULL, 10) : (long)want;
    r->job_cap = cap >= 1 && cap <= RASTER_JOB_MAX ? (uint32_t)cap : (uint32_t)want;
    r->depth_slot = depth;
    if ((res = make_buffers(gpu, sc, ctx->pass->name, r, err))) return res;
    r->n_tris = ((const uint32_t *)r->tri_start.mapped)[r->n_draws];
    pg_set_binding b[10];
    uint32_t n = 0;
    for (int i = 0; i < 4; i++) b[n++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &r->res[i], VK_NULL_HANDLE, 0};
    b[n++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, id, VK_NULL_HANDLE, 0};
    b[n++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &r->res[4], VK_NULL_HANDLE, 0};
    n = pg_vis_geometry_bindings(&r->vis, sc, b, n);
    char name[PG_NAME_MAX + 16];
    snprintf(name, sizeof name, "%s.set", ctx->pass->name);
    if ((res = pg_pass_set_create(gpu, n, b, name, &r->set, err))) return res;
    VkDescriptorSetLayout sets[3] = {ctx->frame_layout, r->set.layout, sc->set_layout};
    if ((res = pg_pipeline_layout_create(gpu, r->masked ? 3 : 2, sets, sizeof(raster_push), &r->layout, err)))
        return res;
    return make_pipelines(ctx, r, err);
}

static void buffer_barrier(VkCommandBuffer cmd, VkBuffer b, VkPipelineStageFlags2 ss, VkAccessFlags2 sa,
                           VkPipelineStageFlags2 ds, VkAccessFlags2 da)
{
    VkBufferMemoryBarrier2 x = pg_buffer_barrier(b, ss, sa, ds, da);
    pg_cmd_barriers(cmd, 0, NULL, 1, &x);
}

void pg_vis_raster_record(const pg_vis_raster *r, const pg_pass_record_ctx *ctx)
{
    VkCommandBuffer cmd = ctx->cmd;
    const VkPipelineStageFlags2 CS = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, TR = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
    const VkAccessFlags2 SRW = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    /* every frame begins with a full barrier (graph_execute.h): the previous frame's uses are done */
    pg_vis_geometry_record(&r->vis, ctx); /* the draws the pose mirrors: culled the other way */
    vkCmdFillBuffer(cmd, r->keys.buffer, 0, VK_WHOLE_SIZE, 0xFFFFFFFFu); /* depth NaN-max, id none */
    vkCmdFillBuffer(cmd, r->jobs.buffer, 0, 16, 0);
    const uint32_t args[4] = {0, 0, 1, 0}; /* no groups until a job is written */
    vkCmdUpdateBuffer(cmd, r->args.buffer, 0, sizeof args, args);
    pg_cmd_memory_barrier(cmd, TR, VK_ACCESS_2_TRANSFER_WRITE_BIT, CS, SRW);
    VkDescriptorSet sets[3] = {ctx->frame_set, r->set.set, PG_SCENE_OF(ctx)->set};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r->layout, 0, r->masked ? 3 : 2, sets, 0, NULL);
    const raster_push push = {r->n_tris, r->n_draws, r->job_cap, r->vis.tri_bits};
    vkCmdPushConstants(cmd, r->layout, PG_PUSH_STAGES, 0, sizeof push, &push);
    const uint32_t groups = (r->n_tris + 63) / 64, gx = groups < 65535 ? groups : 65535;
    if (groups) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r->tris);
        vkCmdDispatch(cmd, gx, (groups + gx - 1) / gx, 1);
    }
    pg_cmd_memory_barrier(cmd, CS, SRW, CS | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                          SRW | VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r->job);
    vkCmdDispatchIndirect(cmd, r->args.buffer, 0);
    pg_cmd_memory_barrier(cmd, CS, SRW, CS, SRW);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r->resolve);
    vkCmdDispatch(cmd, (r->width + 7) / 8, (r->height + 7) / 8, 1);
    buffer_barrier(cmd, r->depth.buffer, CS, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, TR, VK_ACCESS_2_TRANSFER_READ_BIT);
    const pg_phys_resource *depth = pg_ctx_res(ctx, r->depth_slot);
    VkBufferImageCopy c = {.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1},
                           .imageExtent = {r->width, r->height, 1}};
    vkCmdCopyBufferToImage(cmd, r->depth.buffer, depth->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &c);
}

void pg_vis_raster_destroy(pg_gpu *gpu, pg_vis_raster *r)
{
    if (r->tris) vkDestroyPipeline(gpu->device, r->tris, NULL);
    if (r->job) vkDestroyPipeline(gpu->device, r->job, NULL);
    if (r->resolve) vkDestroyPipeline(gpu->device, r->resolve, NULL);
    if (r->layout) vkDestroyPipelineLayout(gpu->device, r->layout, NULL);
    pg_pass_set_destroy(gpu, &r->set);
    pg_buffer *bufs[5] = {&r->keys, &r->jobs, &r->args, &r->tri_start, &r->depth};
    for (int i = 0; i < 5; i++) pg_buffer_destroy(gpu, bufs[i]);
    pg_vis_geometry_destroy(gpu, &r->vis);
    memset(r, 0, sizeof *r);
}
