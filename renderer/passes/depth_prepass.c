/* depth_prepass.c - draws the scene's depth only, before a shading pass (forward_plus with
 * option prepass) that then shades each pixel about once. Two ways, option `test`:
 *
 * "less" (default, exact): the opaque draws, one depth-bias step farther than they are; the
 * shading pass loads that depth and tests LESS with writes, as without pre-pass. Every fragment
 * that wins without the pre-pass passes the biased depth; the ones that pass and lose are
 * overwritten as without it, so the same fragments win. Why a bias and not EQUAL: the shading
 * pipeline's depth of a fragment need not be bit-identical to this pipeline's, even with the same
 * vertex shader (llvmpipe interpolates depth in code generated per pipeline), and EQUAL lets the
 * last of two coplanar surfaces win where LESS keeps the first. The bias (PG_PREPASS_BIAS_*: 16
 * units of the depth's last bit plus one pixel's depth slope) is far above that rounding. The
 * alpha-mask draws are not drawn here (the pass declares no PG_ALPHA_MASK, so scene_draw makes no
 * masked pipeline): the shading pass draws them with their discard (a discard here and one there
 * may disagree on a texel at the cutoff, and a depth kept from a texel the shading pass discards
 * would leave a hole).
 *
 * "equal" (an approximation knob, the classic pre-pass): the opaque and alpha-mask draws without
 * bias, the alpha-mask ones with their discard (depth_prepass.frag with PG_ALPHA_MASK: the same
 * material evaluation as the shading passes, only the discard kept); the shading pass tests EQUAL
 * without writes and draws the alpha-mask draws without discard, so this pass alone decides
 * coverage and the masked draws get early depth tests too. Its error against the pipeline
 * without pre-pass (pixels whose depth the two pipelines round differently, the last of coplanar
 * surfaces winning, derivatives at the alpha cutoff) is measured by tests/test_gpu_prepass.c.
 *
 * Both: the vertex path is the scene-draw one every raster pass uses (scene_draw.c: scene.vert
 * with the same surface defines, `precise gl_Position`, the same per-draw cull mode); "less"
 * fetches and writes the position alone (PG_POSITION_ONLY). BLEND draws
 * are not drawn (forward_transparent draws them later against the depth without writing it).
 * Slots: writes [depth] (cleared to 1, then tested LESS and written). Options: test ("less",
 * "equal"; must match the shading pass's prepass_test). */
#include "scene_draw.h"
#include "scene_vars.h"

/* The depth bias of the pre-pass (Vulkan: constant * 2^(e - 23) for a float depth whose largest
 * exponent in the triangle is e, plus slope * the triangle's largest depth change per pixel). */
#define PG_PREPASS_BIAS_CONSTANT 16.0f
#define PG_PREPASS_BIAS_SLOPE 1.0f

typedef struct dp_params { /* filled once by declare, read by create */
    int test;                    /* PG_PREPASS_LESS or PG_PREPASS_EQUAL */
    pg_scene_draw_features draw;
    pg_slot depth;
} dp_params;

typedef struct depth_prepass {
    pg_scene_draw draw;
    uint32_t depth_slot; /* plan slot of depth */
} depth_prepass;

static pg_result dp_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    static const char *const known[] = {"test", NULL};
    dp_params *p = pg_decl_params(out, sizeof *p);
    pg_result r;
    int test;
    if ((r = pg_opt_check_known(in->desc, known, err))) return r;
    if ((r = pg_opt_enum(in->desc, "test", pg_prepass_tests, PG_PREPASS_LESS, &test, err))) return r;
    p->test = test;
    p->depth = pg_decl_write(out, "depth", PG_RES_IMAGE, PG_ACCESS_DEPTH_WRITE, PG_STAGE_FRAGMENT, PG_FMTCLASS_DEPTH);
    if (test == PG_PREPASS_EQUAL) {
        pg_scene_draw_declare_features(in, out, &p->draw); /* the alpha-mask draws discard here */
        pg_decl_explain(out, "test equal: no depth bias; the shading pass tests EQUAL (an approximation: "
                             "tests/test_gpu_prepass.c measures it)");
    } else {
        pg_scene_draw_declare_vertex_features(in, out, &p->draw);
        if (pg_scene_features_of(in).has_alpha_mask)
            pg_decl_explain(out, "alpha-mask draws left out of the depth pre-pass: the shading pass draws them with "
                                 "their discard");
    }
    pg_geometry_slot_declare(in, out, &p->draw, false);
    return PG_OK;
}

static pg_result dp_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    depth_prepass *p = self;
    const dp_params *pa = PG_PARAMS(ctx, dp_params);
    const int test = pa->test;
    pg_scene_draw_desc d = {
        .fragment_shader = "depth_prepass.frag",
        .features = &pa->draw,
        .n_color = 0,
        .depth_format = pg_ctx_res(ctx, pa->depth)->format,
        .depth_bias_constant = test == PG_PREPASS_LESS ? PG_PREPASS_BIAS_CONSTANT : 0.0f,
        .depth_bias_slope = test == PG_PREPASS_LESS ? PG_PREPASS_BIAS_SLOPE : 0.0f,
        /* "less" draws the opaque draws alone, with an empty fragment stage: the position is all
         * it needs ("equal" keeps the shading pass's vertex path whole: its depths are compared) */
        .position_only_opaque = test == PG_PREPASS_LESS,
    };
    p->depth_slot = pg_plan_slot_of(ctx->pass, pa->depth);
    return pg_scene_draw_create(ctx, &d, &p->draw, err);
}

static void dp_record(void *self, const pg_pass_record_ctx *ctx)
{
    depth_prepass *p = self;
    pg_pass_begin_rendering(ctx, 0, NULL, NULL, (int)p->depth_slot, true, 1.0f);
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
    .summary = "graphics: depth only, for a shading pass that loads it: test less (the opaque draws one depth-bias "
               "step farther, tested LESS) or equal (opaque and alpha-mask draws, tested EQUAL)",
    .instance_size = sizeof(depth_prepass),
    .params_size = sizeof(dp_params),
    .declare = dp_declare,
    .create = dp_create,
    .record = dp_record,
    .destroy = dp_destroy,
};
