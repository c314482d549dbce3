/* tint.c - an example pass-type plug-in (docs/plugins.md): the pass type "tint" multiplies an
 * rgba16f image by a colour, in place, in a compute shader carried in this file.
 *
 *   {"name": "tint", "type": "tint", "writes": ["hdr"], "options": {"r": 1, "g": 0.8, "b": 0.6}}
 *
 * Slots: writes [image] (rgba16f storage image, read and written: storage_rw). Options r, g, b in
 * 0..1000 (default 1). Built by CMake as a shared object that links nothing of passgraph's: its
 * references to pg_* functions bind to the passgraph executable's exports when it is loaded with
 * `--plugin`. Built four times more for the loader's refusal tests: with PG_TINT_API_VERSION=999
 * (another API version), with PG_TINT_NO_ENTRY (no entry points), with PG_TINT_NO_CREATE (no create
 * function) and with PG_TINT_NAME="tint-x" (a type name no pipeline can write). */
#include <string.h>

#include "graph_execute.h"
#include "pass_api.h"
#include "pass_plugin.h"
#include "pass_set.h"
#include "shader.h"
#include "vk_pipeline.h"

#ifndef PG_TINT_API_VERSION
#define PG_TINT_API_VERSION PG_PLUGIN_API_VERSION
#endif
#ifndef PG_TINT_NAME
#define PG_TINT_NAME "tint"
#endif

static const char k_shader[] =
    "#version 460\n"
    "layout(local_size_x = 8, local_size_y = 8) in;\n"
    "layout(set = 0, binding = 0, rgba16f) uniform image2D img;\n"
    "layout(push_constant) uniform Push { vec4 color; } pc;\n"
    "void main()\n"
    "{\n"
    "    ivec2 p = ivec2(gl_GlobalInvocationID.xy);\n"
    "    if (any(greaterThanEqual(p, imageSize(img)))) return;\n"
    "    vec4 c = imageLoad(img, p);\n"
    "    imageStore(img, p, vec4(c.rgb * pc.color.rgb, c.a));\n"
    "}\n";

typedef struct tint_params {
    pg_slot image;
    float color[4];
} tint_params;

typedef struct tint {
    pg_pass_set set;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    pg_slot image;
    float color[4];
} tint;

static pg_result tint_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    static const char *const known[] = {"r", "g", "b", NULL};
    pg_result r = pg_opt_check_known(in->desc, known, err);
    if (r) return r;
    tint_params *p = pg_decl_params(out, sizeof *p);
    for (int k = 0; k < 3; k++) {
        double v;
        if ((r = pg_opt_float(in->desc, known[k], 1.0, 0.0, 1000.0, &v, err))) return r;
        p->color[k] = (float)v;
    }
    p->color[3] = 1.0f;
    p->image = pg_decl_write(out, "image", PG_RES_IMAGE, PG_ACCESS_STORAGE_RW, PG_STAGE_COMPUTE, PG_FMTCLASS_FLOAT);
    char where[32];
    const pg_resource_desc *rd = pg_decl_slot_resource(in, p->image, PG_RES_IMAGE, where, sizeof where);
    if (rd && rd->format != PG_FMT_RGBA16F)
        return pg_fail(err, PG_ERR_FORMAT, "%s: %s.%s: pass '%s': tint works on an rgba16f image; '%s' is %s",
                       in->desc->file, in->desc->json_path, where, in->desc->name, rd->name,
                       pg_format_get(rd->format)->name);
    pg_decl_explain(out, "multiplies the image by (%g, %g, %g)", p->color[0], p->color[1], p->color[2]);
    return PG_OK;
}

static pg_result tint_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    tint *t = self;
    const tint_params *pa = PG_PARAMS(ctx, tint_params);
    t->image = pa->image;
    memcpy(t->color, pa->color, sizeof t->color);
    pg_set_binding b = {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, pg_ctx_res(ctx, pa->image), VK_NULL_HANDLE, 0};
    pg_result r;
    if ((r = pg_pass_set_create(ctx->gpu, 1, &b, ctx->pass->name, &t->set, err))) return r;
    if ((r = pg_pipeline_layout_create(ctx->gpu, 1, &t->set.layout, sizeof t->color, &t->layout, err))) return r;
    const pg_shader_source src = {"plugin_tint.comp", k_shader};
    VkShaderModule cs;
    if ((r = pg_shader_module_ex(ctx->gpu, "plugin_tint.comp", VK_SHADER_STAGE_COMPUTE_BIT, NULL, 0, &src, 1, &cs,
                                 err)))
        return r;
    r = pg_compute_pipeline_create(ctx->gpu, t->layout, cs, ctx->pass->name, &t->pipeline, err);
    vkDestroyShaderModule(ctx->gpu->device, cs, NULL);
    return r;
}

static void tint_record(void *self, const pg_pass_record_ctx *ctx)
{
    tint *t = self;
    const pg_phys_resource *img = pg_ctx_res(ctx, t->image);
    vkCmdBindPipeline(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, t->pipeline);
    vkCmdBindDescriptorSets(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, t->layout, 0, 1, &t->set.set, 0, NULL);
    vkCmdPushConstants(ctx->cmd, t->layout, PG_PUSH_STAGES, 0, sizeof t->color, t->color);
    vkCmdDispatch(ctx->cmd, (img->width + 7) / 8, (img->height + 7) / 8, 1);
}

static void tint_destroy(void *self, pg_gpu *gpu)
{
    tint *t = self;
    if (t->pipeline) vkDestroyPipeline(gpu->device, t->pipeline, NULL);
    if (t->layout) vkDestroyPipelineLayout(gpu->device, t->layout, NULL);
    pg_pass_set_destroy(gpu, &t->set);
}

static const pg_pass_type k_tint = {
    .name = PG_TINT_NAME,
    .summary = "compute (plug-in example): multiply an rgba16f image by a colour, in place",
    .instance_size = sizeof(tint),
    .params_size = sizeof(tint_params),
    .declare = tint_declare,
#ifndef PG_TINT_NO_CREATE /* defined for the loader's "a type it cannot run" test case */
    .create = tint_create,
#endif
    .record = tint_record,
    .destroy = tint_destroy,
};

#ifndef PG_TINT_NO_ENTRY /* defined for the loader's "not a plug-in" test case */
PG_PLUGIN_EXPORT uint32_t passgraph_plugin_api_version(void)
{
    return PG_TINT_API_VERSION;
}

PG_PLUGIN_EXPORT pg_result passgraph_plugin_register(pg_pass_registry *reg, pg_error *err)
{
    return pg_registry_add(reg, &k_tint, err);
}
#else
const pg_pass_type *pg_tint_type_unused = &k_tint;
#endif
#ifdef PG_TINT_NO_CREATE
pg_result (*pg_tint_create_unused)(void *, const pg_pass_create_ctx *, pg_error *) = tint_create;
#endif
