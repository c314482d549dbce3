/* graph_queues.c - async compute in the compiler: which queue each pass runs on, the submission
 * batches, the semaphore waits between them and the queue-family ownership transfers.
 *
 * Pure like the rest of the compiler (no Vulkan calls, only enum values). Two steps, called by
 * pg_graph_compile():
 *
 *   assign   (after lifetimes, before aliasing) each executed pass gets a queue:
 *              - a pass with attachments or vertex/fragment stages ("raster") runs on graphics;
 *                "queue": "compute" on it is an error;
 *              - "graphics" runs on graphics; "compute" on compute (a compute pass: every shader
 *                slot is compute-stage, no attachment);
 *              - "auto" (the default) runs on compute when it is a compute pass, none of the
 *                resources it touches was touched earlier in the frame by a graphics pass (and
 *                no "after" names one), it touches no persistent/imported resource and writes no
 *                output: light animation and cluster assignment, which then overlap the
 *                G-buffer / depth passes;
 *              - with one queue (pg_queue_caps.n_queues < 2), --async-compute off or
 *                --immediate everything runs on graphics and plan->queue_note says why.
 *            resources[r].queues records the queues that use r; phase 6 gives a transient used
 *            on both queues its own memory and packs the others per queue, so memory reuse never
 *            crosses queues.
 *   schedule (after barriers) batches are maximal runs of consecutive passes on one queue, cut
 *            where a pass needs a wait on the other queue's newer work (so the passes before the
 *            cut can overlap it); each batch waits for the newest batch of the other queue it
 *            depends on, at the stages of the dependent accesses (and of the barriers that chain
 *            through the wait); the frame's last batch is a graphics batch that also waits for
 *            the compute queue's last batch (the frame fence then covers both queues); the first
 *            compute batch waits for the previous frame's last graphics batch that touches a
 *            resource the compute queue uses. With queues of different families
 *            (pg_queue_caps.separate_family) every cross-queue use of a resource is an
 *            ownership transfer: a release at the end of the last batch that used it on the old
 *            queue and an acquire at the start of the consumer's batch, same old/new layout in
 *            both; the consumer's ordinary barrier on that resource is dropped (the acquire is
 *            the barrier). With one family only the semaphores and the ordinary barriers remain.
 */
#include "graph.h"

#include <stdio.h>
#include <string.h>
#include <vulkan/vulkan_core.h>

#define WRITE_BITS                                                                           \
    (VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |                 \
     VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT |       \
     VK_ACCESS_2_HOST_WRITE_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT |                             \
     VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT)

/* One resource as one pass touches it (its slots merged). */
typedef struct use {
    bool used, reads, writes;
    uint64_t stages, access;
    uint32_t layout;
} use;

static use use_of(const pg_plan_pass *pp, int r)
{
    use u = {0};
    for (uint32_t s = 0; s < pp->n_slots; s++) {
        const pg_plan_slot *sl = &pp->slots[s];
        if (sl->resource != r || sl->decl.unused) continue;
        u.used = true;
        u.reads |= sl->sync.reads;
        u.writes |= sl->sync.writes;
        u.stages |= sl->sync.stages;
        u.access |= sl->sync.access;
        u.layout = sl->sync.layout;
    }
    return u;
}

static bool is_attachment(pg_access a)
{
    return a == PG_ACCESS_COLOR_WRITE || a == PG_ACCESS_COLOR_RMW || a == PG_ACCESS_DEPTH_WRITE ||
           a == PG_ACCESS_DEPTH_RMW || a == PG_ACCESS_DEPTH_READ;
}

/* "" for a compute pass, else why it is raster (a graphics-queue pass). */
static void raster_reason(const pg_plan_pass *pp, char *buf, size_t n)
{
    buf[0] = 0;
    bool compute_stage = false;
    for (uint32_t s = 0; s < pp->n_slots; s++) {
        const pg_slot_decl *d = &pp->slots[s].decl;
        if (is_attachment(d->access)) {
            snprintf(buf, n, "slot '%s' is an attachment (%s)", d->name, pg_access_name(d->access));
            return;
        }
        if (d->access == PG_ACCESS_VERTEX_INPUT) {
            snprintf(buf, n, "slot '%s' is a vertex stream (vertex_input)", d->name);
            return;
        }
        /* copies to or from a depth aspect are for graphics queues only (vkCmdCopy*Image*) */
        if ((d->access == PG_ACCESS_TRANSFER_DST || d->access == PG_ACCESS_TRANSFER_SRC) &&
            (d->formats & PG_FMTCLASS_DEPTH)) {
            snprintf(buf, n, "slot '%s' copies a depth image (%s)", d->name, pg_access_name(d->access));
            return;
        }
        const bool shader = d->access == PG_ACCESS_SAMPLED || d->access == PG_ACCESS_STORAGE_READ ||
                            d->access == PG_ACCESS_STORAGE_WRITE || d->access == PG_ACCESS_STORAGE_RW ||
                            d->access == PG_ACCESS_UNIFORM;
        if (shader && (d->stages & (PG_STAGE_VERTEX | PG_STAGE_FRAGMENT))) {
            snprintf(buf, n, "slot '%s' is used in vertex/fragment shaders", d->name);
            return;
        }
        if (shader && (d->stages & PG_STAGE_COMPUTE)) compute_stage = true;
    }
    if (!compute_stage) snprintf(buf, n, "no slot is used by a compute shader");
}

static const char *pass_file(const pg_compile_desc *desc, int i)
{
    const pg_pass_desc *p = &desc->pipeline->passes[i];
    if (p->file[0]) return p->file;
    if (desc->pipeline->path[0]) return desc->pipeline->path;
    return "<pipeline>";
}

static void pass_path(const pg_compile_desc *desc, int i, char *buf, size_t n)
{
    const pg_pass_desc *p = &desc->pipeline->passes[i];
    if (p->json_path[0]) snprintf(buf, n, "%s.queue", p->json_path);
    else snprintf(buf, n, "passes[%d].queue", i);
}

static bool names_after(const pg_pass_desc *pd, const char *name)
{
    for (uint32_t k = 0; k < pd->n_after && k < PG_MAX_AFTER; k++)
        if (!strcmp(pd->after[k], name)) return true;
    return false;
}

pg_result pg_queues_assign(pg_graph_plan *plan, const pg_compile_desc *desc, pg_error *err);
pg_result pg_queues_assign(pg_graph_plan *plan, const pg_compile_desc *desc, pg_error *err)
{
    const pg_pipeline *pl = desc->pipeline;
    const pg_queue_caps *caps = &desc->queues;
    bool two = caps->n_queues >= 2 && !caps->async_off && !desc->immediate;
    plan->queue_note[0] = 0;
    if (caps->n_queues < 2)
        snprintf(plan->queue_note, sizeof plan->queue_note, "one queue: %s",
                 caps->why_single[0] ? caps->why_single : "the device has no second compute-capable queue");
    else if (caps->async_off)
        snprintf(plan->queue_note, sizeof plan->queue_note, "one queue: --async-compute off");
    else if (desc->immediate)
        snprintf(plan->queue_note, sizeof plan->queue_note, "one queue: --immediate");
    for (uint32_t p = 0; p < plan->n_passes; p++) {
        plan->passes[p].queue = PG_QUEUE_GRAPHICS;
        plan->passes[p].batch = -1;
        plan->passes[p].queue_reason[0] = 0;
    }
    /* graphics-queue uses so far, per resource (the pass that made it) */
    int gfx_user[PG_MAX_RESOURCES];
    for (uint32_t r = 0; r < PG_MAX_RESOURCES; r++) gfx_user[r] = -1;
    uint32_t n_compute = 0;
    for (uint32_t k = 0; k < plan->n_order; k++) {
        const int p = plan->order[k];
        pg_plan_pass *pp = &plan->passes[p];
        const pg_pass_desc *pd = &pl->passes[pp->desc_index];
        char raster[96], path[PG_JSON_PATH_MAX + 16];
        raster_reason(pp, raster, sizeof raster);
        pass_path(desc, pp->desc_index, path, sizeof path);
        /* what keeps it off the compute queue, or "" */
        char block[128] = "";
        for (uint32_t r = 0; r < plan->n_resources && !block[0]; r++) {
            const use u = use_of(pp, (int)r);
            if (!u.used) continue;
            const pg_plan_resource *pr = &plan->resources[r];
            if (pr->is_output && u.writes)
                snprintf(block, sizeof block, "it writes output '%s' (outputs stay on the graphics queue)", pr->name);
            else if (pr->is_output)
                snprintf(block, sizeof block, "it reads output '%s' (outputs stay on the graphics queue)", pr->name);
            else if (pr->lifetime != PG_LIFETIME_TRANSIENT)
                snprintf(block, sizeof block,
                         "it uses %s resource '%s' (no ownership transfer across frames)",
                         pg_lifetime_name(pr->lifetime), pr->name);
        }
        if (pd->queue == PG_QUEUE_PREF_COMPUTE && raster[0])
            return pg_fail(err, PG_ERR_SCHEMA, "%s: %s: pass '%s' asks for the compute queue but is a raster pass: %s",
                           pass_file(desc, pp->desc_index), path, pp->name, raster);
        if (pd->queue == PG_QUEUE_PREF_COMPUTE && block[0])
            return pg_fail(err, PG_ERR_SCHEMA, "%s: %s: pass '%s' asks for the compute queue but %s",
                           pass_file(desc, pp->desc_index), path, pp->name, block);
        pg_queue q = PG_QUEUE_GRAPHICS;
        char why[sizeof pp->queue_reason] = "";
        const size_t wn = sizeof why;
        if (raster[0]) {
            snprintf(why, wn, "raster: %s", raster);
        } else if (pd->queue == PG_QUEUE_PREF_GRAPHICS) {
            snprintf(why, wn, "\"queue\": \"graphics\"");
        } else if (!two) {
            memcpy(why, plan->queue_note, wn - 1);
        } else if (pd->queue == PG_QUEUE_PREF_COMPUTE) {
            q = PG_QUEUE_COMPUTE;
            snprintf(why, wn, "\"queue\": \"compute\"");
        } else {
            /* auto: does it depend on the graphics queue's work of this frame? */
            for (uint32_t r = 0; r < plan->n_resources && !why[0]; r++)
                if (use_of(pp, (int)r).used && gfx_user[r] >= 0)
                    snprintf(why, wn, "auto: '%s' comes from graphics pass '%s'", plan->resources[r].name,
                             plan->passes[gfx_user[r]].name);
            for (uint32_t j = 0; j < k && !why[0]; j++) {
                const pg_plan_pass *qp = &plan->passes[plan->order[j]];
                if (qp->queue == PG_QUEUE_GRAPHICS && names_after(pd, qp->name))
                    snprintf(why, wn, "auto: \"after\" names graphics pass '%s'", qp->name);
            }
            if (!why[0] && block[0]) snprintf(why, wn, "auto: %s", block);
            if (!why[0]) {
                q = PG_QUEUE_COMPUTE;
                snprintf(why, wn, "auto: a compute pass whose inputs come from no graphics pass");
            }
        }
        pp->queue = q;
        memcpy(pp->queue_reason, why, sizeof why);
        if (q == PG_QUEUE_COMPUTE) n_compute++;
        for (uint32_t r = 0; r < plan->n_resources; r++) {
            const use u = use_of(pp, (int)r);
            if (!u.used) continue;
            plan->resources[r].queues |= (uint8_t)(1u << q);
            /* the pass the reason names: the last graphics pass that wrote it (the first user was
             * named: 'base' where 'add' wrote the image last), else the first that used it */
            if (q == PG_QUEUE_GRAPHICS && (gfx_user[r] < 0 || u.writes)) gfx_user[r] = p;
        }
    }
    plan->async = n_compute > 0;
    plan->qfot = plan->async && caps->separate_family;
    if (two && !plan->async)
        snprintf(plan->queue_note, sizeof plan->queue_note, "one queue: no pass can run on the compute queue");
    return PG_OK;
}

/* Does pass b (later) depend on pass a (earlier, the other queue)? */
static bool depends(const pg_graph_plan *plan, const pg_compile_desc *desc, int a, int b, bool qfot)
{
    const pg_plan_pass *pa = &plan->passes[a], *pb = &plan->passes[b];
    if (names_after(&desc->pipeline->passes[pb->desc_index], pa->name)) return true;
    for (uint32_t r = 0; r < plan->n_resources; r++) {
        const use ua = use_of(pa, (int)r), ub = use_of(pb, (int)r);
        if (!ua.used || !ub.used) continue;
        if (ua.writes || ub.writes || qfot) return true;
        if (plan->resources[r].kind == PG_RES_IMAGE && ua.layout != ub.layout) return true;
    }
    return false;
}

/* The stages of pass b that wait for pass a's queue: its accesses to the shared resources and
 * the source stages of its barriers on them (they chain through the semaphore wait). */
static uint64_t wait_stages(const pg_graph_plan *plan, int a, int b, char *why, size_t wn)
{
    const pg_plan_pass *pa = &plan->passes[a], *pb = &plan->passes[b];
    uint64_t st = 0;
    for (uint32_t r = 0; r < plan->n_resources; r++) {
        const use ua = use_of(pa, (int)r), ub = use_of(pb, (int)r);
        if (!ua.used || !ub.used) continue;
        st |= ub.stages;
        for (uint32_t i = 0; i < pb->n_barriers; i++)
            if (pb->barriers[i].resource == (int)r) st |= pb->barriers[i].src_stages | pb->barriers[i].dst_stages;
        size_t len = strlen(why);
        if (strstr(why, plan->resources[r].name)) continue;
        if (len + 2 < wn)
            snprintf(why + len, wn - len, "%s%s", len ? ", " : "", plan->resources[r].name);
    }
    if (!st) st = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT; /* an "after" edge */
    return st;
}

static void add_wait(pg_plan_batch *b, int batch, uint64_t stages, const char *why)
{
    for (uint32_t i = 0; i < b->n_waits; i++)
        if ((strcmp(b->waits[i].why, "join") == 0) == (strcmp(why, "join") == 0)) {
            if (batch > b->waits[i].batch) b->waits[i].batch = batch;
            b->waits[i].stages |= stages;
            size_t len = strlen(b->waits[i].why);
            if (why[0] && !strstr(b->waits[i].why, why) && len + 3 < sizeof b->waits[i].why)
                snprintf(b->waits[i].why + len, sizeof b->waits[i].why - len, "; %s", why);
            return;
        }
    if (b->n_waits < 2) {
        pg_batch_wait *w = &b->waits[b->n_waits++];
        w->batch = batch;
        w->stages = stages;
        pg_strlcpy(w->why, why, sizeof w->why);
    }
}

/* A compute-only queue family supports these stages and accesses: a barrier recorded there must
 * not name the graphics stages of work that ran on the other queue (the ownership transfer and
 * the semaphore ordered that work already). */
static const uint64_t k_compute_family_stages =
    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT |
    VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT | VK_PIPELINE_STAGE_2_HOST_BIT |
    VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT | VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT | VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT;

static void compute_family_masks(pg_barrier *b)
{
    const uint64_t st = k_compute_family_stages;
    const uint64_t ac = VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_SHADER_WRITE_BIT |
                        VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_UNIFORM_READ_BIT |
                        VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT |
                        VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_HOST_READ_BIT | VK_ACCESS_2_HOST_WRITE_BIT |
                        VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    b->src_stages &= st;
    b->src_access &= ac;
    b->dst_stages &= st;
    b->dst_access &= ac;
}

static void remove_barrier(pg_plan_pass *pp, uint32_t i)
{
    memmove(&pp->barriers[i], &pp->barriers[i + 1], sizeof pp->barriers[0] * (pp->n_barriers - i - 1));
    pp->n_barriers--;
}

/* the newest batch of the other queue that pass order[k] depends on (-1: none) */
static int needed_batch(const pg_graph_plan *plan, const pg_compile_desc *desc, uint32_t k)
{
    const int p = plan->order[k];
    const pg_plan_pass *pp = &plan->passes[p];
    int need = -1;
    for (uint32_t j = 0; j < k; j++) {
        const int a = plan->order[j];
        if (plan->passes[a].queue == pp->queue) continue;
        if (plan->passes[a].batch > need && depends(plan, desc, a, p, plan->qfot)) need = plan->passes[a].batch;
    }
    return need;
}

/* a new batch on `queue` from order[k] on; a batch after a cut on the same queue already waited
 * for what the earlier batch did (waited[]: newest batch of the other queue each batch waits for) */
static pg_plan_batch *open_batch(pg_graph_plan *plan, uint32_t k, pg_queue queue, int *waited)
{
    pg_plan_batch *cur = &plan->batches[plan->n_batches];
    memset(cur, 0, sizeof *cur);
    cur->queue = queue;
    cur->first = k;
    cur->prev_frame_wait = -1;
    waited[plan->n_batches] = -1;
    for (int b = (int)plan->n_batches - 1; b >= 0; b--)
        if (plan->batches[b].queue == queue) {
            waited[plan->n_batches] = waited[b];
            break;
        }
    plan->n_batches++;
    return cur;
}

/* batch `cur` waits for batch `need` at the stages of pass order[k] that wait, for every
 * other-queue pass it depends on */
static void add_pass_wait(const pg_graph_plan *plan, const pg_compile_desc *desc, uint32_t k, pg_plan_batch *cur,
                          int need)
{
    const int p = plan->order[k];
    const pg_plan_pass *pp = &plan->passes[p];
    char why[64] = "";
    uint64_t st = 0;
    for (uint32_t j = 0; j < k; j++) {
        const int a = plan->order[j];
        if (plan->passes[a].queue != pp->queue && depends(plan, desc, a, p, plan->qfot))
            st |= wait_stages(plan, a, p, why, sizeof why);
    }
    /* a compute-queue batch waits at stages its family has: the graphics stages of the other
     * queue's barriers are no wait stage there (color_output in a compute submit's wait) */
    if (pp->queue == PG_QUEUE_COMPUTE) st = (st & k_compute_family_stages) ? (st & k_compute_family_stages)
                                                                           : VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    char w2[64];
    snprintf(w2, sizeof w2, "%s: %s", pp->name, why);
    add_wait(cur, need, st, w2);
}

/* the passes in order cut into batches: a new one at a queue change, or when a pass needs a
 * newer batch of the other queue than its batch waits for */
static void cut_batches(pg_graph_plan *plan, const pg_compile_desc *desc)
{
    /* newest batch of the other queue each batch waits for (-1: none) */
    int waited[PG_MAX_BATCHES];
    for (uint32_t k = 0; k < plan->n_order; k++) {
        pg_plan_pass *pp = &plan->passes[plan->order[k]];
        const int need = needed_batch(plan, desc, k);
        pg_plan_batch *cur = plan->n_batches ? &plan->batches[plan->n_batches - 1] : NULL;
        if (!cur || cur->queue != pp->queue || (need >= 0 && need > waited[plan->n_batches - 1]))
            cur = open_batch(plan, k, pp->queue, waited);
        const int bi = (int)plan->n_batches - 1;
        cur->count++;
        pp->batch = bi;
        if (need >= 0) {
            add_pass_wait(plan, desc, k, cur, need);
            if (need > waited[bi]) waited[bi] = need;
        }
    }
}

/* the frame ends on the graphics queue (an empty batch when the last is a compute one), joined
 * with the compute queue's last batch */
static void end_on_graphics(pg_graph_plan *plan)
{
    int last_compute = -1;
    for (uint32_t b = 0; b < plan->n_batches; b++)
        if (plan->batches[b].queue == PG_QUEUE_COMPUTE) last_compute = (int)b;
    if (!plan->n_batches || plan->batches[plan->n_batches - 1].queue != PG_QUEUE_GRAPHICS) {
        pg_plan_batch *e = &plan->batches[plan->n_batches++];
        memset(e, 0, sizeof *e);
        e->queue = PG_QUEUE_GRAPHICS;
        e->first = plan->n_order;
        e->prev_frame_wait = -1;
    }
    pg_plan_batch *lastb = &plan->batches[plan->n_batches - 1];
    lastb->last = true;
    int lw = -1;
    for (uint32_t i = 0; i < lastb->n_waits; i++)
        if (lastb->waits[i].batch > lw) lw = lastb->waits[i].batch;
    if (last_compute >= 0 && lw < last_compute) add_wait(lastb, last_compute, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, "join");
}

/* frame k + 1's compute work after frame k's graphics work on the shared resources: the first
 * compute batch waits for the last graphics batch that uses a resource of both queues */
static void wait_previous_frame(pg_graph_plan *plan)
{
    int first_compute = -1, prev = -1;
    for (uint32_t b = 0; b < plan->n_batches; b++) {
        const pg_plan_batch *bt = &plan->batches[b];
        if (bt->queue == PG_QUEUE_COMPUTE) {
            if (first_compute < 0) first_compute = (int)b;
            continue;
        }
        for (uint32_t o = bt->first; o < bt->first + bt->count; o++)
            for (uint32_t r = 0; r < plan->n_resources; r++)
                if ((plan->resources[r].queues & 3u) == 3u && use_of(&plan->passes[plan->order[o]], (int)r).used)
                    prev = (int)b;
    }
    if (first_compute >= 0) plan->batches[first_compute].prev_frame_wait = prev;
}

/* each resource's owning queue, its last batch, its accesses since it changed hands, its layout */
typedef struct ownership {
    int owner[PG_MAX_RESOURCES], last_batch[PG_MAX_RESOURCES];
    uint64_t acc_st[PG_MAX_RESOURCES], acc_ac[PG_MAX_RESOURCES];
    uint32_t layout[PG_MAX_RESOURCES];
} ownership;

/* resource r changes hands at pass p (use u): a transfer released after its last batch on the
 * old queue and acquired by p, whose barrier on r it replaces */
static void add_qfot(pg_graph_plan *plan, const ownership *ow, int p, uint32_t r, const use *u)
{
    pg_plan_pass *pp = &plan->passes[p];
    pg_qfot *t = &plan->qfots[plan->n_qfots++];
    memset(t, 0, sizeof *t);
    t->resource = (int)r;
    t->is_image = plan->resources[r].kind == PG_RES_IMAGE;
    t->src_queue = (pg_queue)ow->owner[r];
    t->dst_queue = pp->queue;
    t->release_batch = ow->last_batch[r];
    t->acquire_batch = pp->batch;
    t->consumer_pass = p;
    t->src_stages = ow->acc_st[r];
    t->src_access = ow->acc_ac[r] & WRITE_BITS;
    t->dst_stages = u->stages;
    t->dst_access = u->access;
    t->old_layout = t->new_layout = t->is_image ? ow->layout[r] : 0;
    if (t->is_image) t->new_layout = u->layout;
    /* the acquire is the consumer's barrier on r */
    for (uint32_t i = 0; i < pp->n_barriers; i++)
        if (pp->barriers[i].resource == (int)r) {
            if (t->is_image) t->old_layout = pp->barriers[i].old_layout;
            remove_barrier(pp, i);
            break;
        }
}

/* ownership transfers: walk the frame with each resource's owning queue */
static void ownership_transfers(pg_graph_plan *plan)
{
    ownership ow;
    for (uint32_t r = 0; r < plan->n_resources; r++) ow.owner[r] = -1;
    for (uint32_t k = 0; k < plan->n_order; k++) {
        const int p = plan->order[k];
        const pg_plan_pass *pp = &plan->passes[p];
        for (uint32_t r = 0; r < plan->n_resources; r++) {
            const use u = use_of(pp, (int)r);
            if (!u.used) continue;
            if (ow.owner[r] >= 0 && ow.owner[r] != (int)pp->queue && plan->n_qfots < PG_MAX_QFOTS) {
                add_qfot(plan, &ow, p, r, &u);
                ow.owner[r] = (int)pp->queue;
                ow.acc_st[r] = u.stages;
                ow.acc_ac[r] = u.access;
            } else if (ow.owner[r] < 0) {
                ow.owner[r] = (int)pp->queue;
                ow.acc_st[r] = u.stages;
                ow.acc_ac[r] = u.access;
            } else {
                ow.acc_st[r] |= u.stages;
                ow.acc_ac[r] |= u.access;
            }
            ow.last_batch[r] = pp->batch;
            ow.layout[r] = u.layout;
        }
    }
    for (uint32_t k = 0; k < plan->n_order; k++) {
        pg_plan_pass *pp = &plan->passes[plan->order[k]];
        if (pp->queue != PG_QUEUE_COMPUTE) continue;
        for (uint32_t i = 0; i < pp->n_barriers; i++) compute_family_masks(&pp->barriers[i]);
    }
}

/* One family (semaphores, no ownership transfer): a barrier with a layout transition in a batch
 * that waits for the other queue chains to the wait only if its source stages include the stages
 * the batch waits at. Its source stages were those of the resource's last use, on the other
 * queue (color_output before a compute-queue batch waiting at compute_shader): the transition was
 * not ordered after the wait, and could run while the other queue still wrote the image. The
 * wait's stages are added (the semaphore makes the writes available and visible). */
static void chain_transitions_to_waits(pg_graph_plan *plan)
{
    for (uint32_t k = 0; k < plan->n_order; k++) {
        pg_plan_pass *pp = &plan->passes[plan->order[k]];
        if (pp->batch < 0 || pp->batch >= (int)plan->n_batches) continue;
        const pg_plan_batch *b = &plan->batches[pp->batch];
        uint64_t wait = 0;
        for (uint32_t w = 0; w < b->n_waits; w++) wait |= b->waits[w].stages;
        if (!wait) continue;
        for (uint32_t i = 0; i < pp->n_barriers; i++) {
            pg_barrier *br = &pp->barriers[i];
            if (br->old_layout != br->new_layout && br->src_stages && !(br->src_stages & wait)) br->src_stages |= wait;
        }
    }
}

void pg_queues_schedule(pg_graph_plan *plan, const pg_compile_desc *desc);
/* The two-queue schedule: batches and their semaphore waits, the frame's end and the wait on the
 * previous frame, then (separate families) the ownership transfers. */
void pg_queues_schedule(pg_graph_plan *plan, const pg_compile_desc *desc)
{
    plan->n_batches = 0;
    plan->n_qfots = 0;
    cut_batches(plan, desc);
    end_on_graphics(plan);
    wait_previous_frame(plan);
    if (plan->qfot) ownership_transfers(plan);
    else chain_transitions_to_waits(plan);
}
