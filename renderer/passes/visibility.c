/* visibility.c - the raster half of a visibility buffer: draws the opaque and alpha-mask draws
 * of the scene writing only depth and a 32-bit triangle id per pixel (visibility_common.h:
 * (draw << tri_bits) | gl_PrimitiveID; 0xFFFFFFFF where nothing is drawn), with the cheapest
 * fragment shader there is (shaders/visibility.frag: one store). Alpha-mask materials get a second
 * pipeline that evaluates the material's alpha and discards, made only when the scene has such
 * draws; BLEND draws are left to forward_transparent. The vertex path is the scene-draw one
 * (scene_draw.c). A compute pass then rebuilds each pixel's surface from the id
 * (deferred_lighting with packing "visibility", or visibility_resolve).
 * Needs gl_PrimitiveID in the fragment stage (the device's geometryShader feature).
 * Option raster: "hardware" (default; the above) or "compute": the same ids and depth from compute
 * shaders (visibility_raster.h), which use the whole GPU where the raster units are few.
 * Slots: writes [vis_id (r32ui), depth]. */
#include <string.h>

#include "scene_draw.h"
#include "visibility_common.h"
#include "visibility_raster.h"

typedef struct vis_params { /* filled once by declare, read by create */
    pg_scene_draw_features draw;
    pg_slot vis_id, depth;
    bool compute; /* raster "compute" on this scene */
} vis_params;

typedef struct visibility_pass {
    pg_scene_draw draw;
    uint32_t color_slot, depth_slot; /* plan slots of vis_id and depth */
    bool compute;
    pg_vis_raster raster;            /* raster "compute" */
} visibility_pass;

static const char *const vis_rasters[] = {"hardware", "compute", NULL};

static pg_result vis_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    static const char *const known[] = {"raster", NULL};
    vis_params *p = pg_decl_params(out, sizeof *p);
    pg_result r;
    int raster;
    if ((r = pg_opt_check_known(in->desc, known, err))) return r;
    if ((r = pg_opt_enum(in->desc, "raster", vis_rasters, 0, &raster, err))) return r;
    p->compute = raster == 1;
    if (p->compute) {
        p->vis_id = pg_decl_write(out, "vis_id", PG_RES_IMAGE, PG_ACCESS_STORAGE_WRITE, PG_STAGE_COMPUTE,
                                  PG_FMTCLASS_UINT);
        p->depth = pg_decl_write(out, "depth", PG_RES_IMAGE, PG_ACCESS_TRANSFER_DST, 0, PG_FMTCLASS_DEPTH);
    } else {
        p->vis_id = pg_decl_write(out, "vis_id", PG_RES_IMAGE, PG_ACCESS_COLOR_WRITE, PG_STAGE_FRAGMENT,
                                  PG_FMTCLASS_UINT);
        p->depth = pg_decl_write(out, "depth", PG_RES_IMAGE, PG_ACCESS_DEPTH_WRITE, PG_STAGE_FRAGMENT,
                                 PG_FMTCLASS_DEPTH);
    }
    char where[32];
    const pg_resource_desc *id = pg_decl_slot_resource(in, p->vis_id, PG_RES_IMAGE, where, sizeof where);
    if (id && id->format != PG_FMT_R32UI)
        return pg_fail(err, PG_ERR_FORMAT,
                       "%s: %s.%s: pass '%s' slot vis_id: the triangle id target must be r32ui, not %s (resource '%s')",
                       in->desc->file, in->desc->json_path, where, in->desc->name, pg_format_get(id->format)->name,
                       id->name);
    if (p->compute) {
        pg_decl_explain(out, "raster compute: triangles rasterized by compute shaders (64-bit depth-id minimum)");
        if (pg_scene_features_of(in).has_alpha_mask) /* the alpha test rebuilds the surface */
            pg_scene_draw_declare_features(in, out, &p->draw);
        else
            pg_decl_explain(out, "raster compute: no alpha-mask draws: the alpha test is compiled out");
        pg_geometry_slot_declare(in, out, &p->draw, true);
        return PG_OK;
    }
    pg_scene_draw_declare_features(in, out, &p->draw);
    pg_geometry_slot_declare(in, out, &p->draw, false);
    return PG_OK;
}

static pg_result vis_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    visibility_pass *p = self;
    const vis_params *pa = PG_PARAMS(ctx, vis_params);
    const pg_phys_resource *vis_id = pg_ctx_res(ctx, pa->vis_id);
    pg_result r;
    p->compute = pa->compute;
    if (p->compute) return pg_vis_raster_create(ctx, &pa->draw, pa->vis_id, pa->depth, &p->raster, err);
    if (!ctx->gpu->primitive_id_in_fragment)
        return pg_fail(err, PG_ERR_NO_DEVICE,
                       "%s: the device cannot read gl_PrimitiveID in a fragment shader (no geometryShader "
                       "feature); use a G-buffer pipeline (deferred_oct16.json)",
                       ctx->pass->name);
    if (!PG_SCENE_OF(ctx)) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: needs a scene", ctx->pass->name);
    uint32_t bits;
    if ((r = pg_vis_tri_bits(PG_SCENE_OF(ctx), &bits, err))) return r;
    pg_scene_draw_desc d = {
        .fragment_shader = "visibility.frag",
        .features = &pa->draw,
        .n_color = 1,
        .color_formats = {vis_id->format},
        .depth_format = pg_ctx_res(ctx, pa->depth)->format,
        .position_only_opaque = true,
    };
    p->color_slot = pg_plan_slot_of(ctx->pass, pa->vis_id);
    p->depth_slot = pg_plan_slot_of(ctx->pass, pa->depth);
    if ((r = pg_scene_draw_create(ctx, &d, &p->draw, err))) return r;
    p->draw.push_draw_key = true;
    p->draw.draw_key_shift = bits;
    return PG_OK;
}

static void vis_record(void *self, const pg_pass_record_ctx *ctx)
{
    visibility_pass *p = self;
    if (p->compute) {
        pg_vis_raster_record(&p->raster, ctx);
        return;
    }
    VkClearColorValue clear;
    memset(&clear, 0, sizeof clear);
    clear.uint32[0] = 0xFFFFFFFFu; /* nothing drawn */
    pg_pass_begin_rendering(ctx, 1, &p->color_slot, &clear, (int)p->depth_slot, true, 1.0f);
    pg_scene_draw_record(&p->draw, ctx, VK_NULL_HANDLE);
    vkCmdEndRendering(ctx->cmd);
}

static void vis_destroy(void *self, pg_gpu *gpu)
{
    visibility_pass *p = self;
    pg_scene_draw_destroy(gpu, &p->draw);
    pg_vis_raster_destroy(gpu, &p->raster);
}

const pg_pass_type pg_pass_visibility = {
    .name = "visibility",
    .summary = "graphics or compute (raster): depth and a 32-bit triangle id per pixel (opaque + alpha-mask draws; "
               "alpha-mask discards)",
    .instance_size = sizeof(visibility_pass),
    .params_size = sizeof(vis_params),
    .declare = vis_declare,
    .create = vis_create,
    .record = vis_record,
    .destroy = vis_destroy,
};
