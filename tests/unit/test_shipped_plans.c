/* test_shipped_plans.c - compile-time properties of the shipped pipelines with the built-in pass
 * types (no GPU): what a scene without BLEND materials leaves out. The compiler's own tests with
 * fake pass types are tests/test_graph_compile.c, which links only the base and graph libraries. */
#include <stdlib.h>
#include <string.h>

#include <vulkan/vulkan_core.h>

#include "graph.h"
#include "pass_list.h"
#include "pipeline.h"
#include "scene_vars.h"
#include "test_util.h"

static pg_graph_plan *compile(const pg_compile_desc *d)
{
    pg_graph_plan *plan = NULL;
    pg_error err = {0};
    pg_result r = pg_graph_compile(d, &plan, &err);
    CHECK_MSG(r == PG_OK && plan, "%s: %s", pg_result_name(r), err.msg);
    return r == PG_OK ? plan : NULL;
}
static int pidx(const pg_graph_plan *p, const char *name)
{
    for (uint32_t i = 0; i < p->n_passes; i++) if (!strcmp(p->passes[i].name, name)) return (int)i;
    return -1;
}
static int ridx(const pg_graph_plan *p, const char *name)
{
    for (uint32_t i = 0; i < p->n_resources; i++) if (!strcmp(p->resources[i].name, name)) return (int)i;
    return -1;
}
static int pos(const pg_graph_plan *p, const char *name)
{
    const int i = pidx(p, name);
    for (uint32_t k = 0; k < p->n_order; k++) if (p->order[k] == i) return (int)k;
    return -1;
}
static bool explain_has(const pg_graph_plan *p, const char *frag)
{
    for (uint32_t i = 0; i < p->n_explain; i++) if (strstr(p->explain[i], frag)) return true;
    return false;
}
static const pg_barrier *barrier_for(const pg_graph_plan *p, const char *pass_name, const char *res_name)
{
    const pg_plan_pass *pp = &p->passes[pidx(p, pass_name)];
    const int r = ridx(p, res_name);
    for (uint32_t b = 0; b < pp->n_barriers; b++) if (pp->barriers[b].resource == r) return &pp->barriers[b];
    return NULL;
}

static const pg_plan_pass *pass_named(const pg_graph_plan *p, const char *name)
{
    int i = pidx(p, name);
    return i >= 0 ? &p->passes[i] : NULL;
}

/* Every shipped pipeline ends with forward_transparent 'transparent'. Without BLEND materials it
 * is culled with its reason and the plan is the plan of the same pipeline without that pass
 * (same passes in the same order, same resources, sizes, usages, blocks and barriers): nothing
 * new is allocated or run. With BLEND materials it runs after the opaque lighting, before the
 * display, with hdr loaded as a colour attachment (deferred: from the compute pass's GENERAL
 * layout, the usage union includes both). A debug view skips it too. */
static void test_skip_shipped(void)
{
    static const char *const files[] = {"naive", "forward_plus", "deferred", "deferred_oct16",
                                        "deferred_packed", "reference"};
    pg_pass_registry reg;
    pg_register_builtin_passes(&reg);
    for (size_t f = 0; f < sizeof files / sizeof files[0]; f++) {
        char path[1200];
        snprintf(path, sizeof path, "%s/../pipelines/%s.json", PG_TEST_DIR, files[f]);
        for (int variant = 0; variant < 3; variant++) { /* no blend, blend, blend + debug view */
            pg_param_override view = {"view", "albedo"};
            pg_pipeline *pl = NULL;
            pg_error err = {0};
            pg_result r = pg_pipeline_load(path, &view, variant == 2 ? 1 : 0, &pl, &err);
            CHECK_MSG(r == PG_OK, "%s: %s", files[f], err.msg);
            if (r) continue;
            pg_compile_desc d = {.pipeline = pl, .registry = &reg, .output_width = 64, .output_height = 36};
            pg_scene_vars_set(&d.vars, &(pg_scene_features){.has_blend = variant > 0}, 100, NULL);
            pg_graph_plan *p = compile(&d);
            const pg_plan_pass *t = p ? pass_named(p, "transparent") : NULL;
            CHECK_MSG(t && t->type && strcmp(t->type->name, "forward_transparent") == 0, "%s: no transparent pass",
                      files[f]);
            if (!t) {
                pg_graph_plan_free(p);
                pg_pipeline_free(pl);
                continue;
            }
            const int hdr = ridx(p, "hdr");
            if (variant == 0) {
                CHECK_MSG(t->culled && strcmp(t->cull_reason, "no BLEND materials: no transparent pass") == 0,
                          "%s: %s", files[f], t->cull_reason);
                CHECK_MSG(explain_has(p, "culled pass 'transparent': no BLEND materials: no transparent pass"), "%s",
                          files[f]);
                /* the same pipeline without the pass */
                pg_pipeline *cut = malloc(sizeof *cut);
                memcpy(cut, pl, sizeof *cut);
                const int ti = pidx(p, "transparent");
                memmove(&cut->passes[ti], &cut->passes[ti + 1], (cut->n_passes - ti - 1) * sizeof cut->passes[0]);
                cut->n_passes--;
                pg_compile_desc dc = d;
                dc.pipeline = cut;
                pg_graph_plan *q = compile(&dc);
                if (q) {
                    CHECK_MSG(q->n_order == p->n_order, "%s: %u passes run, %u without the pass", files[f],
                              p->n_order, q->n_order);
                    for (uint32_t k = 0; k < p->n_order && k < q->n_order; k++) {
                        const pg_plan_pass *a = &p->passes[p->order[k]], *b = &q->passes[q->order[k]];
                        CHECK_MSG(strcmp(a->name, b->name) == 0 && a->n_barriers == b->n_barriers &&
                                      memcmp(a->barriers, b->barriers, a->n_barriers * sizeof a->barriers[0]) == 0,
                                  "%s: pass %u (%s) differs from the plan without the transparent pass", files[f], k,
                                  a->name);
                    }
                    CHECK(q->n_resources == p->n_resources && q->n_blocks == p->n_blocks &&
                          q->transient_bytes_aliased == p->transient_bytes_aliased &&
                          q->transient_bytes_unaliased == p->transient_bytes_unaliased);
                    for (uint32_t k = 0; k < p->n_resources && k < q->n_resources; k++) {
                        const pg_plan_resource *a = &p->resources[k], *b = &q->resources[k];
                        CHECK_MSG(a->culled == b->culled && a->usage == b->usage && a->size_bytes == b->size_bytes &&
                                      a->block == b->block && a->first_pass == b->first_pass &&
                                      a->last_pass == b->last_pass,
                                  "%s: resource '%s' differs from the plan without the transparent pass", files[f],
                                  a->name);
                    }
                    CHECK(q->n_final_barriers == p->n_final_barriers &&
                          memcmp(q->final_barriers, p->final_barriers,
                                 p->n_final_barriers * sizeof p->final_barriers[0]) == 0);
                    pg_graph_plan_free(q);
                }
                free(cut);
            } else if (variant == 1) {
                CHECK_MSG(!t->culled, "%s: transparent culled with BLEND materials: %s", files[f], t->cull_reason);
                const int tp = pos(p, "transparent");
                const int dp = pos(p, "display");
                const bool deferred = strncmp(files[f], "deferred", 8) == 0;
                const char *lit = deferred ? (f == 2 ? "lighting" : f == 3 ? "lighting_oct16" : "lighting_packed")
                                           : "shade";
                CHECK_MSG(tp > pos(p, lit) && pos(p, lit) >= 0 && dp == tp + 1, "%s: transparent at %d, %s at %d",
                          files[f], tp, lit, pos(p, lit));
                const pg_barrier *b = barrier_for(p, "transparent", "hdr");
                const bool compute_hdr = deferred || f == 5;
                CHECK_MSG(b && b->new_layout == VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL &&
                              b->old_layout == (compute_hdr ? VK_IMAGE_LAYOUT_GENERAL
                                                            : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL) &&
                              (b->dst_access & VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT),
                          "%s: hdr barrier before transparent", files[f]);
                CHECK(p->resources[hdr].usage & VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
                if (compute_hdr) CHECK(p->resources[hdr].usage & VK_IMAGE_USAGE_STORAGE_BIT);
                const pg_barrier *db = barrier_for(p, "transparent", "depth");
                CHECK_MSG(db && db->new_layout == VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL, "%s: depth", files[f]);
            } else {
                CHECK_MSG(t->culled && strstr(t->cull_reason, "debug view 'albedo'"), "%s: %s", files[f],
                          t->cull_reason);
            }
            pg_graph_plan_free(p);
            pg_pipeline_free(pl);
        }
    }
}

int main(void)
{
    test_skip_shipped();
    return pg_test_finish("test_shipped_plans");
}
