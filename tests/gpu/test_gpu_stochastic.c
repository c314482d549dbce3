/* test_gpu_stochastic.c - statistical tests of the stochastic pipeline (pipelines/ris.json:
 * resampled importance sampling of each pixel's cluster list, shaders/shading.glsl
 * pg_ris_estimate) on lavapipe with validation on (zero messages). The default atrium, 96x54,
 * 300 lights, HDR in rgba32f; the exact image is pipelines/visibility.json with the same
 * surface reconstruction (the estimator's expectation).
 *
 * - Deterministic: the same sample index gives a bit-identical image; another index another one.
 * - Unbiased: K = 64 frames (sample 0..63, ris_candidates 8, one sample a pixel). Per 6x6-pixel
 *   region (144 regions) the K region means (RGB summed) give a mean and a standard error SE; every
 *   region must hold |mean - exact| <= 4 SE + 1e-5 (|exact| + 1e-3) (float rounding of sums that
 *   are exact in expectation; regions without light have SE 0 and must match to that tolerance).
 *   The same per pixel and channel is reported, not asserted (with ~15,000 values a 4-sigma
 *   excursion is expected about once).
 * - Error falls as expected: the RMSE of one frame over that of the mean of 16 frames is
 *   sqrt(16) = 4 for independent samples (asserted within 3..5.3; each RMSE is taken over disjoint
 *   groups of frames, rmse_groups); ris_samples 4 over 1 halves the RMSE of one frame (1.6..2.5,
 *   16 frames each).
 * - Planted biases fail: (a) every frame scaled by M / (M + 1) (the reservoir's weight sum divided by
 *   M + 1 instead of M: a 11% bias at M = 8); (b) max_lights 4, lists that miss lights the exact
 *   image has (an explicit knob: RIS over an incomplete list is biased). Both must break the
 *   region bound somewhere, so the test can fail.
 * - Stochastic light culling (pipelines/stochastic.json, stochastic_threshold 0.02): the same region
 *   test over 64 frames, the RMSE of 1 frame over that of 16 near 4, and a planted bias (a copy
 *   of the pipeline whose shading pass rescales with twice the culling pass's threshold) that must
 *   break the region bound. Per pixel, culling's estimate is far from normal with 64 frames (a few
 *   lights switch on or off together over a whole region of pixels), so only regions are asserted. */
#define _DEFAULT_SOURCE /* mkdtemp, symlink */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "gpu_harness.h"
#include "image_util.h"
#include "pass_list.h"
#include "test_util.h"

#define W 96
#define H 54
#define LIGHTS 300
#define K 64
#define REG 6
#define NRX (W / REG)
#define NRY (H / REG)
#define NREG (NRX * NRY)

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;
static pg_th_scene g_scene;

/* n frames of pipeline (data-folder path) with samples first.. into imgs (n * W*H*4 floats) */
static bool render_frames(const char *pipeline, const pg_param_override *sets, uint32_t n_sets, uint32_t first,
                          uint32_t n, float *imgs)
{
    char path[PG_PATH_MAX];
    if (pipeline[0] == '/') snprintf(path, sizeof path, "%s", pipeline);
    else pg_data_path(path, sizeof path, pipeline);
    pg_session_desc sd = {.pipeline_path = path, .registry = &g_reg, .overrides = sets, .n_overrides = n_sets};
    pg_session *s = NULL;
    pg_error err = {0};
    if (pg_session_create(g_gpu, g_scene.sg, &sd, &s, &err)) {
        CHECK_MSG(0, "%s: session: %s", pipeline, err.msg);
        return false;
    }
    bool ok = true;
    for (uint32_t k = 0; k < n && ok; k++) {
        pg_frame_info fi = g_scene.fi;
        fi.sample = first + k;
        pg_frame_stats st;
        uint32_t w = 0, h = 0;
        pg_format fmt;
        ok = pg_session_render(s, &fi, true, &st, &err) == PG_OK;
        const void *px = ok ? pg_runtime_output(s->runtime, 1, &w, &h, &fmt) : NULL;
        ok = px && w == W && h == H && pg_hdr_to_float(px, fmt, w, h, imgs + (size_t)k * W * H * 4, &err) == PG_OK;
    }
    CHECK_MSG(ok, "%s: render: %s", pipeline, err.msg);
    pg_session_destroy(s);
    return ok;
}

/* Region sums of RGB over one image into r[NREG]. */
static void region_sums(const float *img, double scale, double *r)
{
    memset(r, 0, sizeof(double) * NREG);
    for (uint32_t y = 0; y < NRY * REG; y++)
        for (uint32_t x = 0; x < NRX * REG; x++) {
            const float *p = img + ((size_t)y * W + x) * 4;
            r[(y / REG) * NRX + x / REG] += scale * ((double)p[0] + p[1] + p[2]) / (REG * REG);
        }
}

typedef struct bias_result {
    uint32_t bad_regions;   /* regions outside 4 SE + tolerance */
    double worst_z;         /* largest |mean - exact| / SE over regions with SE > 0 */
    uint32_t px_outside;    /* pixel channels outside 4 SE (reported) */
    uint32_t px_total;
} bias_result;

/* The region test of the mean of n frames (each scaled by `scale`) against the exact image. */
static bias_result bias_test(const float *imgs, uint32_t n, double scale, const float *exact)
{
    bias_result b = {0};
    double ex[NREG], m[NREG] = {0}, m2[NREG] = {0}, r[NREG];
    region_sums(exact, 1.0, ex);
    for (uint32_t k = 0; k < n; k++) {
        region_sums(imgs + (size_t)k * W * H * 4, scale, r);
        for (int i = 0; i < NREG; i++) m[i] += r[i], m2[i] += r[i] * r[i];
    }
    for (int i = 0; i < NREG; i++) {
        double mean = m[i] / n, var = fmax(m2[i] / n - mean * mean, 0) * n / (n - 1), se = sqrt(var / n);
        double d = fabs(mean - ex[i]);
        if (d > 4 * se + 1e-5 * (fabs(ex[i]) + 1e-3)) b.bad_regions++;
        if (se > 0 && d / se > b.worst_z) b.worst_z = d / se;
    }
    for (size_t p = 0; p < (size_t)W * H * 4; p++) {
        if (p % 4 == 3) continue;
        double s = 0, s2 = 0;
        for (uint32_t k = 0; k < n; k++) {
            double v = scale * imgs[(size_t)k * W * H * 4 + p];
            s += v, s2 += v * v;
        }
        double mean = s / n, se = sqrt(fmax(s2 / n - mean * mean, 0) / (n - 1));
        b.px_total++;
        if (fabs(mean - exact[p]) > 4 * se + 1e-5 * (fabs(exact[p]) + 1e-3)) b.px_outside++;
    }
    return b;
}

/* RMSE over RGB of the mean of frames [0, n) against exact. */
static double rmse_of_mean(const float *imgs, uint32_t n, const float *exact);

/* The RMSE of the mean of n frames, as the root of the mean squared error over the `total / n`
 * disjoint groups of n frames (a single group is dominated by a few fireflies: RIS with few
 * candidates is heavy-tailed). */
static double rmse_groups(const float *imgs, uint32_t total, uint32_t n, const float *exact)
{
    double mse = 0;
    for (uint32_t g = 0; g < total / n; g++) {
        double r = rmse_of_mean(imgs + (size_t)g * n * W * H * 4, n, exact);
        mse += r * r;
    }
    return sqrt(mse / (total / n));
}

static double rmse_of_mean(const float *imgs, uint32_t n, const float *exact)
{
    double e = 0;
    for (size_t p = 0; p < (size_t)W * H * 4; p++) {
        if (p % 4 == 3) continue;
        double s = 0;
        for (uint32_t k = 0; k < n; k++) s += imgs[(size_t)k * W * H * 4 + p];
        double d = s / n - exact[p];
        e += d * d;
    }
    return sqrt(e / ((double)W * H * 3));
}

static void check_ris(void)
{
    const size_t px = (size_t)W * H * 4;
    float *exact = malloc(px * sizeof(float)), *imgs = malloc(K * px * sizeof(float));
    float *four = malloc(16 * px * sizeof(float)), *capped = malloc(K * px * sizeof(float));
    pg_param_override f32 = {"hdr_format", "rgba32f"};
    pg_param_override ris[3] = {{"hdr_format", "rgba32f"}, {"ris_candidates", "8"}, {"ris_samples", "1"}};
    bool ok = exact && imgs && four && capped && render_frames("pipelines/visibility.json", &f32, 1, 0, 1, exact) &&
              render_frames("pipelines/ris.json", ris, 3, 0, K, imgs);
    if (ok) {
        /* determinism */
        float *again = four;
        ok = render_frames("pipelines/ris.json", ris, 3, 5, 1, again);
        CHECK_MSG(ok && !memcmp(again, imgs + 5 * px, px * sizeof(float)), "sample 5 rendered twice differs");
        CHECK_MSG(memcmp(imgs, imgs + px, px * sizeof(float)) != 0, "samples 0 and 1 give one image");
        double peak = 0;
        for (size_t p = 0; p < px; p++) peak = fmax(peak, exact[p]);
        CHECK_MSG(peak > 0, "the exact image is black");

        bias_result b = bias_test(imgs, K, 1.0, exact);
        printf("unbiased: %u of %d regions outside 4 SE (worst %.2f SE); pixels: %u of %u channels outside 4 SE\n",
               b.bad_regions, NREG, b.worst_z, b.px_outside, b.px_total);
        CHECK_MSG(b.bad_regions == 0, "RIS biased: %u regions outside 4 SE (worst %.2f)", b.bad_regions, b.worst_z);

        double r1 = rmse_groups(imgs, K, 1, exact), r4 = rmse_groups(imgs, K, 4, exact),
               r16 = rmse_groups(imgs, K, 16, exact), r64 = rmse_of_mean(imgs, K, exact);
        printf("rmse of the mean of n frames (over disjoint groups): 1 %.4g, 4 %.4g, 16 %.4g, 64 %.4g (1/16 ratio "
               "%.2f, expected 4)\n", r1, r4, r16, r64, r1 / r16);
        CHECK_MSG(r1 / r16 > 3.0 && r1 / r16 < 5.3, "rmse 1 -> 16 frames fell by %.2f, not ~4", r1 / r16);
        CHECK_MSG(r1 > r4 && r4 > r16 && r16 > r64, "rmse does not fall with more frames");

        /* planted bias (a): the weight sum over M + 1 */
        bias_result pb = bias_test(imgs, K, 8.0 / 9.0, exact);
        printf("planted bias (x 8/9): %u of %d regions outside 4 SE (worst %.2f SE)\n", pb.bad_regions, NREG, pb.worst_z);
        CHECK_MSG(pb.bad_regions > 0, "the test does not see an 11%% bias");
    }
    if (ok) { /* ris_samples 4: the RMSE of one frame halves */
        pg_param_override r4s[3] = {{"hdr_format", "rgba32f"}, {"ris_candidates", "8"}, {"ris_samples", "4"}};
        ok = render_frames("pipelines/ris.json", r4s, 3, 0, 16, four);
        if (ok) {
            double a = rmse_groups(imgs, 16, 1, exact), c = rmse_groups(four, 16, 1, exact);
            printf("rmse of one frame (16 frames): ris_samples 1 %.4g, 4 %.4g (ratio %.2f, expected 2)\n", a, c, a / c);
            CHECK_MSG(a / c > 1.6 && a / c < 2.5, "ris_samples 4 cut the rmse by %.2f, not ~2", a / c);
        }
    }
    if (ok) { /* planted bias (b): lists capped at 4 lights */
        pg_param_override cap[4] = {{"hdr_format", "rgba32f"}, {"ris_candidates", "8"}, {"ris_samples", "1"},
                                    {"max_lights", "4"}};
        if (render_frames("pipelines/ris.json", cap, 4, 0, K, capped)) {
            bias_result cb = bias_test(capped, K, 1.0, exact);
            printf("planted bias (max_lights 4): %u of %d regions outside 4 SE (worst %.2f SE)\n", cb.bad_regions, NREG,
                   cb.worst_z);
            CHECK_MSG(cb.bad_regions > 0, "the test does not see the bias of capped lists");
        }
    }
    free(exact);
    free(imgs);
    free(four);
    free(capped);
}

/* A copy of pipelines/stochastic.json whose shading pass rescales with twice the culling pass's
 * threshold (a planted bias: the kept lights count 1/p' times with p' != p) at path. */
static bool write_mismatched(const char *path)
{
    char src[PG_PATH_MAX];
    pg_data_path(src, sizeof src, "pipelines/stochastic.json");
    FILE *f = fopen(src, "rb");
    if (!f) return false;
    char buf[16384];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = 0;
    /* the shading pass's option (the second "$stochastic_threshold" reference; the first is the
     * culling pass's) becomes a literal 0.04 while the parameter stays 0.02 */
    char *first = strstr(buf, "\"threshold\": \"$stochastic_threshold\"");
    char *second = first ? strstr(buf, "\"stochastic_threshold\": \"$stochastic_threshold\"") : NULL;
    if (!second) return false;
    FILE *o = fopen(path, "wb");
    if (!o) return false;
    fwrite(buf, 1, (size_t)(second - buf), o);
    fputs("\"stochastic_threshold\": 0.04", o);
    fputs(second + strlen("\"stochastic_threshold\": \"$stochastic_threshold\""), o);
    fclose(o);
    return true;
}

/* Stochastic light culling (pipelines/stochastic.json, threshold 0.02 on this set-up): the same
 * region test over 64 frames (each frame its own random ranges), the 1/sqrt(n) fall, and a planted
 * bias (the shading pass rescaling with another threshold than the culling pass) that must fail. */
static void check_culling(void)
{
    const size_t px = (size_t)W * H * 4;
    float *exact = malloc(px * sizeof(float)), *imgs = malloc(K * px * sizeof(float));
    pg_param_override f32 = {"hdr_format", "rgba32f"};
    pg_param_override sc[2] = {{"hdr_format", "rgba32f"}, {"stochastic_threshold", "0.02"}};
    bool ok = exact && imgs && render_frames("pipelines/visibility.json", &f32, 1, 0, 1, exact) &&
              render_frames("pipelines/stochastic.json", sc, 2, 0, K, imgs);
    if (ok) {
        CHECK_MSG(memcmp(imgs, imgs + px, px * sizeof(float)) != 0, "culling: samples 0 and 1 give one image");
        bias_result b = bias_test(imgs, K, 1.0, exact);
        printf("culling unbiased: %u of %d regions outside 4 SE (worst %.2f SE); pixels: %u of %u channels outside "
               "4 SE\n", b.bad_regions, NREG, b.worst_z, b.px_outside, b.px_total);
        CHECK_MSG(b.bad_regions == 0, "culling biased: %u regions outside 4 SE (worst %.2f)", b.bad_regions, b.worst_z);
        double r1 = rmse_groups(imgs, K, 1, exact), r16 = rmse_groups(imgs, K, 16, exact);
        printf("culling rmse of the mean: 1 frame %.4g, 16 frames %.4g (ratio %.2f, expected 4)\n", r1, r16, r1 / r16);
        CHECK_MSG(r1 > 0 && r1 / r16 > 3.0 && r1 / r16 < 5.3, "culling: rmse 1 -> 16 frames fell by %.2f", r1 / r16);
    }
    /* the copy lives in a folder of its own with a link to the shipped fragments (includes are
     * resolved next to the including file) */
    char dir[] = "/tmp/pg_stochastic_XXXXXX", bad[PG_PATH_MAX], frag[PG_PATH_MAX], link_path[PG_PATH_MAX];
    if (ok && mkdtemp(dir)) {
        snprintf(bad, sizeof bad, "%s/mismatch.json", dir);
        snprintf(link_path, sizeof link_path, "%s/fragments", dir);
        pg_data_path(frag, sizeof frag, "pipelines/fragments");
        CHECK_MSG(symlink(frag, link_path) == 0 && write_mismatched(bad), "could not write the planted-bias pipeline");
        if (render_frames(bad, sc, 2, 0, K, imgs)) {
            bias_result pb = bias_test(imgs, K, 1.0, exact);
            printf("planted bias (rescale with 2x the threshold): %u of %d regions outside 4 SE (worst %.2f SE)\n",
                   pb.bad_regions, NREG, pb.worst_z);
            CHECK_MSG(pb.bad_regions > 0, "the test does not see a mismatched rescale");
        }
        unlink(bad);
        unlink(link_path);
        rmdir(dir);
    }
    free(exact);
    free(imgs);
}

int main(void)
{
    if (getenv("PG_TEST_NO_GPU")) return pg_test_skip("test_gpu_stochastic", "PG_TEST_NO_GPU set");
    pg_register_builtin_passes(&g_reg);
    pg_gpu_desc gd = {.validation = true, .device_index = -1, .quiet = true};
    pg_error err = {0};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_gpu_stochastic: %s\n", err.msg);
        return 1;
    }
    if (pg_th_scene_open(g_gpu, "atrium", "default", NULL, W, H, LIGHTS, &g_scene)) {
        check_ris();
        check_culling();
        pg_th_scene_close(g_gpu, &g_scene);
    } else {
        CHECK_MSG(0, "scene");
    }
    printf("validation messages: %u\n", g_gpu->validation_messages);
    CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_gpu_stochastic");
}
