/* graph_execute_plan.c - plan signatures and pg_runtime_set_plan() (rebuild kinds); owns
 * pg_runtime.cur (graph_execute_internal.h). Calls graph_execute_memory.c (build, re-create,
 * destroy) and graph_execute_record.c (pg_rt_reports_due). */
#include "graph_execute_internal.h"

#include <string.h>

#include <cjson/cJSON.h>

static uint64_t fnv(uint64_t h, const void *data, size_t n)
{
    const uint8_t *p = data;
    for (size_t i = 0; i < n; i++) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

static bool is_runtime_option(const pg_pass_type *t, const char *key)
{
    for (uint32_t i = 0; t->runtime_options && t->runtime_options[i]; i++)
        if (key && !strcmp(t->runtime_options[i], key)) return true;
    return false;
}

/* A pass's options, key by key, as printed JSON; runtime: only (true) or all but (false) the
 * options its type lists in pg_pass_type.runtime_options. */
static uint64_t hash_options(uint64_t s, const pg_pass_type *t, const cJSON *options, bool runtime)
{
    const cJSON *it;
    cJSON_ArrayForEach(it, options)
    {
        if (is_runtime_option(t, it->string) != runtime) continue;
        char *txt = cJSON_PrintUnformatted(it);
        s = fnv(s, it->string ? it->string : "", it->string ? strlen(it->string) + 1 : 1);
        if (txt) {
            s = fnv(s, txt, strlen(txt) + 1);
            cJSON_free(txt);
        }
    }
    return s;
}

/* One resource's part of the memory signature: its size, format, usage, lifetime, memory block
 * and what places it there (first and last pass, may_inherit). */
static uint64_t resource_signature(uint64_t s, const pg_plan_resource *r)
{
    s = fnv(s, r->name, strlen(r->name) + 1);
    s = fnv(s, &r->kind, sizeof r->kind);
    s = fnv(s, &r->format, sizeof r->format);
    s = fnv(s, &r->width, sizeof r->width);
    s = fnv(s, &r->height, sizeof r->height);
    s = fnv(s, &r->size_bytes, sizeof r->size_bytes);
    s = fnv(s, &r->usage, sizeof r->usage);
    s = fnv(s, &r->culled, sizeof r->culled);
    s = fnv(s, &r->growable, sizeof r->growable);
    s = fnv(s, &r->block, sizeof r->block);
    s = fnv(s, &r->lifetime, sizeof r->lifetime);
    s = fnv(s, &r->first_pass, sizeof r->first_pass);
    s = fnv(s, &r->last_pass, sizeof r->last_pass);
    s = fnv(s, &r->may_inherit, sizeof r->may_inherit);
    return s;
}

/* (a) What needs new physical resources: the output size, every resource's part
 * (resource_signature), and which resources are the outputs (the readback buffers). */
static uint64_t memory_signature(const pg_graph_plan *plan, uint32_t w, uint32_t h)
{
    uint64_t s = 1469598103934665603ull;
    s = fnv(s, &w, sizeof w);
    s = fnv(s, &h, sizeof h);
    s = fnv(s, &plan->n_resources, sizeof plan->n_resources);
    s = fnv(s, &plan->n_blocks, sizeof plan->n_blocks);
    s = fnv(s, &plan->output, sizeof plan->output);
    s = fnv(s, &plan->hdr_output, sizeof plan->hdr_output);
    for (uint32_t i = 0; i < plan->n_resources; i++) s = resource_signature(s, &plan->resources[i]);
    return s;
}

static bool same_members(const pg_plan_block *a, const pg_plan_block *b)
{
    return a->n_members == b->n_members && !memcmp(a->members, b->members, sizeof(int) * a->n_members);
}

/* Which resources of the new plan differ from the built plan's (changed[i]) and which memory
 * blocks hold one (dirty[b]), when the rest can be kept: same size, outputs, number of resources
 * and blocks, each changed resource keeps its name, kind and block, a dirty block keeps its
 * members (all of them are then re-created and the block packed again). E.g. the light buffer
 * after a new light count. false: nothing changed, or a full memory rebuild is needed. */
static bool resources_changed(const pg_runtime *rt, const pg_graph_plan *plan, uint32_t w, uint32_t h,
                              bool *changed, bool *dirty)
{
    const pg_graph_plan *old = rt->cur.plan;
    if (!rt->mem.built || !old || w != rt->cur.width || h != rt->cur.height || plan->n_resources != old->n_resources ||
        plan->n_blocks != old->n_blocks || plan->output != old->output || plan->hdr_output != old->hdr_output)
        return false;
    uint32_t n = 0;
    memset(dirty, 0, sizeof(bool) * PG_MAX_RESOURCES);
    for (uint32_t i = 0; i < plan->n_resources; i++) {
        const pg_plan_resource *a = &old->resources[i], *b = &plan->resources[i];
        changed[i] = resource_signature(0, a) != resource_signature(0, b);
        if (!changed[i]) continue;
        if (a->block != b->block || (int)i == plan->output || (int)i == plan->hdr_output || strcmp(a->name, b->name) ||
            a->kind != b->kind)
            return false;
        if (b->block >= 0) {
            if (!same_members(&old->blocks[b->block], &plan->blocks[b->block])) return false;
            dirty[b->block] = true;
        }
        n++;
    }
    for (uint32_t b = 0; b < plan->n_blocks; b++)
        for (uint32_t m = 0; dirty[b] && m < plan->blocks[b].n_members; m++) changed[plan->blocks[b].members[m]] = true;
    return n > 0;
}

/* A pass's params block (what declare parsed, pg_pass_type.params_size bytes): runtime false,
 * everything but the run-time value fields (those zeroed); true, only those fields. */
static uint64_t hash_params(uint64_t s, const pg_plan_pass *p, bool runtime)
{
    const size_t n = p->type->params_size <= PG_MAX_PASS_PARAMS ? p->type->params_size : PG_MAX_PASS_PARAMS;
    const pg_pass_decl *d = &p->decl;
    if (runtime) {
        for (uint32_t i = 0; i < d->n_runtime_params && i < PG_MAX_RUNTIME_PARAMS; i++)
            s = fnv(s, d->params + d->runtime_params[i].offset, d->runtime_params[i].size);
        return s;
    }
    unsigned char fixed[PG_MAX_PASS_PARAMS];
    memcpy(fixed, d->params, n);
    for (uint32_t i = 0; i < d->n_runtime_params && i < PG_MAX_RUNTIME_PARAMS; i++)
        memset(fixed + d->runtime_params[i].offset, 0, d->runtime_params[i].size);
    return fnv(s, fixed, n);
}

/* (b) What needs new pass instances: the caller's block generation, the settings (shared_signature),
 * the executed passes in order with their types, shader variants (defines), bound resources and the
 * options that are not run-time values (pg_pass_type.runtime_options) (pass_signature). */
static uint64_t shared_signature(const pg_runtime *rt, uint64_t user_generation)
{
    uint64_t s = 1469598103934665603ull;
    s = fnv(s, &user_generation, sizeof user_generation);
    for (uint32_t i = 0; i < rt->cfg.n_settings; i++) {
        const char *k = rt->cfg.settings[i].key ? rt->cfg.settings[i].key : "";
        const char *v = rt->cfg.settings[i].value ? rt->cfg.settings[i].value : "";
        s = fnv(s, k, strlen(k) + 1);
        s = fnv(s, v, strlen(v) + 1);
    }
    return s;
}

static uint64_t pass_signature(const pg_pipeline *pl, const pg_plan_pass *p)
{
    uint64_t s = 1469598103934665603ull;
    s = fnv(s, p->name, strlen(p->name) + 1);
    s = fnv(s, p->type->name, strlen(p->type->name) + 1);
    for (uint32_t d = 0; d < p->decl.n_defines; d++) s = fnv(s, p->decl.defines[d], strlen(p->decl.defines[d]) + 1);
    s = hash_options(s, p->type, pl->passes[p->desc_index].options, false);
    s = hash_params(s, p, false);
    s = fnv(s, &p->n_slots, sizeof p->n_slots);
    for (uint32_t k = 0; k < p->n_slots; k++) {
        s = fnv(s, &p->slots[k].resource, sizeof(int));
        s = fnv(s, &p->slots[k].decl.unused, sizeof(bool));
    }
    return fnv(s, &p->queue, sizeof p->queue); /* pass-owned objects are used on one queue */
}

/* Fills sigs[i] (plan pass index) for the executed passes and returns the plan's signature. */
static uint64_t pipeline_signature(const pg_graph_plan *plan, const pg_pipeline *pl, uint64_t shared, uint64_t *sigs)
{
    uint64_t s = shared;
    s = fnv(s, &plan->n_order, sizeof plan->n_order);
    for (uint32_t i = 0; i < plan->n_order; i++) {
        const int pi = plan->order[i];
        sigs[pi] = pass_signature(pl, &plan->passes[pi]);
        s = fnv(s, &plan->order[i], sizeof plan->order[i]);
        s = fnv(s, &sigs[pi], sizeof sigs[pi]);
    }
    return s;
}

/* Same memory, new pass instances: the instances of the current plan's passes whose own signature
 * the new plan's pass of the same name has (and nothing shared changed) move into keep[] at the
 * new plan's index, out of the runtime (pg_rt_destroy_passes then leaves them). */
static void take_unchanged(pg_runtime *rt, const pg_graph_plan *plan, const uint64_t *sigs, uint64_t shared,
                           void **keep)
{
    const pg_graph_plan *old = rt->cur.plan;
    if (!old || shared != rt->cur.shared_sig) return;
    for (uint32_t i = 0; i < plan->n_order; i++) {
        const int pi = plan->order[i];
        for (uint32_t k = 0; k < old->n_order; k++) {
            const int oi = old->order[k];
            if (!rt->mem.pass_state[oi] || sigs[pi] != rt->cur.pass_sig[oi] ||
                strcmp(plan->passes[pi].name, rt->cur.pass_name[oi]))
                continue;
            keep[pi] = rt->mem.pass_state[oi];
            rt->mem.pass_state[oi] = NULL;
            break;
        }
    }
}

/* The per-pass signatures and names of the plan being adopted. */
static void adopt_signatures(pg_runtime *rt, const pg_graph_plan *plan, const uint64_t *sigs, uint64_t shared)
{
    memcpy(rt->cur.pass_sig, sigs, sizeof rt->cur.pass_sig);
    for (uint32_t i = 0; i < plan->n_passes && i < PG_MAX_PASSES; i++)
        pg_strlcpy(rt->cur.pass_name[i], plan->passes[i].name, PG_NAME_MAX);
    rt->cur.shared_sig = shared;
}

/* Kept instances adopt the new plan's run-time values (their type's update()). */
static pg_result update_kept(pg_runtime *rt, void *const *keep, pg_error *err)
{
    const pg_graph_plan *plan = rt->cur.plan;
    for (uint32_t i = 0; i < plan->n_passes; i++) {
        const pg_plan_pass *p = &plan->passes[i];
        if (!keep[i] || !p->type->update) continue;
        pg_result r = p->type->update(keep[i], p->decl.params, err);
        if (r) return pg_error_prefix(err, "pass '%s' (%s)", p->name, p->type->name);
    }
    return PG_OK;
}

/* (c) The run-time values: the options the pass types list as such (pass.update() gets them). */
static uint64_t value_signature(const pg_graph_plan *plan, const pg_pipeline *pl)
{
    uint64_t s = 1469598103934665603ull;
    for (uint32_t i = 0; i < plan->n_order; i++) {
        const pg_plan_pass *p = &plan->passes[plan->order[i]];
        s = hash_options(s, p->type, pl->passes[p->desc_index].options, true);
        s = hash_params(s, p, true);
    }
    return s;
}

/* The state a persistent resource is assumed to start each frame in (its frame-wrap barriers):
 * kept contents are only valid for a new plan that assumes the same. */
static uint64_t wrap_signature(const pg_graph_plan *plan, int ri)
{
    uint64_t s = 1469598103934665603ull;
    for (uint32_t o = 0; o < plan->n_order; o++) {
        const pg_plan_pass *p = &plan->passes[plan->order[o]];
        for (uint32_t b = 0; b < p->n_barriers; b++) {
            const pg_barrier *br = &p->barriers[b];
            if (br->resource != ri || !br->wrap) continue;
            s = fnv(s, &o, sizeof o);
            s = fnv(s, &br->old_layout, sizeof br->old_layout);
            s = fnv(s, &br->src_stages, sizeof br->src_stages);
            s = fnv(s, &br->src_access, sizeof br->src_access);
        }
    }
    for (uint32_t o = 0; o < plan->n_order; o++) { /* and the layout of every access */
        const pg_plan_pass *p = &plan->passes[plan->order[o]];
        for (uint32_t k = 0; k < p->n_slots; k++)
            if (p->slots[k].resource == ri) s = fnv(s, &p->slots[k].sync.layout, sizeof(uint32_t));
    }
    for (uint32_t b = 0; b < plan->n_final_barriers; b++)
        if (plan->final_barriers[b].resource == ri) s = fnv(s, &plan->final_barriers[b].new_layout, sizeof(uint32_t));
    return s;
}

pg_result pg_runtime_set_plan(pg_runtime *rt, const pg_graph_plan *plan, const pg_pipeline *pipeline,
                              pg_user_block user, uint32_t width, uint32_t height, pg_error *err)
{
    const pg_gpu *g = rt->cfg.gpu;
    if (plan->async && (!g->compute_queue || !rt->frames.timeline[0]))
        return pg_fail(err, PG_ERR_INVALID_ARG, "the plan uses the compute queue but the device has none (%s)",
                       g->single_queue_why[0] ? g->single_queue_why : "no timeline semaphores");
    if (plan->async && plan->qfot != (g->compute_family != g->queue_family))
        return pg_fail(err, PG_ERR_INVALID_ARG,
                       "the plan was compiled for queues of %s family, the device's are of %s: compile with "
                       "pg_runtime_queue_caps()", plan->qfot ? "different" : "one", plan->qfot ? "one" : "different");
    const uint64_t msig = memory_signature(plan, width, height);
    uint64_t sigs[PG_MAX_PASSES] = {0};
    const uint64_t shared = shared_signature(rt, user.generation);
    const uint64_t psig = pipeline_signature(plan, pipeline, shared, sigs);
    const uint64_t vsig = value_signature(plan, pipeline);
    pg_rt_reports_due(rt); /* a new light count may need a buffer to grow: read the next report */
    pg_rt_clear_growth(rt); /* requests name resources of the plan being replaced */
    pg_result r;
    if (rt->mem.built && msig == rt->cur.mem_sig && psig == rt->cur.pipe_sig) {
        /* same resources and pass instances: keep every object, adopt the new plan; only the
         * run-time values may differ */
        const pg_graph_plan *old_plan = rt->cur.plan;
        const pg_pipeline *old_pipeline = rt->cur.pipeline;
        const pg_user_block old_user = rt->cur.user;
        rt->cur.plan = plan;
        rt->cur.pipeline = pipeline;
        rt->cur.user = user;
        if (vsig == rt->cur.val_sig) {
            rt->stats.last_rebuild = PG_REBUILD_NONE;
            return PG_OK;
        }
        rt->stats.value_updates++;
        rt->stats.last_rebuild = PG_REBUILD_VALUES;
        /* a frame in flight may still read the old values only through its command buffer
         * (push constants are recorded), so no wait is needed */
        r = pg_rt_update_values(rt, err);
        if (!r) {
            rt->cur.val_sig = vsig;
            return PG_OK;
        }
        /* a pass refused a value: back to the plan the runtime had (the caller frees the new one),
         * its values given to the passes again; failing that, no plan (as the other failures) */
        rt->cur.plan = old_plan;
        rt->cur.pipeline = old_pipeline;
        rt->cur.user = old_user;
        pg_error ignored = {0};
        if (pg_rt_update_values(rt, &ignored) == PG_OK) return r;
        pg_rt_destroy_built(rt);
        rt->cur.plan = NULL;
        return r;
    }
    bool changed[PG_MAX_RESOURCES], dirty[PG_MAX_RESOURCES];
    const bool some = msig != rt->cur.mem_sig && resources_changed(rt, plan, width, height, changed, dirty);
    if (rt->mem.built && (msig == rt->cur.mem_sig || some)) {
        /* same resources: keep them (and what persistent ones hold when the new plan assumes
         * the same state at frame start), re-create the pass instances only */
        vkDeviceWaitIdle(rt->cfg.gpu->device);
        void *keep[PG_MAX_PASSES] = {0};
        if (!some) take_unchanged(rt, plan, sigs, shared, keep);
        pg_rt_destroy_passes(rt);
        for (uint32_t i = 0; i < plan->n_resources; i++)
            if (wrap_signature(plan, (int)i) != wrap_signature(rt->cur.plan, (int)i)) pg_rt_forget_contents(rt, (int)i);
        adopt_signatures(rt, plan, sigs, shared);
        uint32_t kept = 0;
        for (uint32_t i = 0; i < PG_MAX_PASSES; i++) {
            rt->mem.pass_state[i] = keep[i];
            kept += keep[i] != NULL;
        }
        rt->stats.last_passes_kept = kept;
        rt->cur.plan = plan;
        rt->cur.pipeline = pipeline;
        rt->cur.user = user;
        rt->cur.pipe_sig = psig;
        rt->cur.val_sig = vsig;
        if (some) { /* ... but the resources that changed (with their blocks): re-create them */
            rt->cur.mem_sig = msig;
            rt->stats.resource_rebuilds++;
            rt->stats.last_rebuild = PG_REBUILD_RESOURCES;
            r = pg_rt_recreate_resources(rt, changed, dirty, err);
        } else {
            rt->stats.pipeline_rebuilds++;
            rt->stats.last_rebuild = PG_REBUILD_PIPELINES;
            r = PG_OK;
        }
        if (!r) r = pg_rt_build_passes(rt, err);
        if (!r) r = update_kept(rt, keep, err);
    } else {
        pg_rt_carry_persistent(rt, plan); /* e.g. a filtered environment: kept with what it holds */
        pg_rt_destroy_built(rt);
        rt->cur.plan = plan;
        rt->cur.pipeline = pipeline;
        rt->cur.user = user;
        rt->cur.width = width;
        rt->cur.height = height;
        rt->cur.mem_sig = msig;
        rt->cur.pipe_sig = psig;
        rt->cur.val_sig = vsig;
        adopt_signatures(rt, plan, sigs, shared);
        rt->stats.last_passes_kept = 0;
        rt->stats.memory_rebuilds++;
        rt->stats.last_rebuild = PG_REBUILD_MEMORY;
        r = pg_rt_build_memory(rt, err);
        if (!r) r = pg_rt_build_passes(rt, err);
    }
    if (r) {
        pg_rt_destroy_built(rt);
        rt->cur.plan = NULL;
        return r;
    }
    return PG_OK; /* pg_rt_build_passes set mem.built */
}
