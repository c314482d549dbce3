/* visibility_resolve.c - compute pass: rebuilds every pixel's surface from the visibility pass's
 * triangle id (visibility_common.h, shaders/visibility_surface.glsl), evaluates its material and
 * writes a G-buffer (shaders/visibility_resolve.comp):
 *   - packing "packed" (default): the packed G-buffer (gbuffer_layout.h "packed") that
 *     deferred_lighting reads with packing "packed": the visibility pipeline's resolve=gbuffer path,
 *     against which the fused path (deferred_lighting with packing "visibility") is measured;
 *   - packing "float": the float G-buffer with a camera-relative position, as gbuffer with packing
 *     "float" and position_space "camera" writes it, which reference_lighting reads: the reference's
 *     surface=ray path, the surface at each pixel centre from its ray instead of the rasterizer's
 *     interpolation.
 * Slots: reads [vis_id (r32ui)]; writes [packed (rgba32ui storage) | position, normal, albedo
 *        (rgba32f storage each), every pixel written (zeros where nothing is drawn), then emissive
 *        (optional; rgba16f storage, rgba32f with packing float; unused - not allocated - without
 *        emissive materials; not bound: no emission, explain line)].
 * Options: packing; shading (the light model whose values the layout stores, as gbuffer's; default
 * auto). */
#include <stdio.h>
#include <string.h>

#include "scene_draw.h"
#include "scene_vars.h"
#include "shader.h"
#include "shading_common.h"
#include "visibility_common.h"

enum { VR_MAX_TARGETS = 3 };
static const char *const k_vr_packings[] = {"packed", "float", NULL};
static const char *const k_vr_slots[2][VR_MAX_TARGETS] = {{"packed"}, {"position", "normal", "albedo"}};

typedef struct vr_params { /* filled once by declare, read by create */
    pg_scene_draw_features draw;
    int packing;                         /* 0 packed, 1 float */
    uint32_t n_targets;                  /* 1 or 3 */
    pg_slot vis_id, targets[VR_MAX_TARGETS], emissive; /* emissive: PG_SLOT_NONE when not bound */
} vr_params;

typedef struct visibility_resolve {
    pg_slot first; /* the first target: its size is the dispatch's */
    VkSampler sampler;
    pg_vis_geometry vis;
    pg_pass_set set;
    VkPipelineLayout layout;
    VkPipeline pipeline;
} visibility_resolve;

static pg_result vr_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    static const char *const known[] = {"packing", "shading", NULL};
    vr_params *p = pg_decl_params(out, sizeof *p);
    pg_result r;
    int shading;
    if ((r = pg_opt_check_known(in->desc, known, err))) return r;
    if ((r = pg_opt_enum(in->desc, "packing", k_vr_packings, 0, &p->packing, err))) return r;
    if ((r = pg_opt_enum(in->desc, "shading", pg_shading_models, PG_SHADING_AUTO, &shading, err))) return r;
    pg_material_model_declare(in, out, shading);
    p->vis_id = pg_decl_read(out, "vis_id", PG_RES_IMAGE, PG_ACCESS_SAMPLED, PG_STAGE_COMPUTE, PG_FMTCLASS_UINT);
    p->n_targets = p->packing ? 3 : 1;
    const pg_format want = p->packing ? PG_FMT_RGBA32F : PG_FMT_RGBA32UI;
    for (uint32_t t = 0; t < p->n_targets; t++) {
        p->targets[t] = pg_decl_write(out, k_vr_slots[p->packing][t], PG_RES_IMAGE, PG_ACCESS_STORAGE_WRITE,
                                      PG_STAGE_COMPUTE, p->packing ? PG_FMTCLASS_FLOAT : PG_FMTCLASS_UINT);
        char where[32];
        const pg_resource_desc *rd = pg_decl_slot_resource(in, p->targets[t], PG_RES_IMAGE, where, sizeof where);
        if (rd && rd->format != want)
            return pg_fail(err, PG_ERR_FORMAT, "%s: %s.%s: pass '%s' slot %s: the %s G-buffer is %s, resource '%s' is %s",
                           in->desc->file, in->desc->json_path, where, in->desc->name, k_vr_slots[p->packing][t],
                           k_vr_packings[p->packing], pg_format_get(want)->name, rd->name, pg_format_get(rd->format)->name);
    }
    if (p->packing) pg_decl_define(out, "PG_RESOLVE_FLOAT");
    if (in->desc->n_writes > p->n_targets) {
        const pg_format em = p->packing ? PG_FMT_RGBA32F : PG_FMT_RGBA16F;
        p->emissive = pg_decl_write(out, "emissive", PG_RES_IMAGE, PG_ACCESS_STORAGE_WRITE, PG_STAGE_COMPUTE, PG_FMTCLASS_FLOAT);
        const pg_resource_desc *rd = pg_pipeline_find_resource(in->pipeline, in->desc->writes[p->n_targets]);
        if (rd && rd->kind == PG_RES_IMAGE && rd->format != em)
            return pg_fail(err, PG_ERR_FORMAT, "%s: %s.writes[%u]: the emissive target must be %s, resource '%s' is %s",
                           in->desc->file, in->desc->json_path, p->n_targets, pg_format_get(em)->name, rd->name,
                           pg_format_get(rd->format)->name);
        if (!pg_scene_features_of(in).has_emissive)
            pg_decl_mark_unused(out, p->emissive, "no emissive materials: emissive target not allocated");
        else
            pg_decl_define(out, "PG_RESOLVE_EMISSIVE");
    } else if (pg_scene_features_of(in).has_emissive) {
        pg_decl_explain(out, "no emissive slot bound (after the G-buffer targets): emissive materials are not drawn");
    }
    pg_scene_draw_declare_features(in, out, &p->draw);
    pg_geometry_slot_declare(in, out, &p->draw, true);
    return PG_OK;
}

static pg_result vr_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    visibility_resolve *p = self;
    const vr_params *pa = PG_PARAMS(ctx, vr_params);
    pg_gpu *gpu = ctx->gpu;
    pg_result r;
    p->first = pa->targets[0];
    const bool emissive = pg_slot_ok(pa->emissive) && !pg_ctx_unused(ctx, pa->emissive);
    if ((r = pg_vis_geometry_create(ctx, &pa->draw, 2, &p->vis, err))) return r;
    if ((r = pg_sampler_create(gpu, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, &p->sampler, err)))
        return r;
    pg_set_binding b[8];
    uint32_t n = 0;
    b[n++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, pg_ctx_res(ctx, pa->vis_id), p->sampler, 0};
    for (uint32_t t = 0; t < pa->n_targets; t++)
        b[n++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, pg_ctx_res(ctx, pa->targets[t]), VK_NULL_HANDLE, 0};
    if (emissive)
        b[n++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, pg_ctx_res(ctx, pa->emissive), VK_NULL_HANDLE, 0};
    n = pg_vis_geometry_bindings(&p->vis, PG_SCENE_OF(ctx), b, n);
    char name[PG_NAME_MAX + 16];
    snprintf(name, sizeof name, "%s.set", ctx->pass->name);
    if ((r = pg_pass_set_create(gpu, n, b, name, &p->set, err))) return r;
    VkDescriptorSetLayout sets[3] = {ctx->frame_layout, p->set.layout, PG_SCENE_OF(ctx)->set_layout};
    if ((r = pg_pipeline_layout_create(gpu, 3, sets, 0, &p->layout, err))) return r;
    const char *defs[PG_MAX_DEFINES + 16];
    uint32_t nd = pg_vis_geometry_define_list(&p->vis, defs);
    VkShaderModule cs;
    if ((r = pg_shader_module(gpu, "visibility_resolve.comp", VK_SHADER_STAGE_COMPUTE_BIT, defs, nd, &cs, err)))
        return r;
    pg_compute_pipeline_desc pd = {.layout = p->layout, .cs = cs};
    r = pg_compute_pipeline_create_ex(gpu, &pd, ctx->pass->name, &p->pipeline, err);
    vkDestroyShaderModule(gpu->device, cs, NULL);
    return r;
}

static void vr_record(void *self, const pg_pass_record_ctx *ctx)
{
    visibility_resolve *p = self;
    const pg_phys_resource *out = pg_ctx_res(ctx, p->first);
    pg_vis_geometry_record(&p->vis, ctx);
    VkDescriptorSet sets[3] = {ctx->frame_set, p->set.set, PG_SCENE_OF(ctx)->set};
    vkCmdBindPipeline(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipeline);
    vkCmdBindDescriptorSets(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->layout, 0, 3, sets, 0, NULL);
    vkCmdDispatch(ctx->cmd, (out->width + 7) / 8, (out->height + 7) / 8, 1);
}

static void vr_destroy(void *self, pg_gpu *gpu)
{
    visibility_resolve *p = self;
    if (p->pipeline) vkDestroyPipeline(gpu->device, p->pipeline, NULL);
    if (p->layout) vkDestroyPipelineLayout(gpu->device, p->layout, NULL);
    pg_pass_set_destroy(gpu, &p->set);
    pg_vis_geometry_destroy(gpu, &p->vis);
    if (p->sampler) vkDestroySampler(gpu->device, p->sampler, NULL);
}

const pg_pass_type pg_pass_visibility_resolve = {
    .name = "visibility_resolve",
    .summary = "compute: rebuild every pixel's surface from its triangle id and write the packed or float G-buffer",
    .instance_size = sizeof(visibility_resolve),
    .params_size = sizeof(vr_params),
    .declare = vr_declare,
    .create = vr_create,
    .record = vr_record,
    .destroy = vr_destroy,
};
