/* test_gpu_alias.c - memory aliasing changes no pixel: every shipped pipeline (every
 * pipelines/ file) renders byte-identical images, the HDR output as read back (in its own
 * format) and the 8-bit display image, with aliasing on and with it off
 * (pg_session_desc.disable_aliasing, the CLI's --no-aliasing), on lavapipe with validation +
 * synchronization validation (any message fails).
 *
 * Scenes, each with 64 lights, at 160x90, two frames (the second reuses aliased memory that holds
 * the first frame's data): the built-in atrium; tests/corpus/gltf/blend/blend_lit.gltf (BLEND
 * materials: the transparent pass runs); tests/corpus/gltf/emissive/emissive.gltf; Sponza
 * (../shared/assets/dabrovic-sponza/sponza.gltf) with assets/scenarios/cis565.json, skipped with
 * the reason printed when absent.
 *
 * Not vacuous: each aliasing-on plan must have a memory block shared by two or more resources and
 * fewer aliased than unaliased bytes, each aliasing-off plan none, and the image must be lit. */
#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "gpu_harness.h"
#include "pass_list.h"
#include "scenario.h"
#include "shader.h"
#include "test_util.h"

#define W 160
#define H 90
#define LIGHTS 64

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;
static char *g_pipelines[64];
static uint32_t g_n_pipelines;
static uint32_t g_cases;

static int name_cmp(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static void find_pipelines(void)
{
    char dir[PG_PATH_MAX];
    pg_data_path(dir, sizeof dir, "pipelines");
    DIR *dh = opendir(dir);
    CHECK_MSG(dh != NULL, "cannot open %s", dir);
    if (!dh) return;
    for (struct dirent *e; (e = readdir(dh)) && g_n_pipelines < 64;) {
        size_t n = strlen(e->d_name);
        if (n > 5 && !strcmp(e->d_name + n - 5, ".json")) {
            char rel[PG_PATH_MAX];
            snprintf(rel, sizeof rel, "pipelines/%s", e->d_name);
            g_pipelines[g_n_pipelines++] = strdup(rel);
        }
    }
    closedir(dh);
    qsort(g_pipelines, g_n_pipelines, sizeof g_pipelines[0], name_cmp);
}

static void check_scene(const char *label, const char *path, const char *scenario)
{
    pg_th_scene ts;
    if (!pg_th_scene_open(g_gpu, label, path, scenario, W, H, LIGHTS, &ts)) {
        CHECK_MSG(0, "%s: scene", label);
        return;
    }
    const pg_scene_gpu *sg = ts.sg;
    const pg_frame_info fi = ts.fi;
    for (uint32_t p = 0; p < g_n_pipelines; p++) {
        const char *pipe = g_pipelines[p];
        pg_th_frame on, off;
        bool ok_on = pg_th_render(g_gpu, &g_reg, sg, pipe, NULL, 0, &fi, 2, false, &on);
        bool ok_off = pg_th_render(g_gpu, &g_reg, sg, pipe, NULL, 0, &fi, 2, true, &off);
        CHECK_MSG(ok_on && ok_off, "%s %s: render failed", label, pipe);
        if (ok_on && ok_off) {
            g_cases++;
            bool hdr_same = pg_th_hdr_identical(&on, &off);
            bool ldr_same = on.w == off.w && on.h == off.h && !memcmp(on.ldr, off.ldr, (size_t)on.w * on.h * 4);
            double peak = 0;
            pg_th_max_abs(&on, &off, &peak);
            printf("%s %s: passes %s; aliased: %u shared block(s), %llu -> %llu B; no-aliasing: %u shared, "
                   "%llu B; HDR %s, LDR %s, HDR peak %.4g\n",
                   label, pipe, on.order, on.shared_blocks, (unsigned long long)on.transient_bytes_unaliased,
                   (unsigned long long)on.transient_bytes_aliased, off.shared_blocks,
                   (unsigned long long)off.transient_bytes_aliased, hdr_same ? "identical" : "DIFFERENT",
                   ldr_same ? "identical" : "DIFFERENT", peak);
            CHECK_MSG(hdr_same, "%s %s: HDR differs with aliasing off", label, pipe);
            CHECK_MSG(ldr_same, "%s %s: LDR differs with aliasing off", label, pipe);
            CHECK_MSG(on.shared_blocks >= 1 && on.transient_bytes_aliased < on.transient_bytes_unaliased,
                      "%s %s: nothing was aliased: the comparison would be vacuous", label, pipe);
            CHECK_MSG(off.shared_blocks == 0 && off.transient_bytes_aliased == off.transient_bytes_unaliased,
                      "%s %s: aliasing off still shares %u block(s)", label, pipe, off.shared_blocks);
            CHECK_MSG(peak > 0, "%s %s: the image is black", label, pipe);
        }
        pg_th_release(&on);
        pg_th_release(&off);
    }
    pg_th_scene_close(g_gpu, &ts);
}

int main(void)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    if (getenv("PG_TEST_NO_GPU")) return pg_test_skip("test_gpu_alias", "PG_TEST_NO_GPU set");
    pg_register_builtin_passes(&g_reg);
    pg_gpu_desc gd = {.validation = true, .device_index = -1, .quiet = true};
    pg_error err = {0};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_gpu_alias: %s\n", err.msg);
        return 1;
    }
    find_pipelines();
    CHECK_MSG(g_n_pipelines >= 6, "only %u shipped pipelines found", g_n_pipelines);
    check_scene("default", "default", NULL);
    char path[PG_PATH_MAX];
    snprintf(path, sizeof path, "%s/corpus/gltf/blend/blend_lit.gltf", PG_TEST_DIR);
    check_scene("blend_lit", path, NULL);
    snprintf(path, sizeof path, "%s/corpus/gltf/emissive/emissive.gltf", PG_TEST_DIR);
    check_scene("emissive", path, NULL);
    snprintf(path, sizeof path, "%s/assets/dabrovic-sponza/sponza.gltf", PG_SHARED_DIR);
    if (getenv("PG_TEST_NO_SPONZA")) printf("test_gpu_alias: Sponza skipped: PG_TEST_NO_SPONZA is set\n");
    else if (access(path, R_OK) == 0) check_scene("sponza", path, "assets/scenarios/cis565.json");
    else printf("test_gpu_alias: Sponza skipped: %s not found\n", path);
    printf("cases: %u (pipelines x scenes)\n", g_cases);
    for (uint32_t p = 0; p < g_n_pipelines; p++) free(g_pipelines[p]);
    printf("validation messages: %u\n", g_gpu->validation_messages);
    CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_gpu_alias");
}
