#include "scene_draw.h"

#include <stdlib.h>

#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "frame.h"
#include "scene_gpu_anim.h"
#include "shader.h"

/* The scene's vertex streams (shaders/scene.vert): binding 0 pg_vertex; the optional streams of
 * pg_scene.colors / uv1, each a tightly packed float array: binding 1 COLOR_0 (location 4),
 * binding 2 TEXCOORD_1 (location 5). */
static pg_vertex_input scene_vertex_input(bool vertex_colors, bool uv1)
{
    pg_vertex_input v = {
        .n_bindings = 1,
        .n_attributes = 4,
        .bindings = {{0, sizeof(pg_vertex), VK_VERTEX_INPUT_RATE_VERTEX}},
        .attributes = {
            {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(pg_vertex, position)},
            {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(pg_vertex, normal)},
            {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(pg_vertex, uv)},
            {3, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(pg_vertex, tangent)},
        },
    };
    if (vertex_colors) {
        v.bindings[v.n_bindings++] = (VkVertexInputBindingDescription){1, sizeof(float[4]), VK_VERTEX_INPUT_RATE_VERTEX};
        v.attributes[v.n_attributes++] = (VkVertexInputAttributeDescription){4, 1, VK_FORMAT_R32G32B32A32_SFLOAT, 0};
    }
    if (uv1) {
        v.bindings[v.n_bindings++] = (VkVertexInputBindingDescription){2, sizeof(float[2]), VK_VERTEX_INPUT_RATE_VERTEX};
        v.attributes[v.n_attributes++] = (VkVertexInputAttributeDescription){5, 2, VK_FORMAT_R32G32_SFLOAT, 0};
    }
    return v;
}

/* The pass's fragment shader: one of the shaders folder, or a user's file (fragment_user). */
static pg_result fragment_module(pg_gpu *gpu, const pg_scene_draw_desc *d, const char *const *defs, uint32_t n,
                                 VkShaderModule *out, pg_error *err)
{
    if (!d->fragment_user)
        return pg_shader_module(gpu, d->fragment_shader, VK_SHADER_STAGE_FRAGMENT_BIT, defs, n, out, err);
    uint32_t *code;
    size_t words;
    pg_result r = pg_shader_compile_user(d->fragment_shader, VK_SHADER_STAGE_FRAGMENT_BIT, defs, n, gpu->vulkan12,
                                         &code, &words, err);
    if (r) return r;
    const char *cap = pg_spirv_missing_capability(code, words, gpu->shader_int64, gpu->int64_atomics);
    if (cap) {
        free(code);
        return pg_fail(err, PG_ERR_NO_DEVICE, "shader '%s' uses the SPIR-V capability %s, which passgraph does not enable on %s",
                       d->fragment_shader, cap, gpu->props.deviceName);
    }
    r = pg_shader_module_words(gpu, d->fragment_shader, code, words, out, err);
    free(code);
    return r;
}

pg_result pg_scene_draw_create(const pg_pass_create_ctx *ctx, const pg_scene_draw_desc *d, pg_scene_draw *out,
                               pg_error *err)
{
    pg_gpu *gpu = ctx->gpu;
    const pg_plan_pass *pass = ctx->pass;
    pg_result r;
    if (!PG_SCENE_OF(ctx)) return pg_fail(err, PG_ERR_INVALID_ARG, "needs a scene");
    VkDescriptorSetLayout sets[3] = {ctx->frame_layout, PG_SCENE_OF(ctx)->set_layout, d->pass_layout};
    /* push constants: DrawPush {uint material; float ambient;} (shaders/surface.glsl) */
    if ((r = pg_pipeline_layout_create(gpu, d->pass_layout ? 3 : 2, sets, 2 * sizeof(uint32_t), &out->layout, err)))
        return r;
    const char *defs[PG_MAX_DEFINES + 8];
    uint32_t n = 0;
    char tc[32];
    snprintf(tc, sizeof tc, "TEXTURE_COUNT=%u", PG_SCENE_OF(ctx)->n_images);
    defs[n++] = tc;
    const pg_scene_draw_features *f = d->features;
    const bool has_mask = f->alpha_mask;
    out->vertex_colors = f->vertex_colors;
    out->uv1 = f->uv1;
    out->push_draw_key = false;
    out->draw_key_shift = 0;
    out->has_geometry = f->has_geometry;
    out->geometry = f->geometry;
    n += pg_scene_draw_define_list(&pass->decl, f, defs + n, PG_MAX_DEFINES);
    if ((out->vertex_colors && !PG_SCENE_OF(ctx)->colors.buffer) || (out->uv1 && !PG_SCENE_OF(ctx)->uv1.buffer)) {
        r = pg_fail(err, PG_ERR_INVALID_ARG, "%s: compiled with %s but the uploaded scene has no such stream",
                    pass->name, out->vertex_colors && !PG_SCENE_OF(ctx)->colors.buffer ? "PG_VERTEX_COLORS" : "PG_UV1");
        vkDestroyPipelineLayout(gpu->device, out->layout, NULL);
        out->layout = VK_NULL_HANDLE;
        return r;
    }
    for (uint32_t i = 0; i < d->n_extra_defines; i++) defs[n++] = d->extra_defines[i];
    VkShaderModule vs = VK_NULL_HANDLE, vs_pos = VK_NULL_HANDLE, fs = VK_NULL_HANDLE, fs_mask = VK_NULL_HANDLE;
    /* the full vertex shader: the opaque pipeline's, or the alpha-mask one's */
    const bool masked = has_mask && !d->blend && !d->depth_equal &&
                        PG_SCENE_OF(ctx)->n_draws - PG_SCENE_OF(ctx)->n_blend_draws > PG_SCENE_OF(ctx)->n_opaque_draws;
    if ((!d->position_only_opaque || masked) &&
        (r = pg_shader_module(gpu, "scene.vert", VK_SHADER_STAGE_VERTEX_BIT, defs, n, &vs, err)))
        goto out;
    if ((r = fragment_module(gpu, d, defs, n, &fs, err))) goto out;
    const pg_vertex_input vin = scene_vertex_input(out->vertex_colors, out->uv1);
    pg_vertex_input vin_pos = vin; /* binding 0, location 0 alone */
    vin_pos.n_bindings = 1;
    vin_pos.n_attributes = 1;
    if (d->position_only_opaque) {
        defs[n] = "PG_POSITION_ONLY";
        if ((r = pg_shader_module(gpu, "scene.vert", VK_SHADER_STAGE_VERTEX_BIT, defs, n + 1, &vs_pos, err))) goto out;
    }
    pg_gfx_pipeline_desc gd = {
        .layout = out->layout,
        .vs = d->position_only_opaque ? vs_pos : vs,
        .fs = fs,
        .n_color = d->n_color,
        .depth_format = d->depth_format,
        .depth_test = true,
        .depth_write = !d->blend && !d->depth_equal,
        .depth_compare = d->depth_equal ? VK_COMPARE_OP_EQUAL : 0,
        .depth_bias_constant = d->depth_bias_constant,
        .depth_bias_slope = d->depth_bias_slope,
        .dynamic_cull = true,
        .vertex_input = d->position_only_opaque ? &vin_pos : &vin,
        .blend_over = d->blend,
    };
    memcpy(gd.color_formats, d->color_formats, sizeof gd.color_formats);
    if ((r = pg_gfx_pipeline_create(gpu, &gd, pass->name, &out->opaque, err))) goto out;
    out->depth_equal = d->depth_equal;
    if (masked) {
        defs[n++] = "PG_ALPHA_MASK";
        if ((r = fragment_module(gpu, d, defs, n, &fs_mask, err)))
            goto out;
        gd.fs = fs_mask;
        gd.vs = vs;
        gd.vertex_input = &vin;
        char name[PG_NAME_MAX + 16];
        snprintf(name, sizeof name, "%s.masked", pass->name);
        r = pg_gfx_pipeline_create(gpu, &gd, name, &out->masked, err);
    }
out:
    if (vs) vkDestroyShaderModule(gpu->device, vs, NULL);
    if (vs_pos) vkDestroyShaderModule(gpu->device, vs_pos, NULL);
    if (fs) vkDestroyShaderModule(gpu->device, fs, NULL);
    if (fs_mask) vkDestroyShaderModule(gpu->device, fs_mask, NULL);
    return r;
}

static void bind_scene(const pg_scene_draw *sd, const pg_pass_record_ctx *ctx, VkDescriptorSet pass_set)
{
    const pg_scene_gpu *sc = PG_SCENE_OF(ctx);
    VkCommandBuffer cmd = ctx->cmd;
    VkDescriptorSet sets[3] = {ctx->frame_set, sc->set, pass_set};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, sd->opaque);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, sd->layout, 0, pass_set ? 3 : 2, sets, 0, NULL);
    VkDeviceSize zero = 0;
    const VkBuffer vb = sd->has_geometry ? pg_ctx_res(ctx, sd->geometry)->buffer : sc->vertices.buffer;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &zero);
    if (sd->vertex_colors) vkCmdBindVertexBuffers(cmd, 1, 1, &sc->colors.buffer, &zero);
    if (sd->uv1) vkCmdBindVertexBuffers(cmd, 2, 1, &sc->uv1.buffer, &zero);
    vkCmdBindIndexBuffer(cmd, sc->indices.buffer, 0, VK_INDEX_TYPE_UINT32);
}

static void push_draw(VkCommandBuffer cmd, const pg_scene_draw *sd, const pg_draw *d, uint32_t index)
{
    uint32_t push[2] = {d->material, index << sd->draw_key_shift};
    if (!sd->push_draw_key) memcpy(&push[1], &sd->ambient, sizeof(float));
    vkCmdPushConstants(cmd, sd->layout, PG_PUSH_STAGES, 0, sizeof push, push);
}

/* the dynamic state the last draw set (~0u, VK_FRONT_FACE_MAX_ENUM: none yet) */
typedef struct draw_state {
    VkCullModeFlags cull;
    VkFrontFace front;
} draw_state;

/* Draw d's cull mode (none when double-sided) and front face: glTF's counter-clockwise, clockwise
 * where the frame's pose mirrors a moving draw against the winding its indices have (an animated
 * scale through -1: pg_scene_gpu_anim_flipped); drawn in the rest pose (no geometry slot), never. */
static void set_draw_state(const pg_scene_draw *sd, const pg_pass_record_ctx *ctx, const pg_draw *d, draw_state *st)
{
    const VkCullModeFlags cull = d->double_sided ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT;
    VkFrontFace front = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    if (sd->has_geometry && d->anim_prim >= 0) {
        const pg_frame_uniforms *fu = PG_FRAME_OF(ctx);
        if (pg_scene_gpu_anim_flipped(PG_SCENE_OF(ctx)->anim, d->anim_prim, pg_frame_animation(fu), fu->camera_pos[3]))
            front = VK_FRONT_FACE_CLOCKWISE;
    }
    if (cull != st->cull) vkCmdSetCullMode(ctx->cmd, cull);
    if (front != st->front) vkCmdSetFrontFace(ctx->cmd, front);
    st->cull = cull;
    st->front = front;
}

void pg_scene_draw_record_list(const pg_scene_draw *sd, const pg_pass_record_ctx *ctx, VkDescriptorSet pass_set,
                               const uint32_t *order, uint32_t n)
{
    const pg_scene_gpu *sc = PG_SCENE_OF(ctx);
    VkCommandBuffer cmd = ctx->cmd;
    bind_scene(sd, ctx, pass_set);
    draw_state st = {~0u, VK_FRONT_FACE_MAX_ENUM};
    for (uint32_t k = 0; k < n; k++) {
        const pg_draw *d = &sc->draws[order[k]];
        set_draw_state(sd, ctx, d, &st);
        push_draw(cmd, sd, d, order[k]);
        vkCmdDrawIndexed(cmd, d->index_count, 1, d->first_index, d->vertex_offset, 0);
    }
}

void pg_scene_draw_record(const pg_scene_draw *sd, const pg_pass_record_ctx *ctx, VkDescriptorSet pass_set)
{
    const pg_scene_gpu *sc = PG_SCENE_OF(ctx);
    VkCommandBuffer cmd = ctx->cmd;
    bind_scene(sd, ctx, pass_set);
    draw_state st = {~0u, VK_FRONT_FACE_MAX_ENUM};
    for (uint32_t i = 0; i < sc->n_draws - sc->n_blend_draws; i++) { /* BLEND: the transparent pass */
        const pg_draw *d = &sc->draws[i];
        if (i == sc->n_opaque_draws && !sd->depth_equal) { /* depth_equal: the opaque pipeline, no discard */
            if (!sd->masked) break; /* the pass declared no PG_ALPHA_MASK (e.g. depth_prepass, test less) */
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, sd->masked);
            st = (draw_state){~0u, VK_FRONT_FACE_MAX_ENUM};
        }
        set_draw_state(sd, ctx, d, &st);
        push_draw(cmd, sd, d, i);
        vkCmdDrawIndexed(cmd, d->index_count, 1, d->first_index, d->vertex_offset, 0);
    }
}

void pg_scene_draw_destroy(pg_gpu *gpu, pg_scene_draw *sd)
{
    if (sd->opaque) vkDestroyPipeline(gpu->device, sd->opaque, NULL);
    if (sd->masked) vkDestroyPipeline(gpu->device, sd->masked, NULL);
    if (sd->layout) vkDestroyPipelineLayout(gpu->device, sd->layout, NULL);
    memset(sd, 0, sizeof *sd);
}

const char *const pg_prepass_tests[] = {"less", "equal", NULL};

void pg_geometry_slot_declare(const pg_declare_in *in, pg_pass_decl *out, pg_scene_draw_features *f, bool storage)
{
    const bool animated = pg_scene_features_of(in).has_animation;
    f->has_geometry = false;
    f->geometry = PG_SLOT_NONE;
    if (in->desc->n_reads <= out->n_reads) {
        if (animated)
            pg_decl_explain(out, "no geometry slot bound (reads[%u]): the animated scene is drawn in its rest pose",
                            out->n_reads);
        return;
    }
    f->geometry = storage ? pg_decl_read(out, "geometry", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_COMPUTE, 0)
                          : pg_decl_read(out, "geometry", PG_RES_BUFFER, PG_ACCESS_VERTEX_INPUT, PG_STAGE_VERTEX, 0);
    if (!animated) {
        pg_decl_mark_unused(out, f->geometry, "no animation: the static vertex buffer is drawn");
        return;
    }
    f->has_geometry = true;
    pg_decl_explain(out, "draws the scene's vertices at the frame's pose (geometry)");
}

uint32_t pg_scene_draw_define_list(const pg_pass_decl *decl, const pg_scene_draw_features *f, const char **out,
                                   uint32_t max)
{
    const char *all[PG_MAX_DEFINES];
    const uint32_t na = pg_decl_define_list(decl, all, PG_MAX_DEFINES);
    uint32_t n = 0;
    for (uint32_t i = 0; i < na && n < max; i++)
        if (i + 1 != f->mask_define) out[n++] = all[i];
    return n;
}

void pg_scene_draw_declare_features(const pg_declare_in *in, pg_pass_decl *out, pg_scene_draw_features *f)
{
    if (pg_scene_features_of(in).has_alpha_mask) { /* the scene's compile variables */
        f->alpha_mask = true;
        f->mask_define = (uint8_t)(out->n_defines + 1);
        pg_decl_define(out, "PG_ALPHA_MASK");
    } else {
        pg_decl_explain(out, "no alpha-mask materials: alpha-test (discard) variant not compiled");
    }
    pg_scene_draw_declare_vertex_features(in, out, f);
}

void pg_scene_draw_declare_vertex_features(const pg_declare_in *in, pg_pass_decl *out, pg_scene_draw_features *f)
{
    const pg_scene_features sf = pg_scene_features_of(in);
    f->vertex_colors = sf.has_vertex_colors;
    f->uv1 = sf.has_uv1;
    if (sf.has_normal_maps) pg_decl_define(out, "PG_NORMAL_MAPS");
    else pg_decl_explain(out, "no normal maps: tangent-space normal path compiled out");
    if (sf.has_emissive) pg_decl_define(out, "PG_EMISSIVE");
    else pg_decl_explain(out, "no emissive materials: emissive term compiled out");
    if (sf.has_vertex_colors) pg_decl_define(out, "PG_VERTEX_COLORS");
    else pg_decl_explain(out, "no vertex colours: colour attribute path compiled out");
    if (sf.has_uv1) pg_decl_define(out, "PG_UV1");
    else pg_decl_explain(out, "no texture reads TEXCOORD_1: second UV stream compiled out");
    if (sf.has_uv_transform) pg_decl_define(out, "PG_UV_TRANSFORM");
    else pg_decl_explain(out, "no KHR_texture_transform: UV transform compiled out");
}
