/* stochastic_lights.c - compute pass: stochastic light culling (shaders/stochastic_lights.comp):
 * each light's range is cut to a random r(xi) where its contribution falls below a threshold, and
 * the shading pass rescales what it keeps (deferred_lighting option stochastic_threshold, the same
 * value), so the expectation of every pixel is exact. Slots: reads [lights], writes
 * [lights_stochastic] (same layout: position and random range; colour and the true range in w).
 * Options: threshold (luminance of one light's attenuated colour below which it is kept at random;
 * > 0). The random numbers come from the frame's sample index and seed. */
#include <string.h>

#include "frame.h"
#include "graph_execute.h"
#include "scene_vars.h"
#include "pass_api.h"
#include "shader.h"
#include "pass_set.h"
#include "vk_pipeline.h"

typedef struct sl_params { /* filled once by declare, read by create (PG_PARAMS) */
    pg_slot lights, out;
} sl_params;

typedef struct stochastic_lights { /* the instance create builds */
    pg_pass_set set;
    VkPipelineLayout layout;
    VkPipeline pipeline;
} stochastic_lights;

static pg_result sl_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    static const char *const known[] = {"threshold", NULL};
    pg_result r = pg_opt_check_known(in->desc, known, err);
    if (r) return r;
    double tau;
    if ((r = pg_opt_float(in->desc, "threshold", 0.05, 1e-6, 1e6, &tau, err))) return r;
    sl_params *p = pg_decl_params(out, sizeof *p);
    p->lights = pg_decl_read(out, "lights", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_COMPUTE, 0);
    p->out = pg_decl_write(out, "lights_stochastic", PG_RES_BUFFER, PG_ACCESS_STORAGE_WRITE, PG_STAGE_COMPUTE, 0);
    pg_decl_define_int(out, "PG_SC_TAU_MICRO", (int64_t)(tau * 1e6 + 0.5));
    pg_decl_explain(out, "threshold %g: lights are cut to random ranges below it (unbiased, noisy)", tau);
    if (pg_lights_of(in) == 0) pg_decl_explain(out, "0 lights: the culling dispatch records nothing");
    return PG_OK;
}

static pg_result sl_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    stochastic_lights *p = self;
    pg_gpu *gpu = ctx->gpu;
    pg_result r;
    const sl_params *pa = PG_PARAMS(ctx, sl_params);
    pg_set_binding b[2] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, pg_ctx_res(ctx, pa->lights), VK_NULL_HANDLE, 0},
                           {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, pg_ctx_res(ctx, pa->out), VK_NULL_HANDLE, 0}};
    if ((r = pg_pass_set_create(gpu, 2, b, ctx->pass->name, &p->set, err))) return r;
    VkDescriptorSetLayout sets[2] = {ctx->frame_layout, p->set.layout};
    if ((r = pg_pipeline_layout_create(gpu, 2, sets, 0, &p->layout, err))) return r;
    VkShaderModule cs;
    const char *defs[PG_MAX_DEFINES];
    uint32_t nd = pg_decl_define_list(&ctx->pass->decl, defs, PG_MAX_DEFINES);
    if ((r = pg_shader_module(gpu, "stochastic_lights.comp", VK_SHADER_STAGE_COMPUTE_BIT, defs, nd, &cs, err))) return r;
    r = pg_compute_pipeline_create(gpu, p->layout, cs, ctx->pass->name, &p->pipeline, err);
    vkDestroyShaderModule(gpu->device, cs, NULL);
    return r;
}

static void sl_record(void *self, const pg_pass_record_ctx *ctx)
{
    stochastic_lights *p = self;
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

static void sl_destroy(void *self, pg_gpu *gpu)
{
    stochastic_lights *p = self;
    if (p->pipeline) vkDestroyPipeline(gpu->device, p->pipeline, NULL);
    if (p->layout) vkDestroyPipelineLayout(gpu->device, p->layout, NULL);
    pg_pass_set_destroy(gpu, &p->set);
}

const pg_pass_type pg_pass_stochastic_lights = {
    .name = "stochastic_lights",
    .summary = "compute: stochastic light culling, a random range per light below a threshold (unbiased)",
    .instance_size = sizeof(stochastic_lights),
    .params_size = sizeof(sl_params),
    .declare = sl_declare,
    .create = sl_create,
    .record = sl_record,
    .destroy = sl_destroy,
};
