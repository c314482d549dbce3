/* cluster_assign.c - compute pass: builds per-cluster light lists over a grid of screen tiles x
 * exponential depth slices (shaders/cluster_assign.comp). Conservative sphere-vs-AABB test,
 * lists in ascending light order, raw counts kept so overflow is visible; the number of
 * overflowing clusters and dropped light references are read back every frame and reported
 * (counters "overflow_clusters", "overflow_dropped", "max_count", "total_refs").
 * Slots: reads [lights]; writes [cluster_counts (uint per cluster), cluster_lights (max_lights
 * uints per cluster)]. Options: grid_x, grid_y, grid_z, max_lights (defaults 16, 9, 24, 256). */
#include <stdio.h>
#include <string.h>

#include "graph_execute.h"
#include "pass_api.h"
#include "shader.h"
#include "vk_pipeline.h"

typedef struct cluster_assign {
    uint32_t grid[3], max_lights;
    pg_buffer stats;           /* host visible: 4 uints */
    pg_pass_set set;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    bool ran;
} cluster_assign;

static const char *const k_known[] = {"grid_x", "grid_y", "grid_z", "max_lights", NULL};

static pg_result read_opts(const pg_pass_desc *desc, uint32_t grid[3], uint32_t *max_lights, pg_error *err)
{
    pg_result r;
    int64_t v;
    static const char *const gk[3] = {"grid_x", "grid_y", "grid_z"};
    static const int64_t gd[3] = {16, 9, 24};
    if ((r = pg_opt_check_known(desc, k_known, err))) return r;
    for (int k = 0; k < 3; k++) {
        if ((r = pg_opt_int(desc, gk[k], gd[k], 1, 1024, &v, err))) return r;
        grid[k] = (uint32_t)v;
    }
    if ((r = pg_opt_int(desc, "max_lights", 256, 1, 65536, &v, err))) return r;
    *max_lights = (uint32_t)v;
    return PG_OK;
}

static pg_result ca_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    uint32_t grid[3], max_lights;
    pg_result r = read_opts(in->desc, grid, &max_lights, err);
    if (r) return r;
    pg_decl_read(out, "lights", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_COMPUTE, 0);
    pg_decl_write(out, "cluster_counts", PG_RES_BUFFER, PG_ACCESS_STORAGE_WRITE, PG_STAGE_COMPUTE, 0);
    pg_decl_write(out, "cluster_lights", PG_RES_BUFFER, PG_ACCESS_STORAGE_WRITE, PG_STAGE_COMPUTE, 0);
    char def[PG_NAME_MAX];
    snprintf(def, sizeof def, "GRID_X=%u", grid[0]);
    pg_decl_define(out, def);
    snprintf(def, sizeof def, "GRID_Y=%u", grid[1]);
    pg_decl_define(out, def);
    snprintf(def, sizeof def, "GRID_Z=%u", grid[2]);
    pg_decl_define(out, def);
    snprintf(def, sizeof def, "MAX_LIGHTS=%u", max_lights);
    pg_decl_define(out, def);
    return PG_OK;
}

static pg_result ca_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    cluster_assign *p = self;
    pg_gpu *gpu = ctx->gpu;
    pg_result r;
    if ((r = read_opts(ctx->desc, p->grid, &p->max_lights, err))) return r;
    VkPhysicalDeviceSubgroupProperties sp = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceProperties2 pp = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &sp};
    vkGetPhysicalDeviceProperties2(gpu->phys, &pp);
    if (!(sp.supportedOperations & VK_SUBGROUP_FEATURE_BALLOT_BIT) || !(sp.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT))
        return pg_fail(err, PG_ERR_NO_DEVICE, "%s: cluster_assign needs subgroup ballot in compute shaders",
                       gpu->props.deviceName);
    uint64_t cells = (uint64_t)p->grid[0] * p->grid[1] * p->grid[2];
    if (ctx->slots[1]->size < cells * 4 || ctx->slots[2]->size < cells * p->max_lights * 4)
        return pg_fail(err, PG_ERR_INVALID_ARG,
                       "%s: %s: cluster buffers (%llu, %llu bytes) too small for grid %ux%ux%u x %u lights",
                       ctx->desc->file, ctx->desc->json_path, (unsigned long long)ctx->slots[1]->size,
                       (unsigned long long)ctx->slots[2]->size, p->grid[0], p->grid[1], p->grid[2], p->max_lights);
    char name[PG_NAME_MAX + 16];
    snprintf(name, sizeof name, "%s.stats", ctx->pass->name);
    if ((r = pg_buffer_create(gpu, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true,
                              name, &p->stats, err)))
        return r;
    pg_phys_resource stats_res = {.kind = PG_RES_BUFFER, .buffer = p->stats.buffer, .size = 16};
    pg_set_binding b[4] = {
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, ctx->slots[0], VK_NULL_HANDLE, 0},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, ctx->slots[1], VK_NULL_HANDLE, 0},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, ctx->slots[2], VK_NULL_HANDLE, 0},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &stats_res, VK_NULL_HANDLE, 0},
    };
    if ((r = pg_pass_set_create(gpu, 4, b, ctx->pass->name, &p->set, err))) return r;
    VkDescriptorSetLayout sets[2] = {ctx->frame_layout, p->set.layout};
    if ((r = pg_pipeline_layout_create(gpu, 2, sets, 0, &p->layout, err))) return r;
    const char *defs[PG_MAX_DEFINES];
    for (uint32_t i = 0; i < ctx->pass->decl.n_defines; i++) defs[i] = ctx->pass->decl.defines[i];
    VkShaderModule cs;
    if ((r = pg_shader_module(gpu, "cluster_assign.comp", VK_SHADER_STAGE_COMPUTE_BIT, defs,
                              ctx->pass->decl.n_defines, &cs, err)))
        return r;
    r = pg_compute_pipeline_create(gpu, p->layout, cs, ctx->pass->name, &p->pipeline, err);
    vkDestroyShaderModule(gpu->device, cs, NULL);
    return r;
}

static void ca_record(void *self, const pg_pass_record_ctx *ctx)
{
    cluster_assign *p = self;
    VkCommandBuffer cmd = ctx->cmd;
    /* the stats buffer is the pass's own: it places its own barriers */
    vkCmdFillBuffer(cmd, p->stats.buffer, 0, 16, 0);
    VkBufferMemoryBarrier2 b = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2,
        .srcStageMask = VK_PIPELINE_STAGE_2_CLEAR_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
        .srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT,
        .dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
        .dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .buffer = p->stats.buffer,
        .size = VK_WHOLE_SIZE,
    };
    pg_cmd_barriers(cmd, 0, NULL, 1, &b);
    VkDescriptorSet sets[2] = {ctx->frame_set, p->set.set};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->layout, 0, 2, sets, 0, NULL);
    uint32_t cells = p->grid[0] * p->grid[1] * p->grid[2];
    uint32_t gx = cells < 65535 ? cells : 65535;
    vkCmdDispatch(cmd, gx, (cells + gx - 1) / gx, 1);
    b.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    b.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    b.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
    b.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
    pg_cmd_barriers(cmd, 0, NULL, 1, &b);
    p->ran = true;
}

static void ca_report(void *self, pg_pass_report *out)
{
    cluster_assign *p = self;
    if (!p->ran) return;
    const uint32_t *s = p->stats.mapped;
    pg_report_add(out, "overflow_clusters", s[0]);
    pg_report_add(out, "overflow_dropped", s[1]);
    pg_report_add(out, "max_count", s[2]);
    pg_report_add(out, "total_refs", s[3]);
}

static void ca_destroy(void *self, pg_gpu *gpu)
{
    cluster_assign *p = self;
    if (p->pipeline) vkDestroyPipeline(gpu->device, p->pipeline, NULL);
    if (p->layout) vkDestroyPipelineLayout(gpu->device, p->layout, NULL);
    pg_pass_set_destroy(gpu, &p->set);
    pg_buffer_destroy(gpu, &p->stats);
}

const pg_pass_type pg_pass_cluster_assign = {
    .name = "cluster_assign",
    .summary = "compute: per-cluster light lists (conservative sphere vs cluster AABB, overflow counted)",
    .read_slots = "lights",
    .write_slots = "cluster_counts, cluster_lights",
    .instance_size = sizeof(cluster_assign),
    .declare = ca_declare,
    .create = ca_create,
    .record = ca_record,
    .destroy = ca_destroy,
    .report = ca_report,
};
