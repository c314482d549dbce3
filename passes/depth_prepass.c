/* depth_prepass.c - draws the opaque draws of the scene into depth only, one depth-bias step
 * farther than they are, so that the shading pass after it (forward_plus with option prepass:
 * depth loaded, tested LESS and written) shades only the fragments at or in front of the nearest
 * surface: each pixel about once, and exactly the fragments that win without the pre-pass.
 * Why a bias and LESS rather than an EQUAL test: the shading pipeline's depth of a fragment need
 * not be bit-identical to this pipeline's, even with the same vertex shader (llvmpipe interpolates
 * depth in code generated per pipeline: not bit-identical on some pixels), and EQUAL lets the last
 * of two coplanar surfaces win where LESS keeps the first. With the bias (PG_PREPASS_BIAS_*: 16
 * units of the depth's last bit plus one pixel's depth slope, far above that rounding) every
 * fragment that wins without the pre-pass passes the loaded depth; the ones that pass and lose
 * are overwritten as without it (depth written, LESS), so the image is the one without pre-pass.
 * The vertex path is the scene-draw one every raster pass uses (scene_draw.c: scene.vert with the
 * same surface defines, `precise gl_Position`, the same per-draw cull mode). The alpha-mask draws are not
 * drawn here (the pass declares no PG_ALPHA_MASK, so scene_draw makes no masked pipeline): the shading pass draws them with their discard as without pre-pass (a discard here
 * and one there may disagree on a texel at the alpha cutoff, and a pre-pass depth kept from a
 * texel the shading pass discards would leave a hole). BLEND draws are not drawn either
 * (forward_transparent draws them later against the depth without writing it).
 * Slots: writes [depth] (cleared to 1, then tested LESS and written). No options. */
#include "scene_draw.h"

/* The depth bias of the pre-pass (Vulkan: constant * 2^(e - 23) for a float depth whose largest
 * exponent in the triangle is e, plus slope * the triangle's largest depth change per pixel). */
#define PG_PREPASS_BIAS_CONSTANT 16.0f
#define PG_PREPASS_BIAS_SLOPE 1.0f

typedef struct depth_prepass {
    pg_scene_draw draw;
} depth_prepass;

static pg_result dp_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    static const char *const known[] = {NULL};
    pg_result r;
    if ((r = pg_opt_check_known(in->desc, known, err))) return r;
    pg_decl_write(out, "depth", PG_RES_IMAGE, PG_ACCESS_DEPTH_WRITE, PG_STAGE_FRAGMENT, PG_FMTCLASS_DEPTH);
    pg_scene_draw_declare_vertex_features(in, out);
    if (in->features.has_alpha_mask)
        pg_decl_explain(out, "alpha-mask draws left out of the depth pre-pass: the shading pass draws them with "
                             "their discard");
    return PG_OK;
}

static pg_result dp_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    depth_prepass *p = self;
    pg_scene_draw_desc d = {
        .fragment_shader = "depth_prepass.frag",
        .n_color = 0,
        .depth_format = ctx->slots[0]->format,
        .depth_bias_constant = PG_PREPASS_BIAS_CONSTANT,
        .depth_bias_slope = PG_PREPASS_BIAS_SLOPE,
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
    .summary = "graphics: depth only of the opaque draws, one depth-bias step farther, for a shading pass that loads "
               "it and tests LESS",
    .read_slots = "",
    .write_slots = "depth",
    .instance_size = sizeof(depth_prepass),
    .declare = dp_declare,
    .create = dp_create,
    .record = dp_record,
    .destroy = dp_destroy,
};
