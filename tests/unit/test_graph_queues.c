/* test_graph_queues.c - async compute in the compiler (core/graph/graph_queues.c), no GPU.
 *
 * Fake pass types in a local registry, pipelines from JSON strings: queue assignment (auto,
 * "compute", "graphics", the errors), submission batches, semaphore waits (in the frame, the
 * previous frame, the join), queue-family ownership transfers (release/acquire pairs with the
 * layouts the producer left and the consumer needs, the consumer's ordinary barrier replaced),
 * no memory block shared across queues, and the single-queue fallback. The shipped pipelines are
 * compiled with the built-in pass types for the same invariants. */
#include "graph.h"
#include "graph_dump.h"
#include "pass_list.h"
#include "pipeline.h"
#include "fake_passes.h"
#include "scene_vars.h"
#include "test_util.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <vulkan/vulkan_core.h>

#define IMG PG_RES_IMAGE
#define BUF PG_RES_BUFFER
#define FRAG PG_STAGE_FRAGMENT
#define COMP PG_STAGE_COMPUTE

static pg_result d_anim(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_write(d, "lights", BUF, PG_ACCESS_STORAGE_WRITE, COMP, 0);
    return PG_OK;
}
static pg_result d_assign(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_read(d, "lights", BUF, PG_ACCESS_STORAGE_READ, COMP, 0);
    pg_decl_write(d, "clusters", BUF, PG_ACCESS_STORAGE_WRITE, COMP, 0);
    return PG_OK;
}
static pg_result d_raster(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_write(d, "color", IMG, PG_ACCESS_COLOR_WRITE, 0, PG_FMTCLASS_FLOAT);
    pg_decl_write(d, "depth", IMG, PG_ACCESS_DEPTH_WRITE, 0, PG_FMTCLASS_DEPTH);
    return PG_OK;
}
static pg_result d_light_cs(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_read(d, "clusters", BUF, PG_ACCESS_STORAGE_READ, COMP, 0);
    pg_decl_read(d, "depth", IMG, PG_ACCESS_SAMPLED, COMP, PG_FMTCLASS_DEPTH);
    pg_decl_write(d, "hdr", IMG, PG_ACCESS_STORAGE_WRITE, COMP, PG_FMTCLASS_ANY_COLOR);
    return PG_OK;
}
static pg_result d_show(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_read(d, "a", IMG, PG_ACCESS_SAMPLED, FRAG, PG_FMTCLASS_FLOAT);
    pg_decl_write(d, "color", IMG, PG_ACCESS_COLOR_WRITE, 0, PG_FMTCLASS_FLOAT);
    return PG_OK;
}
static pg_result d_stat(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_read(d, "lights", BUF, PG_ACCESS_STORAGE_READ, COMP, 0);
    return PG_OK;
}

#define TYPE(n, fn, rs, ws) {.name = n, .summary = "test type", .declare = fn} /* rs, ws: the slots, for the reader */
static const pg_pass_type g_types[] = {
    TYPE("q_anim", d_anim, "", "lights"),          TYPE("q_assign", d_assign, "lights", "clusters"),
    TYPE("q_noise", pg_fake_storage_write, "", "img"),           TYPE("q_raster", d_raster, "", "color, depth"),
    TYPE("q_light_cs", d_light_cs, "clusters, depth", "hdr"),
    TYPE("q_present2", pg_fake_compose2, "a, b", "color"), TYPE("q_show", d_show, "a", "color"),
    TYPE("q_stat", d_stat, "lights", ""),
};
static pg_pass_registry g_reg;

/* %s slots: the "queue" members of gbuf, anim and light (each "" or ', "queue": "..."') */
static const char *k_p1 =
    "{\"name\": \"p1\", \"output\": \"ldr\",\n"
    " \"resources\": [\n"
    "  {\"name\": \"lights\", \"type\": \"buffer\", \"stride\": 16, \"count\": [64]},\n"
    "  {\"name\": \"clusters\", \"type\": \"buffer\", \"stride\": 16, \"count\": [256]},\n"
    "  {\"name\": \"noise\", \"type\": \"image\", \"format\": \"rgba16f\"},\n"
    "  {\"name\": \"gcol\", \"type\": \"image\", \"format\": \"rgba16f\"},\n"
    "  {\"name\": \"depth\", \"type\": \"image\", \"format\": \"d32f\"},\n"
    "  {\"name\": \"hdr\", \"type\": \"image\", \"format\": \"rgba16f\"},\n"
    "  {\"name\": \"ldr\", \"type\": \"image\", \"format\": \"rgba8\"}],\n"
    " \"passes\": [\n"
    "  {\"name\": \"anim\", \"type\": \"q_anim\", \"writes\": [\"lights\"]%s},\n"
    "  {\"name\": \"assign\", \"type\": \"q_assign\", \"reads\": [\"lights\"], \"writes\": [\"clusters\"]},\n"
    "  {\"name\": \"noise\", \"type\": \"q_noise\", \"writes\": [\"noise\"]},\n"
    "  {\"name\": \"gbuf\", \"type\": \"q_raster\", \"writes\": [\"gcol\", \"depth\"]%s},\n"
    "  {\"name\": \"light\", \"type\": \"q_light_cs\", \"reads\": [\"clusters\", \"depth\"], \"writes\": [\"hdr\"]%s},\n"
    "  {\"name\": \"disp\", \"type\": \"q_present2\", \"reads\": [\"hdr\", \"noise\"], \"writes\": [\"ldr\"]}]}\n";

/* pl compiled at 64x36 for `lights` lights on the queues caps describes */
static pg_result compile_on(const pg_pipeline *pl, const pg_pass_registry *reg, pg_queue_caps caps, uint32_t lights,
                            pg_graph_plan **plan, pg_error *err)
{
    pg_compile_desc d = {.pipeline = pl, .registry = reg, .output_width = 64, .output_height = 36, .queues = caps};
    pg_scene_vars_set(&d.vars, NULL, lights, NULL);
    return pg_graph_compile(&d, plan, err);
}

/* two queues of different families (NVIDIA's case: ownership transfers) */
static const pg_queue_caps k_two_families = {.n_queues = 2, .separate_family = true};

static pg_result compile_p1(const char *q_anim, const char *q_gbuf, const char *q_light, pg_queue_caps caps,
                            pg_pipeline **pl, pg_graph_plan **plan, pg_error *err)
{
    char json[4096];
    snprintf(json, sizeof json, k_p1, q_anim, q_gbuf, q_light);
    *plan = NULL;
    pg_result r = pg_pipeline_load_string(json, "p1.json", NULL, 0, pl, err);
    if (r) return r;
    return compile_on(*pl, &g_reg, caps, 64, plan, err);
}

static const pg_plan_pass *pass_named(const pg_graph_plan *p, const char *name)
{
    for (uint32_t i = 0; i < p->n_passes; i++)
        if (!strcmp(p->passes[i].name, name)) return &p->passes[i];
    return NULL;
}
static int res_named(const pg_graph_plan *p, const char *name)
{
    for (uint32_t i = 0; i < p->n_resources; i++)
        if (!strcmp(p->resources[i].name, name)) return (int)i;
    return -1;
}
static const pg_qfot *qfot_of(const pg_graph_plan *p, const char *res)
{
    int r = res_named(p, res);
    for (uint32_t i = 0; i < p->n_qfots; i++)
        if (p->qfots[i].resource == r) return &p->qfots[i];
    return NULL;
}
static const pg_barrier *barrier_on(const pg_plan_pass *pp, int r)
{
    for (uint32_t i = 0; i < pp->n_barriers; i++)
        if (pp->barriers[i].resource == r) return &pp->barriers[i];
    return NULL;
}
static bool explains(const pg_graph_plan *p, const char *text)
{
    for (uint32_t i = 0; i < p->n_explain; i++)
        if (strstr(p->explain[i], text)) return true;
    return false;
}

/* The layout an image slot of pass pp has for resource r (0 when it has none). */
static uint32_t slot_layout(const pg_plan_pass *pp, int r)
{
    for (uint32_t s = 0; s < pp->n_slots; s++)
        if (pp->slots[s].resource == r && !pp->slots[s].decl.unused) return pp->slots[s].sync.layout;
    return 0;
}

/* Invariants of every two-queue plan. */
static void check_invariants(const pg_graph_plan *p, const char *what)
{
    /* every executed pass is in exactly one batch of its queue; batches cover the order */
    uint32_t covered = 0;
    for (uint32_t b = 0; b < p->n_batches; b++) {
        const pg_plan_batch *bt = &p->batches[b];
        CHECK_MSG(bt->first == covered, "%s: batch %u starts at %u, not %u", what, b, bt->first, covered);
        for (uint32_t o = bt->first; o < bt->first + bt->count; o++) {
            const pg_plan_pass *pp = &p->passes[p->order[o]];
            CHECK_MSG(pp->batch == (int)b && pp->queue == bt->queue, "%s: pass %s in batch %u", what, pp->name, b);
        }
        covered += bt->count;
        for (uint32_t w = 0; w < bt->n_waits; w++) {
            const int wb = bt->waits[w].batch;
            CHECK_MSG(wb >= 0 && wb < (int)b && p->batches[wb].queue != bt->queue && bt->waits[w].stages,
                      "%s: batch %u waits for batch %d", what, b, wb);
        }
        CHECK_MSG(bt->last == (b + 1 == p->n_batches), "%s: last flag of batch %u", what, b);
    }
    CHECK_MSG(covered == p->n_order, "%s: batches cover %u of %u passes", what, covered, p->n_order);
    /* a compute batch waits at stages a compute-only family has (not the color_output of a graphics
     * writer's barrier: an invalid vkQueueSubmit2 there) */
    const uint64_t compute_stages =
        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT |
        VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT | VK_PIPELINE_STAGE_2_HOST_BIT |
        VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT | VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT | VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT;
    for (uint32_t b = 0; b < p->n_batches; b++)
        for (uint32_t w = 0; p->batches[b].queue == PG_QUEUE_COMPUTE && w < p->batches[b].n_waits; w++)
            CHECK_MSG(!(p->batches[b].waits[w].stages & ~compute_stages), "%s: compute batch %u waits at 0x%llx", what,
                      b, (unsigned long long)p->batches[b].waits[w].stages);
    CHECK_MSG(p->n_batches && p->batches[p->n_batches - 1].queue == PG_QUEUE_GRAPHICS, "%s: ends on graphics", what);
    /* the last batch is after every compute batch (the frame fence covers both queues) */
    int last_c = -1, lw = -1;
    for (uint32_t b = 0; b < p->n_batches; b++)
        if (p->batches[b].queue == PG_QUEUE_COMPUTE) last_c = (int)b;
    const pg_plan_batch *lb = &p->batches[p->n_batches - 1];
    for (uint32_t w = 0; w < lb->n_waits; w++)
        if (lb->waits[w].batch > lw) lw = lb->waits[w].batch;
    CHECK_MSG(lw >= last_c, "%s: the last batch waits for batch %d, the last compute batch is %d", what, lw, last_c);
    /* a cross-queue dependency is always covered by a wait on a batch at least as new */
    for (uint32_t k = 0; k < p->n_order; k++)
        for (uint32_t j = 0; j < k; j++) {
            const pg_plan_pass *a = &p->passes[p->order[j]], *b = &p->passes[p->order[k]];
            if (a->queue == b->queue) continue;
            bool dep = false;
            for (uint32_t s = 0; s < a->n_slots && !dep; s++)
                for (uint32_t t = 0; t < b->n_slots && !dep; t++)
                    if (!a->slots[s].decl.unused && !b->slots[t].decl.unused &&
                        a->slots[s].resource == b->slots[t].resource &&
                        (a->slots[s].sync.writes || b->slots[t].sync.writes))
                        dep = true;
            if (!dep) continue;
            int best = -1; /* newest batch of a's queue waited by b's batch or an earlier one on b's queue */
            for (int x = 0; x <= b->batch; x++) {
                if (p->batches[x].queue != b->queue) continue;
                for (uint32_t w = 0; w < p->batches[x].n_waits; w++)
                    if (p->batches[x].waits[w].batch > best) best = p->batches[x].waits[w].batch;
            }
            CHECK_MSG(best >= a->batch, "%s: %s (batch %d) depends on %s (batch %d), waited only to batch %d", what,
                      b->name, b->batch, a->name, a->batch, best);
        }
    /* memory blocks never span queues; resources of both queues own their memory */
    for (uint32_t bl = 0; bl < p->n_blocks; bl++)
        for (uint32_t m = 0; m < p->blocks[bl].n_members; m++) {
            const pg_plan_resource *pr = &p->resources[p->blocks[bl].members[m]];
            CHECK_MSG(pr->queues == (1u << p->blocks[bl].queue), "%s: '%s' (queues %u) in block %u of the %s queue",
                      what, pr->name, pr->queues, bl, pg_queue_name(p->blocks[bl].queue));
        }
    /* ownership transfers: release on the old queue before the acquire on the new, layouts the
     * producer's last use left and the consumer's first use needs, no ordinary barrier left on the
     * consumer for that resource, and the acquiring batch waits for the releasing one */
    for (uint32_t i = 0; i < p->n_qfots; i++) {
        const pg_qfot *t = &p->qfots[i];
        CHECK_MSG(t->src_queue != t->dst_queue && t->release_batch < t->acquire_batch, "%s: qfot %u", what, i);
        CHECK(p->batches[t->release_batch].queue == t->src_queue);
        CHECK(p->batches[t->acquire_batch].queue == t->dst_queue);
        const pg_plan_pass *cons = &p->passes[t->consumer_pass];
        CHECK_MSG(!barrier_on(cons, t->resource), "%s: '%s' keeps a barrier next to its acquire", what,
                  p->resources[t->resource].name);
        int waited = -1;
        for (int x = 0; x <= t->acquire_batch; x++)
            if (p->batches[x].queue == t->dst_queue)
                for (uint32_t w = 0; w < p->batches[x].n_waits; w++)
                    if (p->batches[x].waits[w].batch > waited) waited = p->batches[x].waits[w].batch;
        CHECK_MSG(waited >= t->release_batch, "%s: acquire of '%s' in batch %d does not wait for batch %d", what,
                  p->resources[t->resource].name, t->acquire_batch, t->release_batch);
        if (t->is_image) {
            CHECK(t->new_layout == slot_layout(cons, t->resource));
            /* the producer: the last pass of the releasing batch that uses it */
            uint32_t prod = 0;
            const pg_plan_batch *rb = &p->batches[t->release_batch];
            for (uint32_t o = rb->first; o < rb->first + rb->count; o++)
                if (slot_layout(&p->passes[p->order[o]], t->resource)) prod = slot_layout(&p->passes[p->order[o]], t->resource);
            CHECK_MSG(t->old_layout == prod, "%s: release of '%s' from layout %s, producer left %s", what,
                      p->resources[t->resource].name, pg_layout_name(t->old_layout), pg_layout_name(prod));
        }
    }
}

static void test_auto_separate_families(void)
{
    pg_pipeline *pl = NULL;
    pg_graph_plan *p = NULL;
    pg_error err = {0};
    pg_queue_caps caps = k_two_families;
    CHECK_MSG(compile_p1("", "", "", caps, &pl, &p, &err) == PG_OK, "%s", err.msg);
    if (!p) goto out;
    CHECK(p->async && p->qfot);
    CHECK(pass_named(p, "anim")->queue == PG_QUEUE_COMPUTE);
    CHECK(pass_named(p, "assign")->queue == PG_QUEUE_COMPUTE);
    CHECK(pass_named(p, "noise")->queue == PG_QUEUE_COMPUTE);
    CHECK(pass_named(p, "gbuf")->queue == PG_QUEUE_GRAPHICS);
    CHECK_MSG(pass_named(p, "light")->queue == PG_QUEUE_GRAPHICS, "%s", pass_named(p, "light")->queue_reason);
    CHECK(strstr(pass_named(p, "light")->queue_reason, "'depth' comes from graphics pass 'gbuf'") != NULL);
    CHECK(pass_named(p, "disp")->queue == PG_QUEUE_GRAPHICS);
    /* batches: compute {anim, assign, noise}, graphics {gbuf} (overlaps), graphics {light, disp} */
    CHECK_MSG(p->n_batches == 3, "%u batches", p->n_batches);
    CHECK(p->batches[0].queue == PG_QUEUE_COMPUTE && p->batches[0].count == 3 && p->batches[0].n_waits == 0);
    CHECK(p->batches[1].queue == PG_QUEUE_GRAPHICS && p->batches[1].count == 1 && p->batches[1].n_waits == 0);
    CHECK(p->batches[2].queue == PG_QUEUE_GRAPHICS && p->batches[2].count == 2 && p->batches[2].last);
    CHECK(p->batches[2].n_waits == 1 && p->batches[2].waits[0].batch == 0);
    CHECK(p->batches[2].waits[0].stages & VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    CHECK(p->batches[2].waits[0].stages & VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT); /* disp samples noise */
    /* the next frame's compute work waits for this frame's last graphics batch on shared resources */
    CHECK(p->batches[0].prev_frame_wait == 2);
    /* ownership: clusters and noise move compute -> graphics; lights stays on compute */
    CHECK(p->n_qfots == 2);
    const pg_qfot *tc = qfot_of(p, "clusters"), *tn = qfot_of(p, "noise");
    CHECK(tc && !tc->is_image && tc->release_batch == 0 && tc->acquire_batch == 2);
    CHECK(tc && (tc->src_access & VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT) &&
          tc->dst_access == VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    CHECK(tn && tn->is_image && tn->old_layout == VK_IMAGE_LAYOUT_GENERAL &&
          tn->new_layout == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    CHECK(tn && tn->consumer_pass == (int)(pass_named(p, "disp") - p->passes));
    CHECK(!qfot_of(p, "lights"));
    /* lights is compute-only: may share a block (of the compute queue); clusters own memory */
    CHECK(p->resources[res_named(p, "clusters")].queues == 3 && p->resources[res_named(p, "clusters")].block < 0);
    CHECK(p->resources[res_named(p, "noise")].block < 0);
    CHECK(explains(p, "resource 'noise' is used on the graphics and the compute queue: own memory"));
    check_invariants(p, "p1 separate");
    /* the dump shows queues, batches, waits and transfers (text and JSON) */
    char *txt = NULL;
    size_t txt_n = 0;
    FILE *mf = open_memstream(&txt, &txt_n);
    pg_graph_plan_print(p, pl, mf);
    fclose(mf);
    CHECK_MSG(txt && strstr(txt, "[0] anim (q_anim) on compute, batch 0") && strstr(txt, "batch 1 on graphics: gbuf\n") &&
                  strstr(txt, "batch 2 on graphics: light, disp (last") &&
                  strstr(txt, "waits for batch 0 at fragment_shader|compute_shader (light: clusters; disp: noise)") &&
                  strstr(txt, "release noise          compute -> graphics  compute_shader/storage_write, general -> shader_read_only") &&
                  strstr(txt, "acquire noise          compute -> graphics  fragment_shader/sampled_read, general -> shader_read_only") &&
                  strstr(txt, "waits for batch 2 of the previous frame") && strstr(txt, "own (2 queues)") &&
                  strstr(txt, "0 anim [compute]"),
              "%s", txt ? txt : "");
    free(txt);
    char *js = pg_dump_json(p, pl);
    CHECK(js && strstr(js, "\"queues\"") && strstr(js, "\"ownership_transfers\":\ttrue") &&
          strstr(js, "\"release_batch\":\t0") && strstr(js, "\"old_layout\":\t\"general\""));
    free(js);
out:
    pg_graph_plan_free(p);
    pg_pipeline_free(pl);
}

static void test_same_family(void)
{
    pg_pipeline *pl = NULL;
    pg_graph_plan *p = NULL;
    pg_error err = {0};
    pg_queue_caps caps = {.n_queues = 2, .separate_family = false};
    CHECK_MSG(compile_p1("", "", "", caps, &pl, &p, &err) == PG_OK, "%s", err.msg);
    if (!p) goto out;
    CHECK(p->async && !p->qfot && p->n_qfots == 0);
    CHECK(p->n_batches == 3);
    /* one family: the ordinary barrier stays (general -> shader_read_only before disp) */
    const pg_barrier *b = barrier_on(pass_named(p, "disp"), res_named(p, "noise"));
    CHECK(b && b->old_layout == VK_IMAGE_LAYOUT_GENERAL && b->new_layout == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    /* and the semaphore wait covers its source stage, so the barrier chains through it */
    CHECK(b && (p->batches[2].waits[0].stages & b->src_stages) == b->src_stages);
    check_invariants(p, "p1 one family");
    pg_graph_plan_free(p);
    pg_pipeline_free(pl);
    p = NULL;
    pl = NULL;
    /* the lighting on the compute queue samples the depth gbuf (graphics) wrote: its transition
     * (depth_attachment -> shader_read_only) must chain to the batch's wait. Its source stages
     * were the depth tests alone, which the compute batch's wait (compute_shader) does not cover:
     * the transition could run while the graphics queue still wrote the depth */
    CHECK_MSG(compile_p1("", "", ", \"queue\": \"compute\"", caps, &pl, &p, &err) == PG_OK, "%s", err.msg);
    if (!p) goto out;
    const pg_plan_pass *lp = pass_named(p, "light");
    CHECK(lp && lp->queue == PG_QUEUE_COMPUTE && p->batches[lp->batch].n_waits >= 1);
    b = lp ? barrier_on(lp, res_named(p, "depth")) : NULL;
    CHECK(b && b->old_layout == VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL &&
          b->new_layout == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    for (uint32_t k = 0; k < p->n_order; k++) { /* every transition in a batch that waits chains to the wait */
        const pg_plan_pass *pp = &p->passes[p->order[k]];
        uint64_t wait = 0;
        for (uint32_t w = 0; w < p->batches[pp->batch].n_waits; w++) wait |= p->batches[pp->batch].waits[w].stages;
        for (uint32_t i = 0; wait && i < pp->n_barriers; i++) {
            const pg_barrier *x = &pp->barriers[i];
            CHECK_MSG(x->old_layout == x->new_layout || !x->src_stages || (x->src_stages & wait),
                      "pass %s: the transition of resource %d does not chain to its batch's wait", pp->name, x->resource);
        }
    }
    check_invariants(p, "p1 one family, lighting on compute");
out:
    pg_graph_plan_free(p);
    pg_pipeline_free(pl);
}

static void test_explicit_queues(void)
{
    pg_pipeline *pl = NULL;
    pg_graph_plan *p = NULL;
    pg_error err = {0};
    pg_queue_caps caps = k_two_families;
    /* "graphics" keeps a compute pass on graphics; "compute" moves one with a raster input */
    CHECK_MSG(compile_p1(", \"queue\": \"graphics\"", "", ", \"queue\": \"compute\"", caps, &pl, &p, &err) == PG_OK,
              "%s", err.msg);
    if (p) {
        CHECK(pass_named(p, "anim")->queue == PG_QUEUE_GRAPHICS);
        CHECK(strstr(pass_named(p, "anim")->queue_reason, "\"queue\": \"graphics\"") != NULL);
        /* assign reads lights from the graphics pass anim: auto keeps it on graphics */
        CHECK(pass_named(p, "assign")->queue == PG_QUEUE_GRAPHICS);
        CHECK(pass_named(p, "light")->queue == PG_QUEUE_COMPUTE);
        /* light (compute) waits for gbuf's batch; the depth image moves graphics -> compute */
        const pg_plan_pass *lp = pass_named(p, "light");
        CHECK(p->batches[lp->batch].n_waits >= 1);
        const pg_qfot *td = qfot_of(p, "depth");
        CHECK(td && td->src_queue == PG_QUEUE_GRAPHICS && td->dst_queue == PG_QUEUE_COMPUTE &&
              td->old_layout == VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL &&
              td->new_layout == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        /* barriers on the compute queue (another family) name no graphics stage */
        for (uint32_t i = 0; i < lp->n_barriers; i++)
            CHECK(!((lp->barriers[i].src_stages | lp->barriers[i].dst_stages) &
                    (VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                     VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT)));
        /* hdr back to graphics for disp */
        const pg_qfot *th = qfot_of(p, "hdr");
        CHECK(th && th->src_queue == PG_QUEUE_COMPUTE && th->dst_queue == PG_QUEUE_GRAPHICS);
        check_invariants(p, "p1 explicit");
    }
    pg_graph_plan_free(p);
    pg_pipeline_free(pl);
    p = NULL;
    pl = NULL;
    /* "compute" on a raster pass is an error naming the file, the field and the reason */
    memset(&err, 0, sizeof err);
    CHECK(compile_p1("", ", \"queue\": \"compute\"", "", caps, &pl, &p, &err) == PG_ERR_SCHEMA && !p);
    CHECK_MSG(strstr(err.msg, "p1.json: passes[3].queue: pass 'gbuf' asks for the compute queue but is a raster pass") &&
                  strstr(err.msg, "attachment"),
              "%s", err.msg);
    pg_pipeline_free(pl);
    pl = NULL;
    /* ... also with one queue: it is a property of the pipeline */
    memset(&err, 0, sizeof err);
    pg_queue_caps one = {0};
    CHECK(compile_p1("", ", \"queue\": \"compute\"", "", one, &pl, &p, &err) == PG_ERR_SCHEMA);
    pg_pipeline_free(pl);
    pl = NULL;
    /* an unknown value is a schema error of the loader */
    memset(&err, 0, sizeof err);
    char json[4096];
    snprintf(json, sizeof json, k_p1, ", \"queue\": \"transfer\"", "", "");
    CHECK(pg_pipeline_load_string(json, "p1.json", NULL, 0, &pl, &err) == PG_ERR_SCHEMA && !pl);
    CHECK_MSG(strstr(err.msg, "p1.json") && strstr(err.msg, "passes[0].queue") && strstr(err.msg, "\"transfer\""),
              "%s", err.msg);
    pg_pipeline_free(pl);
}

static void test_join_and_fallback(void)
{
    const char *json =
        "{\"name\": \"p2\", \"output\": \"ldr\",\n"
        " \"resources\": [\n"
        "  {\"name\": \"lights\", \"type\": \"buffer\", \"stride\": 16, \"count\": [64]},\n"
        "  {\"name\": \"gcol\", \"type\": \"image\", \"format\": \"rgba16f\"},\n"
        "  {\"name\": \"depth\", \"type\": \"image\", \"format\": \"d32f\"},\n"
        "  {\"name\": \"ldr\", \"type\": \"image\", \"format\": \"rgba8\"}],\n"
        " \"passes\": [\n"
        "  {\"name\": \"anim\", \"type\": \"q_anim\", \"writes\": [\"lights\"]},\n"
        "  {\"name\": \"stat\", \"type\": \"q_stat\", \"reads\": [\"lights\"], \"side_effects\": true},\n"
        "  {\"name\": \"gbuf\", \"type\": \"q_raster\", \"writes\": [\"gcol\", \"depth\"]},\n"
        "  {\"name\": \"show\", \"type\": \"q_show\", \"reads\": [\"gcol\"], \"writes\": [\"ldr\"]}]}\n";
    pg_pipeline *pl = NULL;
    pg_error err = {0};
    CHECK_MSG(pg_pipeline_load_string(json, "p2.json", NULL, 0, &pl, &err) == PG_OK, "%s", err.msg);
    if (!pl) return;
    pg_compile_desc d = {.pipeline = pl, .registry = &g_reg, .output_width = 64, .output_height = 36,
                         .queues = k_two_families};
    pg_scene_vars_set(&d.vars, NULL, 64, NULL);
    pg_graph_plan *p = NULL;
    CHECK_MSG(pg_graph_compile(&d, &p, &err) == PG_OK, "%s", err.msg);
    if (p) {
        /* compute {anim, stat}; graphics {gbuf, show} joins it: nothing else waits for stat */
        CHECK(p->n_batches == 2 && p->batches[0].queue == PG_QUEUE_COMPUTE && p->batches[0].count == 2);
        CHECK(p->batches[1].n_waits == 1 && p->batches[1].waits[0].batch == 0 &&
              !strcmp(p->batches[1].waits[0].why, "join"));
        /* no resource of both queues: the next frame's compute work need not wait */
        CHECK(p->batches[0].prev_frame_wait == -1);
        CHECK(p->n_qfots == 0);
        check_invariants(p, "p2");
    }
    pg_graph_plan_free(p);
    /* a compute pass last in the order: the frame ends with an empty graphics batch that joins it */
    {
        const char *j3 =
            "{\"name\": \"p3\", \"output\": \"ldr\",\n"
            " \"resources\": [{\"name\": \"lights\", \"type\": \"buffer\", \"stride\": 16, \"count\": [64]},\n"
            "  {\"name\": \"gcol\", \"type\": \"image\", \"format\": \"rgba16f\"},\n"
            "  {\"name\": \"depth\", \"type\": \"image\", \"format\": \"d32f\"},\n"
            "  {\"name\": \"ldr\", \"type\": \"image\", \"format\": \"rgba8\"}],\n"
            " \"passes\": [{\"name\": \"gbuf\", \"type\": \"q_raster\", \"writes\": [\"gcol\", \"depth\"]},\n"
            "  {\"name\": \"show\", \"type\": \"q_show\", \"reads\": [\"gcol\"], \"writes\": [\"ldr\"]},\n"
            "  {\"name\": \"anim\", \"type\": \"q_anim\", \"writes\": [\"lights\"], \"side_effects\": true}]}\n";
        pg_pipeline *p3 = NULL;
        CHECK_MSG(pg_pipeline_load_string(j3, "p3.json", NULL, 0, &p3, &err) == PG_OK, "%s", err.msg);
        pg_compile_desc d3 = d;
        d3.pipeline = p3;
        pg_graph_plan *q = NULL;
        if (p3) CHECK_MSG(pg_graph_compile(&d3, &q, &err) == PG_OK, "%s", err.msg);
        if (q) {
            CHECK(q->n_batches == 3 && q->batches[0].queue == PG_QUEUE_GRAPHICS && q->batches[1].queue == PG_QUEUE_COMPUTE);
            CHECK(q->batches[2].queue == PG_QUEUE_GRAPHICS && q->batches[2].count == 0 && q->batches[2].last &&
                  q->batches[2].n_waits == 1 && q->batches[2].waits[0].batch == 1 &&
                  !strcmp(q->batches[2].waits[0].why, "join"));
            check_invariants(q, "p3");
        }
        pg_graph_plan_free(q);
        pg_pipeline_free(p3);
    }
    /* single-queue fallbacks: everything on graphics, one batch, the dump says why */
    const struct {
        pg_queue_caps caps;
        bool immediate;
        const char *note;
    } cases[] = {
        {{.n_queues = 1, .why_single = "the device has no second compute-capable queue"}, false,
         "one queue: the device has no second compute-capable queue"},
        {{.n_queues = 2, .separate_family = true, .async_off = true}, false, "one queue: --async-compute off"},
        {{.n_queues = 2, .separate_family = true}, true, "one queue: --immediate"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        d.queues = cases[i].caps;
        d.immediate = cases[i].immediate;
        p = NULL;
        CHECK_MSG(pg_graph_compile(&d, &p, &err) == PG_OK, "%s", err.msg);
        if (!p) continue;
        CHECK(!p->async && p->n_batches == 1 && p->batches[0].queue == PG_QUEUE_GRAPHICS &&
              p->batches[0].count == p->n_order && p->batches[0].n_waits == 0 && p->n_qfots == 0);
        for (uint32_t k = 0; k < p->n_order; k++) CHECK(p->passes[p->order[k]].queue == PG_QUEUE_GRAPHICS);
        CHECK_MSG(!strcmp(p->queue_note, cases[i].note) && explains(p, cases[i].note), "case %zu: '%s'", i,
                  p->queue_note);
        pg_graph_plan_free(p);
    }
    pg_pipeline_free(pl);
}

/* The shipped pipelines with the built-in pass types: the light animation and cluster assignment
 * chain runs on compute wherever it exists, the raster passes and their consumers on graphics. */
static void test_shipped(void)
{
    pg_pass_registry reg;
    memset(&reg, 0, sizeof reg);
    pg_register_builtin_passes(&reg);
    const char *names[] = {"naive", "forward_plus", "deferred", "deferred_oct16", "deferred_packed", "reference"};
    for (int fam = 0; fam < 2; fam++)
        for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
            char path[512];
            snprintf(path, sizeof path, "%s/../pipelines/%s.json", PG_TEST_DIR, names[i]);
            pg_pipeline *pl = NULL;
            pg_error err = {0};
            CHECK_MSG(pg_pipeline_load(path, NULL, 0, &pl, &err) == PG_OK, "%s", err.msg);
            if (!pl) continue;
            pg_compile_desc d = {.pipeline = pl, .registry = &reg, .output_width = 320, .output_height = 180,
                                 .queues = {.n_queues = 2, .separate_family = fam == 1}};
            pg_scene_vars_set(&d.vars, NULL, 1000, NULL);
            pg_graph_plan *p = NULL;
            CHECK_MSG(pg_graph_compile(&d, &p, &err) == PG_OK, "%s: %s", names[i], err.msg);
            if (!p) {
                pg_pipeline_free(pl);
                continue;
            }
            const pg_plan_pass *a = pass_named(p, "animate_lights"), *c = pass_named(p, "assign_lights");
            if (a && !a->culled) CHECK_MSG(a->queue == PG_QUEUE_COMPUTE, "%s: animate_lights on %s", names[i], pg_queue_name(a->queue));
            if (c && !c->culled) CHECK_MSG(c->queue == PG_QUEUE_COMPUTE, "%s: assign_lights on %s", names[i], pg_queue_name(c->queue));
            for (uint32_t k = 0; k < p->n_order; k++) {
                const pg_plan_pass *pp = &p->passes[p->order[k]];
                if (pp != a && pp != c)
                    CHECK_MSG(pp->queue == PG_QUEUE_GRAPHICS, "%s: %s on compute (%s)", names[i], pp->name, pp->queue_reason);
            }
            if (!strncmp(names[i], "deferred", 8)) {
                /* the G-buffer pass is in a batch that waits for nothing: it overlaps the compute batch */
                const pg_plan_pass *g = NULL;
                for (uint32_t k = 0; k < p->n_order && !g; k++)
                    if (!strncmp(p->passes[p->order[k]].name, "gbuffer", 7)) g = &p->passes[p->order[k]];
                CHECK_MSG(g && p->batches[g->batch].n_waits == 0 && p->batches[g->batch].prev_frame_wait < 0, "%s", names[i]);
            }
            CHECK(p->qfot == (fam == 1 && p->async));
            check_invariants(p, names[i]);
            pg_graph_plan_free(p);
            pg_pipeline_free(pl);
        }
}

/* The bloom example with its compute shader passes put on the compute queue: they read the HDR image
 * a raster pass wrote (its barrier's source stage is color_output); their batches' semaphore waits
 * stay within the compute family's stages (check_invariants) */
static void test_bloom_on_compute(void)
{
    pg_pass_registry reg;
    memset(&reg, 0, sizeof reg);
    pg_register_builtin_passes(&reg);
    char path[512];
    snprintf(path, sizeof path, "%s/../pipelines/examples/bloom/bloom.json", PG_TEST_DIR);
    pg_pipeline *pl = NULL;
    pg_error err = {0};
    CHECK_MSG(pg_pipeline_load(path, NULL, 0, &pl, &err) == PG_OK, "%s", err.msg);
    if (!pl) return;
    uint32_t moved = 0;
    for (uint32_t i = 0; i < pl->n_passes; i++)
        if (!strncmp(pl->passes[i].name, "bloom_down", 10) || !strncmp(pl->passes[i].name, "bloom_up", 8)) {
            pl->passes[i].queue = PG_QUEUE_PREF_COMPUTE;
            moved++;
        }
    CHECK(moved >= 4);
    pg_graph_plan *p = NULL;
    CHECK_MSG(compile_on(pl, &reg, k_two_families, 16, &p, &err) == PG_OK, "bloom on compute: %s", err.msg);
    if (p) {
        CHECK(p->async && pass_named(p, "bloom_down1") && pass_named(p, "bloom_down1")->queue == PG_QUEUE_COMPUTE);
        check_invariants(p, "bloom on compute");
    }
    pg_graph_plan_free(p);
    pg_pipeline_free(pl);
}

int main(void)
{
    for (size_t i = 0; i < sizeof g_types / sizeof g_types[0]; i++) {
        pg_error err = {0};
        CHECK_MSG(pg_registry_add(&g_reg, &g_types[i], &err) == PG_OK, "%s", err.msg);
    }
    test_auto_separate_families();
    test_bloom_on_compute();
    test_same_family();
    test_explicit_queues();
    test_join_and_fallback();
    test_shipped();
    return pg_test_finish("test_graph_queues");
}
