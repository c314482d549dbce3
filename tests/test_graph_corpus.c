/* test_graph_corpus.c - pipeline files that parse but must fail to compile against the built-in
 * pass types (tests/corpus/graph/MANIFEST: file, exact pg_result, message fragment), and every
 * shipped pipeline in pipelines/ must load and compile for the default scene's features. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "graph.h"
#include "pass_list.h"
#include "pipeline.h"
#include "test_util.h"

static pg_pass_registry g_reg;

static pg_result load_compile(const char *path, pg_error *err)
{
    pg_pipeline *p = NULL;
    pg_result r = pg_pipeline_load(path, NULL, 0, &p, err);
    if (r) return r;
    pg_compile_desc d = {.pipeline = p, .registry = &g_reg, .output_width = 64, .output_height = 36,
                         .features = {.has_textures = true, .has_normal_maps = true, .has_alpha_mask = true,
                                      .light_count = 100}};
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
    DIR *d = opendir(dir);
    CHECK(d != NULL);
    int shipped = 0;
    struct dirent *e;
    while (d && (e = readdir(d))) {
        size_t len = strlen(e->d_name);
        if (len < 6 || strcmp(e->d_name + len - 5, ".json")) continue;
        char path[1400];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        pg_error err = {0};
        pg_result r = load_compile(path, &err);
        CHECK_MSG(r == PG_OK, "shipped %s: %s", e->d_name, err.msg);
        shipped++;
    }
    if (d) closedir(d);
    CHECK(shipped >= 1);
    return pg_test_finish("test_graph_corpus");
}
