#include "gpu_harness.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image_util.h"
#include "accuracy_bounds.h"
#include "default_view.h"
#include "scenario.h"
#include "test_util.h"
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
    pg_th_bound_usage_masked(a, ref, peak, A, B, NULL, 0, usage, need_a);
}

void pg_th_bound_usage_masked(const pg_th_frame *a, const pg_th_frame *ref, double peak, double A, double B,
                              const uint8_t *mask, uint8_t sel, double *usage, double *need_a)
{
    double u = 0, na = 0;
    for (size_t i = 0; i < (size_t)a->w * a->h * 4; i++) {
        if (i % 4 == 3 || (mask ? mask[i / 4] : 0) != sel) continue;
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


void pg_th_pipelines_vs_ref(pg_gpu *gpu, const pg_pass_registry *reg, const pg_scene_gpu *sg, const pg_frame_info *fi,
                            const pg_th_frame *ref, const pg_th_frame *ray_ref, const char *label, double extra)
{
    static const struct {
        const char *path;
        double a, b;
        bool ray; /* its surface is the pixel's ray: measured against ray_ref */
    } pipes[] = {{"pipelines/naive.json", 0, 0, false},
                 {"pipelines/forward_plus.json", 0, 0, false},
                 {"pipelines/deferred.json", FLOAT_PX_A, FLOAT_PX_B, false},
                 {"pipelines/deferred_oct16.json", OCT16_PX_A, OCT16_PX_B, false},
                 {"pipelines/deferred_packed.json", PACKED_PX_A, PACKED_PX_B, false},
                 {"pipelines/visibility.json", VIS_PX_A, VIS_PX_B, true},
                 {"pipelines/lightcut.json", 0.02, 0, true}};
    const size_t n = (size_t)ref->w * ref->h;
    double peak = 0;
    for (size_t i = 0; i < n * 4; i++)
        if (i % 4 != 3) peak = fmax(peak, ref->hdr[i]);
    pg_th_frame naive;
    memset(&naive, 0, sizeof naive);
    for (size_t k = 0; k < sizeof pipes / sizeof pipes[0]; k++) {
        pg_th_frame f;
        if (!pg_th_render(gpu, reg, sg, pipes[k].path, NULL, 0, fi, 1, false, &f)) {
            CHECK_MSG(0, "%s: %s: render failed", label, pipes[k].path);
            continue;
        }
        bool ray = pipes[k].ray && ray_ref;
        const pg_th_frame *r_img = ray ? ray_ref : ref;
        double over = 0;
        for (size_t i = 0; i < n; i++)
            for (int c = 0; c < 3; c++) {
                double r = r_img->hdr[i * 4 + c], d = fabs(f.hdr[i * 4 + c] - r);
                double bound = (pipes[k].a + 2e-3) * fabs(r) + pipes[k].b * peak + extra + 1e-6;
                over = fmax(over, d / bound);
            }
        printf("%s: %s vs reference%s: bound usage %.3f\n", label, pipes[k].path, ray ? " surface=ray" : "", over);
        CHECK_MSG(over <= 1.0, "%s: %s: %.3f of the bound", label, pipes[k].path, over);
        if (k == 0) {
            naive = f;
            continue;
        }
        if (k == 1) CHECK_MSG(pg_th_hdr_identical(&f, &naive), "%s: forward_plus is not bit-identical to naive", label);
        pg_th_release(&f);
    }
    pg_th_release(&naive);
}

bool pg_th_scene_open(pg_gpu *gpu, const char *label, const char *path, const char *scenario, uint32_t w, uint32_t h,
                      uint32_t lights, pg_th_scene *out)
{
    memset(out, 0, sizeof *out);
    pg_error err = {0};
    pg_scenario sc;
    char sc_path[PG_PATH_MAX];
    if (scenario) pg_data_path(sc_path, sizeof sc_path, scenario);
    bool loaded = !(scenario && pg_scenario_load(sc_path, &sc, &err)) && !pg_scene_load(path, &out->scene, &err);
    if (loaded && scenario && pg_scenario_shading(&sc) >= 0) /* as the tools: the scenario's model for "auto" */
        out->scene->features.auto_shading = (uint8_t)pg_scenario_shading(&sc);
    if (!loaded || pg_scene_gpu_create(gpu, out->scene, &out->sg, &err)) {
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

void pg_th_pixel_ray(const pg_frame_info *fi, uint32_t x, uint32_t y, double a[3], double b[3])
{
    pg_camera cam = fi->camera;
    cam.aspect = (float)fi->width / (float)fi->height;
    float V[16], P[16], VP[16], inv[16];
    pg_camera_view(&cam, V);
    pg_camera_proj(&cam, P);
    pg_mat4_mul(P, V, VP);
    pg_mat4_invert(VP, inv);
    double ndc[2] = {(x + 0.5) / fi->width * 2 - 1, (y + 0.5) / fi->height * 2 - 1};
    for (int e = 0; e < 2; e++) {
        double z = e ? 1.0 : 0.0, h[4];
        for (int r = 0; r < 4; r++)
            h[r] = inv[0 * 4 + r] * ndc[0] + inv[1 * 4 + r] * ndc[1] + inv[2 * 4 + r] * z + inv[3 * 4 + r];
        for (int k = 0; k < 3; k++) (e ? b : a)[k] = h[k] / h[3];
    }
}

bool pg_th_floor_point(const pg_frame_info *fi, uint32_t x, uint32_t y, bool box, double p[3])
{
    double a[3], b[3];
    pg_th_pixel_ray(fi, x, y, a, b);
    if (!(fabs(b[1] - a[1]) > 1e-12)) return false;
    double t = -a[1] / (b[1] - a[1]);
    for (int k = 0; k < 3; k++) p[k] = a[k] + t * (b[k] - a[k]);
    if (box) { /* slab test along a + s (b - a), s in [0, t] */
        const double lo[3] = {-0.5, 0, -0.5}, hi[3] = {0.5, 1, 0.5};
        double s0 = 0, s1 = t;
        for (int k = 0; k < 3; k++) {
            double dk = b[k] - a[k];
            if (fabs(dk) < 1e-300) {
                if (a[k] < lo[k] || a[k] > hi[k]) s0 = 2, s1 = 1;
                continue;
            }
            double u = (lo[k] - a[k]) / dk, v = (hi[k] - a[k]) / dk;
            s0 = fmax(s0, fmin(u, v));
            s1 = fmin(s1, fmax(u, v));
        }
        if (s0 <= s1 + 1e-9) return false; /* the box is in the way (or touches the point) */
    }
    return fabs(p[0]) < 4.9 && fabs(p[2]) < 4.9;
}

bool pg_th_file_open(pg_gpu *gpu, const char *rel, uint32_t w, uint32_t h, int shading, pg_th_scene *out)
{
    char path[PG_PATH_MAX];
    snprintf(path, sizeof path, "%s/corpus/gltf/%s", PG_TEST_DIR, rel);
    pg_error err = {0};
    memset(out, 0, sizeof *out);
    if (!pg_scene_load(path, &out->scene, &err) && shading >= 0) out->scene->features.auto_shading = (uint8_t)shading;
    if (!out->scene || pg_scene_gpu_create(gpu, out->scene, &out->sg, &err)) {
        CHECK_MSG(0, "%s: %s", rel, err.msg);
        pg_scene_free(out->scene);
        memset(out, 0, sizeof *out);
        return false;
    }
    pg_frame_info fi = {.time = 0, .width = w, .height = h};
    char cw[256], lw[256];
    if (pg_scene_default_view(out->scene, NULL, (float)w / (float)h, 0, 1, &fi.camera, &fi.lights, cw, sizeof cw, lw,
                              sizeof lw, &err))
        CHECK_MSG(0, "%s: default view: %s", rel, err.msg);
    fi.lights.count = fi.lights.file_count = out->scene->n_lights; /* the file's lights alone */
    out->fi = fi;
    return true;
}

void pg_th_scene_close(pg_gpu *gpu, pg_th_scene *s)
{
    if (s->sg) pg_scene_gpu_destroy(gpu, s->sg);
    pg_scene_free(s->scene);
    memset(s, 0, sizeof *s);
}
