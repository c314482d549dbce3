/* geometry_animate.c - compute pass: the scene's vertices at the frame's pose
 * (shaders/animate_geometry.comp, CPU twin scene/animation.c pg_anim_deform): morph targets, skins
 * and animated node transforms applied to the mesh-space vertices of the moving primitives, the
 * static ones copied. Slots: writes [geometry] (a buffer of stride 48 and count ["vertices"]: the
 * scene's pg_vertex layout), which every scene-drawing pass reads as its vertex stream when bound
 * (renderer/common/scene_draw.h pg_geometry_slot_declare).
 * Each frame it evaluates the pose on the CPU from the frame's time and played animation
 * (pg_frame_uniforms camera_pos.w and light_src.y: node world matrices, joint matrices, morph
 * weights; O(nodes + joints)), writes it into the scene's pose buffer with vkCmdUpdateBuffer
 * (recorded into the frame's commands, so frames in flight each keep their own pose), and deforms
 * every vertex on the GPU, one thread a vertex. Without animation in the scene it skips itself, so
 * the graph culls it and the buffer is not allocated: the drawing passes read the static vertex
 * buffer. No options. */
#include <stdlib.h>
#include <string.h>

#include "frame.h"
#include "pass_api.h"
#include "pass_set.h"
#include "scene_gpu.h"
#include "scene_gpu_anim.h"
#include "scene_vars.h"
#include "shader.h"
#include "vk_pipeline.h"

typedef struct ga_params {
    pg_slot out;
} ga_params;

typedef struct geometry_animate {
    pg_pass_set set;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    const pg_scene_gpu_anim *ga;
    float *pose;         /* the packed pose, ga->pose_floats */
    uint32_t push[3];    /* vertices, joint base, weight base */
} geometry_animate;

static pg_result ga_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    pg_result r = pg_opt_check_known(in->desc, (const char *const[]){NULL}, err);
    if (r) return r;
    ga_params *p = pg_decl_params(out, sizeof *p);
    p->out = pg_decl_write(out, "geometry", PG_RES_BUFFER, PG_ACCESS_STORAGE_WRITE, PG_STAGE_COMPUTE, 0);
    char where[32];
    const pg_resource_desc *rd = pg_decl_slot_resource(in, p->out, PG_RES_BUFFER, where, sizeof where);
    if (rd && rd->stride != sizeof(pg_vertex))
        return pg_fail(err, PG_ERR_SCHEMA,
                       "%s: %s.%s: pass '%s': the deformed vertices are a buffer of stride %zu (scene.h pg_vertex); "
                       "resource '%s' has stride %u",
                       in->desc->file, in->desc->json_path, where, in->desc->name, sizeof(pg_vertex), rd->name,
                       (unsigned)rd->stride);
    if (!pg_scene_features_of(in).has_animation) {
        pg_decl_skip(out, "no animation in the scene (no skins, morph targets or animated nodes): the drawing passes "
                          "read the static vertex buffer");
        return PG_OK;
    }
    pg_decl_explain(out, "deforms the scene's vertices every frame at the frame's time (morph targets, skins, "
                         "animated nodes); the pose is evaluated on the CPU and uploaded with the frame's commands");
    return PG_OK;
}

static pg_result ga_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    geometry_animate *p = self;
    const ga_params *pa = PG_PARAMS(ctx, ga_params);
    const pg_scene_gpu *sg = PG_SCENE_OF(ctx);
    if (!sg || !sg->anim)
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s: the scene has animation but no uploaded animation data",
                       ctx->pass->name);
    const pg_scene_gpu_anim *ga = p->ga = sg->anim;
    const pg_phys_resource *out = pg_ctx_res(ctx, pa->out);
    if (out->size < (VkDeviceSize)ga->n_vertices * sizeof(pg_vertex))
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s: its geometry buffer holds %llu bytes, %u vertices need %llu",
                       ctx->pass->name, (unsigned long long)out->size, ga->n_vertices,
                       (unsigned long long)ga->n_vertices * sizeof(pg_vertex));
    p->pose = malloc((size_t)ga->pose_floats * sizeof(float) + 16);
    if (!p->pose) return pg_fail(err, PG_ERR_OOM, "out of memory");
    p->push[0] = ga->n_vertices;
    p->push[1] = ga->joint_base;
    p->push[2] = ga->weight_base;
    const pg_buffer *in[5] = {&ga->local, &ga->info, &ga->prims, &ga->deltas, &ga->pose};
    pg_phys_resource res[5];
    pg_set_binding b[6] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, out, VK_NULL_HANDLE, 0}};
    for (int i = 0; i < 5; i++) {
        res[i] = (pg_phys_resource){.kind = PG_RES_BUFFER, .buffer = in[i]->buffer, .size = in[i]->size};
        b[i + 1] = (pg_set_binding){VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &res[i], VK_NULL_HANDLE, 0};
    }
    pg_result r;
    if ((r = pg_pass_set_create(ctx->gpu, 6, b, ctx->pass->name, &p->set, err))) return r;
    if ((r = pg_pipeline_layout_create(ctx->gpu, 1, &p->set.layout, sizeof p->push, &p->layout, err))) return r;
    VkShaderModule cs;
    const char *defines[1] = {"PG_ANIM_INFLUENCES8"}; /* 8 joints a vertex: the larger info record */
    if ((r = pg_shader_module(ctx->gpu, "animate_geometry.comp", VK_SHADER_STAGE_COMPUTE_BIT, defines,
                              ga->info_stride > 32 ? 1 : 0, &cs, err)))
        return r;
    r = pg_compute_pipeline_create(ctx->gpu, p->layout, cs, ctx->pass->name, &p->pipeline, err);
    vkDestroyShaderModule(ctx->gpu->device, cs, NULL);
    return r;
}

/* the pose into the scene's pose buffer: after every earlier read, before this frame's */
static void upload_pose(const geometry_animate *p, VkCommandBuffer cmd)
{
    const pg_buffer *pose = &p->ga->pose;
    VkBufferMemoryBarrier2 b = pg_buffer_barrier(pose->buffer, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                                 VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                                                 VK_ACCESS_2_TRANSFER_WRITE_BIT);
    pg_cmd_barriers(cmd, 0, NULL, 1, &b);
    const VkDeviceSize bytes = (VkDeviceSize)p->ga->pose_floats * sizeof(float);
    for (VkDeviceSize off = 0; off < bytes; off += 65536) { /* vkCmdUpdateBuffer: at most 64 KiB a call */
        VkDeviceSize n = bytes - off < 65536 ? bytes - off : 65536;
        vkCmdUpdateBuffer(cmd, pose->buffer, off, n, (const uint8_t *)p->pose + off);
    }
    b = pg_buffer_barrier(pose->buffer, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    pg_cmd_barriers(cmd, 0, NULL, 1, &b);
}

static void ga_record(void *self, const pg_pass_record_ctx *ctx)
{
    geometry_animate *p = self;
    const pg_frame_uniforms *fu = PG_FRAME_OF(ctx);
    const int32_t animation = pg_frame_animation(fu);
    pg_scene_gpu_anim_pack_pose(p->ga, animation, fu->camera_pos[3], p->pose);
    if (p->ga->pose_floats) upload_pose(p, ctx->cmd);
    vkCmdBindPipeline(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipeline);
    vkCmdBindDescriptorSets(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->layout, 0, 1, &p->set.set, 0, NULL);
    vkCmdPushConstants(ctx->cmd, p->layout, PG_PUSH_STAGES, 0, sizeof p->push, p->push);
    vkCmdDispatch(ctx->cmd, (p->ga->n_vertices + 63) / 64, 1, 1);
}

static void ga_report(void *self, pg_pass_report *out)
{
    const geometry_animate *p = self;
    pg_report_add(out, "vertices", p->ga ? p->ga->n_vertices : 0);
}

static void ga_destroy(void *self, pg_gpu *gpu)
{
    geometry_animate *p = self;
    if (p->pipeline) vkDestroyPipeline(gpu->device, p->pipeline, NULL);
    if (p->layout) vkDestroyPipelineLayout(gpu->device, p->layout, NULL);
    pg_pass_set_destroy(gpu, &p->set);
    free(p->pose);
    p->pose = NULL;
}

const pg_pass_type pg_pass_geometry_animate = {
    .name = "geometry_animate",
    .summary = "compute: the scene's vertices at the frame's pose (morph targets, skins, animated nodes)",
    .instance_size = sizeof(geometry_animate),
    .params_size = sizeof(ga_params),
    .declare = ga_declare,
    .create = ga_create,
    .record = ga_record,
    .destroy = ga_destroy,
    .report = ga_report,
};
