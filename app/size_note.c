/* size_note.c - the memory estimate printed before a big frame (size_note.h). */
#include "size_note.h"

#include "pg_file.h"
#include "pipeline.h"
#include "scene_vars.h"

#include <stdlib.h>

uint64_t pg_plan_memory_estimate(const pg_graph_plan *plan)
{
    uint64_t bytes = 0;
    for (uint32_t b = 0; b < plan->n_blocks; b++) bytes += plan->blocks[b].size_bytes;
    for (uint32_t i = 0; i < plan->n_resources; i++) {
        const pg_plan_resource *r = &plan->resources[i];
        if (!r->culled && r->block < 0) bytes += r->size_bytes; /* own memory */
    }
    return bytes;
}

static uint64_t threshold(void)
{
    const char *e = getenv("PASSGRAPH_SIZE_NOTE_MIB");
    if (e && *e) {
        char *end = NULL;
        unsigned long long v = strtoull(e, &end, 10);
        if (end && !*end) return v * PG_MIB;
    }
    return 1024ull * PG_MIB;
}

void pg_size_note_print(FILE *f, const char *cmd, uint32_t width, uint32_t height,
                        const pg_graph_plan *plan)
{
    uint64_t bytes = pg_plan_memory_estimate(plan);
    if (bytes < threshold() || bytes == 0) return;
    char sz[32];
    pg_file_fmt_size(bytes, sz, sizeof sz);
    fprintf(f, "%s: %ux%u needs about %s of device memory (plan estimate); this can take minutes on a CPU device\n",
            cmd, width, height, sz);
    fflush(f);
}

pg_result pg_size_note_check(const pg_app *app, const char *cmd, FILE *f, pg_error *err)
{
    const pg_cli_common *o = &app->opt;
    if (app->gpu) {
        uint32_t lim = app->gpu->props.limits.maxImageDimension2D;
        if (o->width > lim || o->height > lim)
            return pg_fail(err, PG_ERR_INVALID_ARG, "--size %ux%u: over this device's largest image side (%u, "
                           "maxImageDimension2D of %s)", o->width, o->height, lim, app->gpu->props.deviceName);
    }
    pg_pipeline *pl = NULL;
    pg_error ignored;
    if (pg_pipeline_load(app->pipeline_path, o->sets, o->n_sets, &pl, &ignored)) return PG_OK;
    pg_compile_desc cd = {
        .pipeline = pl,
        .registry = &app->registry,
        .output_width = o->width,
        .output_height = o->height,
        .disable_aliasing = o->no_aliasing,
        .immediate = o->immediate,
    };
    pg_graph_plan *plan = NULL;
    if (!pg_scene_vars_set(&cd.vars, app->scene ? &app->scene->features : NULL, app->lights.count, &ignored) &&
        !pg_graph_compile(&cd, &plan, &ignored)) {
        pg_size_note_print(f, cmd, o->width, o->height, plan);
        pg_graph_plan_free(plan);
    }
    pg_pipeline_free(pl);
    return PG_OK;
}
