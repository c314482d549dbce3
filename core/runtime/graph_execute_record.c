/* graph_execute_record.c - pg_runtime_render: one frame in named steps (graph_execute_frames.c
 * begins, submits and settles it; this file records its batches, reads the pass reports and
 * fills its stats); owns pg_runtime.reports (graph_execute_internal.h). Calls the memory, frames
 * and timing files. */
#include "graph_execute_internal.h"
#include "vk_pipeline.h"

#include <string.h>

/* With frames in flight, the most frames between two readings of the pass reports. */
#define PG_REPORT_EVERY 8

/* A global memory barrier before every pass of an immediate-mode plan (pg_graph_plan.immediate):
 * orders everything, the passes' own resources included. */
static void emit_full_barrier(VkCommandBuffer cmd)
{
    pg_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                          VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
}

static void emit_barriers(pg_runtime *rt, VkCommandBuffer cmd, uint32_t n, const pg_barrier *bars)
{
    VkImageMemoryBarrier2 ib[PG_MAX_RESOURCES];
    VkBufferMemoryBarrier2 bb[PG_MAX_RESOURCES];
    uint32_t ni = 0, nb = 0;
    for (uint32_t i = 0; i < n && i < PG_MAX_RESOURCES; i++) {
        const pg_barrier *b = &bars[i];
        const pg_phys_resource *r = &rt->mem.res[b->resource];
        uint64_t src_stages = b->src_stages, src_access = b->src_access;
        uint32_t old_layout = b->old_layout;
        if (b->first_frame && rt->mem.persistent_initialized[b->resource]) continue;
        if (b->wrap && !rt->mem.persistent_initialized[b->resource]) {
            /* very first frame: nothing to wait for, contents undefined */
            src_stages = VK_PIPELINE_STAGE_2_NONE;
            src_access = 0;
            old_layout = VK_IMAGE_LAYOUT_UNDEFINED;
        }
        /* With frames in flight a barrier that waits for nothing (a transient's first use) would
         * not chain to the frame-start barrier: its layout transition could overwrite memory the
         * previous frame still reads (synchronization validation at queue submit reports it).
         * Its own stages make the chain. */
        if (!src_stages && rt->frames.n_in_flight > 1) src_stages = b->dst_stages;
        if (b->is_image) {
            ib[ni++] = pg_image_barrier(r->image, pg_vk_aspect(r->format), src_stages, src_access, b->dst_stages,
                                        b->dst_access, (VkImageLayout)old_layout, (VkImageLayout)b->new_layout);
        } else {
            bb[nb++] = pg_buffer_barrier(r->buffer, src_stages, src_access, b->dst_stages, b->dst_access);
        }
    }
    pg_cmd_barriers(cmd, ni, ib, nb, bb);
}

static uint32_t queue_family(const pg_runtime *rt, pg_queue q)
{
    return q == PG_QUEUE_COMPUTE ? rt->cfg.gpu->compute_family : rt->cfg.gpu->queue_family;
}

/* The release (at the end of batch b) or acquire (at its start) halves of the plan's ownership
 * transfers: same layouts in both; the release's destination and the acquire's source access
 * are empty (the semaphore between the batches orders them; the acquire's source stages are its
 * destination stages, which the batch's semaphore wait covers, so the chain holds). */
static void emit_qfots(pg_runtime *rt, VkCommandBuffer cmd, uint32_t b, bool release)
{
    const pg_graph_plan *plan = rt->cur.plan;
    VkImageMemoryBarrier2 ib[PG_MAX_RESOURCES];
    VkBufferMemoryBarrier2 bb[PG_MAX_RESOURCES];
    uint32_t ni = 0, nb = 0;
    for (uint32_t i = 0; i < plan->n_qfots; i++) {
        const pg_qfot *t = &plan->qfots[i];
        if ((release ? t->release_batch : t->acquire_batch) != (int)b) continue;
        const pg_phys_resource *r = &rt->mem.res[t->resource];
        const uint64_t ss = release ? t->src_stages : t->dst_stages, sa = release ? t->src_access : 0;
        const uint64_t ds = release ? VK_PIPELINE_STAGE_2_NONE : t->dst_stages, da = release ? 0 : t->dst_access;
        const uint32_t sf = queue_family(rt, t->src_queue), df = queue_family(rt, t->dst_queue);
        if (t->is_image && ni < PG_MAX_RESOURCES) {
            VkImageMemoryBarrier2 x = pg_image_barrier(r->image, pg_vk_aspect(r->format), ss, sa, ds, da,
                                                       (VkImageLayout)t->old_layout, (VkImageLayout)t->new_layout);
            x.srcQueueFamilyIndex = sf;
            x.dstQueueFamilyIndex = df;
            ib[ni++] = x;
        } else if (!t->is_image && nb < PG_MAX_RESOURCES) {
            VkBufferMemoryBarrier2 x = pg_buffer_barrier(r->buffer, ss, sa, ds, da);
            x.srcQueueFamilyIndex = sf;
            x.dstQueueFamilyIndex = df;
            bb[nb++] = x;
        }
    }
    if (ni || nb) pg_cmd_barriers(cmd, ni, ib, nb, bb);
}

/* Whether a slot's load op suits its declaration; a full write begun with LOAD_OP_LOAD fails the
 * frame (nothing is submitted) and returns true: the caller then records a clear, so that even the
 * never-submitted commands stay valid (the layer checks a load against the barrier at record time). */
static bool check_load_op(const pg_pass_record_ctx *ctx, uint32_t slot, bool clears)
{
    if (!ctx->record_error || ctx->record_error->msg[0] || !ctx->pass || slot >= ctx->pass->n_slots) return false;
    const pg_slot_decl *d = &ctx->pass->slots[slot].decl;
    const bool full = d->access == PG_ACCESS_COLOR_WRITE || d->access == PG_ACCESS_DEPTH_WRITE;
    const bool loads = d->access == PG_ACCESS_COLOR_RMW || d->access == PG_ACCESS_DEPTH_RMW ||
                       d->access == PG_ACCESS_DEPTH_READ;
    if (!full && !loads)
        pg_fail(ctx->record_error, PG_ERR_INVALID_ARG,
                "pass '%s': slot '%s' is declared %s, not an attachment, but rendering begins on it", ctx->pass->name,
                d->name, pg_access_name(d->access));
    else if (full && !clears) {
        pg_fail(ctx->record_error, PG_ERR_INVALID_ARG,
                "pass '%s': slot '%s' is declared %s (a full write) but rendering begins with LOAD_OP_LOAD: "
                "clear it, or declare a read-modify-write",
                ctx->pass->name, d->name, pg_access_name(d->access));
        return true;
    }
    else if (loads && clears)
        pg_fail(ctx->record_error, PG_ERR_INVALID_ARG,
                "pass '%s': slot '%s' is declared %s (it loads the contents) but rendering begins with "
                "LOAD_OP_CLEAR: load it, or declare a full write",
                ctx->pass->name, d->name, pg_access_name(d->access));
    return false;
}

void pg_pass_begin_rendering(const pg_pass_record_ctx *ctx, uint32_t n_color, const uint32_t *color_slots,
                             const VkClearColorValue *clears, int depth_slot, bool clear_depth, float depth_clear)
{
    VkImageView views[8];
    static const VkClearColorValue zero[8];
    uint32_t w = 0, h = 0;
    if (n_color > 8) n_color = 8;
    for (uint32_t i = 0; i < n_color; i++) {
        const pg_phys_resource *r = ctx->slots[color_slots[i]];
        views[i] = r->view;
        if (!i) w = r->width, h = r->height;
        if (check_load_op(ctx, color_slots[i], clears != NULL)) clears = zero;
    }
    VkImageView dv = VK_NULL_HANDLE;
    if (depth_slot >= 0) {
        const pg_phys_resource *r = ctx->slots[depth_slot];
        dv = r->view;
        if (!n_color) w = r->width, h = r->height;
        if (check_load_op(ctx, (uint32_t)depth_slot, clear_depth)) clear_depth = true;
    }
    pg_cmd_begin_rendering(ctx->cmd, w, h, n_color, views, clears, dv, clear_depth, depth_clear);
}

void pg_rt_reports_due(pg_runtime *rt)
{
    rt->reports.due = true;
}

/* One pass: its timestamps, debug label, barriers and commands. */
static void record_pass(pg_runtime *rt, VkCommandBuffer cmd, uint32_t f, uint32_t o, pg_error *record_error)
{
    pg_gpu *gpu = rt->cfg.gpu;
    const pg_graph_plan *plan = rt->cur.plan;
    const int pi = plan->order[o];
    const pg_plan_pass *pass = &plan->passes[pi];
    pg_rt_timing_stamp(rt, cmd, f, pass->queue, o, false);
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
        .user = rt->cur.user.data,
        .frame_set = rt->frames.slot[f].frame_set,
        .frame = rt->frames.slot[f].frame,
        .frame_size = rt->cfg.frame_size,
        .width = rt->cur.width,
        .height = rt->cur.height,
        .record_error = record_error,
    };
    for (uint32_t s = 0; s < pass->n_slots; s++) ctx.slots[s] = &rt->mem.res[pass->slots[s].resource];
    pass->type->record(rt->mem.pass_state[pi], &ctx);
    if (gpu->cmd_end_label) gpu->cmd_end_label(cmd);
    pg_rt_timing_stamp(rt, cmd, f, pass->queue, o, true);
}

/* Batch b of slot f's frame: at a queue's first batch the frames-in-flight barrier and the
 * timestamp reset; the acquires, the passes, in the last batch the final barriers; the
 * releases; at a queue's last batch the timestamp copy; in the last batch the readbacks. */
static pg_result record_batch(pg_runtime *rt, uint32_t f, uint32_t b, bool first, bool last_of_queue, bool readback,
                              const void *frame_block, pg_error *record_error, pg_error *err)
{
    const pg_graph_plan *plan = rt->cur.plan;
    const pg_plan_batch *bt = &plan->batches[b];
    VkCommandBuffer cmd;
    pg_result r = pg_rt_frame_cmd(rt, f, b, &cmd, err);
    if (r) return r;
    if (first) {
        /* With frames in flight the previous frame may still run: the frames share the graph's
         * resources (persistent and transient bytes), so this frame's work on this queue starts
         * after all earlier work on it (one full barrier; submission order makes it cover
         * earlier submits). The compute queue's first batch also waits for the previous frame's
         * graphics work (prev_frame_wait). The compute queue gets the barrier with one frame in
         * flight too: the slot's fence is signalled by the graphics queue, whose last batch
         * waits for the compute queue's last one, so the host's wait on it orders the previous
         * frame's compute work through that timeline semaphore; the validation layer (Debian's
         * 1.3.239) does not follow that chain and, on an NVIDIA H100 with its separate compute
         * queue, reported cluster_assign's clears of its own masks and counters against the
         * previous frame's dispatches. The barrier states the order on the queue itself, at no
         * cost (the queue is idle there). lavapipe has one queue and emulates the second on it. */
        const bool frame_barrier = rt->frames.n_in_flight > 1 || bt->queue == PG_QUEUE_COMPUTE;
        if (frame_barrier && !rt->frames.test_no_frame_barrier) {
            emit_full_barrier(cmd);
            rt->stats.frame_barriers++;
        }
        pg_rt_timing_begin(rt, cmd, f, bt->queue);
        /* the caller's prologue (pg_runtime_set_frame_prologue), before every pass of the frame */
        if (bt->queue == PG_QUEUE_GRAPHICS && rt->cfg.prologue &&
            rt->cfg.prologue(rt->cfg.prologue_user, cmd, frame_block))
            pg_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                  VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT);
    }
    emit_qfots(rt, cmd, b, false); /* acquires */
    for (uint32_t o = bt->first; o < bt->first + bt->count; o++) record_pass(rt, cmd, f, o, record_error);
    if (bt->last) {
        if (plan->immediate) emit_full_barrier(cmd);
        emit_barriers(rt, cmd, plan->n_final_barriers, plan->final_barriers);
    }
    emit_qfots(rt, cmd, b, true); /* releases */
    if (last_of_queue) pg_rt_timing_copy(rt, cmd, f, bt->queue);
    if (bt->last) pg_rt_frame_record_readback(rt, cmd, f, readback);
    PG_VK_TRY(err, vkEndCommandBuffer(cmd));
    return PG_OK;
}

/* Step 2: every batch of slot f's frame. A pass that broke its declaration while recording
 * fails the frame (nothing is submitted). */
static pg_result record_frame(pg_runtime *rt, uint32_t f, bool readback, const void *frame_block, pg_error *err)
{
    const pg_graph_plan *plan = rt->cur.plan;
    /* the first and last batch of each queue (timestamp reset / copy, frames-in-flight barrier) */
    int first_of[PG_QUEUE_COUNT] = {-1, -1}, last_of[PG_QUEUE_COUNT] = {-1, -1};
    for (uint32_t b = 0; b < plan->n_batches; b++) {
        const int q = plan->batches[b].queue;
        if (first_of[q] < 0) first_of[q] = (int)b;
        last_of[q] = (int)b;
    }
    pg_error record_error = {0};
    for (uint32_t b = 0; b < plan->n_batches; b++) {
        const int q = plan->batches[b].queue;
        pg_result r = record_batch(rt, f, b, first_of[q] == (int)b, last_of[q] == (int)b, readback, frame_block,
                                   &record_error, err);
        if (r) return r;
    }
    if (record_error.msg[0]) {
        pg_rt_frame_drop_readback(rt);
        return pg_fail(err, record_error.code, "%s", record_error.msg);
    }
    return PG_OK;
}

/* Step 5: whether the pass reports can be read after this frame. They read what the passes'
 * host-visible buffers hold: only when no frame is in flight (idle, checked, never waited for),
 * else the passes may be writing them. But they must still arrive: after a new plan or a
 * growth, and at least every PG_REPORT_EVERY frames, wait for the frames in flight. */
static pg_result reports_readable(pg_runtime *rt, bool *idle, double *wait_ms, pg_error *err)
{
    pg_rt_reports *rp = &rt->reports;
    if (!*idle && (rp->due || rp->frames_unreported + 1 >= PG_REPORT_EVERY)) {
        double tw = pg_rt_now_ms();
        pg_result r = pg_runtime_wait_idle(rt, err);
        if (r) return r;
        *wait_ms += pg_rt_now_ms() - tw;
        rt->stats.report_waits++;
        *idle = true;
    }
    rp->due = false;
    rp->frames_unreported = *idle ? 0 : rp->frames_unreported + 1;
    return PG_OK;
}

/* Step 6: the pass reports into the stats (counters, notes) and the runtime's pending growth
 * (the growth requests replace those of the last reports read; applied between frames by
 * pg_runtime_apply_growth). */
static void read_reports(pg_runtime *rt, pg_frame_stats *stats)
{
    const pg_graph_plan *plan = rt->cur.plan;
    pg_rt_clear_growth(rt);
    for (uint32_t o = 0; o < plan->n_order; o++) {
        const pg_plan_pass *pass = &plan->passes[plan->order[o]];
        if (!pass->type->report) continue;
        pg_pass_report rep = {0};
        pass->type->report(rt->mem.pass_state[plan->order[o]], &rep);
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
            rt->reports.due = true; /* the frame after a growth shows whether it sufficed */
            pg_rt_request_growth(rt, ri, rep.grow[k].needed, rep.grow[k].max);
        }
    }
}

/* Step 7: the frame's stats: passes, batches, slot, waits, GPU times, reports, notes. */
static void fill_stats(pg_runtime *rt, uint32_t f, double t0, double wait_ms, bool idle, pg_frame_stats *stats)
{
    const pg_graph_plan *plan = rt->cur.plan;
    memset(stats, 0, sizeof *stats);
    stats->n_passes = plan->n_order;
    for (uint32_t o = 0; o < plan->n_order; o++) {
        pg_strlcpy(stats->pass_names[o], plan->passes[plan->order[o]].name, PG_NAME_MAX);
        stats->pass_queue[o] = (uint8_t)plan->passes[plan->order[o]].queue;
    }
    stats->n_batches = plan->n_batches;
    stats->frame = rt->frames.slot[f].frame_no;
    stats->in_flight = rt->frames.n_in_flight;
    stats->wait_ms = wait_ms;
    pg_rt_timing_fill_stats(rt, stats);
    stats->reports_valid = idle;
    if (!idle) rt->stats.reports_skipped++;
    if (idle) read_reports(rt, stats);
    if (rt->mem.grow_note[0] && stats->n_notes < 4)
        pg_strlcpy(stats->notes[stats->n_notes++], rt->mem.grow_note, sizeof stats->notes[0]);
    stats->cpu_ms = pg_rt_now_ms() - t0 - wait_ms;
}

/* The frame path goes one way: begin (wait for the slot, upload the frame block), record,
 * submit, settle (waits, timestamps), reports, stats. It never allocates memory or creates
 * pass instances: a growth the reports ask for waits for pg_runtime_apply_growth. */
pg_result pg_runtime_render(pg_runtime *rt, const void *frame_block, bool readback, pg_frame_stats *stats,
                            pg_error *err)
{
    if (!rt->mem.built) return pg_fail(err, PG_ERR_INVALID_ARG, "pg_runtime_render: no plan set");
    const double t0 = pg_rt_now_ms();
    double wait_ms = 0;
    uint32_t f;
    bool idle;
    pg_result r;
    if ((r = pg_rt_frame_begin(rt, frame_block, &f, &wait_ms, err))) return r;
    /* the content tags passes set while recording stand for work that is submitted: a frame that
     * fails before its submission gets the tags it started with back (a filtered environment was
     * tagged as written by a frame that never ran, and every later frame skipped its filter) */
    const uint32_t n_res = rt->cur.plan->n_resources;
    uint64_t tags[PG_MAX_RESOURCES];
    for (uint32_t i = 0; i < n_res; i++) tags[i] = rt->mem.res[i].content_tag;
    if (!(r = record_frame(rt, f, readback, frame_block, err))) r = pg_rt_frame_submit(rt, f, err);
    if (r) {
        for (uint32_t i = 0; i < n_res && rt->cur.plan; i++) rt->mem.res[i].content_tag = tags[i];
        return r;
    }
    if ((r = pg_rt_frame_settle(rt, f, readback, &wait_ms, &idle, err))) return r;
    pg_rt_mark_persistent_written(rt);
    if ((r = reports_readable(rt, &idle, &wait_ms, err))) return r;
    pg_frame_stats local_stats;
    fill_stats(rt, f, t0, wait_ms, idle, stats ? stats : &local_stats);
    return PG_OK;
}
