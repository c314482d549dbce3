/* light_tree.c - compute pass: a binary tree over the lights, rebuilt every frame on the GPU for
 * the lightcut shading (shaders/light_tree.comp has the node layout): Morton codes of the light
 * centres in the frame's light box, a bitonic sort of (code, index) keys (unique, so the order
 * never depends on execution order and every frame with the same lights gives the same tree),
 * leaves in that order, then one bottom-up level at a time: bounds of the centres, the largest
 * radius, the summed colour and a colour-weighted representative position. np is the light count
 * rounded up to a power of two; the tree has 2 np nodes of 64 bytes (the light_tree resource must
 * hold 4 x lights nodes: ["lights", 4] at stride 64).
 * Slots: reads [lights]; writes [light_tree]. No options.
 * Cost: log2(np) (log2(np) + 1) / 2 sort dispatches + log2(np) merge dispatches, each over np
 * threads (1,000,000 lights: 210 + 20). Counters: tree_nodes, sort_steps. */
#include <stdio.h>
#include <string.h>

#include "frame.h"
#include "graph_execute.h"
#include "scene_vars.h"
#include "pass_api.h"
#include "shader.h"
#include "pass_set.h"
#include "vk_pipeline.h"

typedef struct lt_params {
    pg_slot lights, tree;
    uint32_t records_per_light; /* 2 with spot lights: their records follow the lights */
} lt_params;

typedef struct light_tree {
    pg_pass_set set;
    pg_buffer keys;         /* np (code, index) pairs */
    VkPipelineLayout layout;
    VkPipeline pipeline;
    uint32_t np, steps;
    uint64_t tree_bytes;
} light_tree;

static uint32_t pow2_at_least(uint32_t n)
{
    uint32_t p = 1;
    while (p < n && p < (1u << 31)) p <<= 1;
    return p;
}

static pg_result lt_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    static const char *const known[] = {NULL};
    pg_result r = pg_opt_check_known(in->desc, known, err);
    if (r) return r;
    lt_params *p = pg_decl_params(out, sizeof *p);
    p->lights = pg_decl_read(out, "lights", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_COMPUTE, 0);
    p->tree = pg_decl_write(out, "light_tree", PG_RES_BUFFER, PG_ACCESS_STORAGE_WRITE, PG_STAGE_COMPUTE, 0);
    if (pg_lights_of(in) == 0) pg_decl_explain(out, "0 lights: no tree is built");
    p->records_per_light = 1;
    if (pg_scene_features_of(in).has_spot_lights) { /* leaves keep spot records */
        pg_decl_define(out, "PG_SPOT_LIGHTS");
        p->records_per_light = 2;
    }
    return PG_OK;
}

static pg_result lt_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    light_tree *p = self;
    pg_gpu *gpu = ctx->gpu;
    const lt_params *pa = PG_PARAMS(ctx, lt_params);
    const pg_phys_resource *lights = pg_ctx_res(ctx, pa->lights), *tree = pg_ctx_res(ctx, pa->tree);
    uint32_t n = (uint32_t)(lights->size / 32 / pa->records_per_light);
    p->np = pow2_at_least(n ? n : 1);
    p->tree_bytes = 2ull * p->np * 64;
    if (tree->size < p->tree_bytes)
        return pg_fail(err, PG_ERR_SCHEMA,
                       "%s: %s: slot light_tree holds %llu bytes; a tree over %u lights needs %llu (2 x %u nodes of "
                       "64 bytes: declare its count as [\"lights\", 4] at stride 64)",
                       ctx->desc->file, ctx->desc->json_path, (unsigned long long)tree->size,
                       n, (unsigned long long)p->tree_bytes, p->np);
    uint32_t lg = 0;
    while ((1u << lg) < p->np) lg++;
    p->steps = lg * (lg + 1) / 2;
    char name[PG_NAME_MAX + 16];
    snprintf(name, sizeof name, "%s.keys", ctx->pass->name);
    pg_result r;
    if ((r = pg_buffer_create(gpu, 8ull * p->np, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false, name, &p->keys, err))) return r;
    pg_phys_resource kr = {.kind = PG_RES_BUFFER, .buffer = p->keys.buffer, .size = p->keys.size};
    pg_set_binding b[3] = {
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, lights, VK_NULL_HANDLE, 0},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, tree, VK_NULL_HANDLE, 0},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &kr, VK_NULL_HANDLE, 0},
    };
    if ((r = pg_pass_set_create(gpu, 3, b, ctx->pass->name, &p->set, err))) return r;
    VkDescriptorSetLayout sets[2] = {ctx->frame_layout, p->set.layout};
    if ((r = pg_pipeline_layout_create(gpu, 2, sets, 16, &p->layout, err))) return r;
    VkShaderModule cs;
    const char *defs[PG_MAX_DEFINES];
    uint32_t nd = pg_decl_define_list(&ctx->pass->decl, defs, PG_MAX_DEFINES);
    if ((r = pg_shader_module(gpu, "light_tree.comp", VK_SHADER_STAGE_COMPUTE_BIT, defs, nd, &cs, err))) return r;
    r = pg_compute_pipeline_create(gpu, p->layout, cs, ctx->pass->name, &p->pipeline, err);
    vkDestroyShaderModule(gpu->device, cs, NULL);
    return r;
}

static void step(VkCommandBuffer cmd, VkPipelineLayout layout, uint32_t which, uint32_t k, uint32_t j, uint32_t np,
                 uint32_t threads)
{
    uint32_t push[4] = {which, k, j, np};
    vkCmdPushConstants(cmd, layout, PG_PUSH_STAGES, 0, 16, push);
    uint32_t groups = (threads + 63) / 64;
    uint32_t gx = groups < 65535 ? groups : 65535;
    vkCmdDispatch(cmd, gx, (groups + gx - 1) / gx, 1);
    pg_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                          VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

static void lt_record(void *self, const pg_pass_record_ctx *ctx)
{
    light_tree *p = self;
    if (!PG_FRAME_OF(ctx)->counts[0]) return;
    VkCommandBuffer cmd = ctx->cmd;
    VkDescriptorSet sets[2] = {ctx->frame_set, p->set.set};
    /* the keys are the pass's own: an earlier frame's steps finish with them first */
    pg_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                          VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                          VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->layout, 0, 2, sets, 0, NULL);
    const uint32_t np = p->np;
    step(cmd, p->layout, 0, 0, 0, np, np);
    for (uint32_t k = 2; k <= np && k; k <<= 1)
        for (uint32_t j = k >> 1; j > 0; j >>= 1) step(cmd, p->layout, 1, k, j, np, np);
    step(cmd, p->layout, 2, 0, 0, np, np);
    for (uint32_t k = np >> 1; k >= 1; k >>= 1) step(cmd, p->layout, 3, k, 0, np, k);
}

static void lt_report(void *self, pg_pass_report *out)
{
    light_tree *p = self;
    pg_report_add(out, "tree_nodes", 2ull * p->np);
    pg_report_add(out, "sort_steps", p->steps);
}

static void lt_destroy(void *self, pg_gpu *gpu)
{
    light_tree *p = self;
    if (p->pipeline) vkDestroyPipeline(gpu->device, p->pipeline, NULL);
    if (p->layout) vkDestroyPipelineLayout(gpu->device, p->layout, NULL);
    pg_pass_set_destroy(gpu, &p->set);
    pg_buffer_destroy(gpu, &p->keys);
}

const pg_pass_type pg_pass_light_tree = {
    .name = "light_tree",
    .summary = "compute: a binary light tree (Morton order, bounds, summed colour) rebuilt every frame",
    .instance_size = sizeof(light_tree),
    .params_size = sizeof(lt_params),
    .declare = lt_declare,
    .create = lt_create,
    .record = lt_record,
    .destroy = lt_destroy,
    .report = lt_report,
};
