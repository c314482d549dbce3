/* test_gpu_lightcut.c - the lightcut pipeline's stated bound (pipelines/lightcut.json,
 * shaders/shading.glsl pg_lightcut, renderer/passes/light_tree.c) on lavapipe with validation on
 * (zero messages). For every light set below and lightcut_error eps in {0.02, 0.2}, every pixel
 * and HDR channel (rgba32f) of lightcut must hold
 *     |lightcut - exact| <= eps |exact| + 1e-4 |exact| + 1e-6 peak
 * against pipelines/visibility.json (the same surfaces, every light of the cluster lists summed);
 * the second and third terms are float rounding (the two sum the same lights in another order).
 * Light sets (the default atrium, 96x54, seeds vary): the scene's default lights; a dense clump
 * (every light in a box 2% of the atrium's size); huge radii (every light reaches everything);
 * tiny radii; lights spread over the floor's height (on the surfaces); 2,000 lights. A light
 * tree of one light and of 0 lights renders too.
 * Blinn-Phong too (the default lights, the clump, lights on the floor), whose image differs from
 * Lambert's on the atrium. Also: the frame is deterministic (rendered twice, bit-identical); eps 0.2 approximates (its
 * image differs from exact by more than rounding: the knob does something); and the checker
 * itself can fail: the eps 0.2 image against the eps 0.02 bound is outside it somewhere (these with
 * lightcut_bucket 1, the plain walk). Every set also with the exact buckets (lightcut_bucket 2, 32: the
 * default, and 256; Blinn-Phong's with 32): within the bound, and on the default lights each image
 * differs from the plain walk's. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gpu_harness.h"
#include "image_util.h"
#include "pass_list.h"
#include "test_util.h"

#define W 96
#define H 54

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;
static const char *g_shading = "lambert"; /* the light model of both pipelines */
/* lightcut_bucket sizes each light set is checked with: "1" the plain walk (every node walked down to
 * its leaves) first, then exact buckets (a refined node of at most that many leaves summed exactly):
 * a small one, the pipeline's default (32) and the largest */
static const char *const k_buckets[] = {"1", "2", "32", "256"};
static const char *const k_bp_buckets[] = {"1", "32"}; /* Blinn-Phong's: the plain walk and the default */
static const char *const *g_buckets = k_buckets;
static int g_nbuckets = 4;

/* worst |a - exact| / (eps |exact| + 1e-4 |exact| + 1e-6 peak) over pixels and RGB (<= 1: inside) */
static double usage(const pg_th_frame *a, const pg_th_frame *exact, double eps, double peak)
{
    double worst = 0;
    for (size_t i = 0; i < (size_t)W * H * 4; i++) {
        if (i % 4 == 3) continue;
        double e = exact->hdr[i], d = fabs((double)a->hdr[i] - e);
        double bound = eps * fabs(e) + 1e-4 * fabs(e) + 1e-6 * peak;
        if (bound > 0) worst = fmax(worst, d / bound);
        else if (d != 0) worst = INFINITY; /* also NaN */
    }
    return worst;
}

/* One bucket size's two lightcut images of the frame (eps 0.02 and 0.2) against the exact one: both
 * within the bound and finite. false when a render failed (lc released then). */
static bool check_bucket(const char *label, const pg_th_scene *ts, const pg_frame_info *fi, const pg_th_frame *ex,
                         double peak, const char *bucket, pg_th_frame lc[2])
{
    const char *eps_s[2] = {"0.02", "0.2"};
    const double eps[2] = {0.02, 0.2};
    bool ok[2];
    for (int k = 0; k < 2; k++) {
        pg_param_override sets[4] = {{"hdr_format", "rgba32f"}, {"lightcut_error", eps_s[k]}, {"shading", g_shading},
                                     {"lightcut_bucket", bucket}};
        ok[k] = pg_th_render(g_gpu, &g_reg, ts->sg, "pipelines/lightcut.json", sets, 4, fi, 1, false, &lc[k]);
        CHECK_MSG(ok[k], "%s: lightcut render (eps %s, bucket %s)", label, eps_s[k], bucket);
        if (!ok[k]) continue;
        double u = usage(&lc[k], ex, eps[k], peak);
        printf("%-22s bucket %-3s lights %7u peak %9.4g  eps %-4s bound usage %.4f  differing pixels %u\n", label,
               bucket, fi->lights.count, peak, eps_s[k], u, pg_th_differ_pixels(&lc[k], ex));
        CHECK_MSG(u <= 1.0, "%s: bucket %s, eps %s: outside the bound (usage %.4f)", label, bucket, eps_s[k], u);
        CHECK_MSG(pg_count_nonfinite(lc[k].hdr, W, H) == 0, "%s: non-finite pixels", label);
    }
    if (ok[0] && ok[1]) return true;
    for (int k = 0; k < 2; k++)
        if (ok[k]) pg_th_release(&lc[k]);
    return false;
}

/* The light set against the exact image (rendered once) with each bucket size of g_buckets, "1" (the
 * plain walk) first. With the plain walk on the default lights: eps 0.2 approximates and is outside
 * the eps 0.02 bound somewhere (the checker can fail); with every other bucket size there, the eps 0.2
 * image differs from the plain walk's (the buckets sum exactly lights the walk approximated). */
static void check_set(const char *label, const pg_th_scene *ts, const pg_light_setup *ls)
{
    pg_frame_info fi = ts->fi;
    fi.lights = *ls;
    pg_param_override f32[2] = {{"hdr_format", "rgba32f"}, {"shading", g_shading}};
    pg_th_frame ex;
    if (!pg_th_render(g_gpu, &g_reg, ts->sg, "pipelines/visibility.json", f32, 2, &fi, 1, false, &ex)) {
        CHECK_MSG(0, "%s: exact render", label);
        return;
    }
    double peak = 0;
    pg_th_max_abs(&ex, &ex, &peak);
    CHECK_MSG(peak > 0 || ls->count == 0, "%s: the exact image is black (the case tests nothing)", label);
    bool powers = !strcmp(label, "default lights");
    pg_th_frame plain; /* the plain walk's eps 0.2 image (powers) */
    bool have_plain = false;
    for (int b = 0; b < g_nbuckets; b++) {
        pg_th_frame lc[2];
        if (!check_bucket(label, ts, &fi, &ex, peak, g_buckets[b], lc)) continue;
        if (b == 0 && ls->count > 1 && peak > 0) {
            double loose = usage(&lc[1], &ex, 0.0, peak); /* eps 0.2 against rounding alone */
            printf("%-22s eps 0.2 against exact with no approximation allowed: usage %.3g; against the 0.02 bound: %.3g\n",
                   label, loose, usage(&lc[1], &ex, 0.02, peak));
            if (powers) {
                CHECK_MSG(loose > 1.0, "%s: eps 0.2 approximates nothing (the knob does nothing)", label);
                CHECK_MSG(usage(&lc[1], &ex, 0.02, peak) > 1.0, "%s: the checker cannot fail", label);
            }
        }
        if (b > 0 && powers && have_plain) {
            uint32_t differ = pg_th_differ_pixels(&lc[1], &plain);
            printf("bucket %s: %u of %u pixels differ from the plain walk (eps 0.2)\n", g_buckets[b], differ, W * H);
            CHECK_MSG(differ > 0, "bucket %s: the image is the plain walk's (the knob does nothing)", g_buckets[b]);
        }
        pg_th_release(&lc[0]);
        if (b == 0 && powers) plain = lc[1], have_plain = true;
        else pg_th_release(&lc[1]);
    }
    if (have_plain) pg_th_release(&plain);
    pg_th_release(&ex);
}

/* Blinn-Phong (its bound adds the specular colour to the albedo): the default lights, the clump and
 * lights on the floor; its exact image differs from Lambert's (the atrium's materials have a
 * specular term, so the case tests the specular bound) */
static void blinn_phong(const pg_th_scene *ts, const pg_light_setup *base)
{
    pg_param_override f32[2] = {{"hdr_format", "rgba32f"}, {"shading", "lambert"}};
    pg_th_frame lam, bp;
    bool ok = pg_th_render(g_gpu, &g_reg, ts->sg, "pipelines/visibility.json", f32, 2, &ts->fi, 1, false, &lam);
    f32[1].value = "blinn_phong";
    ok = pg_th_render(g_gpu, &g_reg, ts->sg, "pipelines/visibility.json", f32, 2, &ts->fi, 1, false, &bp) && ok;
    CHECK_MSG(ok, "blinn_phong: exact renders");
    if (ok) {
        uint32_t differ = pg_th_differ_pixels(&lam, &bp);
        printf("blinn_phong: %u of %u pixels differ from lambert\n", differ, W * H);
        CHECK_MSG(differ > W * H / 10, "blinn_phong: only %u pixels differ from lambert (no specular to bound)", differ);
        pg_th_release(&lam);
        pg_th_release(&bp);
    }
    g_shading = "blinn_phong";
    g_buckets = k_bp_buckets;
    g_nbuckets = 2;
    check_set("bp default lights", ts, base);
    pg_light_setup s = *base;
    float ext[3], mid[3];
    for (int a = 0; a < 3; a++) ext[a] = base->box_max[a] - base->box_min[a], mid[a] = 0.5f * (base->box_max[a] + base->box_min[a]);
    for (int a = 0; a < 3; a++) s.box_min[a] = mid[a] - 0.01f * ext[a], s.box_max[a] = mid[a] + 0.01f * ext[a];
    s.seed = 3;
    check_set("bp dense clump", ts, &s);
    s = *base;
    s.box_max[1] = base->box_min[1] + 0.02f * ext[1];
    s.seed = 6;
    check_set("bp on the floor", ts, &s);
    g_shading = "lambert";
    g_buckets = k_buckets;
    g_nbuckets = 4;
}

static void check_deterministic(const pg_th_scene *ts)
{
    pg_param_override f32 = {"hdr_format", "rgba32f"};
    pg_th_frame a, b;
    bool ok = pg_th_render(g_gpu, &g_reg, ts->sg, "pipelines/lightcut.json", &f32, 1, &ts->fi, 1, false, &a);
    ok = pg_th_render(g_gpu, &g_reg, ts->sg, "pipelines/lightcut.json", &f32, 1, &ts->fi, 1, false, &b) && ok;
    CHECK_MSG(ok && pg_th_hdr_identical(&a, &b), "lightcut: two renders of one frame differ");
    pg_th_release(&a);
    pg_th_release(&b);
}

/* The light sets: the scene's default lights, a dense clump, huge radii, tiny radii, lights in a thin
 * layer at the floor, 2,000 lights, one light and none. */
static void check_sets(const pg_th_scene *ts)
{
    const pg_light_setup base = ts->fi.lights;
    float ext[3], mid[3];
    for (int a = 0; a < 3; a++) ext[a] = base.box_max[a] - base.box_min[a], mid[a] = 0.5f * (base.box_max[a] + base.box_min[a]);
    check_set("default lights", ts, &base);
    pg_light_setup s = base;
    for (int a = 0; a < 3; a++) s.box_min[a] = mid[a] - 0.01f * ext[a], s.box_max[a] = mid[a] + 0.01f * ext[a];
    s.seed = 3;
    check_set("dense clump", ts, &s);
    s = base;
    s.radius = base.radius * 50;
    s.intensity = base.intensity / 50;
    s.seed = 4;
    check_set("huge radii", ts, &s);
    s = base;
    s.radius = base.radius * 0.25f;
    s.intensity = base.intensity * 16;
    s.seed = 5;
    check_set("tiny radii", ts, &s);
    s = base;
    s.box_max[1] = base.box_min[1] + 0.02f * ext[1]; /* a thin layer at the floor */
    s.seed = 6;
    check_set("on the floor", ts, &s);
    s = base;
    s.count = 2000;
    s.seed = 7;
    check_set("2000 lights", ts, &s);
    s = base;
    s.count = 1;
    check_set("one light", ts, &s);
    s.count = 0;
    check_set("no lights", ts, &s);
}

int main(void)
{
    if (getenv("PG_TEST_NO_GPU")) return pg_test_skip("test_gpu_lightcut", "PG_TEST_NO_GPU set");
    pg_register_builtin_passes(&g_reg);
    pg_gpu_desc gd = {.validation = true, .device_index = -1, .quiet = true};
    pg_error err = {0};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_gpu_lightcut: %s\n", err.msg);
        return 1;
    }
    pg_th_scene ts;
    if (!pg_th_scene_open(g_gpu, "atrium", "default", NULL, W, H, 400, &ts)) {
        CHECK_MSG(0, "scene");
        pg_gpu_destroy(g_gpu);
        return pg_test_finish("test_gpu_lightcut");
    }
    check_sets(&ts);
    check_deterministic(&ts);
    const pg_light_setup base = ts.fi.lights;
    blinn_phong(&ts, &base);
    pg_th_scene_close(g_gpu, &ts);
    printf("validation messages: %u\n", g_gpu->validation_messages);
    CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_gpu_lightcut");
}
