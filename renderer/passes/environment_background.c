/* environment_background.c - compute pass: the environment behind the scene. Every pixel that no
 * surface covered (depth still 1) gets the environment's radiance toward its view ray, from the
 * scene's source image at the mip level that matches the pixel's angle
 * (shaders/environment_background.comp); covered pixels keep the shading pass's colour. It runs
 * after the opaque shading and before the transparent pass, so glass blends over the sky as a
 * viewer shows it. The source levels are the uploaded scene's (pg_scene_gpu.environment, static).
 * Slots: reads [depth (sampled)],
 * writes [hdr (rgba16f or rgba32f storage image, read and written: only background pixels change)].
 * Skipped (the graph culls it, with the reason) when the scene has no environment light, or under a
 * debug view. Options: "view" (the pipeline's debug view; default "none"). */

#include "pass_api.h"
#include "pass_set.h"
#include "scene_gpu.h"
#include "scene_vars.h"
#include "shading_common.h"
#include "shader.h"
#include "vk_pipeline.h"

typedef struct eb_params {
    pg_slot depth, hdr;
} eb_params;

typedef struct environment_background {
    pg_pass_set set;
    VkSampler sampler;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    uint32_t width, height;
    pg_phys_resource source;    /* the scene's environment levels (descriptor only) */
    uint32_t push[3];           /* the source's width, height, levels */
} environment_background;

static pg_result eb_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    static const char *const known[] = {"view", NULL};
    pg_result r = pg_opt_check_known(in->desc, known, err);
    if (r) return r;
    int view = 0;
    if ((r = pg_opt_enum(in->desc, "view", pg_debug_views, 0, &view, err))) return r;
    eb_params *p = pg_decl_params(out, sizeof *p);
    p->depth = pg_decl_read(out, "depth", PG_RES_IMAGE, PG_ACCESS_SAMPLED, PG_STAGE_COMPUTE, PG_FMTCLASS_DEPTH);
    p->hdr = pg_decl_write(out, "hdr", PG_RES_IMAGE, PG_ACCESS_STORAGE_RW, PG_STAGE_COMPUTE, PG_FMTCLASS_FLOAT);
    if ((r = pg_hdr_storage_check(in, p->hdr, "the environment background", err))) return r;
    if (!pg_scene_features_of(in).has_environment) {
        pg_decl_skip(out, "no environment light in the scene: the background stays black");
        return PG_OK;
    }
    if (view != 0) {
        pg_decl_skip(out, "debug view '%s': no background", pg_debug_views[view]);
        return PG_OK;
    }
    pg_decl_explain(out, "the environment (its source image at each pixel's level, x intensity, rotated) where no "
                         "surface was drawn");
    return PG_OK;
}

static pg_result eb_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    environment_background *p = self;
    pg_gpu *gpu = ctx->gpu;
    const eb_params *pa = PG_PARAMS(ctx, eb_params);
    const pg_phys_resource *hdr = pg_ctx_res(ctx, pa->hdr);
    pg_result r;
    p->width = hdr->width;
    p->height = hdr->height;
    const pg_scene_gpu *sg = PG_SCENE_OF(ctx);
    if (!sg || !sg->environment.buffer)
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s: the uploaded scene has no environment", ctx->pass->name);
    p->source = (pg_phys_resource){.kind = PG_RES_BUFFER, .buffer = sg->environment.buffer, .size = sg->environment.size};
    p->push[0] = sg->env_width;
    p->push[1] = sg->env_height;
    p->push[2] = sg->env_levels;
    if ((r = pg_sampler_create(gpu, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, &p->sampler, err))) return r;
    pg_set_binding b[3] = {
        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, pg_ctx_res(ctx, pa->depth), p->sampler, 0},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &p->source, VK_NULL_HANDLE, 0},
        {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, hdr, VK_NULL_HANDLE, 0},
    };
    if ((r = pg_pass_set_create(gpu, 3, b, ctx->pass->name, &p->set, err))) return r;
    VkDescriptorSetLayout sets[2] = {ctx->frame_layout, p->set.layout};
    if ((r = pg_pipeline_layout_create(gpu, 2, sets, sizeof p->push, &p->layout, err))) return r;
    char fmt_def[48];
    const char *defs[1] = {pg_hdr_format_define(hdr, fmt_def, sizeof fmt_def)};
    VkShaderModule cs;
    if ((r = pg_shader_module(gpu, "environment_background.comp", VK_SHADER_STAGE_COMPUTE_BIT, defs, 1, &cs, err)))
        return r;
    r = pg_compute_pipeline_create(gpu, p->layout, cs, ctx->pass->name, &p->pipeline, err);
    vkDestroyShaderModule(gpu->device, cs, NULL);
    return r;
}

static void eb_record(void *self, const pg_pass_record_ctx *ctx)
{
    environment_background *p = self;
    VkDescriptorSet sets[2] = {ctx->frame_set, p->set.set};
    vkCmdBindPipeline(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipeline);
    vkCmdBindDescriptorSets(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->layout, 0, 2, sets, 0, NULL);
    vkCmdPushConstants(ctx->cmd, p->layout, PG_PUSH_STAGES, 0, sizeof p->push, p->push);
    vkCmdDispatch(ctx->cmd, (p->width + 7) / 8, (p->height + 7) / 8, 1);
}

static void eb_destroy(void *self, pg_gpu *gpu)
{
    environment_background *p = self;
    if (p->pipeline) vkDestroyPipeline(gpu->device, p->pipeline, NULL);
    if (p->layout) vkDestroyPipelineLayout(gpu->device, p->layout, NULL);
    if (p->sampler) vkDestroySampler(gpu->device, p->sampler, NULL);
    pg_pass_set_destroy(gpu, &p->set);
}

const pg_pass_type pg_pass_environment_background = {
    .name = "environment_background",
    .summary = "compute: the environment light behind the scene, where no surface was drawn",
    .instance_size = sizeof(environment_background),
    .params_size = sizeof(eb_params),
    .declare = eb_declare,
    .create = eb_create,
    .record = eb_record,
    .destroy = eb_destroy,
};
