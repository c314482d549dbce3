/* gbuffer.c - rasterizes the scene into the G-buffer of one packing variant (gbuffer_layout.h)
 * plus depth (shaders/gbuffer.frag).
 * Slots: writes [targets of the variant..., depth, emissive (optional)] - 3, 2 or 1 targets, depth,
 *        then optionally the emissive target (rgba16f or rgba32f, scene-linear emissive colour,
 *        0 where nothing emits or nothing is drawn; gb_emissive in the shipped pipelines). Without
 *        emissive materials that slot is declared unused (its resource is culled, not allocated);
 *        a pipeline that binds none draws no emission (explain line).
 * Options: packing "float" | "oct16" | "packed" (default float). Only the targets the variant
 * uses are bound, allocated and written (the deferred pipelines declare the others under a
 * `when` that drops them).
 *          shading: the light model whose values the layout stores (pg_shading_models, default
 *          auto; the deferred_lighting pass reading the targets must have the same: the shipped
 *          pipelines give both "$shading"): pbr stores metallic and roughness where the others
 *          store specular and shininess, and the occlusion (gbuffer.frag).
 *          position_space "world" (default) | "camera", float packing only: what the position
 *          target holds. "world" is the classic layout (deferred_lighting subtracts the camera
 *          again, which rounds); "camera" stores the interpolated camera-relative position the
 *          forward shaders shade with, unchanged (w = 1 covered, 0 background), which the exact
 *          reference_lighting pass needs. */
#include <string.h>

#include "gbuffer_layout.h"
#include "scene_draw.h"
#include "shading_common.h"

typedef struct gb_params { /* filled once by declare, read by create */
    int packing;
    pg_scene_draw_features draw;
    pg_slot targets[4], depth, emissive; /* emissive: PG_SLOT_NONE when not bound */
} gb_params;

typedef struct gbuffer_pass {
    uint32_t n_color;
    uint32_t color_slots[4]; /* plan slots of the colour attachments (targets, then emissive when written) */
    uint32_t depth_slot;
    pg_scene_draw draw;
} gbuffer_pass;

static const char *const k_spaces[] = {"world", "camera", NULL};

/* packing, position_space (0 world, 1 camera; camera only with the float packing) and shading */
static pg_result gb_options(const pg_pass_desc *desc, int *packing, int *space, int *shading, pg_error *err)
{
    static const char *const known[] = {"packing", "position_space", "shading", NULL};
    pg_result r;
    if ((r = pg_opt_check_known(desc, known, err))) return r;
    if ((r = pg_opt_enum(desc, "shading", pg_shading_models, PG_SHADING_AUTO, shading, err))) return r;
    if ((r = pg_opt_enum(desc, "packing", pg_gbuffer_packings, 0, packing, err))) return r;
    if ((r = pg_opt_enum(desc, "position_space", k_spaces, 0, space, err))) return r;
    if (*packing == PG_GBUFFER_VISIBILITY)
        return pg_fail(err, PG_ERR_SCHEMA,
                       "%s: %s.options.packing: \"visibility\" is written by the visibility pass (type "
                       "\"visibility\"), not by gbuffer",
                       desc->file, desc->json_path);
    if (*space == 1 && *packing != PG_GBUFFER_FLOAT)
        return pg_fail(err, PG_ERR_SCHEMA,
                       "%s: %s.options.position_space: \"camera\" needs packing \"float\" (packing \"%s\" stores no "
                       "position; it is rebuilt from depth)",
                       desc->file, desc->json_path, pg_gbuffer_packings[*packing]);
    return PG_OK;
}

static pg_result gb_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    gb_params *p = pg_decl_params(out, sizeof *p);
    pg_result r;
    int packing, space, shading;
    if ((r = gb_options(in->desc, &packing, &space, &shading, err))) return r;
    p->packing = packing;
    for (uint32_t t = 0; t < pg_gbuffer_targets[packing]; t++)
        p->targets[t] = pg_decl_write(out, pg_gbuffer_slot_names[packing][t], PG_RES_IMAGE, PG_ACCESS_COLOR_WRITE, PG_STAGE_FRAGMENT,
                      packing == PG_GBUFFER_PACKED ? PG_FMTCLASS_UINT : PG_FMTCLASS_FLOAT);
    p->depth = pg_decl_write(out, "depth", PG_RES_IMAGE, PG_ACCESS_DEPTH_WRITE, PG_STAGE_FRAGMENT, PG_FMTCLASS_DEPTH);
    bool emissive;
    if ((r = pg_emissive_slot_declare(in, out, true, false, &p->emissive, &emissive, err))) return r;
    pg_decl_define(out, pg_gbuffer_defines[packing]);
    if (space == 1) pg_decl_define(out, "PG_GBUFFER_CAMERA_POSITION");
    if (emissive) pg_decl_define(out, "PG_GBUFFER_EMISSIVE");
    pg_material_model_declare(in, out, shading);
    pg_scene_draw_declare_features(in, out, &p->draw);
    pg_geometry_slot_declare(in, out, &p->draw, false);
    return PG_OK;
}

static pg_result gb_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    gbuffer_pass *p = self;
    const gb_params *pa = PG_PARAMS(ctx, gb_params);
    const uint32_t n = pg_gbuffer_targets[pa->packing];
    /* the emissive target is written when bound and used (emissive materials) */
    const bool emissive = pg_slot_ok(pa->emissive) && !pg_ctx_unused(ctx, pa->emissive);
    pg_scene_draw_desc d = {
        .fragment_shader = "gbuffer.frag",
        .features = &pa->draw,
        .depth_format = pg_ctx_res(ctx, pa->depth)->format,
    };
    p->n_color = 0;
    for (uint32_t t = 0; t < n; t++) {
        d.color_formats[p->n_color] = pg_ctx_res(ctx, pa->targets[t])->format;
        p->color_slots[p->n_color++] = pg_plan_slot_of(ctx->pass, pa->targets[t]);
    }
    if (emissive) { /* location n (after the targets) */
        d.color_formats[p->n_color] = pg_ctx_res(ctx, pa->emissive)->format;
        p->color_slots[p->n_color++] = pg_plan_slot_of(ctx->pass, pa->emissive);
    }
    d.n_color = p->n_color;
    p->depth_slot = pg_plan_slot_of(ctx->pass, pa->depth);
    return pg_scene_draw_create(ctx, &d, &p->draw, err);
}

static void gb_record(void *self, const pg_pass_record_ctx *ctx)
{
    gbuffer_pass *p = self;
    VkClearColorValue clears[4];
    memset(clears, 0, sizeof clears);
    pg_pass_begin_rendering(ctx, p->n_color, p->color_slots, clears, (int)p->depth_slot, true, 1.0f);
    pg_scene_draw_record(&p->draw, ctx, VK_NULL_HANDLE);
    vkCmdEndRendering(ctx->cmd);
}

static void gb_destroy(void *self, pg_gpu *gpu)
{
    gbuffer_pass *p = self;
    pg_scene_draw_destroy(gpu, &p->draw);
}

const pg_pass_type pg_pass_gbuffer = {
    .name = "gbuffer",
    .summary = "graphics: draw the scene into a G-buffer (packing float | oct16 | packed) and depth",
    .instance_size = sizeof(gbuffer_pass),
    .params_size = sizeof(gb_params),
    .declare = gb_declare,
    .create = gb_create,
    .record = gb_record,
    .destroy = gb_destroy,
};
