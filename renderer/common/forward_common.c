#include "forward_common.h"

pg_result pg_forward_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    pg_forward_pass *p = self;
    const pg_forward_params *pa = PG_PARAMS(ctx, pg_forward_params);
    p->prepass = pa->prepass;
    p->color_slot = pg_plan_slot_of(ctx->pass, pa->color);
    p->depth_slot = pg_plan_slot_of(ctx->pass, pa->depth);
    pg_result r;
    if ((r = pg_light_set_create(ctx, &pa->sh, &p->lights, err))) return r;
    pg_scene_draw_desc d = {
        .fragment_shader = "forward.frag",
        .features = &pa->draw,
        .pass_layout = p->lights.layout,
        .n_color = 1,
        .color_formats = {pg_ctx_res(ctx, pa->color)->format},
        .depth_format = pg_ctx_res(ctx, pa->depth)->format,
        .depth_equal = pa->prepass_equal, /* forward_plus refuses it without prepass */
    };
    char wbuf[2][40];
    d.n_extra_defines = pg_light_set_defines(ctx, &pa->sh, wbuf, d.extra_defines);
    if ((r = pg_scene_draw_create(ctx, &d, &p->draw, err))) return r;
    return pg_forward_update(p, pa, err);
}

pg_result pg_forward_update(void *self, const void *params, pg_error *err)
{
    (void)err;
    pg_forward_pass *p = self;
    const pg_forward_params *pa = params;
    p->draw.ambient = pa->sh.ambient;
    return PG_OK;
}

void pg_forward_record(void *self, const pg_pass_record_ctx *ctx)
{
    pg_forward_pass *p = self;
    VkClearColorValue clear = {{0, 0, 0, 1}};
    pg_pass_begin_rendering(ctx, 1, &p->color_slot, &clear, (int)p->depth_slot, !p->prepass, 1.0f);
    pg_scene_draw_record(&p->draw, ctx, p->lights.set);
    vkCmdEndRendering(ctx->cmd);
}

void pg_forward_destroy(void *self, pg_gpu *gpu)
{
    pg_forward_pass *p = self;
    pg_scene_draw_destroy(gpu, &p->draw);
    pg_pass_set_destroy(gpu, &p->lights);
}
