/* graph_barriers.c - compile phase 7 (barriers); see graph_compile.c. */
#include "graph_compile_internal.h"

#include <string.h>
#include <vulkan/vulkan_core.h>

/* ------------------------------------------------------------------------------------------ */
/* 7. barriers                                                                                */

typedef struct access_req {
    uint64_t stages, access;
    uint32_t layout;
    bool reads, writes;
} access_req;

static access_req req_of(const pass_use *u)
{
    access_req a = {u->stages, u->access, u->layout, u->reads, u->writes};
    return a;
}

static bool visible_to(const res_state *s, const access_req *a)
{
    for (uint32_t k = 0; k < s->n_vis; k++)
        if ((a->stages & ~s->vis_stages[k]) == 0 && (a->access & ~s->vis_access[k]) == 0)
            return true;
    return false;
}

static void add_visible(res_state *s, uint64_t stages, uint64_t access)
{
    if (s->n_vis == MAX_VISIBLE) { /* forget the oldest: at worst one barrier too many */
        memmove(s->vis_stages, s->vis_stages + 1, sizeof s->vis_stages[0] * (MAX_VISIBLE - 1));
        memmove(s->vis_access, s->vis_access + 1, sizeof s->vis_access[0] * (MAX_VISIBLE - 1));
        s->n_vis--;
    }
    s->vis_stages[s->n_vis] = stages;
    s->vis_access[s->n_vis] = access;
    s->n_vis++;
}

/* State after access a (barrier: one was placed right before it; layout_change: it did a layout
 * transition).
 *  - A write becomes the last write; earlier reads are ordered before it (the barrier that
 *    allowed the write waited for them) and nothing has seen it yet: visibility is EMPTY. (Even
 *    the same stages in a later pass need a barrier: e.g. compute storage write, then a compute
 *    storage read in the next dispatch.)
 *  - A read joins the readers; if a barrier brought the last write to it, its (stages, access)
 *    pair now sees the write. A layout transition is itself a write to the image, so after one
 *    only the transition's destination scope is known to see it, and later barriers must chain
 *    through those stages (tracked by "transitioned"). */
static void apply_access(res_state *s, const access_req *a, bool barrier, bool layout_change)
{
    s->seen = true;
    if (a->writes) {
        s->w_valid = true;
        s->w_stages = a->stages;
        s->w_access = a->access & WRITE_ACCESS_BITS;
        if (!s->w_access) s->w_access = a->access;
        s->r_stages = s->r_access = 0;
        s->transitioned = false;
        s->n_vis = 0;
    } else {
        s->r_stages |= a->stages;
        s->r_access |= a->access;
        if (barrier) {
            if (layout_change) {
                s->transitioned = true;
                s->n_vis = 0;
            }
            add_visible(s, a->stages, a->access);
        }
    }
    s->layout = a->layout;
}

/* Barrier rules for an access after the first one of the frame:
 *   layout change                     -> barrier (the transition must wait for earlier users)
 *   write after a write (WAW)         -> src = last write stages/access (+ readers since)
 *   write after reads (WAR)           -> src += reader stages (no access: reads need no flush)
 *   read of a write not yet visible   -> src = last write stages/access (RAW)
 * A read that changes layout (or follows a transition) also waits for the readers so far, so
 * the transition does not pull the image from under them and the chain of barriers holds.
 * Returns true and fills b when a barrier is needed. */
static bool decide_barrier(const res_state *s, const access_req *a, bool is_image, pg_barrier *b)
{
    const bool layout_change = is_image && s->layout != a->layout;
    const bool raw = a->reads && s->w_valid && (layout_change || !visible_to(s, a));
    const bool waw = a->writes && s->w_valid;
    const bool war = a->writes && s->r_stages != 0;
    if (!layout_change && !raw && !waw && !war) return false;
    b->src_stages = s->w_valid ? s->w_stages : 0;
    if (a->writes || layout_change || s->transitioned) b->src_stages |= s->r_stages;
    b->src_access = s->w_valid ? s->w_access : 0;
    b->dst_stages = a->stages;
    b->dst_access = a->access;
    b->old_layout = is_image ? s->layout : VK_IMAGE_LAYOUT_UNDEFINED;
    b->new_layout = is_image ? a->layout : VK_IMAGE_LAYOUT_UNDEFINED;
    char why[48] = "";
    const char *parts[4] = {raw ? "RAW" : NULL, waw ? "WAW" : NULL, war ? "WAR" : NULL,
                            layout_change ? "layout" : NULL};
    for (int k = 0; k < 4; k++)
        if (parts[k]) {
            if (why[0]) strncat(why, "+", sizeof why - strlen(why) - 1);
            strncat(why, parts[k], sizeof why - strlen(why) - 1);
        }
    pg_strlcpy(b->why, why, sizeof b->why);
    return true;
}

static pg_barrier new_barrier(int r, bool is_image)
{
    pg_barrier b;
    memset(&b, 0, sizeof b);
    b.resource = r;
    b.is_image = is_image;
    b.alias_prev = -1;
    return b;
}

static access_req output_req(const compile_ctx *c)
{
    access_req a = {0};
    a.layout = c->desc->output_layout ? c->desc->output_layout
                                      : (uint32_t)VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    a.reads = true;
    if (a.layout != VK_IMAGE_LAYOUT_PRESENT_SRC_KHR) { /* presentation waits on a semaphore */
        a.stages = c->desc->output_stages ? c->desc->output_stages : VK_PIPELINE_STAGE_2_COPY_BIT;
        a.access = VK_ACCESS_2_TRANSFER_READ_BIT;
    }
    return a;
}

static void push_barrier(pg_plan_pass *pp, const pg_barrier *b)
{
    /* one use per resource per pass and at most 2 * PG_MAX_SLOTS uses... */
    if (pp->n_barriers < PG_MAX_BARRIERS_PER_PASS) pp->barriers[pp->n_barriers++] = *b;
}

/* The first use in the frame of a persistent or imported resource (emit pass): the previous
 * frame's end state leads into it. A resource only read all frame long, in one layout, needs
 * nothing from frame to frame; a persistent image that is gets a first-frame barrier out of
 * UNDEFINED. */
static void persistent_first_use(compile_ctx *c, pg_plan_pass *pp, int r, const access_req *ap)
{
    const pg_plan_resource *pr = &c->plan->resources[r];
    const bool img = pr->kind == PG_RES_IMAGE;
    const access_req a = *ap;
    res_state *s = &c->st[r];
    pg_barrier b = new_barrier(r, img);
    *s = c->end[r];
    bool need = true;
    if (!s->w_valid && !a.writes && (!img || s->layout == a.layout)) need = false;
    if (!need && img && pr->lifetime == PG_LIFETIME_PERSISTENT) {
        /* nothing to wait for from frame to frame, but the image starts UNDEFINED: the
         * runtime records this barrier only until a frame has used it */
        b.wrap = b.first_frame = true;
        b.dst_stages = a.stages;
        b.dst_access = a.access;
        b.old_layout = VK_IMAGE_LAYOUT_UNDEFINED;
        b.new_layout = a.layout;
        pg_strlcpy(b.why, "first frame", sizeof b.why);
        push_barrier(pp, &b);
    }
    if (need) {
        b.wrap = true;
        b.src_stages = s->w_stages | s->r_stages;
        b.src_access = s->w_valid ? s->w_access : 0;
        b.dst_stages = a.stages;
        b.dst_access = a.access;
        b.old_layout = img ? s->layout : VK_IMAGE_LAYOUT_UNDEFINED;
        b.new_layout = img ? a.layout : VK_IMAGE_LAYOUT_UNDEFINED;
        pg_strlcpy(b.why, "frame wrap", sizeof b.why);
        push_barrier(pp, &b);
        /* The wrap barrier waited for every access of the last frame: later barriers in
         * this frame chain through it and need not name last frame's readers again. */
        s->r_stages = s->r_access = 0;
        s->n_vis = 0;
    }
    apply_access(s, &a, need, need && img && b.old_layout != b.new_layout);
}

/* Walks the frame. Pass 1 (emit = false) only finds each resource's end-of-frame state (after
 * the output barrier), which is the start state of persistent/imported resources in the next
 * frame. Pass 2 (emit = true) places the barriers. */
static void walk_frame(compile_ctx *c, bool emit)
{
    pg_graph_plan *plan = c->plan;
    memset(c->st, 0, sizeof c->st);
    for (uint32_t k = 0; k < plan->n_order; k++) {
        const int p = plan->order[k];
        pg_plan_pass *pp = &plan->passes[p];
        for (uint32_t i = 0; i < c->n_uses[p]; i++) {
            const pass_use *u = &c->uses[p][i];
            const int r = u->res;
            const pg_plan_resource *pr = &plan->resources[r];
            const bool img = pr->kind == PG_RES_IMAGE;
            res_state *s = &c->st[r];
            const access_req a = req_of(u);
            pg_barrier b = new_barrier(r, img);
            if (!emit && !s->seen) {
                apply_access(s, &a, true, true);
                continue;
            }
            if (s->seen) {
                bool need = decide_barrier(s, &a, img, &b);
                if (emit && need) push_barrier(pp, &b);
                apply_access(s, &a, need, need && img && b.old_layout != b.new_layout);
                continue;
            }
            /* first use in the frame (emit pass) */
            if (pr->lifetime == PG_LIFETIME_TRANSIENT) {
                /* Every earlier member of the block that ended before this use may share bytes
                 * with it at run time, unless it may not inherit (the runtime re-packs the block with the real memory
                 * requirements, only ever inside the block): wait for all their accesses (last
                 * write and the reads since) and discard the contents. alias_prev names the
                 * latest one that overlaps in the planned placement (else the latest one). */
                int prev = -1, prev_overlap = -1;
                uint64_t src_stages = 0, src_access = 0;
                if (pr->block >= 0 && pr->may_inherit) { /* else it shares no earlier byte */
                    const pg_plan_block *bl = &plan->blocks[pr->block];
                    for (uint32_t m = 0; m < bl->n_members; m++) {
                        const int q = bl->members[m];
                        const pg_plan_resource *qr = &plan->resources[q];
                        if (q == r || !(qr->last_pass < pr->first_pass)) continue;
                        src_stages |= c->st[q].w_stages | c->st[q].r_stages;
                        src_access |= c->st[q].w_access;
                        if (prev < 0 || qr->last_pass >= plan->resources[prev].last_pass) prev = q;
                        const bool overlap = qr->block_offset < pr->block_offset + pr->size_bytes &&
                                             pr->block_offset < qr->block_offset + qr->size_bytes;
                        if (overlap && (prev_overlap < 0 ||
                                        qr->last_pass >= plan->resources[prev_overlap].last_pass))
                            prev_overlap = q;
                    }
                }
                bool placed = false;
                if (prev >= 0) {
                    b.src_stages = src_stages;
                    b.src_access = src_access;
                    b.alias_prev = prev_overlap >= 0 ? prev_overlap : prev;
                    pg_strlcpy(b.why, "alias first use", sizeof b.why);
                    placed = true;
                } else if (img) {
                    /* nothing earlier in the frame: the contents are not needed */
                    pg_strlcpy(b.why, "first use", sizeof b.why);
                    placed = true;
                }
                if (placed) {
                    b.dst_stages = a.stages;
                    b.dst_access = a.access;
                    b.old_layout = VK_IMAGE_LAYOUT_UNDEFINED;
                    b.new_layout = img ? a.layout : VK_IMAGE_LAYOUT_UNDEFINED;
                    push_barrier(pp, &b);
                }
                memset(s, 0, sizeof *s);
                apply_access(s, &a, placed, img);
                continue;
            }
            persistent_first_use(c, pp, r, &a);
        }
    }
    /* after the last pass: the outputs go to the layout the caller reads them in */
    const access_req oa = output_req(c);
    const int outs[2] = {plan->output,
                         plan->hdr_output != plan->output ? plan->hdr_output : -1};
    for (int k = 0; k < 2; k++) {
        const int r = outs[k];
        if (r < 0) continue;
        res_state *s = &c->st[r];
        pg_barrier b = new_barrier(r, true);
        bool need = decide_barrier(s, &oa, true, &b);
        if (need && emit) {
            pg_strlcpy(b.why, "output", sizeof b.why);
            plan->final_barriers[plan->n_final_barriers++] = b;
        }
        apply_access(s, &oa, need, need && b.old_layout != b.new_layout);
    }
    if (!emit) memcpy(c->end, c->st, sizeof c->end);
}

void pg_gc_phase_barriers(compile_ctx *c)
{
    walk_frame(c, false);
    walk_frame(c, true);
}
