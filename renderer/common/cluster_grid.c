#include "cluster_grid.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cluster_math.h"

/* A count term as the pipeline wrote it after substitution ("16", "pixels", "lights"). */
static void term_text(const pg_count_term *t, char *out, size_t size)
{
    if (t->kind == PG_COUNT_CONST)
        snprintf(out, size, "%g", t->value);
    else if (t->kind == PG_COUNT_PIXELS)
        snprintf(out, size, "\"pixels\"");
    else
        snprintf(out, size, "\"%s\"", t->var);
}

pg_result pg_cluster_grid_declare(const pg_declare_in *in, pg_slot counts, pg_slot lists, uint32_t grid[3],
                                  pg_error *err)
{
    const pg_pass_desc *d = in->desc;
    grid[0] = PG_CLUSTER_GRID_DEFAULT_X;
    grid[1] = PG_CLUSTER_GRID_DEFAULT_Y;
    grid[2] = PG_CLUSTER_GRID_DEFAULT_Z;
    char where[32], text[48];
    const pg_resource_desc *rc = pg_decl_slot_resource(in, counts, PG_RES_BUFFER, where, sizeof where);
    if (!rc) return PG_OK;
    if (rc->n_count_terms != 3)
        return pg_fail(err, PG_ERR_SCHEMA,
                       "%s: %s.%s: pass '%s' slot cluster_counts: the cluster grid is the count of resource '%s' "
                       "(%s: %s.count), which needs three terms (x, y, z), not %u",
                       d->file, d->json_path, where, d->name, rc->name, rc->file, rc->json_path, rc->n_count_terms);
    uint32_t g[3];
    for (uint32_t k = 0; k < 3; k++) {
        const pg_count_term *t = &rc->count[k];
        term_text(t, text, sizeof text);
        if (t->kind != PG_COUNT_CONST || t->value != floor(t->value) || t->value < 1 ||
            t->value > PG_CLUSTER_GRID_EDGE_MAX)
            return pg_fail(err, PG_ERR_SCHEMA,
                           "%s: %s.%s: pass '%s' slot cluster_counts: the cluster grid is the count of resource '%s' "
                           "(%s: %s.count[%u]): term %s is not a whole number in [1, %u] known when the pipeline "
                           "is compiled",
                           d->file, d->json_path, where, d->name, rc->name, rc->file, rc->json_path, k, text,
                           PG_CLUSTER_GRID_EDGE_MAX);
        g[k] = (uint32_t)t->value;
    }
    if (rc->stride < 16)
        return pg_fail(err, PG_ERR_SCHEMA,
                       "%s: %s.%s: pass '%s' slot cluster_counts: resource '%s' (%s: %s.stride) has stride %u: each "
                       "cluster needs 16 bytes (list offset, stored, raw, 0)",
                       d->file, d->json_path, where, d->name, rc->name, rc->file, rc->json_path, rc->stride);
    if ((uint64_t)g[0] * g[1] * g[2] > PG_CLUSTER_GRID_CELLS_MAX)
        return pg_fail(err, PG_ERR_LIMIT,
                       "%s: %s.%s: pass '%s' slot cluster_counts: cluster grid %ux%ux%u (resource '%s', %s: "
                       "%s.count) has more than 2^22 clusters",
                       d->file, d->json_path, where, d->name, g[0], g[1], g[2], rc->name, rc->file, rc->json_path);
    const pg_resource_desc *rl = pg_decl_slot_resource(in, lists, PG_RES_BUFFER, where, sizeof where);
    if (rl) {
        bool agree = rl->n_count_terms >= 3;
        for (uint32_t k = 0; agree && k < 3; k++)
            agree = rl->count[k].kind == PG_COUNT_CONST && rl->count[k].value == (double)g[k];
        if (!agree) {
            char have[PG_MAX_COUNT_TERMS * 48 + 8];
            size_t len = 0;
            have[0] = 0;
            for (uint32_t k = 0; k < rl->n_count_terms && k < PG_MAX_COUNT_TERMS; k++) {
                term_text(&rl->count[k], text, sizeof text);
                len += (size_t)snprintf(have + len, sizeof have - len, "%s%s", k ? ", " : "", text);
            }
            return pg_fail(err, PG_ERR_SCHEMA,
                           "%s: %s.%s: pass '%s' slot cluster_lights: resource '%s' (%s: %s.count) has count [%s]: "
                           "its first three terms must be the cluster grid %u, %u, %u (the count of '%s')",
                           d->file, d->json_path, where, d->name, rl->name, rl->file, rl->json_path, have, g[0], g[1], g[2], rc->name);
        }
    }
    memcpy(grid, g, sizeof g);
    return PG_OK;
}
