/* test_gpu_compressed.c - compressed and quantized glTF geometry renders like its uncompressed
 * twin (tests/corpus/gltf/compressed): twin.gltf, its EXT_meshopt_compression twin meshopt.gltf,
 * its KHR_mesh_quantization twin q_s16n.gltf and its quantized KHR_draco_mesh_compression twin
 * draco_q.gltf are rendered on the Vulkan device (lavapipe)
 * with the validation layer on (zero messages), 160x90, pipelines/naive.json, with one camera
 * and one light set (the tools' default view of twin.gltf: pg_scene_default_view). The twins' images must equal the uncompressed one
 * within 1 step of 8 bits per channel (LDR) and 1% of the peak in HDR (their normals differ by
 * <= 4e-5 / 4e-5 / 4.5e-4, their positions by 0 / 1.5e-5 / 6.1e-5), and the image must show the lit mesh (> 8% of the pixels lit). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "default_view.h"
#include "gpu_harness.h"
#include "image_util.h"
#include "pass_list.h"
#include "test_util.h"

#define W 160
#define H 90

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;

static bool shoot(const char *file, const pg_frame_info *fi, pg_th_frame *out)
{
    char path[PG_PATH_MAX];
    snprintf(path, sizeof path, "%s/corpus/gltf/compressed/%s", PG_TEST_DIR, file);
    pg_error err = {0};
    pg_scene *scene = NULL;
    if (pg_scene_load(path, &scene, &err)) {
        CHECK_MSG(0, "%s: %s", file, err.msg);
        return false;
    }
    pg_scene_gpu *sg = NULL;
    if (pg_scene_gpu_create(g_gpu, scene, &sg, &err)) {
        CHECK_MSG(0, "%s: %s", file, err.msg);
        pg_scene_free(scene);
        return false;
    }
    bool ok = pg_th_render(g_gpu, &g_reg, sg, "pipelines/naive.json", NULL, 0, fi, 1, false, out);
    CHECK_MSG(ok, "%s: render", file);
    if (ok) {
        char png[256];
        snprintf(png, sizeof png, "test_gpu_compressed_%s.png", file);
        pg_write_png(png, out->ldr, out->w, out->h, &err);
    }
    pg_scene_gpu_destroy(g_gpu, sg);
    pg_scene_free(scene);
    return ok;
}

int main(void)
{
    if (getenv("PG_TEST_NO_GPU")) return pg_test_skip("test_gpu_compressed", "PG_TEST_NO_GPU set");
    pg_register_builtin_passes(&g_reg);
    pg_gpu_desc gd = {.validation = true, .device_index = -1};
    pg_error err = {0};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_gpu_compressed: %s\n", err.msg);
        return 1;
    }
    pg_scene *twin = NULL;
    char path[PG_PATH_MAX];
    snprintf(path, sizeof path, "%s/corpus/gltf/compressed/twin.gltf", PG_TEST_DIR);
    CHECK(pg_scene_load(path, &twin, &err) == PG_OK);
    if (twin) {
        /* the tools' default view of the twin (auto framing, object lights) */
        pg_frame_info fi = {.time = 0, .width = W, .height = H};
        char cw[256], lw[256];
        CHECK(pg_scene_default_view(twin, NULL, (float)W / H, 64, 1, &fi.camera, &fi.lights, cw, sizeof cw, lw,
                                  sizeof lw, &err) == PG_OK);
        pg_th_frame ref, mo, q, dq;
        bool ok_ref = shoot("twin.gltf", &fi, &ref);
        if (ok_ref) {
            pg_image_stats st = pg_rgba8_stats(ref.ldr, ref.w, ref.h);
            printf("twin: mean luma %.1f, lit %.1f%%\n", st.mean_luma, 100 * st.lit_fraction);
            /* the grid covers about 13% of the image */
            CHECK_MSG(st.lit_fraction > 0.08 && st.mean_luma > 5, "twin: image not lit (%.1f%%, luma %.1f)",
                      100 * st.lit_fraction, st.mean_luma);
        }
        const char *files[] = {"meshopt.gltf", "q_s16n.gltf", "draco_q.gltf"};
        pg_th_frame *outs[] = {&mo, &q, &dq};
        for (int i = 0; i < 3; i++) {
            if (!shoot(files[i], &fi, outs[i]) || !ok_ref) continue;
            int ldr_max = 0;
            size_t ldr_diff = 0;
            for (size_t k = 0; k < (size_t)W * H * 4; k++) {
                int d = abs((int)outs[i]->ldr[k] - (int)ref.ldr[k]);
                if (d > ldr_max) ldr_max = d;
                ldr_diff += d != 0;
            }
            double peak = 0, m = pg_th_max_abs(outs[i], &ref, &peak);
            printf("%s vs twin: LDR max %d (%zu channels differ), HDR max %.3g of peak %.3g\n", files[i], ldr_max,
                   ldr_diff, m, peak);
            CHECK_MSG(ldr_max <= 1, "%s: LDR differs from the twin by %d", files[i], ldr_max);
            CHECK_MSG(m <= 0.01 * peak, "%s: HDR differs from the twin by %g (peak %g)", files[i], m, peak);
            pg_th_release(outs[i]);
        }
        if (ok_ref) pg_th_release(&ref);
        pg_scene_free(twin);
    }
    printf("validation messages: %u\n", g_gpu->validation_messages);
    CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_gpu_compressed");
}
