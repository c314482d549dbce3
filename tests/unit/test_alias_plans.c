/* test_alias_plans.c - the sub-allocated placement of every shipped pipeline (pipelines/ *.json)
 * at 1920x1080, compiled for a plain scene and for one with every material feature (blend,
 * emissive, ...). Checks: resources alive at the same time share no byte; a resource that shares
 * an earlier one's bytes starts with a full overwrite and has an alias barrier; offsets honour
 * the estimated alignments; the aliased total is at most the unaliased total and equals the peak
 * of live bytes (the lower bound: no placement can do better with these lifetimes);
 * --no-aliasing gives every transient its own block. Prints the
 * numbers (the README's table comes from tools/alias_table.sh). */
#include <stdlib.h>
#include <string.h>

#include "graph.h"
#include "pass_list.h"
#include "pipeline.h"
#include "scene_vars.h"
#include "test_util.h"

static pg_pass_registry g_reg;

static bool overlap(const pg_plan_resource *a, const pg_plan_resource *b)
{
    return a->block >= 0 && a->block == b->block && a->block_offset < b->block_offset + b->size_bytes &&
           b->block_offset < a->block_offset + a->size_bytes;
}

/* largest sum of live non-growable transient bytes at one position, per kind, summed */
static uint64_t peak_live(const pg_graph_plan *p)
{
    uint64_t total = 0;
    for (int kind = 0; kind < 2; kind++) {
        uint64_t best = 0;
        for (int t = 0; t <= (int)p->n_order; t++) {
            uint64_t s = 0;
            for (uint32_t r = 0; r < p->n_resources; r++) {
                const pg_plan_resource *pr = &p->resources[r];
                if (pr->block < 0 || (int)pr->kind != (kind ? PG_RES_BUFFER : PG_RES_IMAGE)) continue;
                if (pr->first_pass <= t && t <= pr->last_pass) s += pr->size_bytes;
            }
            if (s > best) best = s;
        }
        total += best;
    }
    return total;
}

/* the live peak plus the "grow" buffers (own memory) */
static uint64_t lower_bound(const pg_graph_plan *p)
{
    uint64_t grow = 0;
    for (uint32_t i = 0; i < p->n_resources; i++) {
        const pg_plan_resource *ri = &p->resources[i];
        if (ri->growable && !ri->culled && ri->first_pass >= 0) grow += ri->size_bytes;
    }
    return peak_live(p) + grow;
}

static void check_plan(const pg_graph_plan *p, const char *what)
{
    uint64_t grow = 0;
    for (uint32_t i = 0; i < p->n_resources; i++) {
        const pg_plan_resource *ri = &p->resources[i];
        if (ri->growable && !ri->culled && ri->first_pass >= 0) grow += ri->size_bytes;
        if (ri->block < 0) continue;
        const uint64_t al = ri->kind == PG_RES_IMAGE ? PG_ALIAS_EST_ALIGN_IMAGE : PG_ALIAS_EST_ALIGN_BUFFER;
        CHECK_MSG(ri->block_offset % al == 0, "%s: %s unaligned", what, ri->name);
        CHECK_MSG(ri->block_offset + ri->size_bytes <= p->blocks[ri->block].size_bytes, "%s: %s past its block", what,
                  ri->name);
        for (uint32_t j = 0; j < p->n_resources; j++) {
            const pg_plan_resource *rj = &p->resources[j];
            if (j == i || !overlap(ri, rj)) continue;
            CHECK_MSG(ri->last_pass < rj->first_pass || rj->last_pass < ri->first_pass,
                      "%s: %s and %s alive together share bytes", what, ri->name, rj->name);
            if (rj->last_pass < ri->first_pass) { /* ri starts in rj's bytes */
                CHECK_MSG(ri->may_inherit, "%s: %s starts in %s's bytes without a full write", what, ri->name, rj->name);
                const pg_plan_pass *pp = &p->passes[p->order[ri->first_pass]];
                bool found = false;
                for (uint32_t b = 0; b < pp->n_barriers; b++)
                    found |= pp->barriers[b].resource == (int)i && pp->barriers[b].alias_prev >= 0 &&
                             !strcmp(pp->barriers[b].why, "alias first use");
                CHECK_MSG(found, "%s: %s has no alias barrier in %s", what, ri->name, pp->name);
            }
        }
    }
    const uint64_t lower = peak_live(p) + grow;
    CHECK_MSG(p->transient_bytes_aliased >= lower, "%s: aliased %llu below the live peak %llu", what,
              (unsigned long long)p->transient_bytes_aliased, (unsigned long long)lower);
    CHECK_MSG(p->transient_bytes_aliased <= p->transient_bytes_unaliased, "%s: worse than no aliasing", what);
    printf("%-40s %10llu B unaliased -> %10llu B aliased (live peak %llu B)%s\n", what,
           (unsigned long long)p->transient_bytes_unaliased, (unsigned long long)p->transient_bytes_aliased,
           (unsigned long long)lower, p->transient_bytes_aliased == lower ? " = peak" : "");
}

int main(void)
{
    pg_register_builtin_passes(&g_reg);
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/../pipelines", PG_TEST_DIR);
    char *names[64];
    const int n_names = pg_test_list_files(dir, ".json", names, 64);
    CHECK(n_names >= 0);
    int shipped = 0;
    for (int i = 0; i < n_names; i++) {
        const char *name = names[i];
        char path[1400];
        snprintf(path, sizeof path, "%s/%s", dir, name);
        pg_pipeline *pl = NULL;
        pg_error err = {0};
        if (pg_pipeline_load(path, NULL, 0, &pl, &err)) {
            CHECK_MSG(0, "%s", err.msg);
            continue;
        }
        shipped++;
        for (int rich = 0; rich <= 1; rich++) {
            for (int off = 0; off <= 1; off++) {
                pg_compile_desc cd = {.pipeline = pl, .registry = &g_reg, .output_width = 1920, .output_height = 1080,
                                      .disable_aliasing = off};
                pg_scene_vars_set(&cd.vars,
                                  rich ? &(pg_scene_features){true, true, true, true, true, true, true, true, true, true, true, true, true, true,
                                                               false, 0, PG_SHADING_PBR}
                                       : &(pg_scene_features){.has_textures = true},
                                  256, NULL);
                pg_graph_plan *p = NULL;
                if (pg_graph_compile(&cd, &p, &err)) {
                    CHECK_MSG(0, "%s: %s", name, err.msg);
                    continue;
                }
                char what[128];
                snprintf(what, sizeof what, "%s%s%s", name, rich ? " (all features)" : "",
                         off ? " --no-aliasing" : "");
                check_plan(p, what);
                if (!off) /* the shipped pipelines pack to the lower bound */
                    CHECK_MSG(p->transient_bytes_aliased == lower_bound(p), "%s: %llu aliased, live peak %llu", what,
                              (unsigned long long)p->transient_bytes_aliased, (unsigned long long)lower_bound(p));
                if (off) {
                    CHECK_MSG(p->transient_bytes_aliased == p->transient_bytes_unaliased, "%s: shares", what);
                    for (uint32_t b = 0; b < p->n_blocks; b++)
                        CHECK_MSG(p->blocks[b].n_members == 1, "%s: block %u shared", what, b);
                }
                pg_graph_plan_free(p);
            }
        }
        pg_pipeline_free(pl);
    }
    pg_test_free_names(names, n_names);
    CHECK(shipped >= 6);
    return pg_test_finish("test_alias_plans");
}
