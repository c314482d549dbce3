/* forward_transparent.c - glTF alphaMode BLEND: after the opaque lighting (forward or deferred),
 * draws only the scene's BLEND draws onto the HDR image, sorted back to front every frame by the
 * distance from the camera to each draw's bounds centre (a moving primitive's at the frame's pose:
 * scene_gpu_anim.h pg_scene_gpu_anim_centre), with "over" blending
 * (rgb = a*src + (1-a)*dst, non-premultiplied; a = s.alpha), depth tested against the opaque
 * depth but not written, back faces culled unless the material is double-sided. Each fragment is
 * shaded like forward.frag (pg_surface + pg_shade_point: the same lights, ambient and model).
 * Slots: lights "all":      reads [lights, depth, environment (optional)], writes [color]
 *        lights "clusters": reads [lights, cluster_counts, cluster_lights, depth, environment (optional)],
 *        writes [color] (environment: the filtered environment, shading_common.h)
 * (depth: depth attachment, read-only; color: colour attachment, loaded and blended).
 * Options: lights ("all": every light, as forward_naive; "clusters": the cluster lists, as
 * forward_plus: the grid is the cluster_counts resource's count), shading, ambient, view.
 * Not needed (pg_decl_skip, so the graph culls it and what only it reads) when the scene has no
 * BLEND material, and with a debug view (the views show the opaque surfaces). */
#include <stdlib.h>
#include <string.h>

#include "frame.h"
#include "scene_draw.h"
#include "scene_gpu_anim.h"
#include "scene_vars.h"
#include "shading_common.h"

typedef struct ft_params { /* filled once by declare, read by create/update/record */
    pg_shading_params sh;          /* options (lights "clusters": clustered), light and cluster slots */
    pg_scene_draw_features draw;
    pg_slot depth, color;
} ft_params;

typedef struct pg_transparent_pass {
    pg_slot depth, color;
    pg_pass_set lights;
    pg_scene_draw draw;
    uint32_t n;            /* BLEND draws of the scene */
    uint32_t *order;       /* their indices in scene->draws, sorted every frame */
    float *key;            /* squared camera distance per BLEND draw (scratch) */
    int32_t *anim_prim;    /* per BLEND draw: its moving primitive (sorted by its posed centre), or -1 */
    bool any_moving;
} pg_transparent_pass;

static const char *const k_lights[] = {"all", "clusters", NULL};
static const char *const k_extra[] = {"lights", NULL};

static pg_result read_opts(const pg_pass_desc *desc, pg_shading_params *sp, pg_error *err)
{
    int mode = 0;
    pg_result r = pg_opt_enum(desc, "lights", k_lights, 0, &mode, err);
    if (r) return r;
    /* every debug view skips this pass (ft_declare): a cluster view is no error for "lights": "all"
     * (stochastic.json refused five of its own views) */
    r = pg_shading_opts_read(desc, true, k_extra, sp, err);
    sp->clustered = mode == 1;
    return r;
}

static pg_result ft_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    ft_params *p = pg_decl_params(out, sizeof *p);
    pg_result r = read_opts(in->desc, &p->sh, err);
    if (r) return r;
    const pg_shading_opts o = p->sh.o;
    p->sh.lights = pg_decl_read(out, "lights", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_FRAGMENT, 0);
    if (p->sh.clustered) {
        p->sh.cluster_counts =
            pg_decl_read(out, "cluster_counts", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_FRAGMENT, 0);
        p->sh.cluster_lists =
            pg_decl_read(out, "cluster_lights", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_FRAGMENT, 0);
        if ((r = pg_shading_grid_declare(&p->sh, in, err))) return r;
    }
    p->depth = pg_decl_read(out, "depth", PG_RES_IMAGE, PG_ACCESS_DEPTH_READ, PG_STAGE_FRAGMENT, PG_FMTCLASS_DEPTH);
    pg_environment_slot_declare(in, out, &p->sh, PG_STAGE_FRAGMENT, false);
    pg_geometry_slot_declare(in, out, &p->draw, false);
    p->color = pg_decl_write(out, "color", PG_RES_IMAGE, PG_ACCESS_COLOR_RMW, PG_STAGE_FRAGMENT, PG_FMTCLASS_FLOAT);
    if (!pg_scene_features_of(in).has_blend) {
        pg_decl_skip(out, "no BLEND materials: no transparent pass");
        return PG_OK;
    }
    if (o.view) {
        pg_decl_skip(out, "debug view '%s': transparent surfaces not drawn (the view shows the opaque ones)",
                     pg_debug_views[o.view]);
        return PG_OK;
    }
    pg_scene_draw_declare_features(in, out, &p->draw);
    pg_decl_define(out, "PG_TRANSPARENT");
    pg_shading_declare(&p->sh, in, out);
    return PG_OK;
}

static pg_result ft_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    pg_transparent_pass *p = self;
    const ft_params *pa = PG_PARAMS(ctx, ft_params);
    pg_result r;
    p->depth = pa->depth;
    p->color = pa->color;
    const pg_phys_resource *color = pg_ctx_res(ctx, pa->color);
    VkFormatProperties fp;
    vkGetPhysicalDeviceFormatProperties(ctx->gpu->phys, color->format, &fp);
    if (!(fp.optimalTilingFeatures & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT))
        return pg_fail(err, PG_ERR_FORMAT,
                       "%s: %s.writes[0]: '%s' is %s, which this device cannot blend onto "
                       "(VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT missing): use rgba16f or rgba32f",
                       ctx->desc->file, ctx->desc->json_path, ctx->desc->writes[0],
                       pg_format_get(color->pg_fmt)->name);
    if ((r = pg_light_set_create(ctx, &pa->sh, &p->lights, err))) return r;
    p->n = PG_SCENE_OF(ctx)->n_blend_draws;
    p->order = calloc(p->n ? p->n : 1, sizeof *p->order);
    p->key = calloc(p->n ? p->n : 1, sizeof *p->key);
    p->anim_prim = calloc(p->n ? p->n : 1, sizeof *p->anim_prim);
    if (!p->order || !p->key || !p->anim_prim) return pg_fail(err, PG_ERR_OOM, "%s: out of memory", ctx->pass->name);
    const pg_scene_gpu *sg = PG_SCENE_OF(ctx);
    for (uint32_t i = 0; i < p->n; i++) {
        p->anim_prim[i] = pg_scene_gpu_anim_prim_at(sg->anim, sg->draws[sg->n_draws - p->n + i].vertex_offset);
        p->any_moving = p->any_moving || p->anim_prim[i] >= 0;
    }
    pg_scene_draw_desc d = {
        .fragment_shader = "forward.frag",
        .features = &pa->draw,
        .pass_layout = p->lights.layout,
        .n_color = 1,
        .color_formats = {color->format},
        .depth_format = pg_ctx_res(ctx, pa->depth)->format,
        .blend = true,
    };
    char wbuf[2][40];
    d.n_extra_defines = pg_light_set_defines(ctx, &pa->sh, wbuf, d.extra_defines);
    if ((r = pg_scene_draw_create(ctx, &d, &p->draw, err))) return r;
    p->draw.ambient = pa->sh.ambient;
    return PG_OK;
}

static pg_result ft_update(void *self, const void *params, pg_error *err)
{
    (void)err;
    pg_transparent_pass *p = self;
    p->draw.ambient = ((const ft_params *)params)->sh.ambient;
    return PG_OK;
}

/* Back to front: larger squared distance first; equal distances keep scene draw order. A moving
 * draw's centre is the one of its posed bounds (the frame's pose, evaluated once a frame). */
static void sort_back_to_front(pg_transparent_pass *p, const pg_scene_gpu *sc, const pg_frame_uniforms *fu)
{
    const float *cam = fu->camera_pos;
    const pg_anim_pose *pose = NULL;
    if (p->any_moving && sc->anim) {
        const int32_t animation = pg_frame_animation(fu);
        pose = pg_scene_gpu_anim_pose(sc->anim, animation, fu->camera_pos[3]);
    }
    const uint32_t first = sc->n_draws - p->n;
    for (uint32_t i = 0; i < p->n; i++) {
        float posed[3];
        const float *c = sc->draws[first + i].center;
        if (pose && p->anim_prim[i] >= 0) {
            pg_scene_gpu_anim_centre(sc->anim, (uint32_t)p->anim_prim[i], pose, posed);
            c = posed;
        }
        float dx = c[0] - cam[0], dy = c[1] - cam[1], dz = c[2] - cam[2];
        float k = dx * dx + dy * dy + dz * dz;
        /* insertion sort: a handful of draws, and stable */
        uint32_t j = i;
        while (j > 0 && p->key[j - 1] < k) {
            p->key[j] = p->key[j - 1];
            p->order[j] = p->order[j - 1];
            j--;
        }
        p->key[j] = k;
        p->order[j] = first + i;
    }
}

static void ft_record(void *self, const pg_pass_record_ctx *ctx)
{
    pg_transparent_pass *p = self;
    const pg_phys_resource *depth = pg_ctx_res(ctx, p->depth), *color = pg_ctx_res(ctx, p->color);
    sort_back_to_front(p, PG_SCENE_OF(ctx), PG_FRAME_OF(ctx));
    VkRenderingAttachmentInfo ca = {
        .sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
        .imageView = color->view,
        .imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
        .loadOp = VK_ATTACHMENT_LOAD_OP_LOAD,
        .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
    };
    VkRenderingAttachmentInfo da = {
        .sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
        .imageView = depth->view,
        .imageLayout = VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL,
        .loadOp = VK_ATTACHMENT_LOAD_OP_LOAD,
        .storeOp = VK_ATTACHMENT_STORE_OP_NONE, /* read-only: nothing to store */
    };
    VkRenderingInfo ri = {
        .sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
        .renderArea = {{0, 0}, {color->width, color->height}},
        .layerCount = 1,
        .colorAttachmentCount = 1,
        .pColorAttachments = &ca,
        .pDepthAttachment = &da,
    };
    vkCmdBeginRendering(ctx->cmd, &ri);
    pg_cmd_viewport(ctx->cmd, color->width, color->height);
    pg_scene_draw_record_list(&p->draw, ctx, p->lights.set, p->order, p->n);
    vkCmdEndRendering(ctx->cmd);
}

static void ft_destroy(void *self, pg_gpu *gpu)
{
    pg_transparent_pass *p = self;
    pg_scene_draw_destroy(gpu, &p->draw);
    pg_pass_set_destroy(gpu, &p->lights);
    free(p->order);
    free(p->key);
    free(p->anim_prim);
    p->order = NULL;
    p->key = NULL;
}

const pg_pass_type pg_pass_forward_transparent = {
    .name = "forward_transparent",
    .summary = "graphics: alphaMode BLEND draws, back to front, blended onto the lit HDR image",
    .instance_size = sizeof(pg_transparent_pass),
    .params_size = sizeof(ft_params),
    .declare = ft_declare,
    .create = ft_create,
    .record = ft_record,
    .destroy = ft_destroy,
    .runtime_options = pg_shading_runtime_options,
    .update = ft_update,
};
