/* graph_execute_timing.c - timestamp queries and the GPU times read from them (owns
 * pg_runtime.timing, graph_execute_internal.h). Calls no other file of the runtime. */
#include "graph_execute_internal.h"

#include <string.h>

/* The per-plan query pools and their result buffers (one per frame slot). */
pg_result pg_rt_timing_build(pg_runtime *rt, pg_error *err)
{
    const pg_graph_plan *plan = rt->cur.plan;
    pg_gpu *gpu = rt->cfg.gpu;
    pg_rt_timing *t = &rt->timing;
    pg_result r;
    t->n_queries = 2 * plan->n_order + 1; /* per queue pool; the +1 keeps it non-empty */
    t->compute_stamps = plan->async && gpu->compute_timestamp_valid_bits > 0;
    t->n_on_queue[0] = t->n_on_queue[1] = 0;
    for (uint32_t o = 0; o < plan->n_order; o++) t->qslot[o] = t->n_on_queue[plan->passes[plan->order[o]].queue]++;
    if (!gpu->timestamp_valid_bits) return PG_OK;
    VkQueryPoolCreateInfo qci = {.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
                                 .queryType = VK_QUERY_TYPE_TIMESTAMP, .queryCount = t->n_queries};
    for (uint32_t f = 0; f < PG_MAX_FRAMES_IN_FLIGHT; f++) {
        PG_VK_TRY(err, vkCreateQueryPool(gpu->device, &qci, NULL, &t->slot[f].queries));
        pg_gpu_name(gpu, VK_OBJECT_TYPE_QUERY_POOL, (uint64_t)t->slot[f].queries, "frame%u.timestamps", f);
        if (t->compute_stamps) {
            PG_VK_TRY(err, vkCreateQueryPool(gpu->device, &qci, NULL, &t->slot[f].cqueries));
            pg_gpu_name(gpu, VK_OBJECT_TYPE_QUERY_POOL, (uint64_t)t->slot[f].cqueries, "frame%u.timestamps.compute", f);
        }
        char nm[40];
        snprintf(nm, sizeof nm, "frame%u.timestamp_results", f);
        if ((r = pg_buffer_create(gpu, 2 * sizeof(uint64_t) * t->n_queries, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, nm,
                                  &t->slot[f].timestamps, err)))
            return r;
    }
    return PG_OK;
}

/* The query pools and the GPU times of the plan (the device must be idle). */
void pg_rt_timing_destroy(pg_runtime *rt)
{
    pg_gpu *gpu = rt->cfg.gpu;
    pg_rt_timing *t = &rt->timing;
    for (uint32_t f = 0; f < PG_MAX_FRAMES_IN_FLIGHT; f++) {
        if (t->slot[f].queries) vkDestroyQueryPool(gpu->device, t->slot[f].queries, NULL);
        if (t->slot[f].cqueries) vkDestroyQueryPool(gpu->device, t->slot[f].cqueries, NULL);
        pg_buffer_destroy(gpu, &t->slot[f].timestamps);
        t->slot[f].queries = t->slot[f].cqueries = VK_NULL_HANDLE;
    }
    t->gpu_valid = false;
    memset(t->gpu_hist, 0, sizeof t->gpu_hist);
}

static VkQueryPool pool_of(const pg_runtime *rt, uint32_t f, pg_queue q)
{
    return q == PG_QUEUE_COMPUTE ? rt->timing.slot[f].cqueries : rt->timing.slot[f].queries;
}

/* In the queue's first batch of the frame: reset its pool. */
void pg_rt_timing_begin(const pg_runtime *rt, VkCommandBuffer cmd, uint32_t f, pg_queue q)
{
    VkQueryPool pool = pool_of(rt, f, q);
    if (pool) vkCmdResetQueryPool(cmd, pool, 0, rt->timing.n_queries);
}

/* The begin (end false) or end timestamp of executed pass o. */
void pg_rt_timing_stamp(const pg_runtime *rt, VkCommandBuffer cmd, uint32_t f, pg_queue q, uint32_t o, bool end)
{
    VkQueryPool pool = pool_of(rt, f, q);
    if (pool) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool, 2 * rt->timing.qslot[o] + (end ? 1 : 0));
}

/* In the queue's last batch of the frame: copy its pool to the slot's host-visible results. */
void pg_rt_timing_copy(const pg_runtime *rt, VkCommandBuffer cmd, uint32_t f, pg_queue q)
{
    const pg_rt_timing *t = &rt->timing;
    VkQueryPool pool = pool_of(rt, f, q);
    if (!pool || !t->n_on_queue[q]) return;
    /* the same bytes were written by this slot's copy frames in flight ago, in an earlier submission
     * to this queue: the host's fence wait orders the host, not this copy (write after write; a
     * separate compute queue, whose later batches hold no other barrier, showed it) */
    VkBufferMemoryBarrier2 waw = pg_buffer_barrier(t->slot[f].timestamps.buffer, VK_PIPELINE_STAGE_2_COPY_BIT,
                                                   VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                                                   VK_ACCESS_2_TRANSFER_WRITE_BIT);
    pg_cmd_barriers(cmd, 0, NULL, 1, &waw);
    vkCmdCopyQueryPoolResults(cmd, pool, 0, 2 * t->n_on_queue[q], t->slot[f].timestamps.buffer,
                              (VkDeviceSize)q * t->n_queries * sizeof(uint64_t), sizeof(uint64_t),
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
    VkBufferMemoryBarrier2 tb = pg_buffer_barrier(t->slot[f].timestamps.buffer, VK_PIPELINE_STAGE_2_COPY_BIT,
                                                  VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                                                  VK_ACCESS_2_HOST_READ_BIT);
    pg_cmd_barriers(cmd, 0, NULL, 1, &tb);
}

/* Reads the timestamps of slot f (its fence has signalled; frame_no: the frame it ran) into the
 * GPU times and their history. */
void pg_rt_timing_collect(pg_runtime *rt, uint32_t f, uint64_t frame_no)
{
    pg_gpu *gpu = rt->cfg.gpu;
    const pg_graph_plan *plan = rt->cur.plan;
    pg_rt_timing *t = &rt->timing;
    if (!t->slot[f].queries) return;
    /* the frame copied its query results to a host-visible buffer (vkGetQueryPoolResults on
     * lavapipe blocks until the frame submitted after this one is done too) */
    if (!t->slot[f].timestamps.mapped) return;
    uint64_t ts[2 * (2 * PG_MAX_PASSES + 1)];
    memcpy(ts, t->slot[f].timestamps.mapped, 2 * sizeof(uint64_t) * t->n_queries);
    const uint32_t bits[PG_QUEUE_COUNT] = {gpu->timestamp_valid_bits, gpu->compute_timestamp_valid_bits};
    /* the two queues' timestamps are taken as one timebase (checked on the GPU, README) */
    uint64_t t_min = UINT64_MAX, t_max = 0;
    for (uint32_t o = 0; o < plan->n_order; o++) {
        const pg_queue q = plan->passes[plan->order[o]].queue;
        if (q == PG_QUEUE_COMPUTE && !t->compute_stamps) {
            t->gpu_pass_ms[o] = 0;
            continue;
        }
        const uint64_t mask = bits[q] >= 64 ? ~0ull : ((1ull << bits[q]) - 1);
        const uint64_t b0 = ts[q * t->n_queries + 2 * t->qslot[o]] & mask;
        const uint64_t b1 = ts[q * t->n_queries + 2 * t->qslot[o] + 1] & mask;
        t->gpu_pass_ms[o] = ((b1 - b0) & mask) * (double)gpu->timestamp_period_ns * 1e-6;
        if (b0 < t_min) t_min = b0;
        if (b1 > t_max) t_max = b1;
    }
    t->gpu_total_ms = t_max > t_min ? (t_max - t_min) * (double)gpu->timestamp_period_ns * 1e-6 : 0;
    for (uint32_t o = 0; o < plan->n_order; o++) {
        const pg_queue q = plan->passes[plan->order[o]].queue;
        const uint64_t mask = bits[q] >= 64 ? ~0ull : ((1ull << bits[q]) - 1);
        const uint64_t b0 = ts[q * t->n_queries + 2 * t->qslot[o]] & mask;
        t->gpu_pass_start_ms[o] = (q == PG_QUEUE_COMPUTE && !t->compute_stamps) || b0 < t_min
                                      ? 0 : (b0 - t_min) * (double)gpu->timestamp_period_ns * 1e-6;
    }
    t->gpu_valid = true;
    t->gpu_frame = frame_no;
    gpu_times *h = &t->gpu_hist[t->gpu_frame % 4];
    h->frame = t->gpu_frame;
    h->valid = true;
    h->total_ms = t->gpu_total_ms;
    memcpy(h->pass_ms, t->gpu_pass_ms, sizeof(double) * plan->n_order);
    memcpy(h->pass_start_ms, t->gpu_pass_start_ms, sizeof(double) * plan->n_order);
}

/* The GPU times of the last frame collected, into a frame's stats. */
void pg_rt_timing_fill_stats(const pg_runtime *rt, pg_frame_stats *stats)
{
    const pg_rt_timing *t = &rt->timing;
    if (!t->gpu_valid) return;
    memcpy(stats->pass_ms, t->gpu_pass_ms, sizeof(double) * rt->cur.plan->n_order);
    memcpy(stats->pass_start_ms, t->gpu_pass_start_ms, sizeof(double) * rt->cur.plan->n_order);
    stats->gpu_total_ms = t->gpu_total_ms;
    stats->gpu_frame = t->gpu_frame;
    stats->timestamps_valid = true;
}

bool pg_runtime_gpu_times(const pg_runtime *rt, uint64_t frame, double *total_ms, double *pass_ms)
{
    const gpu_times *h = &rt->timing.gpu_hist[frame % 4];
    if (!h->valid || h->frame != frame || !rt->cur.plan) return false;
    if (total_ms) *total_ms = h->total_ms;
    if (pass_ms) memcpy(pass_ms, h->pass_ms, sizeof(double) * rt->cur.plan->n_order);
    return true;
}
