#include "render_session.h"

#include <stdlib.h>
#include <string.h>

pg_result pg_session_create(pg_gpu *gpu, const pg_scene_gpu *scene, const pg_session_desc *desc, pg_session **out,
                            pg_error *err)
{
    *out = NULL;
    pg_session *s = calloc(1, sizeof *s);
    if (!s) return pg_fail(err, PG_ERR_OOM, "out of memory");
    s->gpu = gpu;
    s->scene = scene;
    s->desc = *desc;
    s->desc.settings = NULL;
    s->desc.n_settings = 0;
    pg_result r = PG_OK;
    if (desc->n_settings && desc->settings) {
        /* one block: the array, then every key and value string */
        size_t bytes = desc->n_settings * sizeof(pg_param_override);
        for (uint32_t i = 0; i < desc->n_settings; i++) {
            bytes += strlen(desc->settings[i].key ? desc->settings[i].key : "") + 1;
            bytes += strlen(desc->settings[i].value ? desc->settings[i].value : "") + 1;
        }
        s->settings = malloc(bytes);
        if (!s->settings) r = pg_fail(err, PG_ERR_OOM, "out of memory");
        char *p = s->settings ? (char *)(s->settings + desc->n_settings) : NULL;
        for (uint32_t i = 0; p && i < desc->n_settings; i++) {
            const char *k = desc->settings[i].key ? desc->settings[i].key : "";
            const char *v = desc->settings[i].value ? desc->settings[i].value : "";
            s->settings[i].key = p;
            memcpy(p, k, strlen(k) + 1);
            p += strlen(k) + 1;
            s->settings[i].value = p;
            memcpy(p, v, strlen(v) + 1);
            p += strlen(v) + 1;
        }
        if (s->settings) {
            s->desc.settings = s->settings;
            s->desc.n_settings = desc->n_settings;
        }
    }
    if (!r) r = pg_pipeline_load(desc->pipeline_path, desc->overrides, desc->n_overrides, &s->pipeline, err);
    if (!r && gpu) r = pg_runtime_create(gpu, &s->runtime, err);
    if (!r && s->runtime) pg_runtime_set_settings(s->runtime, s->desc.settings, s->desc.n_settings);
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
        .immediate = s->desc.immediate,
        .output_stages = s->desc.output_stages,
    };
    if (s->scene) cd.features = s->scene->features;
    if (s->runtime) cd.queues = pg_runtime_queue_caps(s->runtime, s->desc.async_off);
    cd.features.light_count = light_count;
    pg_graph_plan *plan = NULL;
    pg_result r = pg_graph_compile(&cd, &plan, err);
    if (r) return r;
    if (s->desc.test_edit_plan) s->desc.test_edit_plan(plan, s->desc.test_edit_user);
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
    /* A frame after which a "grow" buffer was enlarged was incomplete (a pass had less room than
     * it needed): render it again, so every frame the caller sees is complete unless a budget or
     * the device said no (then the pass counts what it dropped). Growth is geometric, so this
     * happens a few times over a session, not every frame. */
    pg_frame_stats local;
    pg_frame_stats *st = stats ? stats : &local;
    uint32_t n_grown = 0, rerenders = 0;
    pg_grow_event grown[4];
    for (;;) {
        if ((r = pg_runtime_render(s->runtime, info, readback, st, err))) return r;
        for (uint32_t i = 0; i < st->n_grown && n_grown < 4; i++) grown[n_grown++] = st->grown[i];
        if (!st->n_grown || rerenders >= 16) break;
        rerenders++;
    }
    st->n_grown = n_grown;
    memcpy(st->grown, grown, sizeof grown[0] * n_grown);
    st->rerenders = rerenders;
    return PG_OK;
}

pg_result pg_session_set_frames_in_flight(pg_session *s, uint32_t n, pg_error *err)
{
    if (!s->runtime) return pg_fail(err, PG_ERR_INVALID_ARG, "session has no GPU");
    return pg_runtime_set_frames_in_flight(s->runtime, n, err);
}

void pg_session_destroy(pg_session *s)
{
    if (!s) return;
    pg_runtime_destroy(s->runtime);
    pg_graph_plan_free(s->plan);
    pg_pipeline_free(s->pipeline);
    free(s->settings);
    free(s);
}
