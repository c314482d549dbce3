/* graph_execute_record.c - recording and submission of a frame (batches), timestamps, frames in
 * flight. */
#include "graph_execute_internal.h"
#include "vk_pipeline.h"

#include <string.h>
#include <time.h>

/* With frames in flight, the most frames between two readings of the pass reports. */
#define PG_REPORT_EVERY 8

/* A global memory barrier before every pass of an immediate-mode plan (pg_graph_plan.immediate):
 * orders everything, the passes' own resources included. */
static void emit_full_barrier(VkCommandBuffer cmd)
{
    VkMemoryBarrier2 mb = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2,
        .srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
        .srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT,
        .dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
        .dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
    };
    VkDependencyInfo di = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .memoryBarrierCount = 1,
                           .pMemoryBarriers = &mb};
    vkCmdPipelineBarrier2(cmd, &di);
}

static void emit_barriers(pg_runtime *rt, VkCommandBuffer cmd, uint32_t n, const pg_barrier *bars)
{
    VkImageMemoryBarrier2 ib[PG_MAX_RESOURCES];
    VkBufferMemoryBarrier2 bb[PG_MAX_RESOURCES];
    uint32_t ni = 0, nb = 0;
    for (uint32_t i = 0; i < n && i < PG_MAX_RESOURCES; i++) {
        const pg_barrier *b = &bars[i];
        const pg_phys_resource *r = &rt->res[b->resource];
        uint64_t src_stages = b->src_stages, src_access = b->src_access;
        uint32_t old_layout = b->old_layout;
        if (b->wrap && !rt->persistent_initialized[b->resource]) {
            /* very first frame: nothing to wait for, contents undefined */
            src_stages = VK_PIPELINE_STAGE_2_NONE;
            src_access = 0;
            old_layout = VK_IMAGE_LAYOUT_UNDEFINED;
        }
        /* With frames in flight a barrier that waits for nothing (a transient's first use) would
         * not chain to the frame-start barrier: its layout transition could overwrite memory the
         * previous frame still reads (synchronization validation at queue submit reports it).
         * Its own stages make the chain. */
        if (!src_stages && rt->n_in_flight > 1) src_stages = b->dst_stages;
        if (b->is_image) {
            ib[ni++] = pg_image_barrier(r->image, pg_vk_aspect(r->format), src_stages, src_access, b->dst_stages,
                                        b->dst_access, (VkImageLayout)old_layout, (VkImageLayout)b->new_layout);
        } else {
            bb[nb++] = (VkBufferMemoryBarrier2){
                .sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2,
                .srcStageMask = src_stages,
                .srcAccessMask = src_access,
                .dstStageMask = b->dst_stages,
                .dstAccessMask = b->dst_access,
                .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                .buffer = r->buffer,
                .size = VK_WHOLE_SIZE,
            };
        }
    }
    pg_cmd_barriers(cmd, ni, ib, nb, bb);
}

uint32_t pg_rt_queue_family(const pg_runtime *rt, pg_queue q)
{
    return q == PG_QUEUE_COMPUTE ? rt->gpu->compute_family : rt->gpu->queue_family;
}

/* The release (at the end of batch b) or acquire (at its start) halves of the plan's ownership
 * transfers: same layouts in both; the release's destination and the acquire's source access
 * are empty (the semaphore between the batches orders them; the acquire's source stages are its
 * destination stages, which the batch's semaphore wait covers, so the chain holds). */
static void emit_qfots(pg_runtime *rt, VkCommandBuffer cmd, uint32_t b, bool release)
{
    const pg_graph_plan *plan = rt->plan;
    VkImageMemoryBarrier2 ib[PG_MAX_RESOURCES];
    VkBufferMemoryBarrier2 bb[PG_MAX_RESOURCES];
    uint32_t ni = 0, nb = 0;
    for (uint32_t i = 0; i < plan->n_qfots; i++) {
        const pg_qfot *t = &plan->qfots[i];
        if ((release ? t->release_batch : t->acquire_batch) != (int)b) continue;
        const pg_phys_resource *r = &rt->res[t->resource];
        const uint64_t ss = release ? t->src_stages : t->dst_stages, sa = release ? t->src_access : 0;
        const uint64_t ds = release ? VK_PIPELINE_STAGE_2_NONE : t->dst_stages, da = release ? 0 : t->dst_access;
        const uint32_t sf = pg_rt_queue_family(rt, t->src_queue), df = pg_rt_queue_family(rt, t->dst_queue);
        if (t->is_image && ni < PG_MAX_RESOURCES) {
            VkImageMemoryBarrier2 x = pg_image_barrier(r->image, pg_vk_aspect(r->format), ss, sa, ds, da,
                                                       (VkImageLayout)t->old_layout, (VkImageLayout)t->new_layout);
            x.srcQueueFamilyIndex = sf;
            x.dstQueueFamilyIndex = df;
            ib[ni++] = x;
        } else if (!t->is_image && nb < PG_MAX_RESOURCES) {
            bb[nb++] = (VkBufferMemoryBarrier2){
                .sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2,
                .srcStageMask = ss, .srcAccessMask = sa, .dstStageMask = ds, .dstAccessMask = da,
                .srcQueueFamilyIndex = sf, .dstQueueFamilyIndex = df,
                .buffer = r->buffer, .size = VK_WHOLE_SIZE,
            };
        }
    }
    if (ni || nb) pg_cmd_barriers(cmd, ni, ib, nb, bb);
}

static void check_load_op(const pg_pass_record_ctx *ctx, uint32_t slot, bool clears)
{
    if (!ctx->record_error || ctx->record_error->msg[0] || !ctx->pass || slot >= ctx->pass->n_slots) return;
    const pg_slot_decl *d = &ctx->pass->slots[slot].decl;
    const bool full = d->access == PG_ACCESS_COLOR_WRITE || d->access == PG_ACCESS_DEPTH_WRITE;
    const bool loads = d->access == PG_ACCESS_COLOR_RMW || d->access == PG_ACCESS_DEPTH_RMW ||
                       d->access == PG_ACCESS_DEPTH_READ;
    if (!full && !loads)
        pg_fail(ctx->record_error, PG_ERR_INVALID_ARG,
                "pass '%s': slot '%s' is declared %s, not an attachment, but rendering begins on it", ctx->pass->name,
                d->name, pg_access_name(d->access));
    else if (full && !clears)
        pg_fail(ctx->record_error, PG_ERR_INVALID_ARG,
                "pass '%s': slot '%s' is declared %s (a full write) but rendering begins with LOAD_OP_LOAD: "
                "clear it, or declare a read-modify-write",
                ctx->pass->name, d->name, pg_access_name(d->access));
    else if (loads && clears)
        pg_fail(ctx->record_error, PG_ERR_INVALID_ARG,
                "pass '%s': slot '%s' is declared %s (it loads the contents) but rendering begins with "
                "LOAD_OP_CLEAR: load it, or declare a full write",
                ctx->pass->name, d->name, pg_access_name(d->access));
}

void pg_pass_begin_rendering(const pg_pass_record_ctx *ctx, uint32_t n_color, const uint32_t *color_slots,
                             const VkClearColorValue *clears, int depth_slot, bool clear_depth, float depth_clear)
{
    VkImageView views[8];
    uint32_t w = 0, h = 0;
    if (n_color > 8) n_color = 8;
    for (uint32_t i = 0; i < n_color; i++) {
        const pg_phys_resource *r = ctx->slots[color_slots[i]];
        views[i] = r->view;
        if (!i) w = r->width, h = r->height;
        check_load_op(ctx, color_slots[i], clears != NULL);
    }
    VkImageView dv = VK_NULL_HANDLE;
    if (depth_slot >= 0) {
        const pg_phys_resource *r = ctx->slots[depth_slot];
        dv = r->view;
        if (!n_color) w = r->width, h = r->height;
        check_load_op(ctx, (uint32_t)depth_slot, clear_depth);
    }
    pg_cmd_begin_rendering(ctx->cmd, w, h, n_color, views, clears, dv, clear_depth, depth_clear);
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

/* Reads the timestamps of slot f (its fence has signalled) into rt->gpu_*. */
static void collect_timestamps(pg_runtime *rt, uint32_t f)
{
    pg_gpu *gpu = rt->gpu;
    const pg_graph_plan *plan = rt->plan;
    rt->slot[f].pending = false;
    if (!rt->slot[f].queries) return;
    /* the frame copied its query results to a host-visible buffer (vkGetQueryPoolResults on
     * lavapipe blocks until the frame submitted after this one is done too) */
    if (!rt->slot[f].timestamps.mapped) return;
    uint64_t ts[2 * (2 * PG_MAX_PASSES + 1)];
    memcpy(ts, rt->slot[f].timestamps.mapped, 2 * sizeof(uint64_t) * rt->n_queries);
    const uint32_t bits[PG_QUEUE_COUNT] = {gpu->timestamp_valid_bits, gpu->compute_timestamp_valid_bits};
    /* the two queues' timestamps are taken as one timebase (checked on the GPU, README) */
    uint64_t t_min = UINT64_MAX, t_max = 0;
    for (uint32_t o = 0; o < plan->n_order; o++) {
        const pg_queue q = plan->passes[plan->order[o]].queue;
        if (q == PG_QUEUE_COMPUTE && !rt->compute_stamps) {
            rt->gpu_pass_ms[o] = 0;
            continue;
        }
        const uint64_t mask = bits[q] >= 64 ? ~0ull : ((1ull << bits[q]) - 1);
        const uint64_t b0 = ts[q * rt->n_queries + 2 * rt->qslot[o]] & mask;
        const uint64_t b1 = ts[q * rt->n_queries + 2 * rt->qslot[o] + 1] & mask;
        rt->gpu_pass_ms[o] = ((b1 - b0) & mask) * (double)gpu->timestamp_period_ns * 1e-6;
        if (b0 < t_min) t_min = b0;
        if (b1 > t_max) t_max = b1;
    }
    rt->gpu_total_ms = t_max > t_min ? (t_max - t_min) * (double)gpu->timestamp_period_ns * 1e-6 : 0;
    for (uint32_t o = 0; o < plan->n_order; o++) {
        const pg_queue q = plan->passes[plan->order[o]].queue;
        const uint64_t mask = bits[q] >= 64 ? ~0ull : ((1ull << bits[q]) - 1);
        const uint64_t b0 = ts[q * rt->n_queries + 2 * rt->qslot[o]] & mask;
        rt->gpu_pass_start_ms[o] = (q == PG_QUEUE_COMPUTE && !rt->compute_stamps) || b0 < t_min
                                       ? 0 : (b0 - t_min) * (double)gpu->timestamp_period_ns * 1e-6;
    }
    rt->gpu_valid = true;
    rt->gpu_frame = rt->slot[f].frame_no;
    gpu_times *h = &rt->gpu_hist[rt->gpu_frame % 4];
    h->frame = rt->gpu_frame;
    h->valid = true;
    h->total_ms = rt->gpu_total_ms;
    memcpy(h->pass_ms, rt->gpu_pass_ms, sizeof(double) * plan->n_order);
    memcpy(h->pass_start_ms, rt->gpu_pass_start_ms, sizeof(double) * plan->n_order);
}

/* Waits for slot f's frame if it is pending; counts a wait that found the fence unsignalled. */
static pg_result wait_slot(pg_runtime *rt, uint32_t f, double *wait_ms, pg_error *err)
{
    if (!rt->slot[f].pending) return PG_OK;
    VkDevice dev = rt->gpu->device;
    VkResult st = vkGetFenceStatus(dev, rt->slot[f].fence);
    if (st == VK_NOT_READY) {
        rt->stats.fence_waits++;
        double tw = now_ms();
        PG_VK_TRY(err, vkWaitForFences(dev, 1, &rt->slot[f].fence, VK_TRUE, UINT64_MAX));
        *wait_ms += now_ms() - tw;
    } else if (st != VK_SUCCESS) {
        return pg_fail(err, PG_ERR_VULKAN, "frame fence: %s", pg_vk_result_name(st));
    }
    collect_timestamps(rt, f);
    return PG_OK;
}

void pg_runtime_test_drop_frame_barrier(pg_runtime *rt, bool drop)
{
    rt->test_no_frame_barrier = drop;
}

pg_result pg_runtime_set_frames_in_flight(pg_runtime *rt, uint32_t n, pg_error *err)
{
    if (n < 1 || n > PG_MAX_FRAMES_IN_FLIGHT)
        return pg_fail(err, PG_ERR_INVALID_ARG, "frames in flight: %u (1..%d)", n, PG_MAX_FRAMES_IN_FLIGHT);
    pg_result r = pg_runtime_wait_idle(rt, err);
    if (r) return r;
    rt->n_in_flight = n;
    return PG_OK;
}

bool pg_runtime_gpu_times(const pg_runtime *rt, uint64_t frame, double *total_ms, double *pass_ms)
{
    const gpu_times *h = &rt->gpu_hist[frame % 4];
    if (!h->valid || h->frame != frame || !rt->plan) return false;
    if (total_ms) *total_ms = h->total_ms;
    if (pass_ms) memcpy(pass_ms, h->pass_ms, sizeof(double) * rt->plan->n_order);
    return true;
}

pg_result pg_runtime_wait_idle(pg_runtime *rt, pg_error *err)
{
    double w = 0;
    for (uint32_t k = 1; k <= PG_MAX_FRAMES_IN_FLIGHT; k++) { /* oldest first: the freshest times win */
        pg_result r = wait_slot(rt, (rt->cur + k) % PG_MAX_FRAMES_IN_FLIGHT, &w, err);
        if (r) return r;
    }
    return PG_OK;
}

pg_result pg_runtime_render(pg_runtime *rt, const void *frame_block, bool readback, pg_frame_stats *stats,
                            pg_error *err)
{
    if (!rt->built) return pg_fail(err, PG_ERR_INVALID_ARG, "pg_runtime_render: no plan set");
    pg_gpu *gpu = rt->gpu;
    const pg_graph_plan *plan = rt->plan;
    double t0 = now_ms(), wait_ms = 0;
    const uint32_t n_fif = rt->n_in_flight;
    const uint32_t f = (uint32_t)(rt->frame_no % n_fif);
    pg_result wr = wait_slot(rt, f, &wait_ms, err); /* the frame that used this slot n_fif frames ago */
    if (wr) return wr;
    memcpy(rt->slot[f].frame, frame_block, rt->frame_size);
    memcpy(rt->slot[f].frame_ubo.mapped, rt->slot[f].frame, rt->frame_size);
    VkQueryPool qpool[PG_QUEUE_COUNT] = {rt->slot[f].queries, rt->slot[f].cqueries};
    /* the first and last batch of each queue (timestamp reset / copy, frames-in-flight barrier) */
    int first_of[PG_QUEUE_COUNT] = {-1, -1}, last_of[PG_QUEUE_COUNT] = {-1, -1};
    for (uint32_t b = 0; b < plan->n_batches; b++) {
        const int q = plan->batches[b].queue;
        if (first_of[q] < 0) first_of[q] = (int)b;
        last_of[q] = (int)b;
    }
    pg_error record_error = {0};
    for (uint32_t b = 0; b < plan->n_batches; b++) {
        const pg_plan_batch *bt = &plan->batches[b];
        const int q = bt->queue;
        VkCommandPool pool = q == PG_QUEUE_COMPUTE ? gpu->compute_cmd_pool : gpu->cmd_pool;
        if (rt->slot[f].cmds[b] && rt->slot[f].cmd_pool[b] != pool) {
            vkFreeCommandBuffers(gpu->device, rt->slot[f].cmd_pool[b], 1, &rt->slot[f].cmds[b]);
            rt->slot[f].cmds[b] = VK_NULL_HANDLE;
        }
        if (!rt->slot[f].cmds[b]) {
            VkCommandBufferAllocateInfo cai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                               .commandPool = pool, .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                               .commandBufferCount = 1};
            PG_VK_TRY(err, vkAllocateCommandBuffers(gpu->device, &cai, &rt->slot[f].cmds[b]));
            rt->slot[f].cmd_pool[b] = pool;
            pg_gpu_name(gpu, VK_OBJECT_TYPE_COMMAND_BUFFER, (uint64_t)(uintptr_t)rt->slot[f].cmds[b],
                        "frame%u.batch%u.%s", f, b, pg_queue_name((pg_queue)q));
        }
        VkCommandBuffer cmd = rt->slot[f].cmds[b];
        PG_VK_TRY(err, vkResetCommandBuffer(cmd, 0));
        VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                       .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
        PG_VK_TRY(err, vkBeginCommandBuffer(cmd, &bi));
        if (first_of[q] == (int)b) {
            /* With frames in flight the previous frame may still run: the frames share the
             * graph's resources (persistent and transient bytes), so this frame's work on this
             * queue starts after all earlier work on it (one full barrier; submission order
             * makes it cover earlier submits). The compute queue's first batch also waits for
             * the previous frame's graphics work (prev_frame_wait). */
            if (n_fif > 1 && !rt->test_no_frame_barrier) emit_full_barrier(cmd);
            if (qpool[q]) vkCmdResetQueryPool(cmd, qpool[q], 0, rt->n_queries);
        }
        emit_qfots(rt, cmd, b, false); /* acquires */
        for (uint32_t o = bt->first; o < bt->first + bt->count; o++) {
            int pi = plan->order[o];
            const pg_plan_pass *pass = &plan->passes[pi];
            if (qpool[q]) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, qpool[q], 2 * rt->qslot[o]);
            if (gpu->cmd_begin_label) {
                VkDebugUtilsLabelEXT label = {.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT, .pLabelName = pass->name};
                gpu->cmd_begin_label(cmd, &label);
            }
            if (plan->immediate) emit_full_barrier(cmd);
            emit_barriers(rt, cmd, pass->n_barriers, pass->barriers);
            pg_pass_record_ctx ctx = {
                .gpu = gpu,
                .cmd = cmd,
                .pass = pass,
                .user = rt->user.data,
                .frame_set = rt->slot[f].frame_set,
                .frame = rt->slot[f].frame,
                .frame_size = rt->frame_size,
                .width = rt->width,
                .height = rt->height,
                .record_error = &record_error,
            };
            for (uint32_t s = 0; s < pass->n_slots; s++) ctx.slots[s] = &rt->res[pass->slots[s].resource];
            pass->type->record(rt->pass_state[pi], &ctx);
            if (gpu->cmd_end_label) gpu->cmd_end_label(cmd);
            if (qpool[q]) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, qpool[q], 2 * rt->qslot[o] + 1);
        }
        if (bt->last) {
            if (plan->immediate) emit_full_barrier(cmd);
            emit_barriers(rt, cmd, plan->n_final_barriers, plan->final_barriers);
        }
        emit_qfots(rt, cmd, b, true); /* releases */
        if (qpool[q] && last_of[q] == (int)b && rt->n_on_queue[q]) {
            vkCmdCopyQueryPoolResults(cmd, qpool[q], 0, 2 * rt->n_on_queue[q], rt->slot[f].timestamps.buffer,
                                      (VkDeviceSize)q * rt->n_queries * sizeof(uint64_t), sizeof(uint64_t),
                                      VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
            VkBufferMemoryBarrier2 tb = pg_buffer_barrier(rt->slot[f].timestamps.buffer, VK_PIPELINE_STAGE_2_COPY_BIT,
                                                          VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                                                          VK_ACCESS_2_HOST_READ_BIT);
            pg_cmd_barriers(cmd, 0, NULL, 1, &tb);
        }
        if (bt->last) {
            int outs[2] = {plan->output, plan->hdr_output};
            for (int k = 0; k < 2; k++) {
                rt->readback_valid[k] = false;
                if (!readback || outs[k] < 0 || !rt->slot[f].readback[k].buffer) continue;
                const pg_phys_resource *r = &rt->res[outs[k]];
                VkBufferImageCopy c = {.imageSubresource = {pg_vk_aspect(r->format), 0, 0, 1},
                                       .imageExtent = {r->width, r->height, 1}};
                vkCmdCopyImageToBuffer(cmd, r->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                       rt->slot[f].readback[k].buffer, 1, &c);
                VkBufferMemoryBarrier2 hb =
                    pg_buffer_barrier(rt->slot[f].readback[k].buffer, VK_PIPELINE_STAGE_2_COPY_BIT,
                                      VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
                pg_cmd_barriers(cmd, 0, NULL, 1, &hb);
                rt->readback_valid[k] = true;
            }
        }
        PG_VK_TRY(err, vkEndCommandBuffer(cmd));
    }
    if (record_error.msg[0]) { /* a pass broke its declaration: not submitted */
        rt->readback_valid[0] = rt->readback_valid[1] = false;
        return pg_fail(err, record_error.code, "%s", record_error.msg);
    }
    /* submit the batches in plan order: each signals its queue's timeline semaphore; a batch
     * waits for the newest other-queue batch it depends on (and the first compute batch for the
     * previous frame's graphics work); the last (graphics) batch signals the fence */
    PG_VK_TRY(err, vkResetFences(gpu->device, 1, &rt->slot[f].fence));
    uint64_t value[PG_MAX_BATCHES] = {0};
    const uint64_t gfx_before = rt->tl_value[PG_QUEUE_GRAPHICS];
    for (uint32_t b = 0; b < plan->n_batches; b++) {
        const pg_plan_batch *bt = &plan->batches[b];
        const int q = bt->queue, other = 1 - q;
        uint64_t wv = 0, wst = 0;
        for (uint32_t w = 0; w < bt->n_waits; w++) {
            if (value[bt->waits[w].batch] > wv) wv = value[bt->waits[w].batch];
            wst |= bt->waits[w].stages;
        }
        if (bt->prev_frame_wait >= 0 && other == PG_QUEUE_GRAPHICS && gfx_before) {
            uint64_t v = rt->prev_gen == plan->generation ? rt->prev_batch_value[bt->prev_frame_wait] : gfx_before;
            if (v > wv) wv = v;
            wst |= VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        }
        VkSemaphoreSubmitInfo wsi = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = rt->timeline[other],
                                     .value = wv, .stageMask = wst};
        VkSemaphoreSubmitInfo ssi = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = rt->timeline[q],
                                     .value = 0, .stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT};
        const bool sem = plan->async && rt->timeline[q];
        if (sem) value[b] = ssi.value = ++rt->tl_value[q];
        VkCommandBufferSubmitInfo cbi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO,
                                         .commandBuffer = rt->slot[f].cmds[b]};
        VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2,
                            .waitSemaphoreInfoCount = sem && wv ? 1 : 0, .pWaitSemaphoreInfos = &wsi,
                            .commandBufferInfoCount = 1, .pCommandBufferInfos = &cbi,
                            .signalSemaphoreInfoCount = sem ? 1 : 0, .pSignalSemaphoreInfos = &ssi};
        VkQueue queue = q == PG_QUEUE_COMPUTE ? gpu->compute_queue : gpu->queue;
        VkResult sr = pg_vk_fault_next("vkQueueSubmit2(batch)") ? VK_ERROR_DEVICE_LOST
                                                                 : vkQueueSubmit2(queue, 1, &si, bt->last ? rt->slot[f].fence : VK_NULL_HANDLE);
        if (sr != VK_SUCCESS) {
            if (sem) rt->tl_value[q]--; /* never signalled: no later wait may name it */
            return pg_fail(err, PG_ERR_VULKAN, "vkQueueSubmit2(batch %u of %u, %s queue) failed: %s", b, plan->n_batches,
                           pg_queue_name((pg_queue)q), pg_vk_result_name(sr));
        }
    }
    memcpy(rt->prev_batch_value, value, sizeof value);
    rt->prev_gen = plan->generation;
    rt->slot[f].pending = true;
    rt->slot[f].frame_no = rt->frame_no++;
    rt->cur = f;
    rt->stats.frames_submitted++;
    /* one frame in flight, or a read-back: wait for this frame (its staging is read after its fence) */
    if (n_fif == 1 || readback) {
        rt->stats.sync_waits++;
        double tw = now_ms();
        PG_VK_TRY(err, vkWaitForFences(gpu->device, 1, &rt->slot[f].fence, VK_TRUE, UINT64_MAX));
        wait_ms += now_ms() - tw;
        collect_timestamps(rt, f);
    }
    for (uint32_t i = 0; i < plan->n_resources; i++)
        if (!plan->resources[i].culled && plan->resources[i].lifetime != PG_LIFETIME_TRANSIENT)
            rt->persistent_initialized[i] = true;
    /* pass reports read what the passes' host-visible buffers hold: only when no frame is in
     * flight (checked, never waited for), else the passes may be writing them */
    bool idle = true;
    for (uint32_t k = 1; k <= n_fif; k++) {
        uint32_t g = (f + k) % n_fif; /* oldest first */
        if (!rt->slot[g].pending) continue;
        VkResult fs = vkGetFenceStatus(gpu->device, rt->slot[g].fence);
        if (fs == VK_SUCCESS) collect_timestamps(rt, g);
        else idle = false;
    }
    /* Pass reports (overflow counters, growth requests) must still arrive: after a new plan or a
     * growth, and at least every PG_REPORT_EVERY frames, wait for the frames in flight. */
    if (!idle && (rt->report_due || rt->frames_unreported + 1 >= PG_REPORT_EVERY)) {
        double tw = now_ms();
        pg_result ir = pg_runtime_wait_idle(rt, err);
        if (ir) return ir;
        wait_ms += now_ms() - tw;
        rt->stats.report_waits++;
        idle = true;
    }
    rt->report_due = false;
    rt->frames_unreported = idle ? 0 : rt->frames_unreported + 1;

    pg_frame_stats local_stats;
    if (!stats) stats = &local_stats;
    {
        memset(stats, 0, sizeof *stats);
        stats->n_passes = plan->n_order;
        for (uint32_t o = 0; o < plan->n_order; o++) {
            pg_strlcpy(stats->pass_names[o], plan->passes[plan->order[o]].name, PG_NAME_MAX);
            stats->pass_queue[o] = (uint8_t)plan->passes[plan->order[o]].queue;
        }
        stats->n_batches = plan->n_batches;
        stats->frame = rt->slot[f].frame_no;
        stats->in_flight = n_fif;
        stats->wait_ms = wait_ms;
        if (rt->gpu_valid) {
            memcpy(stats->pass_ms, rt->gpu_pass_ms, sizeof(double) * plan->n_order);
            memcpy(stats->pass_start_ms, rt->gpu_pass_start_ms, sizeof(double) * plan->n_order);
            stats->gpu_total_ms = rt->gpu_total_ms;
            stats->gpu_frame = rt->gpu_frame;
            stats->timestamps_valid = true;
        }
        stats->reports_valid = idle;
        if (!idle) rt->stats.reports_skipped++;
        for (uint32_t o = 0; o < plan->n_order && idle; o++) {
            const pg_plan_pass *pass = &plan->passes[plan->order[o]];
            if (!pass->type->report) continue;
            pg_pass_report rep = {0};
            pass->type->report(rt->pass_state[plan->order[o]], &rep);
            for (uint32_t k = 0; k < rep.n && stats->n_counters < 32; k++) {
                pg_strlcpy(stats->counters[stats->n_counters].pass, pass->name, PG_NAME_MAX);
                pg_strlcpy(stats->counters[stats->n_counters].name, rep.counters[k].name, 32);
                stats->counters[stats->n_counters].value = rep.counters[k].value;
                stats->n_counters++;
            }
            for (uint32_t k = 0; k < rep.n_notes && stats->n_notes < 4; k++)
                pg_strlcpy(stats->notes[stats->n_notes++], rep.notes[k], sizeof stats->notes[0]);
            for (uint32_t k = 0; k < rep.n_grow; k++) {
                if (rep.grow[k].slot >= pass->n_slots) continue;
                int ri = pass->slots[rep.grow[k].slot].resource;
                if (ri < 0 || !plan->resources[ri].growable) continue;
                rt->report_due = true; /* the frame after a growth shows whether it sufficed */
                pg_result gr = pg_rt_grow_buffer(rt, ri, rep.grow[k].needed, rep.grow[k].max, stats, err);
                if (gr) return gr;
                if (!rt->built) return pg_fail(err, PG_ERR_VULKAN, "runtime lost its plan while growing a buffer");
            }
        }
        if (rt->grow_note[0] && stats->n_notes < 4)
            pg_strlcpy(stats->notes[stats->n_notes++], rt->grow_note, sizeof stats->notes[0]);
        stats->cpu_ms = now_ms() - t0 - wait_ms;
    }
    return PG_OK;
}
