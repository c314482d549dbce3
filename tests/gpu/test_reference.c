/* test_reference.c - pipelines/reference.json (gbuffer with camera-relative rgba32f position, then
 * the reference_lighting compute pass) against the naive forward reference, on lavapipe with
 * validation + synchronization validation (any message fails the test).
 *
 * Claim: the reference's HDR image is BIT-IDENTICAL to naive's in the same format (naive is
 * rendered with hdr_format=rgba32f, the reference's default; both in rgba16f are compared too).
 * Why it can be: the surface is the same (gbuffer.frag runs the same vertex shader, rasterizer
 * and pg_surface() as forward.frag, and stores albedo, normal, specular, shininess and the
 * interpolated camera-relative position in rgba32f, i.e. unrounded; depth testing keeps the same
 * fragment), the light loop is the same (pg_accumulate_light for lights 0, 1, ..., N-1 in that
 * order, only fetched through shared memory), the ending is the same (pg_shade_combine,
 * pg_hdr_sanitize), and splitting the loop over dispatches stores the fp32 sums in rgba32f
 * images, which changes no bit. So the test compares memory (memcmp of the float images), not a
 * tolerance. A driver that compiled the same expressions differently in a fragment and a
 * compute shader (e.g. contracting a*b+c into an FMA in one only) would break equality; then the
 * difference is rounding, a few ulp of each light's term, and this test would say so.
 *
 * Cases: the generated atrium and Sponza (skipped if absent) at 320x180, 0, 1, 100 and 1000
 * lights, lambert and blinn_phong; on the atrium also 0 lights with ambient, the split light loop
 * (lights_per_dispatch 37 and 256: several dispatches, a partial last tile), both targets in
 * rgba16f, and the debug views albedo, normal, depth. 0 lights: the light animation is culled.
 * Controls (the comparison can fail): a different ambient and half the lights must differ.
 * 1,000,000 lights at 32x18: finite, lit, and the same bits with two different splits (32768
 * and 20000 lights a dispatch), so no dispatch drops lights.
 *
 * surface=ray (a visibility pass and visibility_resolve with packing float instead of the raster
 * G-buffer): on the atrium (100 lights), the pbr spheres, a textured normal-mapped model, an
 * emissive scene and a TEXCOORD_1 texture, within the visibility pipeline's bounds of the raster
 * surface (accuracy_bounds.h; RMSE only where textured) and not bit-identical to it (the ray path
 * ran); on the atrium, whose lights all have a range, the visibility pipeline in rgba32f is
 * bit-identical to it; half the lights must differ (control).
 *
 * Naive is not compared above 65,535 lights: llvmpipe ends every loop of a shader invocation once
 * all of them together ran 65535 iterations (gallivm LP_MAX_TGSI_LOOP_ITERATIONS), so naive's
 * fragment loop silently stops at light 65535 on lavapipe. The reference keeps each dispatch at
 * <= 32768 lights for that reason. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "accuracy_bounds.h"
#include "default_view.h"
#include "gpu_harness.h"
#include "image_util.h"
#include "pass_list.h"
#include "test_util.h"

#define W 320
#define H 180
#define FILE_W 160 /* the corpus files of surface_ray */
#define FILE_H 90

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;

static pg_frame_info frame_for(const pg_scene *scene, uint32_t lights, uint32_t w, uint32_t h)
{
    pg_frame_info fi = {
        .camera = pg_camera_default_for_scene(scene, (float)w / h),
        .lights = pg_light_setup_default(scene, lights, 7),
        .time = 1.25f,
        .width = w,
        .height = h,
    };
    return fi;
}

typedef struct diff {
    double max_abs, peak;
    uint64_t pixels; /* pixels with any channel (alpha included) not bit-identical */
} diff;

static diff compare(const pg_th_frame *a, const pg_th_frame *ref)
{
    diff d = {0};
    d.max_abs = pg_th_max_abs(a, ref, &d.peak);
    for (size_t p = 0; p < (size_t)a->w * a->h; p++)
        if (memcmp(a->hdr + 4 * p, ref->hdr + 4 * p, 4 * sizeof(float))) d.pixels++;
    return d;
}

static bool identical(const pg_th_frame *a, const pg_th_frame *ref)
{
    return a->w == ref->w && a->h == ref->h && memcmp(a->hdr, ref->hdr, (size_t)a->w * a->h * 4 * sizeof(float)) == 0 &&
           memcmp(a->ldr, ref->ldr, (size_t)a->w * a->h * 4) == 0;
}

static bool render(const pg_scene_gpu *sg, const char *pipeline, const pg_param_override *sets, uint32_t n_sets,
                   const pg_frame_info *fi, pg_th_frame *out)
{
    return pg_th_render(g_gpu, &g_reg, sg, pipeline, sets, n_sets, fi, 1, false, out);
}

/* Renders the reference with sets and checks it is bit-identical to ref. */
static void expect_identical(const char *what, const pg_scene_gpu *sg, const pg_param_override *sets, uint32_t n_sets,
                             const pg_frame_info *fi, const pg_th_frame *ref)
{
    pg_th_frame f;
    if (!render(sg, "pipelines/reference.json", sets, n_sets, fi, &f)) {
        CHECK_MSG(0, "%s: reference does not render", what);
        return;
    }
    diff d = compare(&f, ref);
    printf("  %-52s peak %-10.4g %s (max |d| %g, %llu pixels differ) gpu %.1f ms\n", what, d.peak,
           identical(&f, ref) ? "bit-identical" : "DIFFERENT", d.max_abs, (unsigned long long)d.pixels,
           f.stats.gpu_total_ms);
    CHECK_MSG(identical(&f, ref), "%s: reference differs from naive: max |d| %g (peak %g), %llu pixels", what,
              d.max_abs, d.peak, (unsigned long long)d.pixels);
    CHECK_MSG(pg_count_nonfinite(f.hdr, f.w, f.h) == 0, "%s: non-finite pixels", what);
    pg_th_release(&f);
}

/* A deliberately different frame must be reported as different: more than 1% of the pixels
 * differ by more than 1e-3 of their own value (the ambient control adds a few hundredths to
 * pixels that reach 100 elsewhere, so a bound relative to the peak would not see it). */
static void expect_different(const char *what, const pg_th_frame *f, const pg_th_frame *ref)
{
    diff d = compare(f, ref);
    uint64_t n = 0;
    for (size_t p = 0; p < (size_t)f->w * f->h; p++) {
        bool differs = false;
        for (int k = 0; k < 3; k++) {
            double a = f->hdr[4 * p + k], b = ref->hdr[4 * p + k];
            differs |= fabs(a - b) > 1e-3 * fmax(fabs(b), 1e-6);
        }
        n += differs;
    }
    double share = (double)n / ((double)f->w * f->h);
    printf("  control: %-43s max |d| %g (%.3g of peak), %.1f%% of the pixels differ by > 1e-3 of their value\n", what,
           d.max_abs, d.peak > 0 ? d.max_abs / d.peak : 0.0, 100 * share);
    CHECK_MSG(share > 0.01, "%s: not told apart from naive (%.3f%% of the pixels differ)", what, 100 * share);
}

static void exactness(const char *name, const pg_scene *scene, const pg_scene_gpu *sg, bool extras)
{
    static const uint32_t counts[] = {0, 1, 100, 1000};
    static const char *const shadings[] = {"lambert", "blinn_phong"};
    printf("%s, %dx%d, reference vs naive (hdr_format=rgba32f):\n", name, W, H);
    for (size_t c = 0; c < sizeof counts / sizeof counts[0]; c++) {
        for (int s = 0; s < 2; s++) {
            uint32_t n = counts[c];
            pg_frame_info fi = frame_for(scene, n, W, H);
            if (n == 1) fi.lights.radius *= 10; /* one light that reaches the visible part of the scene */
            pg_param_override nsets[2] = {{"hdr_format", "rgba32f"}, {"shading", shadings[s]}};
            pg_th_frame ref;
            if (!render(sg, "pipelines/naive.json", nsets, 2, &fi, &ref)) {
                CHECK_MSG(0, "%s: naive %u lights %s", name, n, shadings[s]);
                continue;
            }
            char what[128];
            snprintf(what, sizeof what, "%u lights, %s", n, shadings[s]);
            pg_param_override rsets[2] = {{"shading", shadings[s]}, {"lights_per_dispatch", "0"}};
            expect_identical(what, sg, rsets, 1, &fi, &ref);
            double peak;
            pg_th_max_abs(&ref, &ref, &peak);
            if (n > 0) CHECK_MSG(peak > 0, "%s: %s: the image is black, equality would prove nothing", name, what);
            if (extras && n == 1000) {
                /* several dispatches through the running-sum images; 37 leaves a partial tile in each */
                static const char *const splits[] = {"37", "256"};
                for (int k = 0; k < 2; k++) {
                    rsets[1].value = splits[k];
                    snprintf(what, sizeof what, "%u lights, %s, lights_per_dispatch %s", n, shadings[s], splits[k]);
                    expect_identical(what, sg, rsets, 2, &fi, &ref);
                }
                if (s == 0) {
                    pg_th_frame f;
                    pg_param_override amb = {"ambient", "0.05"};
                    if (render(sg, "pipelines/reference.json", &amb, 1, &fi, &f)) {
                        expect_different("ambient 0.05 vs 0", &f, &ref);
                        pg_th_release(&f);
                    } else {
                        CHECK_MSG(0, "ambient control renders");
                    }
                    pg_frame_info half = frame_for(scene, n / 2, W, H);
                    if (render(sg, "pipelines/reference.json", NULL, 0, &half, &f)) {
                        expect_different("500 lights vs 1000", &f, &ref);
                        pg_th_release(&f);
                    } else {
                        CHECK_MSG(0, "light count control renders");
                    }
                }
            }
            pg_th_release(&ref);
        }
    }
    if (!extras) return;

    /* 0 lights: the light animation is culled; with ambient the image is not black */
    pg_frame_info fi = frame_for(scene, 0, W, H);
    pg_param_override amb[2] = {{"ambient", "0.3"}, {"hdr_format", "rgba32f"}};
    pg_th_frame ref, f;
    if (render(sg, "pipelines/naive.json", amb, 2, &fi, &ref)) {
        expect_identical("0 lights, ambient 0.3", sg, amb, 1, &fi, &ref);
        pg_th_release(&ref);
    } else {
        CHECK_MSG(0, "naive 0 lights ambient");
    }
    if (render(sg, "pipelines/reference.json", NULL, 0, &fi, &f)) {
        printf("  0 lights: reference runs %s\n", f.order);
        CHECK_MSG(!strstr(f.order, "animate_lights") && strstr(f.order, "shade"), "0 lights: %s", f.order);
        pg_th_release(&f);
    } else {
        CHECK_MSG(0, "reference 0 lights");
    }
    fi = frame_for(scene, 100, W, H);
    if (render(sg, "pipelines/reference.json", NULL, 0, &fi, &f)) {
        CHECK_MSG(strstr(f.order, "animate_lights") != NULL, "100 lights: %s", f.order);
        pg_th_release(&f);
    }

    /* both in rgba16f: the same fp32 value rounds to the same half */
    pg_param_override h16 = {"hdr_format", "rgba16f"};
    if (render(sg, "pipelines/naive.json", &h16, 1, &fi, &ref)) {
        expect_identical("100 lights, both rgba16f", sg, &h16, 1, &fi, &ref);
        pg_th_release(&ref);
    } else {
        CHECK_MSG(0, "naive rgba16f");
    }

    /* debug views read no lights: the same surface attributes */
    static const char *const views[] = {"albedo", "normal", "depth"};
    for (int v = 0; v < 3; v++) {
        pg_param_override vs[2] = {{"view", views[v]}, {"hdr_format", "rgba32f"}};
        if (!render(sg, "pipelines/naive.json", vs, 2, &fi, &ref)) {
            CHECK_MSG(0, "naive view %s", views[v]);
            continue;
        }
        char what[64];
        snprintf(what, sizeof what, "view %s", views[v]);
        expect_identical(what, sg, vs, 1, &fi, &ref);
        pg_th_release(&ref);
    }
}

/* 1,000,000 lights at 32x18: 31 dispatches of 32768 lights (auto) against 50 of 20000. */
static void million(const pg_scene *scene, const pg_scene_gpu *sg)
{
    pg_frame_info fi = frame_for(scene, 1000000, 32, 18);
    pg_param_override split = {"lights_per_dispatch", "20000"};
    pg_th_frame a, b;
    bool ok_a = render(sg, "pipelines/reference.json", NULL, 0, &fi, &a);
    bool ok_b = ok_a && render(sg, "pipelines/reference.json", &split, 1, &fi, &b);
    CHECK_MSG(ok_a && ok_b, "1,000,000 lights render");
    if (!ok_a || !ok_b) {
        if (ok_a) pg_th_release(&a);
        return;
    }
    double peak;
    pg_th_max_abs(&a, &a, &peak);
    diff d = compare(&b, &a);
    printf("1,000,000 lights, %ux%u: %.0f ms (auto split) and %.0f ms (20000 a dispatch), peak %g, %s\n", a.w, a.h,
           a.stats.gpu_total_ms, b.stats.gpu_total_ms, peak, identical(&a, &b) ? "bit-identical" : "DIFFERENT");
    CHECK(pg_count_nonfinite(a.hdr, a.w, a.h) == 0);
    CHECK_MSG(peak > 0, "1,000,000 lights: black image");
    CHECK_MSG(identical(&a, &b), "1,000,000 lights: the two splits differ: max |d| %g, %llu pixels", d.max_abs,
              (unsigned long long)d.pixels);
    pg_th_release(&a);
    pg_th_release(&b);
}

/* surface=ray against surface=raster: per pixel within the visibility pipeline's bound against naive
 * (the same surface rebuilt from the pixel's ray against the same rasterizer's: accuracy_bounds.h
 * VIS_PX_*, VIS_PBR_PX_* under pbr); a textured scene only in RMSE (its texture levels come from
 * analytic derivatives instead of the 2x2 quads'). Returns false when a frame does not render; ray_out
 * (or NULL) receives the surface=ray frame. */
static bool ray_vs_raster(const char *label, const pg_scene_gpu *sg, const pg_frame_info *fi, bool pbr,
                            pg_th_frame *ray_out)
{
    const pg_param_override raster = {"surface", "raster"}, ray = {"surface", "ray"};
    pg_th_frame a, b;
    if (!render(sg, "pipelines/reference.json", &raster, 1, fi, &a)) {
        CHECK_MSG(0, "%s: surface=raster does not render", label);
        return false;
    }
    if (!render(sg, "pipelines/reference.json", &ray, 1, fi, &b)) {
        CHECK_MSG(0, "%s: surface=ray does not render", label);
        pg_th_release(&a);
        return false;
    }
    const bool textured = sg->features.has_textures || sg->features.has_normal_maps;
    const double A = pbr ? VIS_PBR_PX_A : VIS_PX_A, B = pbr ? VIS_PBR_PX_B : VIS_PX_B;
    double peak = 0, usage = 0, se = 0;
    const size_t n = (size_t)a.w * a.h;
    for (size_t i = 0; i < n * 4; i++)
        if (i % 4 != 3) peak = fmax(peak, a.hdr[i]);
    for (size_t i = 0; i < n * 4; i++) {
        if (i % 4 == 3) continue;
        const double d = fabs((double)b.hdr[i] - a.hdr[i]);
        se += d * d;
        usage = fmax(usage, d / (A * fabs(a.hdr[i]) + B * peak + 1e-12));
    }
    const double rmse_rel = peak > 0 ? sqrt(se / (3.0 * n)) / peak : 0;
    const diff d = compare(&b, &a);
    printf("  %-24s surface=ray vs raster%s%s: peak %.4g, %llu pixels differ, max |d| %.3g, px usage %.3g, rmse %.3g "
           "of peak; gpu %.1f ms vs %.1f\n", label, textured ? " (textured)" : "", pbr ? " (pbr)" : "", peak,
           (unsigned long long)d.pixels, d.max_abs, usage, rmse_rel, b.stats.gpu_total_ms, a.stats.gpu_total_ms);
    CHECK_MSG(pg_count_nonfinite(b.hdr, b.w, b.h) == 0, "%s: surface=ray: non-finite pixels", label);
    CHECK_MSG(d.pixels > 0, "%s: surface=ray is bit-identical to surface=raster: the ray path did not run", label);
    CHECK_MSG(rmse_rel <= VIS_RMSE_REL, "%s: surface=ray: rmse %.3g of the peak > %g", label, rmse_rel, VIS_RMSE_REL);
    if (!textured) CHECK_MSG(usage <= 1.0, "%s: surface=ray: %.3g of the per-pixel bound", label, usage);
    pg_th_release(&a);
    if (ray_out) *ray_out = b;
    else pg_th_release(&b);
    return true;
}

/* The reference with surface=ray (a visibility pass, then visibility_resolve writing the float
 * G-buffer): near the rasterized reference (ray_vs_raster), and, where every light has a range (so
 * the clustered lists drop only lights that add exactly 0), bit-identical to the visibility
 * pipeline in the same HDR format: the same surface and the same light sum in the same order. */
static void surface_ray(const pg_scene *scene, const pg_scene_gpu *sg)
{
    printf("surface=ray:\n");
    pg_frame_info fi = frame_for(scene, 100, W, H);
    pg_th_frame ray;
    if (ray_vs_raster("default, 100 lights", sg, &fi, false, &ray)) {
        const pg_param_override f32 = {"hdr_format", "rgba32f"};
        pg_th_frame vis;
        if (render(sg, "pipelines/visibility.json", &f32, 1, &fi, &vis)) {
            diff d = compare(&vis, &ray);
            printf("  %-24s visibility (rgba32f) vs surface=ray: %s (max |d| %g, %llu pixels differ)\n", "default",
                   d.pixels ? "DIFFERENT" : "bit-identical", d.max_abs, (unsigned long long)d.pixels);
            CHECK_MSG(d.pixels == 0, "visibility differs from the reference with surface=ray: max |d| %g, %llu pixels",
                      d.max_abs, (unsigned long long)d.pixels);
            pg_th_release(&vis);
        } else {
            CHECK_MSG(0, "visibility does not render");
        }
        pg_th_frame other;
        pg_frame_info half = frame_for(scene, 50, W, H);
        const pg_param_override ray_set = {"surface", "ray"};
        if (render(sg, "pipelines/reference.json", &ray_set, 1, &half, &other)) {
            expect_different("surface=ray, 50 lights vs 100", &other, &ray);
            pg_th_release(&other);
        }
        pg_th_release(&ray);
    }
    /* glossy pbr spheres, a textured and normal-mapped model, emission, a texture on TEXCOORD_1 */
    static const char *const files[] = {"pbr/spheres.gltf", "models/desk_lamp.gltf", "emissive/emissive.gltf",
                                        "features/texcoord1.gltf"};
    for (size_t k = 0; k < sizeof files / sizeof files[0]; k++) {
        pg_th_scene f;
        if (!pg_th_file_open(g_gpu, files[k], FILE_W, FILE_H, -1, &f)) continue;
        /* a file without lights gets 64 generated ones, placed as the tools place them (away from
         * the surfaces: a light in a surface's plane adds exactly 0 to the rasterized plane, and
         * noise to a point rebuilt from a ray, 1e-7 off the plane), since under the object view's
         * ambient alone the image depends on the albedo only, the same texels on both paths */
        if (f.fi.lights.count == 0) {
            pg_camera cam;
            char cw[256], lw[256];
            pg_error err = {0};
            CHECK_MSG(!pg_scene_default_view(f.scene, NULL, (float)FILE_W / FILE_H, 64, 7, &cam, &f.fi.lights, cw, sizeof cw, lw,
                                             sizeof lw, &err),
                      "%s: default view: %s", files[k], err.msg);
        }
        ray_vs_raster(files[k], f.sg, &f.fi, f.scene->features.auto_shading == PG_SHADING_PBR, NULL);
        pg_th_scene_close(g_gpu, &f);
    }
}

static void run_scene(const char *name, const char *path, bool extras)
{
    pg_error err = {0};
    pg_scene *scene = NULL;
    pg_scene_gpu *sg = NULL;
    if (pg_scene_load(path, &scene, &err) || pg_scene_gpu_create(g_gpu, scene, &sg, &err)) {
        CHECK_MSG(0, "%s: %s", name, err.msg);
        pg_scene_free(scene);
        return;
    }
    exactness(name, scene, sg, extras);
    if (extras) million(scene, sg);
    if (extras) surface_ray(scene, sg);
    pg_scene_gpu_destroy(g_gpu, sg);
    pg_scene_free(scene);
}

int main(void)
{
    pg_register_builtin_passes(&g_reg);
    pg_gpu_desc gd = {.validation = true, .device_index = -1, .quiet = true};
    pg_error err = {0};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_reference: %s\n", err.msg);
        return 1;
    }
    run_scene("default", "default", true);
    char sponza[PG_PATH_MAX];
    snprintf(sponza, sizeof sponza, "%s/assets/dabrovic-sponza/sponza.gltf", PG_SHARED_DIR);
    if (getenv("PG_TEST_NO_SPONZA")) printf("test_reference: Sponza skipped: PG_TEST_NO_SPONZA is set\n");
    else if (access(sponza, R_OK) == 0) run_scene("sponza", sponza, false);
    else printf("test_reference: Sponza skipped: %s not found\n", sponza);
    printf("validation messages: %u\n", g_gpu->validation_messages);
    CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_reference");
}
