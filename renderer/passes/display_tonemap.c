/* display_tonemap.c - scene-linear HDR -> 8-bit display image, the simple alternative to the
 * OpenColorIO display pass (display_ocio): exposure, then "clamp" | "reinhard" | "aces" (default
 * clamp, which keeps the reference projects' look: output = albedo x light sum, saturated at 1).
 * sRGB encoding: an rgba8_srgb target encodes on write; for a UNORM target (rgba8, rgba16) the
 * shader applies the sRGB curve itself (define PG_ENCODE_SRGB); float targets get linear values.
 * Slots: reads [hdr] (sampled, fragment); writes [ldr]. Options: exposure (> 0, default 1),
 * operator. */
#include <string.h>

#include "display_common.h"
#include "graph_execute.h"
#include "pass_api.h"
#include "shader.h"
#include "pass_set.h"
#include "vk_pipeline.h"

typedef struct dt_params { /* filled once by declare, read by create/update/record */
    float exposure;        /* a run-time value: push constant */
    pg_slot hdr, ldr;
} dt_params;

typedef struct display_tonemap {
    pg_pass_set set;
    VkSampler sampler;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    float exposure;
    uint32_t ldr_slot;     /* plan slot of ldr (pg_pass_begin_rendering) */
} display_tonemap;

static const char *const k_ops[] = {"clamp", "reinhard", "aces", NULL};

static pg_result dt_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    static const char *const known[] = {"exposure", "operator", NULL};
    dt_params *p = pg_decl_params(out, sizeof *p);
    pg_result r;
    double exposure;
    int op;
    if ((r = pg_opt_check_known(in->desc, known, err))) return r;
    if ((r = pg_opt_float(in->desc, "exposure", 1.0, 1e-6, 1e6, &exposure, err))) return r;
    if ((r = pg_opt_enum(in->desc, "operator", k_ops, 0, &op, err))) return r;
    p->exposure = (float)exposure;
    pg_decl_runtime_param(out, &p->exposure, sizeof p->exposure);
    p->hdr = pg_decl_read(out, "hdr", PG_RES_IMAGE, PG_ACCESS_SAMPLED, PG_STAGE_FRAGMENT, PG_FMTCLASS_FLOAT);
    p->ldr = pg_decl_write(out, "ldr", PG_RES_IMAGE, PG_ACCESS_COLOR_WRITE, PG_STAGE_FRAGMENT, PG_FMTCLASS_FLOAT);
    pg_decl_define_int(out, "PG_TONEMAP", op);
    const pg_resource_desc *ldr =
        in->desc->n_writes >= 1 && in->pipeline ? pg_pipeline_find_resource(in->pipeline, in->desc->writes[0]) : NULL;
    if (ldr && ldr->kind == PG_RES_IMAGE &&
        (ldr->format == PG_FMT_RGBA8_UNORM || ldr->format == PG_FMT_RGBA16_UNORM)) {
        pg_decl_define(out, "PG_ENCODE_SRGB");
        pg_decl_explain(out, "target '%s' is %s (UNORM): the shader applies the sRGB curve", ldr->name,
                        pg_format_get(ldr->format)->name);
    }
    return PG_OK;
}

static pg_result dt_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    display_tonemap *p = self;
    pg_gpu *gpu = ctx->gpu;
    const dt_params *pa = PG_PARAMS(ctx, dt_params);
    pg_result r;
    p->exposure = pa->exposure;
    p->ldr_slot = pg_plan_slot_of(ctx->pass, pa->ldr);
    if ((r = pg_sampler_create(gpu, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, &p->sampler, err))) return r;
    pg_set_binding b = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, pg_ctx_res(ctx, pa->hdr), p->sampler, 0};
    if ((r = pg_pass_set_create(gpu, 1, &b, ctx->pass->name, &p->set, err))) return r;
    VkDescriptorSetLayout sets[2] = {ctx->frame_layout, p->set.layout};
    if ((r = pg_pipeline_layout_create(gpu, 2, sets, sizeof(float), &p->layout, err))) return r;
    const char *defs[PG_MAX_DEFINES];
    const uint32_t nd = pg_decl_define_list(&ctx->pass->decl, defs, PG_MAX_DEFINES);
    VkShaderModule vs = VK_NULL_HANDLE, fs = VK_NULL_HANDLE;
    if ((r = pg_shader_module(gpu, "fullscreen.vert", VK_SHADER_STAGE_VERTEX_BIT, NULL, 0, &vs, err))) goto out;
    if ((r = pg_shader_module(gpu, "display_tonemap.frag", VK_SHADER_STAGE_FRAGMENT_BIT, defs, nd, &fs,
                              err)))
        goto out;
    pg_gfx_pipeline_desc d = {
        .layout = p->layout,
        .vs = vs,
        .fs = fs,
        .n_color = 1,
        .color_formats = {pg_ctx_res(ctx, pa->ldr)->format},
    };
    r = pg_gfx_pipeline_create(gpu, &d, ctx->pass->name, &p->pipeline, err);
out:
    if (vs) vkDestroyShaderModule(gpu->device, vs, NULL);
    if (fs) vkDestroyShaderModule(gpu->device, fs, NULL);
    return r;
}

static void dt_record(void *self, const pg_pass_record_ctx *ctx)
{
    display_tonemap *p = self;
    pg_display_record_fullscreen(ctx, p->ldr_slot, p->pipeline, p->layout, p->set.set, p->exposure);
}

static void dt_destroy(void *self, pg_gpu *gpu)
{
    display_tonemap *p = self;
    if (p->pipeline) vkDestroyPipeline(gpu->device, p->pipeline, NULL);
    if (p->layout) vkDestroyPipelineLayout(gpu->device, p->layout, NULL);
    if (p->sampler) vkDestroySampler(gpu->device, p->sampler, NULL);
    pg_pass_set_destroy(gpu, &p->set);
}

/* exposure is a push constant: a new value re-creates nothing (runtime_options) */
static const char *const k_runtime[] = {"exposure", NULL};

static pg_result dt_update(void *self, const void *params, pg_error *err)
{
    (void)err;
    display_tonemap *p = self;
    p->exposure = ((const dt_params *)params)->exposure;
    return PG_OK;
}

const pg_pass_type pg_pass_display_tonemap = {
    .name = "display_tonemap",
    .summary = "graphics: HDR -> 8-bit sRGB display image (exposure + clamp/Reinhard/ACES)",
    .instance_size = sizeof(display_tonemap),
    .params_size = sizeof(dt_params),
    .declare = dt_declare,
    .create = dt_create,
    .record = dt_record,
    .destroy = dt_destroy,
    .runtime_options = k_runtime,
    .update = dt_update,
};
