/* shader_pass.c - the `shader` pass type: a pass written by the user in the pipeline JSON and a
 * GLSL file (docs/user-passes.md), in three forms:
 *   compute     a compute shader dispatched per pixel of an image, per element of a buffer, or
 *               a fixed number of workgroups;
 *   fullscreen  a fragment shader over one full-screen triangle into colour targets (blend none,
 *               add or over);
 *   draw        the scene's draws through passgraph's vertex path (scene.vert, materials, the
 *               posed geometry) with the user's fragment shader, into targets with a depth test.
 * Set 0 is the frame block, set 1 the scene (draw; an empty set otherwise), set 2 the user's
 * bindings, at the binding numbers the shader gave them. Push constants carry options.params, a
 * run-time value: a new value re-creates nothing (update()). declare: shader_pass_declare.c. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "graph_execute.h"
#include "pass_set.h"
#include "shader.h"
#include "shader_pass.h"
#include "visibility_common.h"
#include "vk_pipeline.h"

typedef struct shader_pass {
    pg_pass_set set, empty;     /* empty: set 1 (or, "surface": "visibility", the vertex streams) */
    pg_vis_geometry vis;        /* "surface": "visibility" */
    bool vis_surface;
    VkSampler sampler;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    pg_scene_draw draw;
    _Alignas(16) unsigned char push[SP_PUSH_MAX];
} shader_pass;

static pg_result user_module(const pg_pass_create_ctx *ctx, const char *path, VkShaderStageFlagBits stage,
                             const pg_pass_decl *decl, const pg_vis_geometry *vis, VkShaderModule *out, pg_error *err)
{
    pg_gpu *gpu = ctx->gpu;
    const char *defs[PG_MAX_DEFINES + 16];
    uint32_t nd;
    if (vis) { /* the scene's defines (TEXTURE_COUNT, PG_VIS_TRI_BITS, ...) and where the streams are */
        nd = pg_vis_geometry_define_list(vis, defs);
        defs[nd++] = "PG_VIS_SET=1";
        defs[nd++] = "PG_VIS_BINDING=0";
    } else {
        nd = pg_decl_define_list(decl, defs, PG_MAX_DEFINES);
    }
    uint32_t *code;
    size_t words;
    pg_result r = pg_shader_compile_user(path, stage, defs, nd, gpu->vulkan12, &code, &words, err);
    if (r) return r;
    const char *cap = pg_spirv_missing_capability(code, words, gpu->shader_int64, gpu->int64_atomics);
    if (cap) {
        free(code);
        return pg_fail(err, PG_ERR_NO_DEVICE,
                       "%s: %s: shader '%s' uses the SPIR-V capability %s, which passgraph does not enable on %s",
                       ctx->desc->file, ctx->desc->json_path, path, cap, gpu->props.deviceName);
    }
    r = pg_shader_module_words(gpu, path, code, words, out, err);
    free(code);
    return r;
}

static pg_result make_set(shader_pass *s, const pg_pass_create_ctx *ctx, const sp_params *pa, pg_error *err)
{
    pg_set_binding b[SP_MAX_BINDINGS];
    uint32_t numbers[SP_MAX_BINDINGS];
    bool sampled = false;
    for (uint32_t k = 0; k < pa->n_bindings; k++) sampled |= pa->bindings[k].type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    pg_result r;
    if (sampled && (r = pg_sampler_create(ctx->gpu, (VkFilter)pa->filter, (VkSamplerAddressMode)pa->address,
                                          &s->sampler, err)))
        return r;
    for (uint32_t k = 0; k < pa->n_bindings; k++) {
        b[k] = (pg_set_binding){(VkDescriptorType)pa->bindings[k].type, pg_ctx_res(ctx, pa->bindings[k].slot),
                                s->sampler, 0};
        numbers[k] = pa->bindings[k].number;
        const bool buffer = b[k].type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER || b[k].type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        if (buffer && pa->bindings[k].block_size > b[k].res->size) /* its fixed part would read past the end */
            return pg_fail(err, PG_ERR_LIMIT,
                           "%s: %s: shader '%s' binding %u is a block of %u bytes (without a runtime array), buffer "
                           "'%s' is %llu bytes",
                           ctx->desc->file, ctx->desc->json_path, pa->path, (unsigned)numbers[k],
                           pa->bindings[k].block_size,
                           ctx->plan->resources[ctx->pass->slots[pg_plan_slot_of(ctx->pass, pa->bindings[k].slot)].resource]
                               .name,
                           (unsigned long long)b[k].res->size);
        if (b[k].type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER && b[k].res->size > ctx->gpu->max_storage_buffer_range)
            return pg_fail(err, PG_ERR_LIMIT,
                           "%s: %s: binding %u reads '%s' as one storage buffer of %.1f MiB, more than one binding "
                           "spans on %s (%.1f MiB): make it smaller (the light lists: fewer lights or a coarser "
                           "grid)",
                           ctx->desc->file, ctx->desc->json_path, (unsigned)numbers[k],
                           ctx->plan->resources[ctx->pass->slots[pg_plan_slot_of(ctx->pass, pa->bindings[k].slot)].resource]
                               .name,
                           b[k].res->size / 1048576.0, ctx->gpu->props.deviceName,
                           ctx->gpu->max_storage_buffer_range / 1048576.0);
    }
    return pg_pass_set_create_numbered(ctx->gpu, pa->n_bindings, b, numbers, ctx->pass->name, &s->set, err);
}

static pg_result create_fullscreen(shader_pass *s, const pg_pass_create_ctx *ctx, const sp_params *pa, pg_error *err)
{
    pg_gpu *gpu = ctx->gpu;
    VkShaderModule vs = VK_NULL_HANDLE, fs = VK_NULL_HANDLE;
    pg_result r = pg_shader_module(gpu, "fullscreen.vert", VK_SHADER_STAGE_VERTEX_BIT, NULL, 0, &vs, err);
    if (!r) r = user_module(ctx, pa->path, VK_SHADER_STAGE_FRAGMENT_BIT, &ctx->pass->decl, NULL, &fs, err);
    if (!r) {
        pg_gfx_pipeline_desc d = {
            .layout = s->layout,
            .vs = vs,
            .fs = fs,
            .n_color = pa->n_targets,
            .blend_over = pa->blend == SP_BLEND_OVER,
            .blend_add = pa->blend == SP_BLEND_ADD,
        };
        for (uint32_t t = 0; t < pa->n_targets; t++) d.color_formats[t] = pg_ctx_res(ctx, pa->targets[t])->format;
        r = pg_gfx_pipeline_create(gpu, &d, ctx->pass->name, &s->pipeline, err);
    }
    if (vs) vkDestroyShaderModule(gpu->device, vs, NULL);
    if (fs) vkDestroyShaderModule(gpu->device, fs, NULL);
    return r;
}

static pg_result create_draw(shader_pass *s, const pg_pass_create_ctx *ctx, const sp_params *pa, pg_error *err)
{
    pg_scene_draw_desc d = {
        .fragment_shader = pa->path,
        .fragment_user = true,
        .features = &pa->draw,
        .pass_layout = s->set.layout,
        .n_color = pa->n_targets,
        .depth_format = pg_ctx_res(ctx, pa->depth)->format,
        .blend = pa->blend == SP_BLEND_OVER,
        .depth_equal = pa->depth_compare == VK_COMPARE_OP_EQUAL,
    };
    for (uint32_t t = 0; t < pa->n_targets; t++) d.color_formats[t] = pg_ctx_res(ctx, pa->targets[t])->format;
    return pg_scene_draw_create(ctx, &d, &s->draw, err);
}

/* Set 1: empty, or ("surface": "visibility") the scene's vertex streams, indices and draw table. */
static pg_result create_set1(shader_pass *s, const pg_pass_create_ctx *ctx, const sp_params *pa, pg_error *err)
{
    s->vis_surface = pa->vis_surface;
    if (!pa->vis_surface) return pg_pass_set_create(ctx->gpu, 0, NULL, ctx->pass->name, &s->empty, err);
    if (!PG_SCENE_OF(ctx)) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: \"surface\": \"visibility\" needs a scene", ctx->pass->name);
    pg_result r = pg_vis_geometry_create(ctx, &pa->draw, SP_SCENE_SET, &s->vis, err);
    if (r) return r;
    pg_set_binding b[8];
    const uint32_t n = pg_vis_geometry_bindings(&s->vis, PG_SCENE_OF(ctx), b, 0);
    char name[PG_NAME_MAX + 16];
    snprintf(name, sizeof name, "%s.streams", ctx->pass->name);
    return pg_pass_set_create(ctx->gpu, n, b, name, &s->empty, err);
}

/* The compute shader's workgroup against the device's limits (the SPIR-V is valid anyway: a device
 * may not run it). */
static pg_result check_workgroup(const pg_pass_create_ctx *ctx, const sp_params *pa, pg_error *err)
{
    const VkPhysicalDeviceLimits *l = &ctx->gpu->props.limits;
    const uint64_t n = (uint64_t)pa->local[0] * pa->local[1] * pa->local[2];
    const char *file = ctx->desc->file, *path = ctx->desc->json_path;
    for (int k = 0; k < 3; k++)
        if (pa->local[k] > l->maxComputeWorkGroupSize[k])
            return pg_fail(err, PG_ERR_LIMIT, "%s: %s: shader '%s': local_size_%c = %u is more than %s allows (%u)", file,
                           path, pa->path, 'x' + k, pa->local[k], ctx->gpu->props.deviceName,
                           l->maxComputeWorkGroupSize[k]);
    if (n > l->maxComputeWorkGroupInvocations)
        return pg_fail(err, PG_ERR_LIMIT, "%s: %s: shader '%s': a workgroup of %ux%ux%u = %llu invocations is more "
                       "than %s allows (%u)",
                       file, path, pa->path, pa->local[0], pa->local[1], pa->local[2], (unsigned long long)n,
                       ctx->gpu->props.deviceName, l->maxComputeWorkGroupInvocations);
    if (pa->shared_bytes > l->maxComputeSharedMemorySize)
        return pg_fail(err, PG_ERR_LIMIT, "%s: %s: shader '%s': %u bytes of shared memory (at least) are more than %s "
                       "allows (%u)",
                       file, path, pa->path, pa->shared_bytes, ctx->gpu->props.deviceName, l->maxComputeSharedMemorySize);
    return PG_OK;
}

static pg_result sp_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    shader_pass *s = self;
    const sp_params *pa = PG_PARAMS(ctx, sp_params);
    memcpy(s->push, pa->push, sizeof s->push);
    pg_result r = make_set(s, ctx, pa, err);
    if (r) return r;
    if (pa->form == SP_DRAW) return create_draw(s, ctx, pa, err);
    if ((r = create_set1(s, ctx, pa, err))) return r;
    VkDescriptorSetLayout sets[4] = {ctx->frame_layout, s->empty.layout, s->set.layout,
                                     s->vis_surface ? PG_SCENE_OF(ctx)->set_layout : VK_NULL_HANDLE};
    if ((r = pg_pipeline_layout_create(ctx->gpu, s->vis_surface ? 4 : 3, sets, pa->push_size, &s->layout, err))) return r;
    if (pa->form == SP_FULLSCREEN) return create_fullscreen(s, ctx, pa, err);
    if ((r = check_workgroup(ctx, pa, err))) return r;
    VkShaderModule cs;
    if ((r = user_module(ctx, pa->path, VK_SHADER_STAGE_COMPUTE_BIT, &ctx->pass->decl,
                         s->vis_surface ? &s->vis : NULL, &cs, err)))
        return r;
    r = pg_compute_pipeline_create(ctx->gpu, s->layout, cs, ctx->pass->name, &s->pipeline, err);
    vkDestroyShaderModule(ctx->gpu->device, cs, NULL);
    return r;
}

static uint32_t div_up(uint64_t n, uint32_t d)
{
    uint64_t g = (n + d - 1) / d;
    return g > 65535 ? 65535 : (uint32_t)g;
}

static void bind_and_push(const shader_pass *s, const pg_pass_record_ctx *ctx, const sp_params *pa,
                          VkPipelineBindPoint point)
{
    VkDescriptorSet sets[4] = {ctx->frame_set, s->empty.set, s->set.set,
                               s->vis_surface ? PG_SCENE_OF(ctx)->set : VK_NULL_HANDLE};
    vkCmdBindPipeline(ctx->cmd, point, s->pipeline);
    vkCmdBindDescriptorSets(ctx->cmd, point, s->layout, 0, s->vis_surface ? 4 : 3, sets, 0, NULL);
    if (pa->push_size) vkCmdPushConstants(ctx->cmd, s->layout, PG_PUSH_STAGES, 0, pa->push_size, s->push);
}

static void begin_targets(const pg_pass_record_ctx *ctx, const sp_params *pa)
{
    uint32_t slots[SP_MAX_TARGETS];
    VkClearColorValue clears[SP_MAX_TARGETS];
    memset(clears, 0, sizeof clears);
    for (uint32_t t = 0; t < pa->n_targets; t++) slots[t] = pg_plan_slot_of(ctx->pass, pa->targets[t]);
    const int depth = pg_slot_ok(pa->depth) ? (int)pg_plan_slot_of(ctx->pass, pa->depth) : -1;
    pg_pass_begin_rendering(ctx, pa->n_targets, slots, pa->clear_targets ? clears : NULL, depth, pa->depth_clear, 1.0f);
}

static void sp_record(void *self, const pg_pass_record_ctx *ctx)
{
    shader_pass *s = self;
    const sp_params *pa = PG_PARAMS(ctx, sp_params);
    pg_vis_geometry_record(&s->vis, ctx); /* "surface": "visibility": the draws the pose mirrors */
    if (pa->form == SP_COMPUTE) {
        bind_and_push(s, ctx, pa, VK_PIPELINE_BIND_POINT_COMPUTE);
        uint32_t g[3] = {pa->groups[0], pa->groups[1], pa->groups[2]};
        if (pa->dispatch == SP_DISPATCH_IMAGE) {
            const pg_phys_resource *img = pg_ctx_res(ctx, pa->dispatch_slot);
            g[0] = div_up(img->width, pa->local[0]);
            g[1] = div_up(img->height, pa->local[1]);
            g[2] = 1;
        } else if (pa->dispatch == SP_DISPATCH_BUFFER) {
            const pg_phys_resource *buf = pg_ctx_res(ctx, pa->dispatch_slot);
            g[0] = div_up(buf->size / pa->dispatch_stride, pa->local[0]);
            g[1] = g[2] = 1;
        }
        if (g[0] && g[1] && g[2]) vkCmdDispatch(ctx->cmd, g[0], g[1], g[2]);
        return;
    }
    begin_targets(ctx, pa);
    if (pa->form == SP_DRAW) {
        pg_scene_draw_record(&s->draw, ctx, s->set.set);
    } else {
        bind_and_push(s, ctx, pa, VK_PIPELINE_BIND_POINT_GRAPHICS);
        vkCmdDraw(ctx->cmd, 3, 1, 0, 0);
    }
    vkCmdEndRendering(ctx->cmd);
}

static void sp_destroy(void *self, pg_gpu *gpu)
{
    shader_pass *s = self;
    pg_scene_draw_destroy(gpu, &s->draw);
    if (s->pipeline) vkDestroyPipeline(gpu->device, s->pipeline, NULL);
    if (s->layout) vkDestroyPipelineLayout(gpu->device, s->layout, NULL);
    if (s->sampler) vkDestroySampler(gpu->device, s->sampler, NULL);
    pg_pass_set_destroy(gpu, &s->set);
    pg_pass_set_destroy(gpu, &s->empty);
    pg_vis_geometry_destroy(gpu, &s->vis);
}

/* options.params are push constants: a new value re-creates nothing */
static const char *const k_runtime[] = {"params", NULL};

static pg_result sp_update(void *self, const void *params, pg_error *err)
{
    (void)err;
    shader_pass *s = self;
    memcpy(s->push, ((const sp_params *)params)->push, sizeof s->push);
    return PG_OK;
}

const pg_pass_type pg_pass_shader = {
    .name = "shader",
    .summary = "user pass: a GLSL compute, full-screen or scene-draw shader named in the pipeline JSON",
    .instance_size = sizeof(shader_pass),
    .params_size = sizeof(sp_params),
    .declare = pg_shader_pass_declare,
    .create = sp_create,
    .record = sp_record,
    .destroy = sp_destroy,
    .runtime_options = k_runtime,
    .update = sp_update,
};
