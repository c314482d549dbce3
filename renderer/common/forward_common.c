#include "forward_common.h"

pg_result pg_forward_create(pg_forward_pass *p, const pg_pass_create_ctx *ctx, bool clustered, bool prepass,
                            bool prepass_equal, pg_error *err)
{
    p->clustered = clustered;
    p->prepass = prepass;
    int n_reads = clustered ? 3 : 1;
    pg_result r;
    if (clustered) {
        pg_shading_opts o;
        static const char *const extra[] = {"prepass", "prepass_test", NULL};
        if ((r = pg_shading_opts_read(ctx->desc, true, extra, &o, err))) return r;
        if ((r = pg_check_cluster_buffers(ctx, &o, 1, err))) return r;
    }
    if ((r = pg_light_set_create(ctx, clustered, 0, 1, &p->lights, err))) return r;
    pg_scene_draw_desc d = {
        .fragment_shader = "forward.frag",
        .pass_layout = p->lights.layout,
        .n_color = 1,
        .color_formats = {ctx->slots[n_reads]->format},
        .depth_format = ctx->slots[n_reads + 1]->format,
        .depth_equal = prepass_equal, /* forward_plus refuses it without prepass */
    };
    if ((r = pg_scene_draw_create(ctx, &d, &p->draw, err))) return r;
    return pg_forward_update(p, ctx->desc, err);
}

pg_result pg_forward_update(void *self, const pg_pass_desc *desc, pg_error *err)
{
    pg_forward_pass *p = self;
    return pg_shading_ambient(desc, &p->draw.ambient, err);
}

void pg_forward_record(void *self, const pg_pass_record_ctx *ctx)
{
    pg_forward_pass *p = self;
    int n_reads = p->clustered ? 3 : 1;
    VkClearColorValue clear = {{0, 0, 0, 1}};
    const uint32_t color_slot = (uint32_t)n_reads;
    pg_pass_begin_rendering(ctx, 1, &color_slot, &clear, n_reads + 1, !p->prepass, 1.0f);
    pg_scene_draw_record(&p->draw, ctx, p->lights.set);
    vkCmdEndRendering(ctx->cmd);
}

void pg_forward_destroy(void *self, pg_gpu *gpu)
{
    pg_forward_pass *p = self;
    pg_scene_draw_destroy(gpu, &p->draw);
    pg_pass_set_destroy(gpu, &p->lights);
}
