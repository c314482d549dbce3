/* graph_handle.c - typed, versioned handles into a compiled plan (see graph.h). Pure. */
#include "graph.h"

#include <stddef.h>
#include <string.h>

uint64_t pg_plan_generation(const pg_graph_plan *plan); /* graph_compile.c */

/* FNV-1a over the plan with its generation field taken as 0: plans are calloc'd and filled
 * deterministically (padding included), so equal plans hash equal. */
uint64_t pg_plan_generation(const pg_graph_plan *plan)
{
    const unsigned char *b = (const unsigned char *)plan;
    const size_t gen_at = offsetof(pg_graph_plan, generation), gen_end = gen_at + sizeof plan->generation;
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < sizeof *plan; i++) {
        h ^= (i >= gen_at && i < gen_end) ? 0u : b[i];
        h *= 1099511628211ull;
    }
    return h ? h : 1;
}

pg_result pg_plan_find_resource(const pg_graph_plan *plan, const char *name, pg_res_handle *out, pg_error *err)
{
    if (out) memset(out, 0, sizeof *out);
    if (!plan || !name || !out) return pg_fail(err, PG_ERR_INVALID_ARG, "pg_plan_find_resource: NULL argument");
    for (uint32_t i = 0; i < plan->n_resources && i < PG_MAX_RESOURCES; i++)
        if (!strcmp(plan->resources[i].name, name)) {
            out->index = i;
            out->generation = plan->generation;
            return PG_OK;
        }
    return pg_fail(err, PG_ERR_UNKNOWN_RESOURCE, "the compiled graph has no resource '%s'", name);
}

pg_result pg_plan_find_pass(const pg_graph_plan *plan, const char *name, pg_pass_handle *out, pg_error *err)
{
    if (out) memset(out, 0, sizeof *out);
    if (!plan || !name || !out) return pg_fail(err, PG_ERR_INVALID_ARG, "pg_plan_find_pass: NULL argument");
    for (uint32_t i = 0; i < plan->n_passes && i < PG_MAX_PASSES; i++)
        if (!strcmp(plan->passes[i].name, name)) {
            out->index = i;
            out->generation = plan->generation;
            return PG_OK;
        }
    return pg_fail(err, PG_ERR_UNKNOWN_PASS, "the compiled graph has no pass '%s'", name);
}

static pg_result check(const pg_graph_plan *plan, const char *what, uint32_t index, uint64_t generation,
                       uint32_t count, pg_error *err)
{
    if (!plan) return pg_fail(err, PG_ERR_INVALID_ARG, "%s handle #%u: no plan", what, index);
    if (generation == 0) return pg_fail(err, PG_ERR_INVALID_ARG, "%s handle #%u: not a handle (generation 0)", what, index);
    if (generation != plan->generation)
        return pg_fail(err, PG_ERR_INVALID_ARG,
                       "stale %s handle #%u: it is from another compiled plan (generation %016llx, this plan's "
                       "is %016llx); look the name up again in this plan",
                       what, index, (unsigned long long)generation, (unsigned long long)plan->generation);
    if (index >= count)
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s handle #%u: out of range (%u in the plan)", what, index, count);
    return PG_OK;
}

pg_result pg_plan_resource_get(const pg_graph_plan *plan, pg_res_handle h, const pg_plan_resource **out,
                               pg_error *err)
{
    if (out) *out = NULL;
    pg_result r = check(plan, "resource", h.index, h.generation, plan ? plan->n_resources : 0, err);
    if (!r && out) *out = &plan->resources[h.index];
    return r;
}

pg_result pg_plan_pass_get(const pg_graph_plan *plan, pg_pass_handle h, const pg_plan_pass **out, pg_error *err)
{
    if (out) *out = NULL;
    pg_result r = check(plan, "pass", h.index, h.generation, plan ? plan->n_passes : 0, err);
    if (!r && out) *out = &plan->passes[h.index];
    return r;
}
