/* test_graph_corpus.c - pipeline files that parse but must fail to compile against the built-in
 * pass types (tests/corpus/graph/MANIFEST: file, exact pg_result, message fragment), and every
 * shipped pipeline in pipelines/ must load and compile for the default scene's features. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "graph.h"
#include "pass_list.h"
#include "pipeline.h"
#include "scene_vars.h"
#include "test_util.h"

static pg_pass_registry g_reg;

static pg_result load_compile(const char *path, pg_error *err)
{
    pg_pipeline *p = NULL;
    pg_result r = pg_pipeline_load(path, NULL, 0, &p, err);
    if (r) return r;
    pg_compile_desc d = {.pipeline = p, .registry = &g_reg, .output_width = 64, .output_height = 36};
    pg_scene_vars_set(&d.vars,
                      &(pg_scene_features){.has_textures = true, .has_normal_maps = true, .has_alpha_mask = true},
                      100, NULL);
    pg_graph_plan *plan = NULL;
    r = pg_graph_compile(&d, &plan, err);
    pg_graph_plan_free(plan);
    pg_pipeline_free(p);
    return r;
}

int main(void)
{
    pg_register_builtin_passes(&g_reg);
    char manifest[1024];
    snprintf(manifest, sizeof manifest, "%s/corpus/graph/MANIFEST", PG_TEST_DIR);
    FILE *f = fopen(manifest, "r");
    CHECK_MSG(f != NULL, "cannot open %s", manifest);
    int n = 0;
    char line[1024];
    while (f && fgets(line, sizeof line, f)) {
        if (line[0] == '#' || line[0] == '\n') continue;
        char file[256], code[64];
        int off = 0;
        if (sscanf(line, "%255s %63s %n", file, code, &off) < 2) continue;
        char *sub = line + off;
        sub[strcspn(sub, "\n")] = 0;
        char path[1400];
        snprintf(path, sizeof path, "%s/corpus/graph/%s", PG_TEST_DIR, file);
        pg_error err = {0};
        pg_result r = load_compile(path, &err);
        CHECK_MSG(strcmp(pg_result_name(r), code) == 0, "%s: expected %s, got %s: %s", file, code, pg_result_name(r),
                  err.msg);
        CHECK_MSG(strstr(err.msg, sub) != NULL, "%s: message lacks '%s': %s", file, sub, err.msg);
        CHECK_MSG(strstr(err.msg, file) != NULL, "%s: message does not name the file: %s", file, err.msg);
        n++;
    }
    if (f) fclose(f);
    printf("test_graph_corpus: %d bad pipelines\n", n);
    CHECK(n >= 15);

    /* every shipped pipeline compiles */
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/../pipelines", PG_TEST_DIR);
    char *names[64];
    const int n_names = pg_test_list_files(dir, ".json", names, 64);
    CHECK(n_names >= 0);
    int shipped = 0;
    for (int i = 0; i < n_names; i++) {
        char path[1400];
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        pg_error err = {0};
        pg_result r = load_compile(path, &err);
        CHECK_MSG(r == PG_OK, "shipped %s: %s", names[i], err.msg);
        shipped++;
    }
    pg_test_free_names(names, n_names);
    CHECK(shipped >= 5);

    /* leave out what the scene does not need: compile the shipped pipelines for a scene without
     * alpha-mask materials, normal maps or lights, and check variants, culls and reasons */
    const char *pipes[] = {"naive.json", "forward_plus.json", "deferred.json", "deferred_oct16.json",
                           "deferred_packed.json", "reference.json"};
    for (int i = 0; i < 6; i++) {
        char path[1400];
        snprintf(path, sizeof path, "%s/%s", dir, pipes[i]);
        pg_pipeline *p = NULL;
        pg_error err = {0};
        if (pg_pipeline_load(path, NULL, 0, &p, &err)) {
            CHECK_MSG(0, "%s", err.msg);
            continue;
        }
        for (int lights = 0; lights <= 1; lights++) {
            pg_compile_desc cd = {.pipeline = p, .registry = &g_reg, .output_width = 64, .output_height = 36};
            pg_scene_vars_set(&cd.vars, &(pg_scene_features){.has_textures = true}, (uint32_t)lights * 100, NULL);
            pg_graph_plan *plan = NULL;
            if (pg_graph_compile(&cd, &plan, &err)) {
                CHECK_MSG(0, "%s", err.msg);
                continue;
            }
            bool any_mask = false, any_nmap = false, said_mask = false, said_nmap = false, anim = false;
            for (uint32_t k = 0; k < plan->n_order; k++) {
                const pg_plan_pass *pp = &plan->passes[plan->order[k]];
                for (uint32_t dd = 0; dd < pp->decl.n_defines; dd++) {
                    any_mask |= !strcmp(pp->decl.defines[dd], "PG_ALPHA_MASK");
                    any_nmap |= !strcmp(pp->decl.defines[dd], "PG_NORMAL_MAPS");
                }
                anim |= !strcmp(pp->type->name, "light_animate") || !strcmp(pp->type->name, "cluster_assign");
            }
            for (uint32_t e = 0; e < plan->n_explain; e++) {
                said_mask |= strstr(plan->explain[e], "no alpha-mask materials") != NULL;
                said_nmap |= strstr(plan->explain[e], "no normal maps") != NULL;
            }
            CHECK_MSG(!any_mask && !any_nmap && said_mask && said_nmap, "%s: features not left out", pipes[i]);
            CHECK_MSG(anim == (lights == 1), "%s, %d lights: light animation/assignment %s", pipes[i], lights * 100,
                      anim ? "runs" : "culled");
            pg_graph_plan_free(plan);
        }
        pg_pipeline_free(p);
    }
    return pg_test_finish("test_graph_corpus");
}
