/* graph_order.c - compile phases 3 (order) and 4 (cull); see graph_compile.c. */
#include "graph_compile_internal.h"

#include <stdio.h>
#include <string.h>

/* ------------------------------------------------------------------------------------------ */
/* 3. order                                                                                   */

static bool has_after(const pg_pass_desc *p, const char *name)
{
    for (uint32_t k = 0; k < p->n_after && k < PG_MAX_AFTER; k++)
        if (strcmp(p->after[k], name) == 0) return true;
    return false;
}

static bool dfs_cycle(const compile_ctx *c, const bool *done, int u, int *color, int *path,
                      int *len, int *cyc, int *cyc_len)
{
    const int n = (int)c->pl->n_passes;
    color[u] = 1;
    path[(*len)++] = u;
    for (int v = 0; v < n; v++) {
        if (!c->edge[u][v] || done[v]) continue;
        if (color[v] == 1) {
            int start = 0;
            while (path[start] != v) start++;
            *cyc_len = 0;
            for (int k = start; k < *len; k++) cyc[(*cyc_len)++] = path[k];
            return true;
        }
        if (color[v] == 0 && dfs_cycle(c, done, v, color, path, len, cyc, cyc_len)) return true;
    }
    color[u] = 2;
    (*len)--;
    return false;
}

static pg_result report_cycle(compile_ctx *c, const bool *done)
{
    const int n = (int)c->pl->n_passes;
    int color[PG_MAX_PASSES] = {0}, path[PG_MAX_PASSES], cyc[PG_MAX_PASSES];
    int len = 0, cyc_len = 0;
    for (int s = 0; s < n && !cyc_len; s++)
        if (!done[s] && color[s] == 0) {
            len = 0;
            dfs_cycle(c, done, s, color, path, &len, cyc, &cyc_len);
        }
    if (cyc_len == 0) /* cannot happen: Kahn's algorithm stalled, so a cycle exists */
        return pg_fail(c->err, PG_ERR_CYCLE, "%s: cycle between passes", pg_gc_pass_file(c, 0));
    /* start the path at its first declared pass, so the message is the same however found */
    int lo = 0;
    for (int k = 1; k < cyc_len; k++)
        if (cyc[k] < cyc[lo]) lo = k;
    char msg[PG_ERROR_MSG_MAX - 64];
    size_t m = 0;
    msg[0] = 0;
    for (int k = 0; k <= cyc_len && m < sizeof msg; k++) {
        int w = snprintf(msg + m, sizeof msg - m, "%s%s", k ? " -> " : "",
                         c->pl->passes[cyc[(lo + k) % cyc_len]].name);
        if (w < 0) break;
        m += (size_t)w;
    }
    return pg_fail(c->err, PG_ERR_CYCLE,
                   "%s: cycle: %s (each pass must run after the one before it, through the "
                   "resources it reads and writes or \"after\")",
                   pg_gc_pass_file(c, cyc[lo]), msg);
}

pg_result pg_gc_phase_order(compile_ctx *c)
{
    const pg_pipeline *pl = c->pl;
    const int n = (int)pl->n_passes;
    /* Writers of a resource, in declaration order, form a chain: the first may simply write;
     * every later one must read it (load, RMW) or name the previous writer in "after", otherwise
     * the order of the two writes would be a guess. Pure readers run after the LAST writer: a
     * resource has one final value per frame that every pure reader sees. */
    for (uint32_t r = 0; r < pl->n_resources; r++) {
        int prev = -1;
        for (int p = 0; p < n; p++) {
            pass_use *u = pg_gc_find_use(c, p, (int)r);
            if (!u || !u->writes) continue;
            if (prev >= 0) {
                if (!u->reads && !has_after(&pl->passes[p], pl->passes[prev].name)) {
                    char sp[PG_JSON_PATH_MAX + 48], pp[PG_JSON_PATH_MAX + 16];
                    int s = u->slot;
                    /* name a write slot bound to r */
                    for (uint32_t k = 0; k < c->plan->passes[p].n_slots; k++)
                        if (c->plan->passes[p].slots[k].resource == (int)r &&
                            c->plan->passes[p].slots[k].is_write) {
                            s = (int)k;
                            break;
                        }
                    pg_gc_slot_path(c, p, s, sp, sizeof sp);
                    pg_gc_pass_path(c, prev, pp, sizeof pp);
                    return pg_fail(c->err, PG_ERR_WRITE_CONFLICT,
                                   "%s: %s: resource '%s' is also written by pass '%s' (%s) with "
                                   "no ordering between them: make the later pass read it (load) "
                                   "or add \"after\": [\"%s\"]",
                                   pg_gc_pass_file(c, p), sp, pl->resources[r].name,
                                   pl->passes[prev].name, pp, pl->passes[prev].name);
                }
                c->edge[prev][p] = true;
            }
            prev = p;
        }
        if (prev < 0) continue;
        for (int p = 0; p < n; p++) {
            pass_use *u = pg_gc_find_use(c, p, (int)r);
            if (u && !u->writes && p != prev) c->edge[prev][p] = true;
        }
    }
    for (int p = 0; p < n; p++) {
        const pg_pass_desc *pd = &pl->passes[p];
        for (uint32_t k = 0; k < pd->n_after; k++) {
            int q = pg_gc_find_pass(pl, pd->after[k]);
            if (q < 0) {
                char pp[PG_JSON_PATH_MAX + 16];
                pg_gc_pass_path(c, p, pp, sizeof pp);
                return pg_fail(c->err, PG_ERR_SCHEMA, "%s: %s.after[%u]: unknown pass '%s'",
                               pg_gc_pass_file(c, p), pp, k, pd->after[k]);
            }
            c->edge[q][p] = true; /* q == p is a one-pass cycle, reported below */
        }
    }
    /* Kahn's algorithm, always taking the ready pass declared first: deterministic, and it keeps
     * declaration order wherever dependencies allow (immediate mode runs this order too: the
     * compiler moves a pass only where a dependency requires it). O(n^2) with n <= 64. */
    int indeg[PG_MAX_PASSES] = {0};
    bool done[PG_MAX_PASSES] = {false};
    for (int a = 0; a < n; a++)
        for (int b = 0; b < n; b++)
            if (c->edge[a][b]) indeg[b]++;
    for (int k = 0; k < n; k++) {
        int pick = -1;
        for (int p = 0; p < n && pick < 0; p++)
            if (!done[p] && indeg[p] == 0) pick = p;
        if (pick < 0) return report_cycle(c, done);
        done[pick] = true;
        c->topo[k] = pick;
        for (int b = 0; b < n; b++)
            if (c->edge[pick][b]) indeg[b]--;
    }
    /* A transient has no contents at the start of a frame: its first access must write it
     * without reading it first: a full write, a write declared partial (its readers read only
     * what it wrote), or a read-modify-write slot the pass marks as initialized by itself. A
     * blend, a depth load or a storage read-write as the first use would read undefined memory.
     * Checked over all passes, culled or not, so a mistake does not hide behind a cull. */
    for (uint32_t r = 0; r < pl->n_resources; r++) {
        if (pl->resources[r].lifetime != PG_LIFETIME_TRANSIENT) continue;
        for (int k = 0; k < n; k++) {
            int p = c->topo[k];
            pass_use *u = pg_gc_find_use(c, p, (int)r);
            if (!u) continue;
            if (!u->writes) {
                char sp[PG_JSON_PATH_MAX + 48];
                pg_gc_slot_path(c, p, u->slot, sp, sizeof sp);
                return pg_fail(c->err, PG_ERR_READ_BEFORE_WRITE,
                               "%s: %s: pass '%s' reads transient resource '%s' before any pass "
                               "writes it (make a pass write it first, or declare it persistent)",
                               pg_gc_pass_file(c, p), sp, pl->passes[p].name, pl->resources[r].name);
            }
            if (u->reads && !u->full_write) {
                /* name the slot that reads what it writes (else the first reading slot) */
                const pg_plan_pass *pp = &c->plan->passes[p];
                int s = -1;
                for (uint32_t k = 0; k < pp->n_slots; k++) {
                    const pg_plan_slot *ps = &pp->slots[k];
                    if (ps->resource != (int)r || ps->decl.unused || !ps->sync.reads) continue;
                    if (s < 0 || (ps->is_write && !pp->slots[s].is_write)) s = (int)k;
                }
                if (s < 0) s = u->slot;
                char sp[PG_JSON_PATH_MAX + 48];
                pg_gc_slot_path(c, p, s, sp, sizeof sp);
                return pg_fail(c->err, PG_ERR_READ_BEFORE_WRITE,
                               "%s: %s: pass '%s' reads transient resource '%s' before it is fully "
                               "written: it is the first pass to use it and slot '%s' (%s) reads "
                               "its contents, undefined at the start of a frame (write it in full "
                               "first, e.g. clear it, declare it persistent, or, if the pass writes "
                               "every element before reading any, mark the slot with "
                               "pg_decl_mark_initializes())",
                               pg_gc_pass_file(c, p), sp, pl->passes[p].name, pl->resources[r].name,
                               pp->slots[s].decl.name, pg_access_name(pp->slots[s].decl.access));
            }
            break;
        }
    }
    return PG_OK;
}

/* ------------------------------------------------------------------------------------------ */
/* 4. cull                                                                                    */

static bool pass_has_side_effects(const compile_ctx *c, int p)
{
    return c->pl->passes[p].side_effects || c->plan->passes[p].decl.side_effects;
}

pg_result pg_gc_phase_cull(compile_ctx *c)
{
    const pg_pipeline *pl = c->pl;
    pg_graph_plan *plan = c->plan;
    const int n = (int)pl->n_passes;
    bool needed[PG_MAX_PASSES] = {false};
    /* Outputs must be produced by something. */
    const int outs[2] = {plan->output, plan->hdr_output};
    const char *keys[2] = {"output", "hdr_output"};
    for (int k = 0; k < 2; k++) {
        if (outs[k] < 0) continue;
        bool written = false;
        int skipped = -1;
        for (int p = 0; p < n && !written; p++) {
            pass_use *u = pg_gc_find_use(c, p, outs[k]);
            if (u && u->writes && plan->passes[p].decl.skip) skipped = p;
            else written = u && u->writes;
        }
        if (!written && skipped >= 0)
            return pg_fail(c->err, PG_ERR_NO_OUTPUT,
                           "%s: %s: '%s' is written only by pass '%s', which is skipped for this "
                           "scene (%s)",
                           pl->path[0] ? pl->path : "<pipeline>", keys[k],
                           pl->resources[outs[k]].name, plan->passes[skipped].name,
                           plan->passes[skipped].decl.skip_reason);
        if (!written)
            return pg_fail(c->err, PG_ERR_NO_OUTPUT, "%s: %s: no pass writes '%s'",
                           pl->path[0] ? pl->path : "<pipeline>", keys[k],
                           pl->resources[outs[k]].name);
        c->needed_res[outs[k]] = true;
    }
    /* Roots: passes with side effects and (below) the writers of the outputs. A pass runs if it
     * writes a needed resource; everything a running pass touches is needed. Iterate to a fixed
     * point (at most n rounds): a chain a -> b -> out needs two rounds in the worst order. */
    /* A pass that declared itself not needed for this scene (pg_decl_skip) is never a root and
     * never needed: its writes keep the previous writer's value, which is the one readers get. */
    for (int p = 0; p < n; p++) needed[p] = pass_has_side_effects(c, p) && !plan->passes[p].decl.skip;
    bool changed = true;
    while (changed) {
        changed = false;
        for (int p = 0; p < n; p++) {
            if (plan->passes[p].decl.skip) continue;
            if (!needed[p])
                for (uint32_t k = 0; k < c->n_uses[p]; k++)
                    if (c->uses[p][k].writes && c->needed_res[c->uses[p][k].res]) {
                        needed[p] = true;
                        changed = true;
                        break;
                    }
            if (needed[p])
                for (uint32_t k = 0; k < c->n_uses[p]; k++)
                    if (!c->needed_res[c->uses[p][k].res]) {
                        c->needed_res[c->uses[p][k].res] = true;
                        changed = true;
                    }
        }
    }
    plan->n_order = 0;
    for (int k = 0; k < n; k++) {
        int p = c->topo[k];
        pg_plan_pass *pp = &plan->passes[p];
        if (needed[p]) {
            plan->order[plan->n_order++] = p;
            continue;
        }
        pp->culled = true;
        if (pp->decl.skip) {
            pg_strlcpy(pp->cull_reason, pp->decl.skip_reason, sizeof pp->cull_reason);
            continue;
        }
        char list[PG_EXPLAIN_MAX];
        size_t len = 0;
        list[0] = 0;
        for (uint32_t u = 0; u < c->n_uses[p] && len < sizeof list; u++) {
            if (!c->uses[p][u].writes) continue;
            int w = snprintf(list + len, sizeof list - len, "%s%s", len ? ", " : "",
                             pl->resources[c->uses[p][u].res].name);
            if (w < 0) break;
            len += (size_t)w;
        }
        if (!list[0])
            snprintf(pp->cull_reason, sizeof pp->cull_reason,
                     "it writes nothing and has no side effects");
        else if (plan->hdr_output >= 0 && plan->hdr_output != plan->output)
            pg_gc_fmt_into(pp->cull_reason, sizeof pp->cull_reason,
                     "nothing reads its writes (%s) on the way to output '%s' or hdr_output '%s'",
                     list, pl->output, pl->hdr_output);
        else
            pg_gc_fmt_into(pp->cull_reason, sizeof pp->cull_reason,
                     "nothing reads its writes (%s) on the way to output '%s'", list, pl->output);
    }
    for (uint32_t r = 0; r < pl->n_resources; r++) {
        pg_plan_resource *pr = &plan->resources[r];
        if (c->needed_res[r]) continue;
        pr->culled = true;
        snprintf(pr->cull_reason, sizeof pr->cull_reason, "%s",
                 c->used_at_all[r] ? "not used by any pass that runs" : "not used by any pass");
    }
    return PG_OK;
}
