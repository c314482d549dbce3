/* environment_filter.c - compute pass: fills the filtered environment (shaders/environment.glsl's
 * layout: diffuse table, split-sum table, prefiltered levels) from the scene's environment light
 * (pg_scene_gpu.environment, scene/environment.h), shaders/environment_filter.comp.
 * Slots: writes [environment] (a persistent buffer of stride 16 and count PG_ENV_TEXELS,
 * renderer/common/environment_layout.h).
 * It records its dispatch only when the buffer does not hold this environment yet: the first frame
 * after the buffer was created, or after the scene's environment changed (the buffer's content tag,
 * pg_ctx_content_tag, holds the id of the environment it was filtered from). A new plan that keeps
 * the buffer (new run-time values, new pipelines of the same memory) filters nothing again; the
 * counter filter_runs says whether this frame did.
 * Without an environment in the scene it skips itself ("no environment light"), so the graph culls
 * it and the buffer is not allocated. No options. */
#include <stdio.h>
#include <string.h>

#include "environment_layout.h"
#include "pass_api.h"
#include "pass_set.h"
#include "scene_gpu.h"
#include "scene_vars.h"
#include "shader.h"
#include "vk_pipeline.h"

typedef struct ef_params {
    pg_slot out;
} ef_params;

typedef struct environment_filter {
    pg_slot out;
    pg_pass_set set;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    uint32_t push[3];    /* source level 0 width, height, level count */
    uint64_t env_id;     /* the scene's environment */
    bool ran;            /* the last recorded frame dispatched */
} environment_filter;

static pg_result ef_check_resource(const pg_declare_in *in, pg_slot s, pg_error *err)
{
    char where[32];
    const pg_resource_desc *rd = pg_decl_slot_resource(in, s, PG_RES_BUFFER, where, sizeof where);
    if (!rd) return PG_OK; /* the graph reports an unbound or non-buffer slot */
    const bool sized = rd->stride == 16 && rd->n_count_terms == 1 && rd->count[0].kind == PG_COUNT_CONST &&
                       rd->count[0].value == (double)PG_ENV_TEXELS;
    if (!sized)
        return pg_fail(err, PG_ERR_SCHEMA,
                       "%s: %s.%s: pass '%s': the filtered environment is a buffer of stride 16 and count [%u] "
                       "(renderer/common/environment_layout.h); resource '%s' (%s %s) is not",
                       in->desc->file, in->desc->json_path, where, in->desc->name, PG_ENV_TEXELS, rd->name, rd->file,
                       rd->json_path);
    if (rd->lifetime != PG_LIFETIME_PERSISTENT)
        return pg_fail(err, PG_ERR_SCHEMA,
                       "%s: %s.%s: pass '%s': resource '%s' must have \"lifetime\": \"persistent\" (it is filtered "
                       "once and kept across frames)",
                       in->desc->file, in->desc->json_path, where, in->desc->name, rd->name);
    return PG_OK;
}

static pg_result ef_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    pg_result r = pg_opt_check_known(in->desc, (const char *const[]){NULL}, err);
    if (r) return r;
    ef_params *p = pg_decl_params(out, sizeof *p);
    p->out = pg_decl_write(out, "environment", PG_RES_BUFFER, PG_ACCESS_STORAGE_WRITE, PG_STAGE_COMPUTE, 0);
    if ((r = ef_check_resource(in, p->out, err))) return r;
    if (!pg_scene_features_of(in).has_environment) {
        pg_decl_skip(out, "no environment light in the scene (--environment, or a glTF file without lights)");
        return PG_OK;
    }
    pg_decl_explain(out, "filters the environment once into its persistent buffer (%u texels: diffuse 32x16, "
                         "split-sum table 32x32, %u prefiltered levels from 256x128); again only when the "
                         "environment changes",
                    PG_ENV_TEXELS, PG_ENV_SPEC_LEVELS);
    return PG_OK;
}

static pg_result ef_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    environment_filter *p = self;
    const ef_params *pa = PG_PARAMS(ctx, ef_params);
    const pg_scene_gpu *sg = PG_SCENE_OF(ctx);
    if (!sg || !sg->environment.buffer)
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s: the scene has an environment but no uploaded texels",
                       ctx->pass->name);
    p->out = pa->out;
    p->env_id = sg->env_id;
    p->push[0] = sg->env_width;
    p->push[1] = sg->env_height;
    p->push[2] = sg->env_levels;
    pg_phys_resource src = {.kind = PG_RES_BUFFER, .buffer = sg->environment.buffer, .size = sg->environment.size};
    pg_set_binding b[2] = {
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &src, VK_NULL_HANDLE, 0},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, pg_ctx_res(ctx, pa->out), VK_NULL_HANDLE, 0},
    };
    pg_result r;
    if ((r = pg_pass_set_create(ctx->gpu, 2, b, ctx->pass->name, &p->set, err))) return r;
    if ((r = pg_pipeline_layout_create(ctx->gpu, 1, &p->set.layout, sizeof p->push, &p->layout, err))) return r;
    VkShaderModule cs;
    if ((r = pg_shader_module(ctx->gpu, "environment_filter.comp", VK_SHADER_STAGE_COMPUTE_BIT, NULL, 0, &cs, err)))
        return r;
    r = pg_compute_pipeline_create(ctx->gpu, p->layout, cs, ctx->pass->name, &p->pipeline, err);
    vkDestroyShaderModule(ctx->gpu->device, cs, NULL);
    return r;
}

static void ef_record(void *self, const pg_pass_record_ctx *ctx)
{
    environment_filter *p = self;
    uint64_t *tag = pg_ctx_content_tag(ctx, p->out);
    p->ran = *tag != p->env_id;
    if (!p->ran) return; /* the buffer holds this environment already */
    vkCmdBindPipeline(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipeline);
    vkCmdBindDescriptorSets(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->layout, 0, 1, &p->set.set, 0, NULL);
    vkCmdPushConstants(ctx->cmd, p->layout, PG_PUSH_STAGES, 0, sizeof p->push, p->push);
    vkCmdDispatch(ctx->cmd, (PG_ENV_TEXELS + 63) / 64, 1, 1);
    *tag = p->env_id;
}

static void ef_report(void *self, pg_pass_report *out)
{
    pg_report_add(out, "filter_runs", ((environment_filter *)self)->ran ? 1 : 0);
}

static void ef_destroy(void *self, pg_gpu *gpu)
{
    environment_filter *p = self;
    if (p->pipeline) vkDestroyPipeline(gpu->device, p->pipeline, NULL);
    if (p->layout) vkDestroyPipelineLayout(gpu->device, p->layout, NULL);
    pg_pass_set_destroy(gpu, &p->set);
}

const pg_pass_type pg_pass_environment_filter = {
    .name = "environment_filter",
    .summary = "compute: filter the scene's environment light (diffuse, split-sum table, prefiltered levels) once "
               "into a persistent buffer",
    .instance_size = sizeof(environment_filter),
    .params_size = sizeof(ef_params),
    .declare = ef_declare,
    .create = ef_create,
    .record = ef_record,
    .destroy = ef_destroy,
    .report = ef_report,
};
