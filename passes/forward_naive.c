/* forward_naive.c - the exact reference: draws the scene once with depth, and every fragment
 * loops over every light (shaders/forward_naive.frag).
 * Slots: reads [lights] (storage buffer, fragment); writes [color, depth].
 * Options: shading "lambert" | "blinn_phong" (default lambert), ambient >= 0 (default 0).
 * Variants: PG_ALPHA_MASK only if the scene has alpha-mask materials (a second pipeline for those
 * draws), PG_NORMAL_MAPS only if it has normal maps, PG_BLINN_PHONG for that shading. */
#include <stdio.h>
#include <string.h>

#include "graph_execute.h"
#include "pass_api.h"
#include "shader.h"
#include "vk_pipeline.h"

typedef struct forward_naive {
    pg_pass_set set;
    VkPipelineLayout layout;
    VkPipeline opaque, masked;
} forward_naive;

static const char *const k_shading[] = {"lambert", "blinn_phong", NULL};

static pg_result fn_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    static const char *const known[] = {"shading", "ambient", NULL};
    pg_result r;
    int shading;
    double ambient;
    if ((r = pg_opt_check_known(in->desc, known, err))) return r;
    if ((r = pg_opt_enum(in->desc, "shading", k_shading, 0, &shading, err))) return r;
    if ((r = pg_opt_float(in->desc, "ambient", 0.0, 0.0, 1e6, &ambient, err))) return r;
    pg_decl_read(out, "lights", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_FRAGMENT, 0);
    pg_decl_write(out, "color", PG_RES_IMAGE, PG_ACCESS_COLOR_WRITE, PG_STAGE_FRAGMENT, PG_FMTCLASS_FLOAT);
    pg_decl_write(out, "depth", PG_RES_IMAGE, PG_ACCESS_DEPTH_WRITE, PG_STAGE_FRAGMENT, PG_FMTCLASS_DEPTH);
    char def[PG_NAME_MAX];
    snprintf(def, sizeof def, "PG_AMBIENT=%.9g", ambient);
    pg_decl_define(out, def);
    if (shading == 1) pg_decl_define(out, "PG_BLINN_PHONG");
    if (in->features.has_alpha_mask) pg_decl_define(out, "PG_ALPHA_MASK");
    else pg_decl_explain(out, "no alpha-mask materials: alpha-test (discard) variant not compiled");
    if (in->features.has_normal_maps) pg_decl_define(out, "PG_NORMAL_MAPS");
    else pg_decl_explain(out, "no normal maps: tangent-space normal path compiled out");
    if (in->features.light_count == 0) pg_decl_explain(out, "0 lights: the light loop runs no iteration");
    return PG_OK;
}

static pg_result fn_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    forward_naive *p = self;
    pg_gpu *gpu = ctx->gpu;
    const pg_plan_pass *pass = ctx->pass;
    pg_result r;
    if (!ctx->scene) return pg_fail(err, PG_ERR_INVALID_ARG, "needs a scene");
    pg_set_binding b = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, ctx->slots[0], VK_NULL_HANDLE, 0};
    if ((r = pg_pass_set_create(gpu, 1, &b, pass->name, &p->set, err))) return r;
    VkDescriptorSetLayout sets[3] = {ctx->frame_layout, ctx->scene->set_layout, p->set.layout};
    if ((r = pg_pipeline_layout_create(gpu, 3, sets, sizeof(uint32_t), &p->layout, err))) return r;

    const char *defs[PG_MAX_DEFINES + 1];
    uint32_t n = 0;
    char tc[32];
    snprintf(tc, sizeof tc, "TEXTURE_COUNT=%u", ctx->scene->n_images);
    defs[n++] = tc;
    bool has_mask = false;
    for (uint32_t i = 0; i < pass->decl.n_defines; i++) {
        if (strcmp(pass->decl.defines[i], "PG_ALPHA_MASK") == 0) {
            has_mask = true;
            continue;
        }
        defs[n++] = pass->decl.defines[i];
    }
    VkShaderModule vs = VK_NULL_HANDLE, fs = VK_NULL_HANDLE, fs_mask = VK_NULL_HANDLE;
    if ((r = pg_shader_module(gpu, "scene.vert", VK_SHADER_STAGE_VERTEX_BIT, defs, n, &vs, err))) goto out;
    if ((r = pg_shader_module(gpu, "forward_naive.frag", VK_SHADER_STAGE_FRAGMENT_BIT, defs, n, &fs, err))) goto out;
    pg_gfx_pipeline_desc d = {
        .layout = p->layout,
        .vs = vs,
        .fs = fs,
        .n_color = 1,
        .color_formats = {ctx->slots[1]->format},
        .depth_format = ctx->slots[2]->format,
        .depth_test = true,
        .depth_write = true,
        .dynamic_cull = true,
        .scene_vertices = true,
    };
    if ((r = pg_gfx_pipeline_create(gpu, &d, pass->name, &p->opaque, err))) goto out;
    if (has_mask && ctx->scene->n_draws > ctx->scene->n_opaque_draws) {
        defs[n++] = "PG_ALPHA_MASK";
        if ((r = pg_shader_module(gpu, "forward_naive.frag", VK_SHADER_STAGE_FRAGMENT_BIT, defs, n, &fs_mask, err)))
            goto out;
        d.fs = fs_mask;
        r = pg_gfx_pipeline_create(gpu, &d, "forward_naive.masked", &p->masked, err);
    }
out:
    if (vs) vkDestroyShaderModule(gpu->device, vs, NULL);
    if (fs) vkDestroyShaderModule(gpu->device, fs, NULL);
    if (fs_mask) vkDestroyShaderModule(gpu->device, fs_mask, NULL);
    return r;
}

static void fn_record(void *self, const pg_pass_record_ctx *ctx)
{
    forward_naive *p = self;
    const pg_scene_gpu *sc = ctx->scene;
    VkCommandBuffer cmd = ctx->cmd;
    const pg_phys_resource *color = ctx->slots[1], *depth = ctx->slots[2];
    VkClearColorValue clear = {{0, 0, 0, 1}};
    pg_cmd_begin_rendering(cmd, color->width, color->height, 1, &color->view, &clear, depth->view, true, 1.0f);
    VkDescriptorSet sets[3] = {ctx->frame_set, sc->set, p->set.set};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p->opaque);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p->layout, 0, 3, sets, 0, NULL);
    VkDeviceSize zero = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &sc->vertices.buffer, &zero);
    vkCmdBindIndexBuffer(cmd, sc->indices.buffer, 0, VK_INDEX_TYPE_UINT32);
    VkCullModeFlags cull = ~0u;
    for (uint32_t i = 0; i < sc->n_draws; i++) {
        const pg_draw *d = &sc->draws[i];
        if (i == sc->n_opaque_draws) {
            if (!p->masked) break;
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p->masked);
            cull = ~0u; /* dynamic state must be set again after a bind that could reset it */
        }
        VkCullModeFlags want = d->double_sided ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT;
        if (want != cull) {
            vkCmdSetCullMode(cmd, want);
            cull = want;
        }
        vkCmdPushConstants(cmd, p->layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT |
                                               VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(uint32_t), &d->material);
        vkCmdDrawIndexed(cmd, d->index_count, 1, d->first_index, d->vertex_offset, 0);
    }
    vkCmdEndRendering(cmd);
}

static void fn_destroy(void *self, pg_gpu *gpu)
{
    forward_naive *p = self;
    if (p->opaque) vkDestroyPipeline(gpu->device, p->opaque, NULL);
    if (p->masked) vkDestroyPipeline(gpu->device, p->masked, NULL);
    if (p->layout) vkDestroyPipelineLayout(gpu->device, p->layout, NULL);
    pg_pass_set_destroy(gpu, &p->set);
}

const pg_pass_type pg_pass_forward_naive = {
    .name = "forward_naive",
    .summary = "graphics: draw the scene, every fragment shades with every light (exact reference)",
    .read_slots = "lights",
    .write_slots = "color, depth",
    .instance_size = sizeof(forward_naive),
    .declare = fn_declare,
    .create = fn_create,
    .record = fn_record,
    .destroy = fn_destroy,
};
