/* cluster_assign.c - compute pass: per-cluster light lists over a grid of screen tiles x
 * exponential depth slices, exact by default at any light count.
 *
 * Four dispatches in one pass (method "binned", the default):
 *   1. bin   (shaders/cluster_bin.comp)   each light sets its bit in the masks of the tiles and
 *            depth slices its sphere can reach (conservative; O(lights x (gx + gy + gz)));
 *   2. count (shaders/cluster_lists.comp) per cluster and segment of 16,384 lights, the candidates (tile mask AND slice mask,
 *            32 lights a word) get the exact sphere-vs-box test; raw count per cluster;
 *   3. scan  (shaders/cluster_scan.comp)  offsets, the optional per-cluster cap, and the
 *            deterministic subset when the list buffer is too small;
 *   4. fill  (cluster_lists.comp, PG_FILL) the same walk again, writing the hits in ascending
 *            light order at each cluster's offset.
 * Step 1 also stores each light's view-space sphere, which steps 2 and 4 test; with spot lights
 * also its view-space cone, so a cluster the cone misses does not list the light. Method
 * "brute_force" only stores the spheres in step 1 and makes every light a candidate of every
 * cluster (O(clusters x lights)): the oracle tests/test_cluster_assign.c checks the binned lists
 * against.
 *
 * The list buffer (slot cluster_lights) is a "grow" buffer: when the lists need more room than
 * it has, the pass keeps a deterministic subset this frame, counts the rest, and asks the runtime
 * (pg_report_grow) for the size it needs; the session renders the frame again with the larger
 * buffer. Growth stops at the memory budget (option budget_mb; 0, the default: PG_AUTO_BUDGET_SHARE
 * of the device's largest device-local heap; either clamped to pg_list_max_bytes: up to 8 windows
 * of one buffer when the lists outgrow one storage-buffer binding, cluster_windows.h; the lists
 * hold at most the budget also in a buffer grown before it was lowered): past it the clusters keep their first k lights for the largest k that fits and the
 * dropped references are counted (counters overflow_clusters, overflow_dropped) and the frame is
 * inexact (pg_frame_stats.refs_dropped; bench status "inexact").
 *
 * Slots: reads [lights]; writes [cluster_counts (16 bytes per cluster: offset, stored, raw, 0),
 * cluster_lights (grow buffer of uint light indices)].
 * The grid (x tiles, y tiles, z slices) is the count of the resource bound to cluster_counts (three
 * constants; cluster_lights' count starts with the same three: renderer/common/cluster_grid.h).
 * Options: max_lights (per-cluster cap, 0 = none: the
 * default), budget_mb (list memory budget in MiB, 0 = auto: the default), method ("binned" | "brute_force"),
 * subgroups (bool, default true: one full subgroup per workgroup where the device allows it;
 * false: 64-wide workgroups with shared-memory scans).
 * Counters: overflow_clusters, overflow_dropped, dropped_cap, total_refs, needed_refs,
 * max_count, list_bytes, mask_bytes (masks + spheres), bin_ns, count_ns, scan_ns, fill_ns (GPU
 * time of each step). */
#include <stdio.h>
#include <string.h>

#include "cluster_grid.h"
#include "cluster_windows.h"
#include "cluster_math.h"
#include "graph_execute.h"
#include "pass_api.h"
#include "shader.h"
#include "shading_common.h"
#include "pass_set.h"
#include "scene_vars.h"
#include "vk_pipeline.h"

/* words (32 lights each) one count/fill workgroup walks: 16,384 lights, so 1,000,000 lights give
 * 62 workgroups per cluster (enough in flight on a large GPU) and 4,000 lights one */
#define SEG_WORDS 512u
/* the automatic list budget: half the device's largest device-local heap (lists are the one
 * buffer that scales with lights x clusters; the other half is left to images, the scene and
 * other processes) */
#define PG_AUTO_BUDGET_SHARE 0.5
enum { PIPE_BIN, PIPE_COUNT, PIPE_SEGSCAN, PIPE_SCAN, PIPE_FILL, PIPE_N };

typedef struct ca_opts {
    uint32_t grid[3];
    uint32_t max_lights; /* 0: no cap */
    uint64_t budget_bytes; /* 0: auto (PG_AUTO_BUDGET_SHARE of the device-local heap) */
    int method;          /* 0 binned, 1 brute_force */
    bool subgroups;
} ca_opts;

typedef struct ca_params { /* filled once by declare, read by create */
    ca_opts o;
    bool spots;          /* the scene has spot lights: the lights buffer holds a spot record per light */
    pg_slot lights, records, lists;
} ca_params;

typedef struct ca_stats { /* mirrors Stats in cluster_scan.comp */
    uint32_t needed, stored, dropped, overflow_clusters, max_count, dropped_cap, fair_cap, capacity;
} ca_stats;

typedef struct cluster_assign {
    ca_opts o;
    uint32_t clusters, light_count, words;
    uint32_t record_vec4;       /* vec4s per light in spheres: 1, or 3 with spot lights (bound sphere, cone, ball) */
    uint64_t budget;            /* bytes the lists may grow to (budget clamped to the device) */
    bool budget_clamped;
    pg_buffer stats;            /* host visible */
    pg_buffer tile_masks, slice_masks;
    pg_buffer spheres;          /* view-space sphere per light (bin step), read by count/fill */
    pg_buffer segments;         /* hits per (cluster, segment of SEG_WORDS words) */
    uint32_t n_segments;
    pg_pass_set set;
    VkPipelineLayout layout;
    VkPipeline pipe[PIPE_N];
    uint64_t list_bytes;        /* capacity of the list buffer this instance was created with */
    uint32_t lists_slot;        /* plan slot of cluster_lights (pg_report_grow) */
    VkQueryPool queries;        /* timestamps around the four steps (when the queue has them) */
    pg_gpu *gpu;                /* borrowed, for report() */
    bool ran;
} cluster_assign;

static const char *const k_known[] = {"max_lights", "budget_mb", "method", "subgroups", NULL};
static const char *const k_methods[] = {"binned", "brute_force", NULL};

static pg_result read_opts(const pg_pass_desc *desc, ca_opts *o, pg_error *err)
{
    pg_result r;
    int64_t v;
    memset(o, 0, sizeof *o);
    if ((r = pg_opt_check_known(desc, k_known, err))) return r;
    if ((r = pg_opt_int(desc, "max_lights", 0, 0, 16777216, &v, err))) return r;
    o->max_lights = (uint32_t)v;
    double mb;
    if ((r = pg_opt_float(desc, "budget_mb", 0.0, 0.0, 1048576.0, &mb, err))) return r;
    o->budget_bytes = (uint64_t)(mb * 1048576.0) & ~(uint64_t)255;
    if (mb > 0 && o->budget_bytes == 0) o->budget_bytes = 256; /* a budget, however small: 0 means auto */
    if ((r = pg_opt_enum(desc, "method", k_methods, 0, &o->method, err))) return r;
    if ((r = pg_opt_bool(desc, "subgroups", true, &o->subgroups, err))) return r;
    return PG_OK;
}

static pg_result ca_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    ca_params *p = pg_decl_params(out, sizeof *p);
    pg_result r = read_opts(in->desc, &p->o, err);
    if (r) return r;
    p->lights = pg_decl_read(out, "lights", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_COMPUTE, 0);
    p->records = pg_decl_write(out, "cluster_counts", PG_RES_BUFFER, PG_ACCESS_STORAGE_WRITE, PG_STAGE_COMPUTE, 0);
    p->lists = pg_decl_write(out, "cluster_lights", PG_RES_BUFFER, PG_ACCESS_STORAGE_WRITE, PG_STAGE_COMPUTE, 0);
    pg_decl_mark_partial(out, p->lists); /* filled up to each cluster's count; readers read only that */
    if ((r = pg_cluster_grid_declare(in, p->records, p->lists, p->o.grid, err))) return r;
    const ca_opts o = p->o;
    p->spots = pg_scene_features_of(in).has_spot_lights;
    if (p->spots) pg_decl_define(out, "PG_SPOT_LIGHTS"); /* lists leave out clusters a cone misses */
    pg_decl_define_int(out, "GRID_X", o.grid[0]);
    pg_decl_define_int(out, "GRID_Y", o.grid[1]);
    pg_decl_define_int(out, "GRID_Z", o.grid[2]);
    if (o.method == 1) {
        pg_decl_define(out, "PG_BRUTE_FORCE");
        pg_decl_explain(out, "method brute_force: every light tested against every cluster (the oracle)");
    }
    if (o.max_lights)
        pg_decl_explain(out, "max_lights %u: at most %u lights per cluster (an approximation: the rest is "
                        "counted as overflow)", o.max_lights, o.max_lights);
    return PG_OK;
}

static pg_result shader(const cluster_assign *p, pg_gpu *gpu, const pg_plan_pass *pass, const char *file,
                        const char *extra1, const char *extra2, VkShaderModule *out, pg_error *err)
{
    const char *defs[PG_MAX_DEFINES + 4];
    char wbuf[2][40];
    uint32_t n = pg_decl_define_list(&pass->decl, defs, PG_MAX_DEFINES);
    if (extra1) defs[n++] = extra1;
    if (extra2) defs[n++] = extra2;
    n += pg_list_window_defines(gpu, p->list_bytes, wbuf, defs + n); /* the fill step writes the lists */
    return pg_shader_module(gpu, file, VK_SHADER_STAGE_COMPUTE_BIT, defs, n, out, err);
}

static pg_result make_pipe(cluster_assign *p, pg_gpu *gpu, const pg_plan_pass *pass, int which, pg_error *err)
{
    static const char *const files[PIPE_N] = {"cluster_bin.comp", "cluster_lists.comp", "cluster_scan.comp",
                                              "cluster_scan.comp", "cluster_lists.comp"};
    static const char *const suffix[PIPE_N] = {"bin", "count", "segscan", "scan", "fill"};
    bool lists = which == PIPE_COUNT || which == PIPE_FILL;
    bool one_sg = lists && p->o.subgroups && gpu->exact_subgroups;
    VkShaderModule cs;
    pg_result r = shader(p, gpu, pass, files[which],
                         which == PIPE_FILL ? "PG_FILL" : which == PIPE_SEGSCAN ? "PG_SEGMENT_SCAN" : NULL,
                         one_sg ? "PG_ONE_SUBGROUP" : NULL, &cs, err);
    if (r) return r;
    uint32_t spec[1] = {gpu->subgroup_size};
    pg_compute_pipeline_desc d = {
        .layout = p->layout,
        .cs = cs,
        .spec_data = one_sg ? spec : NULL,
        .n_spec = one_sg ? 1 : 0,
        .subgroup_size = one_sg ? gpu->subgroup_size : 0,
    };
    char name[PG_NAME_MAX + 16];
    snprintf(name, sizeof name, "%s.%s", pass->name, suffix[which]);
    r = pg_compute_pipeline_create_ex(gpu, &d, name, &p->pipe[which], err);
    vkDestroyShaderModule(gpu->device, cs, NULL);
    return r;
}

static pg_result ca_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    cluster_assign *p = self;
    pg_gpu *gpu = ctx->gpu;
    const ca_params *pa = PG_PARAMS(ctx, ca_params);
    const pg_phys_resource *lights = pg_ctx_res(ctx, pa->lights), *records = pg_ctx_res(ctx, pa->records),
                           *lists = pg_ctx_res(ctx, pa->lists);
    pg_result r;
    p->o = pa->o;
    p->lists_slot = pg_plan_slot_of(ctx->pass, pa->lists);
    p->gpu = gpu;
    p->clusters = p->o.grid[0] * p->o.grid[1] * p->o.grid[2];
    /* 32 bytes a light, then as many spot records with spot lights (scene_vars.c) */
    p->light_count = (uint32_t)(lights->size / 32 / (pa->spots ? 2 : 1));
    p->record_vec4 = pa->spots ? 3 : 1;
    p->words = (p->light_count + 31) / 32;
    /* the lists' budget, within what the device lets them take (cluster_windows.h: windows of one
     * buffer when they outgrow one storage-buffer binding) */
    uint64_t dev_max = pg_list_max_bytes(gpu);
    p->budget = p->o.budget_bytes;
    if (!p->budget) p->budget = (uint64_t)(pg_gpu_device_local_bytes(gpu) * PG_AUTO_BUDGET_SHARE) & ~(uint64_t)255;
    if (!p->budget) p->budget = 1024ull << 20; /* a device without a device-local heap */
    if (dev_max && p->budget > dev_max) {
        p->budget = dev_max;
        p->budget_clamped = true;
    }
    p->list_bytes = lists->size;
    char name[PG_NAME_MAX + 16];
    snprintf(name, sizeof name, "%s.stats", ctx->pass->name);
    if ((r = pg_buffer_create(gpu, sizeof(ca_stats), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                              true, name, &p->stats, err)))
        return r;
    const bool binned = p->o.method == 0;
    uint64_t tile_bytes = (uint64_t)p->o.grid[0] * p->o.grid[1] * p->words * 4;
    uint64_t slice_bytes = (uint64_t)p->o.grid[2] * p->words * 4;
    if (binned) {
        if (tile_bytes > gpu->max_storage_buffer_range)
            return pg_fail(err, PG_ERR_LIMIT,
                           "%s: %s: %u lights need %llu bytes of tile masks, more than %s binds (%llu): use fewer "
                           "lights or a coarser grid",
                           ctx->desc->file, ctx->desc->json_path, p->light_count, (unsigned long long)tile_bytes,
                           gpu->props.deviceName, (unsigned long long)gpu->max_storage_buffer_range);
        snprintf(name, sizeof name, "%s.tile_masks", ctx->pass->name);
        if ((r = pg_buffer_create(gpu, tile_bytes ? tile_bytes : 16,
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false, name,
                                  &p->tile_masks, err)))
            return r;
        snprintf(name, sizeof name, "%s.slice_masks", ctx->pass->name);
        if ((r = pg_buffer_create(gpu, slice_bytes ? slice_bytes : 16,
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false, name,
                                  &p->slice_masks, err)))
            return r;
    }
    snprintf(name, sizeof name, "%s.spheres", ctx->pass->name);
    if ((r = pg_buffer_create(gpu, (uint64_t)(p->light_count ? p->light_count : 1) * 16 * p->record_vec4,
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false, name, &p->spheres, err)))
        return r;
    p->n_segments = p->words ? (p->words + SEG_WORDS - 1) / SEG_WORDS : 1;
    if ((uint64_t)p->clusters * p->n_segments > 65535ull * 65535ull ||
        (uint64_t)p->clusters * p->n_segments * 4 > gpu->max_storage_buffer_range)
        return pg_fail(err, PG_ERR_LIMIT, "%s: %s: %u clusters x %u lights is too large for %s: use fewer lights or a "
                       "coarser grid", ctx->desc->file, ctx->desc->json_path, p->clusters, p->light_count,
                       gpu->props.deviceName);
    snprintf(name, sizeof name, "%s.segments", ctx->pass->name);
    if ((r = pg_buffer_create(gpu, (uint64_t)p->clusters * p->n_segments * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                              false, name, &p->segments, err)))
        return r;
    pg_phys_resource stats_res = {.kind = PG_RES_BUFFER, .buffer = p->stats.buffer, .size = p->stats.size};
    pg_phys_resource tm = {.kind = PG_RES_BUFFER, .buffer = p->tile_masks.buffer, .size = p->tile_masks.size};
    pg_phys_resource sm = {.kind = PG_RES_BUFFER, .buffer = p->slice_masks.buffer, .size = p->slice_masks.size};
    pg_phys_resource sp = {.kind = PG_RES_BUFFER, .buffer = p->spheres.buffer, .size = p->spheres.size};
    pg_phys_resource sg = {.kind = PG_RES_BUFFER, .buffer = p->segments.buffer, .size = p->segments.size};
    /* one set for every step: 0 lights, 1 records, 2 lists, 3 tile masks, 4 slice masks, 5 stats,
     * 6 spheres, 7 segments (the brute-force method binds the stats buffer in the mask slots) */
    pg_set_binding b[8] = {
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, lights, VK_NULL_HANDLE, 0},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, records, VK_NULL_HANDLE, 0},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, lists, VK_NULL_HANDLE, 0},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, binned ? &tm : &stats_res, VK_NULL_HANDLE, 0},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, binned ? &sm : &stats_res, VK_NULL_HANDLE, 0},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &stats_res, VK_NULL_HANDLE, 0},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &sp, VK_NULL_HANDLE, 0},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &sg, VK_NULL_HANDLE, 0},
    };
    const uint32_t windows[8] = {0, 0, pg_list_windows(gpu, lists->size)}; /* the lists: cluster_windows.h */
    if ((r = pg_pass_set_create_windowed(gpu, 8, b, NULL, windows, pg_list_window_bytes(gpu), ctx->pass->name, &p->set,
                                         err)))
        return r;
    VkDescriptorSetLayout sets[2] = {ctx->frame_layout, p->set.layout};
    if ((r = pg_pipeline_layout_create(gpu, 2, sets, 16, &p->layout, err))) return r;
    for (int i = 0; i < PIPE_N; i++)
        if ((r = make_pipe(p, gpu, ctx->pass, i, err))) return r;
    if (gpu->timestamp_valid_bits) {
        VkQueryPoolCreateInfo qci = {.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
                                     .queryType = VK_QUERY_TYPE_TIMESTAMP, .queryCount = 5};
        PG_VK_TRY(err, vkCreateQueryPool(gpu->device, &qci, NULL, &p->queries));
    }
    return PG_OK;
}

/* compute -> compute on every buffer the steps share */
static void step_barrier(VkCommandBuffer cmd)
{
    pg_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                          VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

static void dispatch_groups(VkCommandBuffer cmd, uint32_t groups)
{
    if (!groups) return;
    uint32_t gx = groups < 65535 ? groups : 65535;
    vkCmdDispatch(cmd, gx, (groups + gx - 1) / gx, 1);
}

static void ca_record(void *self, const pg_pass_record_ctx *ctx)
{
    cluster_assign *p = self;
    VkCommandBuffer cmd = ctx->cmd;
    const bool binned = p->o.method == 0;
    /* the stats and mask buffers are the pass's own: it places their barriers */
    vkCmdFillBuffer(cmd, p->stats.buffer, 0, VK_WHOLE_SIZE, 0);
    if (binned) {
        vkCmdFillBuffer(cmd, p->tile_masks.buffer, 0, VK_WHOLE_SIZE, 0);
        vkCmdFillBuffer(cmd, p->slice_masks.buffer, 0, VK_WHOLE_SIZE, 0);
    }
    VkBufferMemoryBarrier2 bb[3];
    uint32_t nb = 0;
    const uint64_t xfer = VK_PIPELINE_STAGE_2_CLEAR_BIT | VK_PIPELINE_STAGE_2_COPY_BIT;
    const uint64_t rw = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    bb[nb++] = pg_buffer_barrier(p->stats.buffer, xfer, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                   rw);
    if (binned) {
        bb[nb++] = pg_buffer_barrier(p->tile_masks.buffer, xfer, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, rw);
        bb[nb++] = pg_buffer_barrier(p->slice_masks.buffer, xfer, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, rw);
    }
    pg_cmd_barriers(cmd, 0, NULL, nb, bb);

    if (p->queries) {
        vkCmdResetQueryPool(cmd, p->queries, 0, 5);
        vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, p->queries, 0);
    }
#define STAMP(i) \
    if (p->queries) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, p->queries, i)
    VkDescriptorSet sets[2] = {ctx->frame_set, p->set.set};
    /* the lists hold at most the budget, also in a buffer grown larger before the budget was lowered */
    uint64_t cap_bytes = p->list_bytes < p->budget ? p->list_bytes : p->budget;
    uint32_t capacity = (uint32_t)(cap_bytes / 4 > 0xffffffffu ? 0xffffffffu : cap_bytes / 4);
    uint32_t push[4] = {p->words, p->n_segments, SEG_WORDS, 0};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->layout, 0, 2, sets, 0, NULL);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipe[PIPE_BIN]);
    vkCmdPushConstants(cmd, p->layout, PG_PUSH_STAGES, 0, 16, push);
    dispatch_groups(cmd, (p->light_count + 63) / 64);
    step_barrier(cmd);
    STAMP(1);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipe[PIPE_COUNT]);
    vkCmdPushConstants(cmd, p->layout, PG_PUSH_STAGES, 0, 16, push);
    dispatch_groups(cmd, p->clusters * p->n_segments);
    step_barrier(cmd);
    STAMP(2);
    uint32_t scan_push[4] = {p->clusters, capacity, p->o.max_lights, p->n_segments};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipe[PIPE_SEGSCAN]);
    vkCmdPushConstants(cmd, p->layout, PG_PUSH_STAGES, 0, 16, scan_push);
    dispatch_groups(cmd, p->clusters);
    step_barrier(cmd);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipe[PIPE_SCAN]);
    vkCmdPushConstants(cmd, p->layout, PG_PUSH_STAGES, 0, 16, scan_push);
    vkCmdDispatch(cmd, 1, 1, 1);
    step_barrier(cmd);
    STAMP(3);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipe[PIPE_FILL]);
    vkCmdPushConstants(cmd, p->layout, PG_PUSH_STAGES, 0, 16, push);
    dispatch_groups(cmd, p->clusters * p->n_segments);
    STAMP(4);
#undef STAMP
    bb[0] = pg_buffer_barrier(p->stats.buffer, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                   VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    pg_cmd_barriers(cmd, 0, NULL, 1, bb);
    p->ran = true;
}

/* digits after the point for a size in MiB in the notes: 1 from 0.1 MiB, 4 below (a budget of
 * 0.05 MiB read "0.0 MiB") */
static int mib_digits(double bytes)
{
    return bytes >= 0.1 * 1048576.0 ? 1 : 4;
}

static void ca_report(void *self, pg_pass_report *out)
{
    cluster_assign *p = self;
    if (!p->ran) return;
    uint64_t ts[5];
    if (p->queries && vkGetQueryPoolResults(p->gpu->device, p->queries, 0, 5, sizeof ts, ts, sizeof ts[0],
                                            VK_QUERY_RESULT_64_BIT) == VK_SUCCESS) {
        /* nanoseconds per step (each includes the barrier before the next) */
        static const char *const names[4] = {"bin_ns", "count_ns", "scan_ns", "fill_ns"};
        uint64_t mask = p->gpu->timestamp_valid_bits >= 64 ? ~0ull : ((1ull << p->gpu->timestamp_valid_bits) - 1);
        for (int i = 0; i < 4; i++)
            pg_report_add(out, names[i], (uint64_t)(((ts[i + 1] - ts[i]) & mask) * (double)p->gpu->timestamp_period_ns));
    }
    const ca_stats *s = p->stats.mapped;
    pg_report_add(out, "overflow_clusters", s->overflow_clusters);
    pg_report_add(out, "overflow_dropped", s->dropped);
    pg_report_add(out, "dropped_cap", s->dropped_cap);
    pg_report_add(out, "total_refs", s->stored);
    pg_report_add(out, "needed_refs", s->needed);
    pg_report_add(out, "max_count", s->max_count);
    pg_report_add(out, "list_bytes", p->list_bytes);
    pg_report_add(out, "mask_bytes", p->tile_masks.size + p->slice_masks.size + p->spheres.size);
    uint64_t needed = (uint64_t)s->needed * 4;
    if (needed > p->list_bytes) pg_report_grow(out, p->lists_slot, needed, p->budget);
    if (needed > p->budget) {
        if (p->budget_clamped)
            pg_report_note(out, "light lists need %.*f MiB, over the %.*f MiB they may take on this device (%u "
                           "storage-buffer windows of %.4g MiB): %u refs dropped (use fewer lights or a coarser grid)",
                           mib_digits(needed), needed / 1048576.0, mib_digits(p->budget), p->budget / 1048576.0,
                           pg_list_windows(p->gpu, p->budget),
                           pg_list_window_bytes(p->gpu) / 1048576.0, s->dropped - s->dropped_cap);
        else
            pg_report_note(out, "light lists need %.*f MiB, over the %.*f MiB budget: %u refs dropped (raise "
                           "list_budget_mb; 0 = half the device-local heap)", mib_digits(needed), needed / 1048576.0,
                           mib_digits(p->budget), p->budget / 1048576.0, s->dropped - s->dropped_cap);
    }
}

static void ca_destroy(void *self, pg_gpu *gpu)
{
    cluster_assign *p = self;
    for (int i = 0; i < PIPE_N; i++)
        if (p->pipe[i]) vkDestroyPipeline(gpu->device, p->pipe[i], NULL);
    if (p->layout) vkDestroyPipelineLayout(gpu->device, p->layout, NULL);
    if (p->queries) vkDestroyQueryPool(gpu->device, p->queries, NULL);
    pg_pass_set_destroy(gpu, &p->set);
    pg_buffer_destroy(gpu, &p->stats);
    pg_buffer_destroy(gpu, &p->tile_masks);
    pg_buffer_destroy(gpu, &p->slice_masks);
    pg_buffer_destroy(gpu, &p->spheres);
    pg_buffer_destroy(gpu, &p->segments);
}

const pg_pass_type pg_pass_cluster_assign = {
    .name = "cluster_assign",
    .summary = "compute: per-cluster light lists, exact by default (binned lights, exact test, growing lists)",
    .instance_size = sizeof(cluster_assign),
    .params_size = sizeof(ca_params),
    .declare = ca_declare,
    .create = ca_create,
    .record = ca_record,
    .destroy = ca_destroy,
    .report = ca_report,
};
