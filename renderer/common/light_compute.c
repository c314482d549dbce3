#include "light_compute.h"

#include "frame.h"
#include "shader.h"
#include "vk_pipeline.h"

pg_result pg_light_compute_create(const pg_pass_create_ctx *ctx, const char *shader,
                                  const pg_phys_resource *const *buffers, uint32_t n, pg_light_compute *out,
                                  pg_error *err)
{
    pg_gpu *gpu = ctx->gpu;
    pg_result r;
    pg_set_binding b[4];
    if (n > 4) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: %u buffers for a light pass (at most 4)", ctx->pass->name, n);
    for (uint32_t i = 0; i < n; i++) b[i] = (pg_set_binding){VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, buffers[i], VK_NULL_HANDLE, 0};
    if ((r = pg_pass_set_create(gpu, n, b, ctx->pass->name, &out->set, err))) return r;
    VkDescriptorSetLayout sets[2] = {ctx->frame_layout, out->set.layout};
    if ((r = pg_pipeline_layout_create(gpu, 2, sets, 0, &out->layout, err))) return r;
    const char *defs[PG_MAX_DEFINES];
    uint32_t nd = pg_decl_define_list(&ctx->pass->decl, defs, PG_MAX_DEFINES);
    VkShaderModule cs;
    if ((r = pg_shader_module(gpu, shader, VK_SHADER_STAGE_COMPUTE_BIT, defs, nd, &cs, err))) return r;
    r = pg_compute_pipeline_create(gpu, out->layout, cs, ctx->pass->name, &out->pipeline, err);
    vkDestroyShaderModule(gpu->device, cs, NULL);
    return r;
}

void pg_light_compute_record(const pg_light_compute *lc, const pg_pass_record_ctx *ctx)
{
    uint32_t n = PG_FRAME_OF(ctx)->counts[0];
    if (!n) return;
    VkDescriptorSet sets[2] = {ctx->frame_set, lc->set.set};
    vkCmdBindPipeline(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, lc->pipeline);
    vkCmdBindDescriptorSets(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, lc->layout, 0, 2, sets, 0, NULL);
    uint32_t groups = (n + 63) / 64;
    uint32_t gx = groups < 65535 ? groups : 65535;
    vkCmdDispatch(ctx->cmd, gx, (groups + gx - 1) / gx, 1);
}

void pg_light_compute_destroy(pg_light_compute *lc, pg_gpu *gpu)
{
    if (lc->pipeline) vkDestroyPipeline(gpu->device, lc->pipeline, NULL);
    if (lc->layout) vkDestroyPipelineLayout(gpu->device, lc->layout, NULL);
    pg_pass_set_destroy(gpu, &lc->set);
}
