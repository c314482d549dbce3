#include "render_session.h"

#include <stdlib.h>

pg_result pg_session_create(pg_gpu *gpu, const pg_scene_gpu *scene, const pg_session_desc *desc, pg_session **out,
                            pg_error *err)
{
    *out = NULL;
    pg_session *s = calloc(1, sizeof *s);
    if (!s) return pg_fail(err, PG_ERR_OOM, "out of memory");
    s->gpu = gpu;
    s->scene = scene;
    s->desc = *desc;
    pg_result r = pg_pipeline_load(desc->pipeline_path, desc->overrides, desc->n_overrides, &s->pipeline, err);
    if (!r && gpu) r = pg_runtime_create(gpu, &s->runtime, err);
    if (r) {
        pg_session_destroy(s);
        return r;
    }
    *out = s;
    return PG_OK;
}

pg_result pg_session_compile(pg_session *s, uint32_t light_count, uint32_t width, uint32_t height, pg_error *err)
{
    if (s->plan && light_count == s->light_count && width == s->width && height == s->height) return PG_OK;
    pg_compile_desc cd = {
        .pipeline = s->pipeline,
        .registry = s->desc.registry,
        .output_width = width,
        .output_height = height,
        .disable_aliasing = s->desc.disable_aliasing,
        .output_stages = s->desc.output_stages,
    };
    if (s->scene) cd.features = s->scene->features;
    cd.features.light_count = light_count;
    pg_graph_plan *plan = NULL;
    pg_result r = pg_graph_compile(&cd, &plan, err);
    if (r) return r;
    if (s->runtime) {
        r = pg_runtime_set_plan(s->runtime, plan, s->pipeline, s->scene, width, height, err);
        if (r) {
            pg_graph_plan_free(plan);
            return r;
        }
    }
    pg_graph_plan_free(s->plan);
    s->plan = plan;
    s->light_count = light_count;
    s->width = width;
    s->height = height;
    s->compiles++;
    return PG_OK;
}

pg_result pg_session_render(pg_session *s, const pg_frame_info *info, bool readback, pg_frame_stats *stats,
                            pg_error *err)
{
    if (!s->runtime) return pg_fail(err, PG_ERR_INVALID_ARG, "session has no GPU");
    pg_result r = pg_session_compile(s, info->lights.count, info->width, info->height, err);
    if (r) return r;
    return pg_runtime_render(s->runtime, info, readback, stats, err);
}

void pg_session_destroy(pg_session *s)
{
    if (!s) return;
    pg_runtime_destroy(s->runtime);
    pg_graph_plan_free(s->plan);
    pg_pipeline_free(s->pipeline);
    free(s);
}
