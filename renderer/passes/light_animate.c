/* light_animate.c - compute pass: writes the light buffer (32 bytes a light) from the seed and
 * the frame time (shaders/light_animate.comp). Slots: writes [lights]. No options. */
#include <string.h>

#include "frame.h"
#include "graph_execute.h"
#include "scene_vars.h"
#include "pass_api.h"
#include "shader.h"
#include "pass_set.h"
#include "vk_pipeline.h"

typedef struct la_params { /* filled once by declare, read by create (PG_PARAMS) */
    pg_slot lights;
} la_params;

typedef struct light_animate { /* the instance create builds */
    pg_pass_set set;
    VkPipelineLayout layout;
    VkPipeline pipeline;
} light_animate;

static pg_result la_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    static const char *const known[] = {NULL};
    pg_result r = pg_opt_check_known(in->desc, known, err);
    if (r) return r;
    la_params *p = pg_decl_params(out, sizeof *p);
    p->lights = pg_decl_write(out, "lights", PG_RES_BUFFER, PG_ACCESS_STORAGE_WRITE, PG_STAGE_COMPUTE, 0);
    if (pg_lights_of(in) == 0) pg_decl_explain(out, "0 lights: the animation dispatch records nothing");
    return PG_OK;
}

static pg_result la_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    light_animate *p = self;
    pg_gpu *gpu = ctx->gpu;
    pg_result r;
    const la_params *pa = PG_PARAMS(ctx, la_params);
    pg_set_binding b = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, pg_ctx_res(ctx, pa->lights), VK_NULL_HANDLE, 0};
    if ((r = pg_pass_set_create(gpu, 1, &b, ctx->pass->name, &p->set, err))) return r;
    VkDescriptorSetLayout sets[2] = {ctx->frame_layout, p->set.layout};
    if ((r = pg_pipeline_layout_create(gpu, 2, sets, 0, &p->layout, err))) return r;
    VkShaderModule cs;
    if ((r = pg_shader_module(gpu, "light_animate.comp", VK_SHADER_STAGE_COMPUTE_BIT, NULL, 0, &cs, err))) return r;
    r = pg_compute_pipeline_create(gpu, p->layout, cs, ctx->pass->name, &p->pipeline, err);
    vkDestroyShaderModule(gpu->device, cs, NULL);
    return r;
}

static void la_record(void *self, const pg_pass_record_ctx *ctx)
{
    light_animate *p = self;
    uint32_t n = PG_FRAME_OF(ctx)->counts[0];
    if (!n) return;
    VkDescriptorSet sets[2] = {ctx->frame_set, p->set.set};
    vkCmdBindPipeline(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipeline);
    vkCmdBindDescriptorSets(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->layout, 0, 2, sets, 0, NULL);
    /* 2D dispatch so any count fits the guaranteed 65535 groups per dimension */
    uint32_t groups = (n + 63) / 64;
    uint32_t gx = groups < 65535 ? groups : 65535;
    uint32_t gy = (groups + gx - 1) / gx;
    vkCmdDispatch(ctx->cmd, gx, gy, 1);
}

static void la_destroy(void *self, pg_gpu *gpu)
{
    light_animate *p = self;
    if (p->pipeline) vkDestroyPipeline(gpu->device, p->pipeline, NULL);
    if (p->layout) vkDestroyPipelineLayout(gpu->device, p->layout, NULL);
    pg_pass_set_destroy(gpu, &p->set);
}

const pg_pass_type pg_pass_light_animate = {
    .name = "light_animate",
    .summary = "compute: animate N point lights from (seed, time) into a buffer",
    .instance_size = sizeof(light_animate),
    .params_size = sizeof(la_params),
    .declare = la_declare,
    .create = la_create,
    .record = la_record,
    .destroy = la_destroy,
};
