/* test_gpu_blend.c - glTF alphaMode BLEND through forward_transparent in every shipped pipeline,
 * on lavapipe with validation + synchronization validation (any message fails the test). Scenes:
 * tests/corpus/gltf/blend/ (gen_blend.py). Read-back HDR, small images.
 *
 *  - over: 0 lights, ambient 1, camera straight above. The BLEND quad (1, 0.25, 0), alpha 0.5, over
 *    the opaque floor: the centre pixel is 0.5 * quad + 0.5 * floor, with floor the pipeline's own
 *    floor pixel beside the quad (which is 0.8 within the G-buffer's quantization); alpha stays 1.
 *    From below, the single-sided quad's back face is culled (naive, deferred, deferred_packed).
 *  - order: two overlapping BLEND quads, red below green, no floor. From above (green nearer) the
 *    overlap is 0.5 G + 0.25 R, from below (red nearer) 0.5 R + 0.25 G: back to front, whichever
 *    side the camera is on (scene order is right from above only).
 *  - lit: the lit scene with 100 lights, Lambert and Blinn-Phong, against the reference
 *    (rgba32f): naive and forward+ are
 *    bit-identical, the deferred packings (hdr_format rgba32f) within the bounds of
 *    test_gpu_clustered.c (|out - ref| <= A |ref| + B peak per channel); the transparent pass runs
 *    in each. (The reference's own transparent pass shades every light, like naive's.)
 *  - a scene without BLEND (the atrium): 'transparent' is not run. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gpu_harness.h"
#include "pass_list.h"
#include "test_util.h"

#define W 160
#define H 90

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;

static const char *const k_pipelines[] = {"naive", "forward_plus", "deferred", "deferred_oct16", "deferred_packed",
                                          "reference"};
#define N_PIPELINES 6

static bool load(const char *name, pg_scene **scene, pg_scene_gpu **sg)
{
    char path[PG_PATH_MAX];
    snprintf(path, sizeof path, "%s/corpus/gltf/blend/%s", PG_TEST_DIR, name);
    pg_error err = {0};
    *scene = NULL;
    *sg = NULL;
    if (!pg_scene_load(path, scene, &err)) /* the blending arithmetic is checked on Lambert's albedo x ambient */
        (*scene)->features.auto_shading = PG_SHADING_LAMBERT;
    if (!*scene || pg_scene_gpu_create(g_gpu, *scene, sg, &err)) {
        CHECK_MSG(0, "%s: %s", name, err.msg);
        pg_scene_free(*scene);
        *scene = NULL;
        return false;
    }
    return true;
}

static pg_frame_info top_view(float y, uint32_t lights, const pg_scene *scene)
{
    pg_frame_info fi = {
        .camera = {.position = {0, y, 0}, .target = {0, 0, 0}, .up = {0, 0, -1}, .fov_y_deg = 45,
                   .near_z = 0.05f, .far_z = 50, .aspect = (float)W / H},
        .lights = pg_light_setup_default(scene, lights, 7),
        .time = 0.5f,
        .width = W,
        .height = H,
    };
    return fi;
}

static const float *px(const pg_th_frame *f, uint32_t x, uint32_t y)
{
    return f->hdr + 4 * ((size_t)y * f->w + x);
}

static bool render(const pg_scene_gpu *sg, const char *pipeline, const pg_param_override *sets, uint32_t n,
                   const pg_frame_info *fi, pg_th_frame *out)
{
    char path[96];
    snprintf(path, sizeof path, "pipelines/%s.json", pipeline);
    bool ok = pg_th_render(g_gpu, &g_reg, sg, path, sets, n, fi, 1, false, out);
    CHECK_MSG(ok, "%s renders", pipeline);
    return ok;
}

static bool near3(const float *got, const double *want, double rel)
{
    for (int k = 0; k < 3; k++)
        if (!(fabs(got[k] - want[k]) <= rel * fmax(fabs(want[k]), 0.05))) return false;
    return true;
}

static void test_over(void)
{
    pg_scene *scene;
    pg_scene_gpu *sg;
    if (!load("blend_over.gltf", &scene, &sg)) return;
    pg_frame_info fi = top_view(4.0f, 0, scene);
    pg_param_override sets[1] = {{"ambient", "1"}};
    static const double quad[3] = {1.0, 0.25, 0.0};
    for (int p = 0; p < N_PIPELINES; p++) {
        pg_th_frame f;
        if (!render(sg, k_pipelines[p], sets, 1, &fi, &f)) continue;
        const float *c = px(&f, W / 2, H / 2), *fl = px(&f, W / 2, H / 2 - 32);
        double want[3];
        for (int k = 0; k < 3; k++) want[k] = 0.5 * quad[k] + 0.5 * fl[k];
        printf("over %-16s floor (%.4f %.4f %.4f) centre (%.4f %.4f %.4f) a %.4f, want (%.4f %.4f %.4f) [%s]\n",
               k_pipelines[p], fl[0], fl[1], fl[2], c[0], c[1], c[2], c[3], want[0], want[1], want[2], f.order);
        const double floor_want[3] = {0.8, 0.8, 0.8};
        CHECK_MSG(near3(fl, floor_want, 0.01), "%s: floor pixel %g", k_pipelines[p], fl[0]);
        CHECK_MSG(near3(c, want, 2e-3), "%s: centre is not alpha*quad + (1-alpha)*floor", k_pipelines[p]);
        CHECK_MSG(fabs(c[3] - 1.0) < 1e-3, "%s: alpha %g", k_pipelines[p], c[3]);
        CHECK_MSG(strstr(f.order, "transparent") != NULL, "%s: %s", k_pipelines[p], f.order);
        pg_th_release(&f);
    }
    /* from below: the single-sided quad shows its back and is culled (the floor too): black */
    fi = top_view(-4.0f, 0, scene);
    for (int p = 0; p < N_PIPELINES; p += 2) {
        pg_th_frame f;
        if (!render(sg, k_pipelines[p], sets, 1, &fi, &f)) continue;
        const float *c = px(&f, W / 2, H / 2);
        printf("over %-16s from below: centre (%.4f %.4f %.4f)\n", k_pipelines[p], c[0], c[1], c[2]);
        CHECK_MSG(c[0] == 0 && c[1] == 0 && c[2] == 0, "%s: back face of a single-sided BLEND quad drawn",
                  k_pipelines[p]);
        pg_th_release(&f);
    }
    pg_scene_gpu_destroy(g_gpu, sg);
    pg_scene_free(scene);
}

static void test_order(void)
{
    pg_scene *scene;
    pg_scene_gpu *sg;
    if (!load("blend_order.gltf", &scene, &sg)) return;
    pg_param_override sets[1] = {{"ambient", "1"}};
    for (int side = 0; side < 2; side++) {
        pg_frame_info fi = top_view(side == 0 ? 4.0f : -4.0f, 0, scene);
        /* nearer quad last: 0.5 near + 0.25 far */
        const double want[3] = {side == 0 ? 0.25 : 0.5, side == 0 ? 0.5 : 0.25, 0.0};
        for (int p = 0; p < N_PIPELINES; p++) {
            pg_th_frame f;
            if (!render(sg, k_pipelines[p], sets, 1, &fi, &f)) continue;
            const float *c = px(&f, W / 2, H / 2);
            printf("order %-5s %-16s overlap (%.4f %.4f %.4f), want (%.2f %.2f %.2f)\n", side == 0 ? "above" : "below",
                   k_pipelines[p], c[0], c[1], c[2], want[0], want[1], want[2]);
            CHECK_MSG(near3(c, want, 2e-3), "%s from %s: overlap not back to front", k_pipelines[p],
                      side == 0 ? "above" : "below");
            pg_th_release(&f);
        }
    }
    pg_scene_gpu_destroy(g_gpu, sg);
    pg_scene_free(scene);
}

static void test_lit(void)
{
    pg_scene *scene;
    pg_scene_gpu *sg;
    if (!load("blend_lit.gltf", &scene, &sg)) return;
    pg_frame_info fi = {
        .camera = pg_camera_default_for_scene(scene, (float)W / H),
        .lights = pg_light_setup_default(scene, 100, 7),
        .time = 1.25f,
        .width = W,
        .height = H,
    };
    static const char *const shadings[] = {"lambert", "blinn_phong"};
    for (int sh = 0; sh < 2; sh++) {
        pg_param_override rsets[1] = {{"shading", shadings[sh]}};
        pg_param_override psets[2] = {{"hdr_format", "rgba32f"}, {"shading", shadings[sh]}};
        pg_th_frame ref;
        if (!render(sg, "reference", rsets, 1, &fi, &ref)) goto out;
        double peak;
        pg_th_max_abs(&ref, &ref, &peak);
        CHECK_MSG(peak > 0 && strstr(ref.order, "transparent"), "reference: peak %g, %s", peak, ref.order);
        /* (A, B): 0 = bit-identical; the deferred bounds of test_gpu_clustered.c */
        static const double bounds[N_PIPELINES][2] = {{0, 0}, {0, 0}, {2e-3, 1e-5}, {0.03, 6e-3}, {0.015, 2e-3}, {0, 0}};
        for (int p = 0; p < N_PIPELINES - 1; p++) {
            pg_th_frame f;
            if (!render(sg, k_pipelines[p], psets, 2, &fi, &f)) continue;
            double worst = 0, max_abs = 0;
            size_t bad = 0;
            for (size_t i = 0; i < (size_t)W * H; i++)
                for (int k = 0; k < 3; k++) {
                    double a = f.hdr[4 * i + k], b = ref.hdr[4 * i + k];
                    double bound = bounds[p][0] * fabs(b) + bounds[p][1] * peak;
                    double d = fabs(a - b);
                    if (d > max_abs) max_abs = d;
                    if (bound > 0 && d / bound > worst) worst = d / bound;
                    bad += !(d <= bound);
                }
            printf("lit %-11s %-16s vs reference: max |d| %.3g (peak %.3g), %s %.3g of the bound, %zu channels over [%s]\n",
                   shadings[sh], k_pipelines[p], max_abs, peak, bounds[p][0] ? "worst" : "bit-identical:", worst, bad,
                   f.order);
            if (bounds[p][0] == 0)
                CHECK_MSG(pg_th_hdr_identical(&f, &ref), "%s %s: not bit-identical to the reference", k_pipelines[p],
                          shadings[sh]);
            else
                CHECK_MSG(bad == 0, "%s %s: %zu channels outside the bound", k_pipelines[p], shadings[sh], bad);
            CHECK_MSG(strstr(f.order, "transparent") != NULL, "%s: %s", k_pipelines[p], f.order);
            pg_th_release(&f);
        }
        pg_th_release(&ref);
    }
out:
    pg_scene_gpu_destroy(g_gpu, sg);
    pg_scene_free(scene);
}

static void test_no_blend(void)
{
    pg_scene *scene = NULL;
    pg_scene_gpu *sg = NULL;
    pg_error err = {0};
    if (pg_scene_load("default", &scene, &err) || pg_scene_gpu_create(g_gpu, scene, &sg, &err)) {
        CHECK_MSG(0, "default scene: %s", err.msg);
        pg_scene_free(scene);
        return;
    }
    pg_frame_info fi = {.camera = pg_camera_default_for_scene(scene, (float)W / H),
                        .lights = pg_light_setup_default(scene, 10, 7), .width = W, .height = H};
    for (int p = 0; p < N_PIPELINES; p++) {
        pg_th_frame f;
        if (!render(sg, k_pipelines[p], NULL, 0, &fi, &f)) continue;
        CHECK_MSG(!strstr(f.order, "transparent"), "%s without BLEND runs %s", k_pipelines[p], f.order);
        pg_th_release(&f);
    }
    pg_scene_gpu_destroy(g_gpu, sg);
    pg_scene_free(scene);
}

int main(void)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    if (getenv("PG_TEST_NO_GPU")) return pg_test_skip("test_gpu_blend", "PG_TEST_NO_GPU");
    pg_register_builtin_passes(&g_reg);
    pg_gpu_desc gd = {.validation = true, .device_index = -1, .quiet = true};
    pg_error err = {0};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_gpu_blend: %s\n", err.msg);
        return 1;
    }
    test_over();
    test_order();
    test_lit();
    test_no_blend();
    printf("validation messages: %u\n", g_gpu->validation_messages);
    CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_gpu_blend");
}
