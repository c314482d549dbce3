/* test_gpu_embed.c - the embedding API's contract (include/passgraph/passgraph.h,
 * docs/embedding.md) on the Vulkan device (lavapipe) with validation on (zero messages), where
 * examples/embed (scripts/check-install.sh) shows the happy path:
 *   - passgraph_open compiles the pipeline, as the header says: a value the pass refuses at
 *     declare fails the open, naming the file and option (it was accepted, and every render failed);
 *   - passgraph_set_param before any frame refuses such a value and takes it back (it was accepted,
 *     and the session stayed broken);
 *   - every call given a NULL session or a NULL required pointer returns PG_ERR_INVALID_ARG or a
 *     neutral value (they crashed);
 *   - passgraph_render_to_image refuses an integer or depth format (it recorded an invalid blit and
 *     returned PG_OK), an empty pipeline path, one side of the size 0, an over-long reference path;
 *   - a pipeline file's "plugins" are loaded by the library as by the tool (they were ignored, and
 *     the pass type was unknown). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "passgraph.h"
#include "plugins.h"
#include "test_util.h"

#define W 48
#define H 27

static char g_hist[PG_PATH_MAX];

static bool has(const pg_error *e, const char *s)
{
    bool ok = strstr(e->msg, s) != NULL;
    if (!ok) fprintf(stderr, "  expected \"%s\" in \"%s\"\n", s, e->msg);
    return ok;
}

static passgraph *open_with(const char *pipeline, const char *const *params, uint32_t n, uint32_t w, uint32_t h,
                            pg_result *r, pg_error *err)
{
    passgraph_desc d = {.pipeline = pipeline, .width = w, .height = h, .params = params, .n_params = n,
                        .device = -1, .validation = true};
    passgraph *p = NULL;
    *r = passgraph_open(&d, &p, err);
    return p;
}

static void test_open_compiles(void)
{
    pg_error err = {0};
    pg_result r;
    const char *bad[] = {"bins=1000"};
    passgraph *p = open_with(g_hist, bad, 1, W, H, &r, &err);
    CHECK_MSG(r == PG_ERR_SCHEMA && !p, "open with bins=1000: %d '%s'", (int)r, err.msg);
    CHECK(has(&err, "histogram.json: passes[2].options.bins: expected an integer in [8, 256], got 1000"));
    passgraph_close(p);
}

static void test_set_param_before_render(void)
{
    pg_error err = {0};
    pg_result r;
    passgraph *p = open_with(g_hist, NULL, 0, W, H, &r, &err);
    CHECK_MSG(r == PG_OK && p, "open: %s", err.msg);
    if (!p) return;
    r = passgraph_set_param(p, "bins", "1000", &err);
    CHECK_MSG(r == PG_ERR_SCHEMA, "set_param bins=1000 before a frame: %d '%s'", (int)r, err.msg);
    CHECK(passgraph_set_param(p, "bins", "16", &err) == PG_OK);
    r = passgraph_render(p, &err);
    CHECK_MSG(r == PG_OK, "render after the refused value: %s", err.msg);
    uint8_t *px = malloc((size_t)W * H * 4);
    CHECK(px && passgraph_read_rgba8(p, px, (size_t)W * H * 4, &err) == PG_OK);
    free(px);
    CHECK(passgraph_validation_messages(p) == 0);
    passgraph_close(p);
}

static void test_null_arguments(void)
{
    pg_error err = {0};
    const float v[3] = {0, 1, 0};
    CHECK(passgraph_set_camera(NULL, v, v, v, 60, 0, 0, &err) == PG_ERR_INVALID_ARG);
    CHECK(passgraph_set_lights(NULL, 1, 1, 0, &err) == PG_ERR_INVALID_ARG);
    CHECK(passgraph_set_param(NULL, "a", "b", &err) == PG_ERR_INVALID_ARG);
    CHECK(passgraph_render(NULL, &err) == PG_ERR_INVALID_ARG);
    uint8_t b[4];
    float f[4];
    CHECK(passgraph_read_rgba8(NULL, b, sizeof b, &err) == PG_ERR_INVALID_ARG);
    CHECK(passgraph_read_hdr(NULL, f, sizeof f, &err) == PG_ERR_INVALID_ARG);
    CHECK(passgraph_render_to_image(NULL, VK_NULL_HANDLE, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_LAYOUT_UNDEFINED,
                                    VK_IMAGE_LAYOUT_GENERAL, &err) == PG_ERR_INVALID_ARG);
    passgraph_error_stats st;
    CHECK(passgraph_error_against(NULL, NULL, &st, &err) == PG_ERR_INVALID_ARG);
    CHECK(passgraph_pass_count(NULL) == 0 && passgraph_pass_name(NULL, 0) == NULL);
    CHECK(isnan(passgraph_pass_ms(NULL, 0)) && isnan(passgraph_gpu_ms(NULL)));
    CHECK(passgraph_validation_messages(NULL) == 0);
    CHECK(passgraph_embed_version() == PASSGRAPH_EMBED_VERSION);
    uint32_t w = 1, h = 1;
    passgraph_size(NULL, &w, &h);
    CHECK(w == 0 && h == 0);
    passgraph_vulkan vk;
    memset(&vk, 0xff, sizeof vk);
    passgraph_get_vulkan(NULL, &vk);
    CHECK(vk.device == VK_NULL_HANDLE);
    passgraph_close(NULL);
}

static void test_refusals(void)
{
    pg_error err = {0};
    pg_result r;
    passgraph *p = open_with("", NULL, 0, W, H, &r, &err);
    CHECK(r == PG_ERR_INVALID_ARG && !p && has(&err, "passgraph_open: pipeline \"\": an empty path"));
    p = open_with(NULL, NULL, 0, 0, 100, &r, &err);
    CHECK(r == PG_ERR_INVALID_ARG && !p && has(&err, "size 0x100: give both sides, or 0x0 for 1280x720"));
    p = open_with(NULL, NULL, 0, W, H, &r, &err);
    CHECK_MSG(r == PG_OK && p, "open forward_plus: %s", err.msg);
    if (!p) return;
    passgraph_vulkan vk;
    passgraph_get_vulkan(p, &vk);
    /* a real image, so that only the format can be wrong */
    VkImageCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, .imageType = VK_IMAGE_TYPE_2D,
                            .format = VK_FORMAT_R8G8B8A8_UINT, .extent = {W, H, 1}, .mipLevels = 1, .arrayLayers = 1,
                            .samples = VK_SAMPLE_COUNT_1_BIT, .tiling = VK_IMAGE_TILING_OPTIMAL,
                            .usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT, .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED};
    VkImage img = VK_NULL_HANDLE;
    CHECK(vkCreateImage(vk.device, &ci, NULL, &img) == VK_SUCCESS);
    const VkFormat bad[] = {VK_FORMAT_R8G8B8A8_UINT, VK_FORMAT_R32_SINT, VK_FORMAT_D32_SFLOAT,
                            VK_FORMAT_D24_UNORM_S8_UINT};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        r = passgraph_render_to_image(p, img, bad[i], VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, &err);
        CHECK_MSG(r == PG_ERR_FORMAT && has(&err, "is an integer, depth/stencil or compressed format"),
                  "render_to_image VkFormat %d: %d '%s'", (int)bad[i], (int)r, err.msg);
    }
    vkDestroyImage(vk.device, img, NULL);
    char long_path[PG_PATH_MAX + 8];
    memset(long_path, 'a', sizeof long_path - 1);
    long_path[sizeof long_path - 1] = 0;
    CHECK(passgraph_render(p, &err) == PG_OK);
    passgraph_error_stats st;
    r = passgraph_error_against(p, long_path, &st, &err);
    CHECK(r == PG_ERR_INVALID_ARG && has(&err, "reference path longer than"));
    CHECK(passgraph_validation_messages(p) == 0);
    passgraph_close(p);
}

/* The tint plug-in (examples/plugins/tint) listed by a pipeline file next to it. */
static void test_pipeline_plugins(void)
{
    char dir[] = "/tmp/pg_embed_XXXXXX", so[PG_PATH_MAX], json[PG_PATH_MAX], cmd[3 * PG_PATH_MAX];
    if (!mkdtemp(dir)) {
        CHECK_MSG(0, "mkdtemp");
        return;
    }
    snprintf(so, sizeof so, "%s/libpg_tint.so", dir);
    snprintf(json, sizeof json, "%s/tint.json", dir);
    snprintf(cmd, sizeof cmd, "cp '%s/libpg_tint.so' '%s'", PG_PLUGIN_DIR, so);
    CHECK(system(cmd) == 0);
    FILE *f = fopen(json, "w");
    CHECK(f != NULL);
    if (f) {
        fprintf(f,
                "{\"name\": \"tint\", \"plugins\": [\"libpg_tint.so\"],\n"
                " \"include\": [\"%s/pipelines/fragments/lights.json\", \"%s/pipelines/fragments/shading_params.json\",\n"
                "             \"%s/pipelines/fragments/display.json\"],\n"
                " \"resources\": [{\"name\": \"hdr\", \"type\": \"image\", \"format\": \"$hdr_format\"},\n"
                "               {\"name\": \"depth\", \"type\": \"image\", \"format\": \"d32f\"}],\n"
                " \"passes\": [{\"name\": \"shade\", \"type\": \"forward_naive\", \"reads\": [\"lights\", \"environment\", "
                "\"geometry\"], \"writes\": [\"hdr\", \"depth\"]},\n"
                "            {\"name\": \"tint\", \"type\": \"tint\", \"writes\": [\"hdr\"], \"options\": {\"r\": 0, \"g\": 0, "
                "\"b\": 0}}],\n"
                " \"output\": \"ldr\", \"hdr_output\": \"hdr\"}\n",
                passgraph_data_dir(), passgraph_data_dir(), passgraph_data_dir());
        fclose(f);
    }
    pg_error err = {0};
    pg_result r;
    passgraph *p = open_with(json, NULL, 0, W, H, &r, &err);
    CHECK_MSG(r == PG_OK && p, "open a pipeline listing a plug-in: %s", err.msg);
    if (p) {
        CHECK_MSG(passgraph_render(p, &err) == PG_OK, "render: %s", err.msg);
        float *hdr = malloc((size_t)W * H * 4 * sizeof(float));
        CHECK(hdr && passgraph_read_hdr(p, hdr, (size_t)W * H * 4 * sizeof(float), &err) == PG_OK);
        double peak = 0; /* the tint (0, 0, 0) ran: black */
        for (size_t i = 0; hdr && i < (size_t)W * H; i++)
            for (int c = 0; c < 3; c++) peak = fmax(peak, fabs(hdr[4 * i + c]));
        CHECK_MSG(peak == 0.0, "the plug-in's pass did not run: peak %g", peak);
        free(hdr);
        CHECK(passgraph_pass_count(p) >= 2 && !strcmp(passgraph_pass_name(p, passgraph_pass_count(p) - 2), "tint"));
        CHECK(passgraph_validation_messages(p) == 0);
        passgraph_close(p);
    }
    unlink(so);
    unlink(json);
    rmdir(dir);
}

/* A plug-in that fails to load fails again when loaded again: it was recorded before its checks,
 * and a second load of its path said PG_OK and loaded nothing (the viewer's reload, a second
 * open), then the compile failed with "unknown pass type" */
static void test_failed_plugin_again(void)
{
    char so[PG_PATH_MAX];
    snprintf(so, sizeof so, "%s/libpg_tint_nocreate.so", PG_PLUGIN_DIR);
    const char *paths[1] = {so};
    pg_pass_registry reg = {0};
    pg_plugins pl;
    memset(&pl, 0, sizeof pl);
    for (int k = 0; k < 2; k++) {
        pg_error err = {0};
        pg_result r = pg_plugins_load(&reg, paths, 1, &pl, &err);
        CHECK_MSG(r == PG_ERR_INVALID_ARG && strstr(err.msg, "has no create function"), "load %d: %s", k + 1, err.msg);
        CHECK(pl.n == 0 && reg.count == 0); /* nothing kept, its type not registered */
    }
    pg_plugins_close(&pl);
}

int main(void)
{
    if (getenv("PG_TEST_NO_GPU")) return pg_test_skip("test_gpu_embed", "PG_TEST_NO_GPU set");
    snprintf(g_hist, sizeof g_hist, "%s/corpus/pipelines/good/histogram.json", PG_TEST_DIR);
    {
        pg_error err = {0};
        pg_result r;
        passgraph *p = open_with(NULL, NULL, 0, 16, 9, &r, &err);
        if (!p && strstr(err.msg, "no Vulkan")) return pg_test_skip("test_gpu_embed", err.msg);
        passgraph_close(p);
    }
    test_failed_plugin_again();
    test_open_compiles();
    test_set_param_before_render();
    test_null_arguments();
    test_refusals();
    test_pipeline_plugins();
    return pg_test_finish("test_gpu_embed");
}
