/* graph_execute.c - physical resources, pass instances, recording and submission of a plan.
 * This file: create/destroy, settings and the lookup API (owns pg_runtime.cfg);
 * graph_execute_internal.h lists the others. */
#include "graph_execute_internal.h"

#include <stdlib.h>
#include <string.h>

pg_result pg_runtime_create(pg_gpu *gpu, uint32_t frame_block_size, pg_runtime **out, pg_error *err)
{
    *out = NULL;
    if (!frame_block_size || frame_block_size > 65536)
        return pg_fail(err, PG_ERR_INVALID_ARG, "pg_runtime_create: frame block of %u bytes (1..65536)",
                       frame_block_size);
    pg_runtime *rt = calloc(1, sizeof *rt);
    if (!rt) return pg_fail(err, PG_ERR_OOM, "out of memory");
    rt->cfg.gpu = gpu;
    rt->cfg.frame_size = frame_block_size;
    pg_result r = pg_rt_frames_create(rt, err);
    if (r) {
        pg_runtime_destroy(rt);
        return r;
    }
    *out = rt;
    return PG_OK;
}

void pg_runtime_destroy(pg_runtime *rt)
{
    if (!rt) return;
    pg_rt_destroy_built(rt);
    pg_rt_frames_destroy(rt);
    free(rt);
}

void pg_runtime_set_settings(pg_runtime *rt, const pg_param_override *settings, uint32_t n_settings)
{
    rt->cfg.settings = n_settings ? settings : NULL;
    rt->cfg.n_settings = settings ? n_settings : 0;
}

void pg_runtime_set_frame_prologue(pg_runtime *rt, pg_frame_prologue_fn fn, void *user)
{
    rt->cfg.prologue = fn;
    rt->cfg.prologue_user = fn ? user : NULL;
}

uint64_t pg_frame_counter_sum(const pg_frame_stats *st, const char *name)
{
    uint64_t sum = 0;
    for (uint32_t i = 0; st && name && i < st->n_counters; i++)
        if (!strcmp(st->counters[i].name, name)) sum += st->counters[i].value;
    return sum;
}

bool pg_frame_counter_has(const pg_frame_stats *st, const char *name)
{
    for (uint32_t i = 0; st && name && i < st->n_counters; i++)
        if (!strcmp(st->counters[i].name, name)) return true;
    return false;
}

const char *pg_ctx_setting(const pg_pass_create_ctx *ctx, const char *key)
{
    const char *found = NULL;
    for (uint32_t i = 0; ctx && key && i < ctx->n_settings; i++)
        if (ctx->settings[i].key && !strcmp(ctx->settings[i].key, key)) found = ctx->settings[i].value;
    return found;
}

const void *pg_runtime_output(const pg_runtime *rt, int which, uint32_t *w, uint32_t *h, pg_format *fmt)
{
    if (which < 0 || which > 1 || !rt->cur.plan || !rt->frames.readback_valid[which]) return NULL;
    int idx = which ? rt->cur.plan->hdr_output : rt->cur.plan->output;
    if (idx < 0) return NULL;
    const pg_plan_resource *pr = &rt->cur.plan->resources[idx];
    if (w) *w = pr->width;
    if (h) *h = pr->height;
    if (fmt) *fmt = pr->format;
    return rt->frames.slot[rt->frames.cur].readback[which].mapped;
}

const char *pg_rebuild_kind_name(pg_rebuild_kind k)
{
    static const char *const names[] = {"none", "values", "pipelines", "resources", "memory"};
    return (unsigned)k < 5 ? names[k] : "?";
}

pg_runtime_stats pg_runtime_get_stats(const pg_runtime *rt)
{
    pg_runtime_stats st = rt->stats;
    st.grow_bytes = 0;
    for (uint32_t i = 0; rt->cur.plan && i < rt->cur.plan->n_resources; i++)
        if (rt->cur.plan->resources[i].growable && !rt->cur.plan->resources[i].culled) st.grow_bytes += rt->mem.res[i].size;
    return st;
}

const pg_phys_resource *pg_runtime_output_image(const pg_runtime *rt, int which)
{
    if (!rt->cur.plan || which < 0 || which > 1) return NULL;
    int idx = which ? rt->cur.plan->hdr_output : rt->cur.plan->output;
    return idx >= 0 ? &rt->mem.res[idx] : NULL;
}

pg_result pg_runtime_resource(const pg_runtime *rt, pg_res_handle h, const pg_phys_resource **out, pg_error *err)
{
    if (out) *out = NULL;
    if (!rt || !rt->mem.built) return pg_fail(err, PG_ERR_INVALID_ARG, "pg_runtime_resource: no plan set");
    pg_result r = pg_plan_resource_get(rt->cur.plan, h, NULL, err);
    if (!r && out) *out = &rt->mem.res[h.index];
    return r;
}

/* by name, through a handle of the current plan */
static int buffer_index(const pg_runtime *rt, const char *name)
{
    pg_res_handle h;
    const pg_plan_resource *pr;
    if (!rt->cur.plan || !name || pg_plan_find_resource(rt->cur.plan, name, &h, NULL) ||
        pg_plan_resource_get(rt->cur.plan, h, &pr, NULL))
        return -1;
    return pr->kind == PG_RES_BUFFER && !pr->culled && rt->mem.res[h.index].buffer ? (int)h.index : -1;
}

uint64_t pg_runtime_buffer_size(const pg_runtime *rt, const char *name)
{
    int i = buffer_index(rt, name);
    return i < 0 ? 0 : rt->mem.res[i].size;
}

pg_result pg_runtime_read_buffer(pg_runtime *rt, const char *name, uint64_t offset, uint64_t size, void *dst,
                                 pg_error *err)
{
    int i = buffer_index(rt, name);
    if (i < 0) return pg_fail(err, PG_ERR_INVALID_ARG, "read_buffer: no buffer resource '%s' in the plan", name ? name : "");
    const pg_phys_resource *r = &rt->mem.res[i];
    if (offset > r->size || size > r->size - offset)
        return pg_fail(err, PG_ERR_INVALID_ARG, "read_buffer: '%s': bytes %llu..%llu past its %llu bytes", name,
                       (unsigned long long)offset, (unsigned long long)(offset + size), (unsigned long long)r->size);
    if (!size) return PG_OK;
    pg_buffer staging;
    pg_result res = pg_buffer_create(rt->cfg.gpu, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, "readback.buffer",
                                     &staging, err);
    if (res) return res;
    VkCommandBuffer cmd;
    if ((res = pg_gpu_begin_once(rt->cfg.gpu, &cmd, err))) {
        pg_buffer_destroy(rt->cfg.gpu, &staging);
        return res;
    }
    pg_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferCopy c = {offset, 0, size};
    vkCmdCopyBuffer(cmd, r->buffer, staging.buffer, 1, &c);
    VkBufferMemoryBarrier2 hb = pg_buffer_barrier(staging.buffer, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                                  VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    pg_cmd_barriers(cmd, 0, NULL, 1, &hb);
    res = pg_gpu_end_once(rt->cfg.gpu, cmd, err);
    if (!res) memcpy(dst, staging.mapped, size);
    pg_buffer_destroy(rt->cfg.gpu, &staging);
    return res;
}

pg_queue_caps pg_runtime_queue_caps(const pg_runtime *rt, bool async_off)
{
    pg_queue_caps c;
    memset(&c, 0, sizeof c);
    const pg_gpu *g = rt->cfg.gpu;
    c.async_off = async_off;
    if (g->compute_queue && rt->frames.timeline[0]) {
        c.n_queues = 2;
        c.separate_family = g->compute_family != g->queue_family;
    } else {
        c.n_queues = 1;
        snprintf(c.why_single, sizeof c.why_single, "%s",
                 g->single_queue_why[0] ? g->single_queue_why : "the device lacks timelineSemaphore");
    }
    return c;
}

const pg_phys_resource *pg_runtime_resource_at(const pg_runtime *rt, int index)
{
    if (!rt || !rt->cur.plan || index < 0 || (uint32_t)index >= rt->cur.plan->n_resources) return NULL;
    return &rt->mem.res[index];
}
