#include "render_session.h"

#include "scene_gpu_anim.h"

#include <stdlib.h>
#include <string.h>

/* The frame prologue of a scene with animated materials (KHR_animation_pointer): their records at
 * the frame's played animation and time, before any pass reads the material table. */
static bool material_prologue(void *user, VkCommandBuffer cmd, const void *frame_block)
{
    const pg_scene_gpu *sg = user;
    const pg_frame_uniforms *fu = frame_block;
    const int32_t animation = pg_frame_animation(fu);
    return pg_scene_gpu_anim_update_materials(sg->anim, sg->materials.buffer, animation, fu->camera_pos[3], cmd);
}

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
    if (!r && gpu) r = pg_runtime_create(gpu, sizeof(pg_frame_uniforms), &s->runtime, err);
    if (!r && s->runtime) pg_runtime_set_settings(s->runtime, s->desc.settings, s->desc.n_settings);
    if (!r && s->runtime && scene && scene->anim && scene->anim->n_moving_materials)
        pg_runtime_set_frame_prologue(s->runtime, material_prologue, (void *)scene);
    if (r) {
        pg_session_destroy(s);
        return r;
    }
    *out = s;
    return PG_OK;
}

/* The runtime's user block: the session's scene, which does not change over the session's life
 * (one generation). */
static pg_user_block session_user(const pg_session *s)
{
    return (pg_user_block){.data = s->scene, .generation = 1};
}

/* Compiles pipeline for (light_count, width, height) and sets the plan on the runtime. */
static pg_result compile_plan(pg_session *s, const pg_pipeline *pipeline, uint32_t light_count, uint32_t width,
                              uint32_t height, pg_graph_plan **out, pg_error *err)
{
    pg_compile_desc cd = {
        .pipeline = pipeline,
        .registry = s->desc.registry,
        .output_width = width,
        .output_height = height,
        .disable_aliasing = s->desc.disable_aliasing,
        .immediate = s->desc.immediate,
        .output_stages = s->desc.output_stages,
    };
    if (s->runtime) cd.queues = pg_runtime_queue_caps(s->runtime, s->desc.async_off);
    pg_result r = pg_scene_vars_set(&cd.vars, s->scene ? &s->scene->features : NULL, light_count, err);
    if (r) return r;
    pg_graph_plan *plan = NULL;
    if ((r = pg_graph_compile(&cd, &plan, err))) return r;
    if (s->desc.test_edit_plan) s->desc.test_edit_plan(plan, s->desc.test_edit_user);
    if (s->runtime) {
        r = pg_runtime_set_plan(s->runtime, plan, pipeline, session_user(s), width, height, err);
        if (r) {
            pg_graph_plan_free(plan);
            return r;
        }
    }
    *out = plan;
    return PG_OK;
}

/* After a failure: a runtime left without a plan (pg_runtime_set_plan's failures, a failed
 * growth) gets the session's plan again; failing that, the session forgets it, so the next call
 * compiles. It kept it, and since its light count and size still matched, every later render
 * found the runtime without a plan ("no plan set"), also after going back to the old settings. */
static void resync_plan(pg_session *s)
{
    if (!s->runtime || !s->plan || pg_runtime_output_image(s->runtime, 0)) return;
    pg_error e2 = {0};
    if (pg_runtime_set_plan(s->runtime, s->plan, s->pipeline, session_user(s), s->width, s->height, &e2)) {
        pg_graph_plan_free(s->plan);
        s->plan = NULL;
    }
}

pg_result pg_session_compile(pg_session *s, uint32_t light_count, uint32_t width, uint32_t height, pg_error *err)
{
    if (s->plan && light_count == s->light_count && width == s->width && height == s->height) return PG_OK;
    pg_graph_plan *plan = NULL;
    pg_result r = compile_plan(s, s->pipeline, light_count, width, height, &plan, err);
    if (r) {
        resync_plan(s);
        return r;
    }
    pg_graph_plan_free(s->plan);
    s->plan = plan;
    s->light_count = light_count;
    s->width = width;
    s->height = height;
    s->compiles++;
    return PG_OK;
}

pg_result pg_session_reload(pg_session *s, const char *pipeline_path, const pg_param_override *overrides,
                            uint32_t n_overrides, pg_error *err)
{
    pg_pipeline *pl = NULL;
    pg_result r = pg_pipeline_load(pipeline_path, overrides, n_overrides, &pl, err);
    if (r) return r;
    pg_graph_plan *plan = NULL;
    if (s->plan && (r = compile_plan(s, pl, s->light_count, s->width, s->height, &plan, err))) {
        resync_plan(s); /* a failed set_plan leaves the runtime without a plan: set the old one again */
        pg_pipeline_free(pl);
        return r;
    }
    if (plan) {
        pg_graph_plan_free(s->plan);
        s->plan = plan;
        s->compiles++;
    }
    pg_pipeline_free(s->pipeline);
    s->pipeline = pl;
    return PG_OK;
}

pg_result pg_session_render(pg_session *s, const pg_frame_info *info, bool readback, pg_frame_stats *stats,
                            pg_error *err)
{
    if (!s->runtime) return pg_fail(err, PG_ERR_INVALID_ARG, "session has no GPU");
    pg_result r = pg_session_compile(s, info->lights.count, info->width, info->height, err);
    if (r) return r;
    /* the per-frame block every built-in pass reads (set 0): the runtime only copies it */
    pg_frame_info fi = *info;
    fi.width = s->width;
    fi.height = s->height;
    pg_frame_uniforms u;
    pg_frame_uniforms_fill(&fi, &u);
    pg_frame_stats local;
    pg_frame_stats *st = stats ? stats : &local;
    uint32_t n_grown = 0, rerenders = 0;
    pg_grow_event grown[4];
    /* A frame whose pass reports ask a "grow" buffer for more room was incomplete (a pass had
     * less room than it needed): grow it between frames and render the frame again, so every
     * frame the caller sees is complete unless a budget or the device said no (then the pass
     * counts what it dropped). Growth is geometric, so this happens a few times over a session,
     * not every frame; at most 16 re-renders. */
    for (;;) {
        if ((r = pg_runtime_render(s->runtime, &u, readback, st, err))) return r;
        if (!pg_runtime_growth_pending(s->runtime)) break;
        /* between frames: the runtime grows the buffers and re-creates the passes bound to them */
        if ((r = pg_runtime_apply_growth(s->runtime, st, err))) {
            resync_plan(s); /* a failed growth left the runtime without a plan */
            return r;
        }
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
