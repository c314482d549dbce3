/* test_gpu_histogram.c - the luminance_histogram pass (renderer/passes/luminance_histogram.c) on
 * the Vulkan device (lavapipe) with the validation layer on (zero messages): the default scene
 * at 64x36 through tests/corpus/pipelines/good/histogram.json (the naive pipeline plus the pass);
 * the bins read back from the "histogram" buffer must sum to width x height exactly and match a
 * histogram of the read-back HDR image computed here with the same formula, within a few pixels
 * moved to an adjacent bin (log2 on the GPU and in C may round differently at a bin boundary).
 * Also at 16 and 256 bins with another range, and bins = 1000 refused by declare with a message
 * naming the file, the JSON path and the option. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gpu_harness.h"
#include "image_util.h"
#include "pass_list.h"
#include "test_util.h"

#define W 64
#define H 36
#define LIGHTS 64

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;

static void pipeline_path(char *buf, size_t size)
{
    snprintf(buf, size, "%s/corpus/pipelines/good/histogram.json", PG_TEST_DIR);
}

/* The pass's binning (shaders/luminance_histogram.comp) in C. */
static uint32_t cpu_bin(const float *c, uint32_t bins, float min_ev, float max_ev)
{
    float l = 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
    if (!(l > 0.0f)) return 0;
    float t = floorf((log2f(l) - min_ev) / (max_ev - min_ev) * (float)bins);
    return t < 0 ? 0 : t > (float)(bins - 1) ? bins - 1 : (uint32_t)t;
}

static void check_histogram(const pg_th_scene *ts, uint32_t bins, float min_ev, float max_ev)
{
    char path[PG_PATH_MAX], sb[32], smin[32], smax[32];
    pipeline_path(path, sizeof path);
    snprintf(sb, sizeof sb, "%u", bins);
    snprintf(smin, sizeof smin, "%g", min_ev);
    snprintf(smax, sizeof smax, "%g", max_ev);
    pg_param_override sets[3] = {{.key = "bins", .value = sb}, {.key = "min_ev", .value = smin},
                                 {.key = "max_ev", .value = smax}};
    pg_session_desc sd = {.pipeline_path = path, .registry = &g_reg, .overrides = sets, .n_overrides = 3};
    pg_session *s = NULL;
    pg_error err = {0};
    if (pg_session_create(g_gpu, ts->sg, &sd, &s, &err)) {
        CHECK_MSG(0, "bins %u: session: %s", bins, err.msg);
        return;
    }
    pg_frame_stats st;
    uint32_t gpu_bins[256] = {0}, cpu_bins[256] = {0};
    float *hdr = malloc((size_t)W * H * 4 * sizeof(float));
    bool ok = hdr && pg_session_render(s, &ts->fi, true, &st, &err) == PG_OK;
    CHECK_MSG(ok, "bins %u: render: %s", bins, err.msg);
    if (ok) {
        uint32_t w = 0, h = 0;
        pg_format fmt;
        const void *px = pg_runtime_output(s->runtime, 1, &w, &h, &fmt);
        ok = px && w == W && h == H && pg_hdr_to_float(px, fmt, w, h, hdr, &err) == PG_OK;
        CHECK_MSG(ok, "bins %u: no HDR read-back", bins);
    }
    if (ok) {
        ok = pg_runtime_read_buffer(s->runtime, "histogram", 0, 4ull * bins, gpu_bins, &err) == PG_OK;
        CHECK_MSG(ok, "bins %u: read_buffer: %s", bins, err.msg);
    }
    if (ok) {
        for (size_t i = 0; i < (size_t)W * H; i++) cpu_bins[cpu_bin(&hdr[4 * i], bins, min_ev, max_ev)]++;
        uint64_t sum = 0, l1 = 0;
        int64_t cum = 0, cum_max = 0;
        uint32_t nonempty = 0, peak = 0;
        for (uint32_t b = 0; b < bins; b++) {
            sum += gpu_bins[b];
            l1 += (uint64_t)llabs((long long)gpu_bins[b] - cpu_bins[b]);
            cum += (int64_t)gpu_bins[b] - cpu_bins[b];
            if (llabs(cum) > cum_max) cum_max = llabs(cum);
            nonempty += gpu_bins[b] != 0;
            if (gpu_bins[b] > gpu_bins[peak]) peak = b;
        }
        printf("bins %u [%g, %g]: sum %llu, %u bins used, peak bin %u (%u px), |gpu - cpu| %llu, largest "
               "cumulative difference %lld\n",
               bins, min_ev, max_ev, (unsigned long long)sum, nonempty, peak, gpu_bins[peak],
               (unsigned long long)l1, (long long)cum_max);
        CHECK_MSG(sum == (uint64_t)W * H, "bins %u: the bins sum to %llu, not %u", bins, (unsigned long long)sum,
                  W * H);
        /* a pixel moved to the next bin changes two bins by 1 and one cumulative sum by 1 */
        CHECK_MSG(l1 <= 8 && cum_max <= 4, "bins %u: GPU and CPU histograms differ by %llu (cumulative %lld)", bins,
                  (unsigned long long)l1, (long long)cum_max);
        CHECK_MSG(nonempty >= 3, "bins %u: only %u bins used: the image is not lit", bins, nonempty);
    }
    free(hdr);
    pg_session_destroy(s);
}

static void check_bins_refused(const pg_th_scene *ts)
{
    char path[PG_PATH_MAX];
    pipeline_path(path, sizeof path);
    pg_param_override set = {.key = "bins", .value = "1000"};
    pg_session_desc sd = {.pipeline_path = path, .registry = &g_reg, .overrides = &set, .n_overrides = 1};
    pg_session *s = NULL;
    pg_error err = {0};
    /* the session loads the file; declare runs when it compiles (as passgraph dump would) */
    pg_result r = pg_session_create(g_gpu, ts->sg, &sd, &s, &err);
    CHECK_MSG(r == PG_OK, "bins=1000: the file itself must load: %s", err.msg);
    if (r) return;
    r = pg_session_compile(s, LIGHTS, W, H, &err);
    pg_session_destroy(s);
    printf("bins=1000: %s\n", err.msg);
    CHECK_MSG(r == PG_ERR_SCHEMA, "bins=1000: expected PG_ERR_SCHEMA, got %d", (int)r);
    CHECK_MSG(strstr(err.msg, "histogram.json: passes[2].options.bins:") && strstr(err.msg, "1000"),
              "bins=1000: the message names no file, JSON path or option: %s", err.msg);
}

int main(void)
{
    if (getenv("PG_TEST_NO_GPU")) return pg_test_skip("test_gpu_histogram", "PG_TEST_NO_GPU set");
    pg_register_builtin_passes(&g_reg);
    pg_gpu_desc gd = {.validation = true, .device_index = -1};
    pg_error err = {0};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_gpu_histogram: %s\n", err.msg);
        return 1;
    }
    pg_th_scene ts;
    if (pg_th_scene_open(g_gpu, "histogram", "default", NULL, W, H, LIGHTS, &ts)) {
        check_histogram(&ts, 64, -8.0f, 8.0f);
        check_histogram(&ts, 16, -4.0f, 4.0f);
        check_histogram(&ts, 256, -10.0f, 6.0f);
        check_bins_refused(&ts);
        pg_th_scene_close(g_gpu, &ts);
    } else {
        CHECK_MSG(0, "default scene not opened");
    }
    printf("validation messages: %u\n", g_gpu->validation_messages);
    CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_gpu_histogram");
}
