#include "gpu_harness.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image_util.h"
#include "scenario.h"
#include "shader.h"

bool pg_th_render(pg_gpu *gpu, const pg_pass_registry *reg, const pg_scene_gpu *sg, const char *pipeline,
                  const pg_param_override *sets, uint32_t n_sets, const pg_frame_info *fi, uint32_t frames,
                  bool no_alias, pg_th_frame *out)
{
    memset(out, 0, sizeof *out);
    char path[PG_PATH_MAX];
    pg_data_path(path, sizeof path, pipeline);
    pg_session_desc sd = {.pipeline_path = path, .registry = reg, .disable_aliasing = no_alias,
                          .overrides = sets, .n_overrides = n_sets};
    pg_session *s = NULL;
    pg_error err = {0};
    if (pg_session_create(gpu, sg, &sd, &s, &err)) {
        fprintf(stderr, "%s: %s\n", pipeline, err.msg);
        return false;
    }
    bool ok = true;
    for (uint32_t f = 0; f < frames && ok; f++) {
        if (pg_session_render(s, fi, f + 1 == frames, &out->stats, &err)) {
            fprintf(stderr, "%s: render: %s\n", pipeline, err.msg);
            ok = false;
        }
    }
    if (ok) {
        pg_format fmt, hf;
        uint32_t hw, hh;
        const uint8_t *p = pg_runtime_output(s->runtime, 0, &out->w, &out->h, &fmt);
        const void *hp = pg_runtime_output(s->runtime, 1, &hw, &hh, &hf);
        ok = p && hp && hw == out->w && hh == out->h;
        const pg_format_info *hi = ok ? pg_format_get(hf) : NULL;
        ok = ok && hi && hi->bytes_per_pixel > 0;
        if (ok) {
            out->hdr_format = hf;
            out->hdr_raw_bytes = (size_t)hw * hh * hi->bytes_per_pixel;
            out->ldr = malloc((size_t)out->w * out->h * 4);
            out->hdr = malloc((size_t)hw * hh * 4 * sizeof(float));
            out->hdr_raw = malloc(out->hdr_raw_bytes);
            ok = out->ldr && out->hdr && out->hdr_raw;
        }
        if (ok) {
            memcpy(out->ldr, p, (size_t)out->w * out->h * 4);
            memcpy(out->hdr_raw, hp, out->hdr_raw_bytes);
            ok = !pg_hdr_to_float(hp, hf, hw, hh, out->hdr, &err);
        }
        out->creations = pg_runtime_get_stats(s->runtime).resource_creations;
        out->n_order = s->plan->n_order;
        for (uint32_t b = 0; b < s->plan->n_blocks; b++) out->shared_blocks += s->plan->blocks[b].n_members >= 2;
        out->transient_bytes_unaliased = s->plan->transient_bytes_unaliased;
        out->transient_bytes_aliased = s->plan->transient_bytes_aliased;
        for (uint32_t k = 0; k < s->plan->n_order; k++) {
            size_t len = strlen(out->order);
            snprintf(out->order + len, sizeof out->order - len, "%s%s", k ? "," : "",
                     s->plan->passes[s->plan->order[k]].name);
        }
    }
    pg_session_destroy(s);
    if (!ok) pg_th_release(out);
    return ok;
}

void pg_th_release(pg_th_frame *f)
{
    free(f->ldr);
    free(f->hdr);
    free(f->hdr_raw);
    f->ldr = NULL;
    f->hdr = NULL;
    f->hdr_raw = NULL;
    f->hdr_raw_bytes = 0;
}

bool pg_th_hdr_identical(const pg_th_frame *a, const pg_th_frame *b)
{
    return a->hdr_raw && b->hdr_raw && a->w == b->w && a->h == b->h && a->hdr_format == b->hdr_format &&
           a->hdr_raw_bytes == b->hdr_raw_bytes && memcmp(a->hdr_raw, b->hdr_raw, a->hdr_raw_bytes) == 0;
}

double pg_th_max_abs(const pg_th_frame *a, const pg_th_frame *b, double *ref_peak)
{
    double m = 0, peak = 0;
    for (size_t i = 0; i < (size_t)a->w * a->h * 4; i++) {
        if (i % 4 == 3) continue;
        double d = fabs((double)a->hdr[i] - b->hdr[i]);
        if (!(d <= m)) m = d; /* NaN propagates as "larger" */
        if (b->hdr[i] > peak) peak = b->hdr[i];
    }
    if (ref_peak) *ref_peak = peak;
    return m;
}

uint32_t pg_th_differ_pixels(const pg_th_frame *a, const pg_th_frame *b)
{
    uint32_t n = 0;
    for (size_t i = 0; i < (size_t)a->w * a->h * 4; i += 4)
        if (memcmp(&a->hdr[i], &b->hdr[i], 3 * sizeof(float)) != 0) n++;
    return n;
}

void pg_th_bound_usage(const pg_th_frame *a, const pg_th_frame *ref, double peak, double A, double B, double *usage,
                       double *need_a)
{
    double u = 0, na = 0;
    for (size_t i = 0; i < (size_t)a->w * a->h * 4; i++) {
        if (i % 4 == 3) continue;
        double r = fabs((double)ref->hdr[i]), d = fabs((double)a->hdr[i] - ref->hdr[i]);
        double lim = A * r + B * peak;
        double ui = d == 0 ? 0 : lim > 0 ? d / lim : INFINITY;
        if (!(ui <= u)) u = isnan(ui) ? INFINITY : ui;
        double over = d - B * peak;
        if (over > 0 || isnan(d)) {
            double ai = r > 0 ? over / r : INFINITY;
            if (!(ai <= na)) na = isnan(ai) ? INFINITY : ai;
        }
    }
    *usage = u;
    *need_a = na;
}


bool pg_th_scene_open(pg_gpu *gpu, const char *label, const char *path, const char *scenario, uint32_t w, uint32_t h,
                      uint32_t lights, pg_th_scene *out)
{
    memset(out, 0, sizeof *out);
    pg_error err = {0};
    pg_scenario sc;
    char sc_path[PG_PATH_MAX];
    if (scenario) pg_data_path(sc_path, sizeof sc_path, scenario);
    if ((scenario && pg_scenario_load(sc_path, &sc, &err)) || pg_scene_load(path, &out->scene, &err) ||
        pg_scene_gpu_create(gpu, out->scene, &out->sg, &err)) {
        fprintf(stderr, "%s: %s\n", label, err.msg);
        pg_scene_free(out->scene);
        memset(out, 0, sizeof *out);
        return false;
    }
    out->fi = (pg_frame_info){.camera = pg_camera_default_for_scene(out->scene, (float)w / (float)h),
                              .lights = pg_light_setup_default(out->scene, lights, 7),
                              .time = 0.5f,
                              .width = w,
                              .height = h};
    if (scenario) pg_scenario_apply(&sc, &out->fi.lights, &out->fi.camera);
    out->fi.lights.count = lights;
    return true;
}

void pg_th_scene_close(pg_gpu *gpu, pg_th_scene *s)
{
    if (s->sg) pg_scene_gpu_destroy(gpu, s->sg);
    pg_scene_free(s->scene);
    memset(s, 0, sizeof *s);
}
