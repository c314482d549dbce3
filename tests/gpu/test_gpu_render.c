/* test_gpu_render.c - renders real scenes on the Vulkan device (lavapipe in CI) with the
 * Khronos validation layer and synchronization validation on; any validation message fails.
 * Checks that images are lit (not blank), deterministic across runs, animated over time,
 * identical with aliasing disabled, finite in HDR, and that resources are not re-created per
 * frame. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "image_util.h"
#include "pass_list.h"
#include "render_session.h"
#include "scenario.h"
#include "shader.h"
#include "test_util.h"

#define W 320
#define H 180

typedef struct frame_out {
    uint8_t *ldr;
    float *hdr;
    uint32_t w, h;
    pg_frame_stats stats;
    uint32_t creations;
} frame_out;

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;

static bool render(const pg_scene_gpu *sg, const pg_scene *scene, const char *pipeline, uint32_t lights, float t,
                   bool no_alias, uint32_t frames, const pg_param_override *sets, uint32_t n_sets, frame_out *out)
{
    memset(out, 0, sizeof *out);
    char path[PG_PATH_MAX];
    pg_data_path(path, sizeof path, pipeline);
    pg_session_desc sd = {.pipeline_path = path, .registry = &g_reg, .disable_aliasing = no_alias,
                          .overrides = sets, .n_overrides = n_sets};
    pg_session *s = NULL;
    pg_error err = {0};
    if (pg_session_create(g_gpu, sg, &sd, &s, &err)) {
        fprintf(stderr, "session: %s\n", err.msg);
        return false;
    }
    pg_frame_info fi = {
        .camera = pg_camera_default_for_scene(scene, (float)W / H),
        .lights = pg_light_setup_default(scene, lights, 7),
        .time = t,
        .width = W,
        .height = H,
    };
    bool ok = true;
    for (uint32_t f = 0; f < frames && ok; f++) {
        if (pg_session_render(s, &fi, f + 1 == frames, &out->stats, &err)) {
            fprintf(stderr, "render: %s\n", err.msg);
            ok = false;
        }
    }
    if (ok) {
        pg_format fmt;
        const uint8_t *p = pg_runtime_output(s->runtime, 0, &out->w, &out->h, &fmt);
        uint32_t hw, hh;
        pg_format hf;
        const void *hp = pg_runtime_output(s->runtime, 1, &hw, &hh, &hf);
        ok = p && hp;
        if (ok) {
            out->ldr = malloc((size_t)out->w * out->h * 4);
            out->hdr = malloc((size_t)hw * hh * 4 * sizeof(float));
            memcpy(out->ldr, p, (size_t)out->w * out->h * 4);
            ok = !pg_hdr_to_float(hp, hf, hw, hh, out->hdr, &err);
        }
        out->creations = pg_runtime_get_stats(s->runtime).resource_creations;
    }
    pg_session_destroy(s);
    return ok;
}

static void release(frame_out *f)
{
    free(f->ldr);
    free(f->hdr);
    memset(f, 0, sizeof *f);
}

static void check_scene(const char *label, const char *scene_path)
{
    pg_error err = {0};
    pg_scene *scene = NULL;
    if (pg_scene_load(scene_path, &scene, &err)) {
        CHECK_MSG(0, "%s: %s", label, err.msg);
        return;
    }
    pg_scene_gpu *sg = NULL;
    if (pg_scene_gpu_create(g_gpu, scene, &sg, &err)) {
        CHECK_MSG(0, "%s: %s", label, err.msg);
        pg_scene_free(scene);
        return;
    }
    frame_out a, b, c, d;
    bool ok_a = render(sg, scene, "pipelines/naive.json", 256, 1.0f, false, 3, NULL, 0, &a);
    bool ok_b = render(sg, scene, "pipelines/naive.json", 256, 1.0f, false, 1, NULL, 0, &b);
    bool ok_c = render(sg, scene, "pipelines/naive.json", 256, 7.5f, false, 1, NULL, 0, &c);
    bool ok_d = render(sg, scene, "pipelines/naive.json", 256, 1.0f, true, 1, NULL, 0, &d);
    CHECK_MSG(ok_a && ok_b && ok_c && ok_d, "%s: renders", label);
    if (ok_a && ok_b && ok_c && ok_d) {
        pg_image_stats st = pg_rgba8_stats(a.ldr, a.w, a.h);
        printf("%s: mean luma %.1f, lit %.1f%%, %u distinct colours sampled, gpu %.2f ms\n", label, st.mean_luma,
               100 * st.lit_fraction, st.distinct_colors_sampled, a.stats.gpu_total_ms);
        CHECK_MSG(st.mean_luma > 10.0, "%s: image too dark (mean luma %.1f)", label, st.mean_luma);
        CHECK_MSG(st.lit_fraction > 0.25, "%s: only %.1f%% of pixels lit", label, 100 * st.lit_fraction);
        CHECK_MSG(st.distinct_colors_sampled > 200, "%s: only %u distinct colours (blank/flat?)", label,
                  st.distinct_colors_sampled);
        CHECK_MSG(memcmp(a.ldr, b.ldr, (size_t)a.w * a.h * 4) == 0, "%s: not deterministic across runs", label);
        CHECK_MSG(memcmp(a.hdr, b.hdr, (size_t)a.w * a.h * 16) == 0, "%s: HDR not deterministic", label);
        CHECK_MSG(memcmp(a.ldr, c.ldr, (size_t)a.w * a.h * 4) != 0, "%s: lights do not move over time", label);
        CHECK_MSG(memcmp(a.ldr, d.ldr, (size_t)a.w * a.h * 4) == 0, "%s: --no-aliasing changes the image", label);
        CHECK_MSG(pg_count_nonfinite(a.hdr, a.w, a.h) == 0, "%s: non-finite HDR pixels", label);
        CHECK_MSG(a.creations == 1, "%s: resources re-created %u times over 3 frames", label, a.creations);
        CHECK_MSG(a.stats.timestamps_valid && a.stats.gpu_total_ms > 0, "%s: no GPU timings", label);
        char png[256];
        snprintf(png, sizeof png, "test_gpu_render_%s.png", label);
        pg_write_png(png, a.ldr, a.w, a.h, &err);
    }
    release(&a);
    release(&b);
    release(&c);
    release(&d);
    pg_scene_gpu_destroy(g_gpu, sg);
    pg_scene_free(scene);
}

/* Extreme light settings must give finite, bounded HDR: zero radius, huge radius and
 * intensity, zero lights. */
static void check_extremes(void)
{
    pg_error err = {0};
    pg_scene *scene = NULL;
    pg_scene_gpu *sg = NULL;
    if (pg_scene_create_default(&scene, &err) || pg_scene_gpu_create(g_gpu, scene, &sg, &err)) {
        CHECK_MSG(0, "extremes: %s", err.msg);
        pg_scene_free(scene);
        return;
    }
    struct {
        const char *label;
        uint32_t lights;
        float radius, intensity;
    } cases[] = {
        {"zero lights", 0, 1.0f, 1.0f},
        {"radius 0", 16, 0.0f, 1.0f},
        {"radius 1e6 intensity 1e6", 16, 1e6f, 1e6f},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char path[PG_PATH_MAX];
        pg_data_path(path, sizeof path, "pipelines/naive.json");
        pg_session_desc sd = {.pipeline_path = path, .registry = &g_reg};
        pg_session *s = NULL;
        if (pg_session_create(g_gpu, sg, &sd, &s, &err)) {
            CHECK_MSG(0, "%s: %s", cases[i].label, err.msg);
            continue;
        }
        pg_frame_info fi = {.camera = pg_camera_default_for_scene(scene, (float)W / H),
                            .lights = pg_light_setup_default(scene, cases[i].lights, 3),
                            .time = 0.5f, .width = W, .height = H};
        fi.lights.radius = cases[i].radius;
        fi.lights.intensity = cases[i].intensity;
        pg_frame_stats st;
        bool ok = !pg_session_render(s, &fi, true, &st, &err);
        CHECK_MSG(ok, "%s: %s", cases[i].label, err.msg);
        uint32_t hw, hh;
        pg_format hf;
        const void *hp = ok ? pg_runtime_output(s->runtime, 1, &hw, &hh, &hf) : NULL;
        if (hp) {
            float *hdr = malloc((size_t)hw * hh * 16);
            pg_hdr_to_float(hp, hf, hw, hh, hdr, &err);
            float maxv = 0;
            for (size_t k = 0; k < (size_t)hw * hh * 4; k++)
                if (k % 4 != 3 && isfinite(hdr[k]) && hdr[k] > maxv) maxv = hdr[k]; /* RGB only */
            uint64_t bad = pg_count_nonfinite(hdr, hw, hh);
            printf("extremes: %s: max HDR %.6g, non-finite %llu\n", cases[i].label, maxv, (unsigned long long)bad);
            CHECK_MSG(bad == 0, "%s: %llu non-finite pixels", cases[i].label, (unsigned long long)bad);
            CHECK_MSG(maxv <= 65000.0f, "%s: HDR above the bound: %g", cases[i].label, maxv);
            if (cases[i].lights == 0 || cases[i].radius == 0.0f)
                CHECK_MSG(maxv == 0.0f, "%s: expected black (ambient 0), max %g", cases[i].label, maxv);
            free(hdr);
        }
        pg_session_destroy(s);
    }
    pg_scene_gpu_destroy(g_gpu, sg);
    pg_scene_free(scene);
}

int main(void)
{
    pg_register_builtin_passes(&g_reg);
    pg_gpu_desc gd = {.validation = true, .device_index = -1};
    pg_error err = {0};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_gpu_render: %s\n", err.msg);
        return 1;
    }
    check_scene("default", "default");
    check_extremes();
    char sponza[PG_PATH_MAX];
    snprintf(sponza, sizeof sponza, "%s/assets/dabrovic-sponza/sponza.gltf", PG_SHARED_DIR);
    if (access(sponza, R_OK) == 0) check_scene("sponza", sponza);
    else printf("test_gpu_render: Sponza skipped: %s not found\n", sponza);
    printf("validation messages: %u\n", g_gpu->validation_messages);
    CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_gpu_render");
}
