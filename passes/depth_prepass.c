/* depth_prepass.c - draws the opaque and alpha-mask draws of the scene into depth only, so that
 * a later shading pass (forward_plus with option prepass) shades each pixel once with an EQUAL
 * depth test. The vertex path is the scene-draw one every raster pass uses (scene_draw.c:
 * scene.vert with the same defines, `invariant gl_Position`, the same per-draw cull mode), so the
 * depth the shading pass computes is bit-identical to what this pass stored. Alpha-mask
 * materials discard here (their pipeline is made only when the scene has such draws, from
 * shaders/depth_prepass.frag with PG_ALPHA_MASK); BLEND draws are not drawn (forward_transparent
 * draws them later against this depth without writing it).
 * Slots: writes [depth] (cleared to 1, then tested LESS and written). No options. */
#include "scene_draw.h"

typedef struct depth_prepass {
    pg_scene_draw draw;
} depth_prepass;

static pg_result dp_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    static const char *const known[] = {NULL};
    pg_result r;
    if ((r = pg_opt_check_known(in->desc, known, err))) return r;
    pg_decl_write(out, "depth", PG_RES_IMAGE, PG_ACCESS_DEPTH_WRITE, PG_STAGE_FRAGMENT, PG_FMTCLASS_DEPTH);
    pg_scene_draw_declare_features(in, out);
    return PG_OK;
}

static pg_result dp_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    depth_prepass *p = self;
    pg_scene_draw_desc d = {
        .fragment_shader = "depth_prepass.frag",
        .n_color = 0,
        .depth_format = ctx->slots[0]->format,
    };
    return pg_scene_draw_create(ctx, &d, &p->draw, err);
}

static void dp_record(void *self, const pg_pass_record_ctx *ctx)
{
    depth_prepass *p = self;
    pg_pass_begin_rendering(ctx, 0, NULL, NULL, 0, true, 1.0f);
    pg_scene_draw_record(&p->draw, ctx, VK_NULL_HANDLE);
    vkCmdEndRendering(ctx->cmd);
}

static void dp_destroy(void *self, pg_gpu *gpu)
{
    depth_prepass *p = self;
    pg_scene_draw_destroy(gpu, &p->draw);
}

const pg_pass_type pg_pass_depth_prepass = {
    .name = "depth_prepass",
    .summary = "graphics: depth only of the opaque and alpha-mask draws (alpha-mask discards), for an EQUAL-tested "
               "shading pass",
    .read_slots = "",
    .write_slots = "depth",
    .instance_size = sizeof(depth_prepass),
    .declare = dp_declare,
    .create = dp_create,
    .record = dp_record,
    .destroy = dp_destroy,
};
