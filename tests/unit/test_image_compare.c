/* test_image_compare.c - image error metrics (core/image/image_compare.c) on synthetic images with known
 * answers, the error heatmap's colours and the colormap's monotone luminance. CPU only. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "image_compare.h"
#include "test_util.h"

#define W 4
#define H 2
#define N (W * H)

static bool near(double a, double b, double tol)
{
    return fabs(a - b) <= tol * (1.0 + fabs(b));
}

static void fill(float *hdr, uint8_t *ldr, float v, uint8_t c)
{
    for (int i = 0; i < N; i++) {
        for (int k = 0; k < 3; k++) {
            hdr[i * 4 + k] = v;
            ldr[i * 4 + k] = c;
        }
        hdr[i * 4 + 3] = 1.0f;
        ldr[i * 4 + 3] = 255;
    }
}

static double srgb_decode(uint8_t v)
{
    double x = v / 255.0;
    return x <= 0.04045 ? x / 12.92 : pow((x + 0.055) / 1.055, 2.4);
}

static bool close_rgb(const uint8_t *x, const uint8_t *y)
{
    for (int k = 0; k < 3; k++)
        if (abs((int)x[k] - (int)y[k]) > 2) return false;
    return true;
}

static double luminance(const uint8_t rgb[3])
{
    return 0.2126 * srgb_decode(rgb[0]) + 0.7152 * srgb_decode(rgb[1]) + 0.0722 * srgb_decode(rgb[2]);
}

static void test_identical(void)
{
    float a[N * 4], b[N * 4];
    uint8_t la[N * 4], lb[N * 4];
    fill(a, la, 0.75f, 100);
    fill(b, lb, 0.75f, 100);
    pg_image_error e;
    pg_error err = {0};
    CHECK(pg_image_error_compute(a, b, la, lb, W, H, 1.0, &e, &err) == PG_OK);
    CHECK(e.rmse_linear == 0 && e.max_abs_linear == 0 && isinf(e.psnr_linear) && e.psnr_linear > 0);
    CHECK(e.rmse_display == 0 && e.max_abs_display == 0 && isinf(e.psnr_display) && e.psnr_display > 0);
    CHECK(e.share_over_threshold == 0 && e.over_threshold == 0);
    CHECK(e.nonfinite_a == 0 && e.nonfinite_b == 0);
    CHECK(e.width == W && e.height == H && e.compared_linear == N);
    CHECK(e.peak_linear == 0.75);
}

static void test_one_pixel_off(void)
{
    float a[N * 4], b[N * 4];
    uint8_t la[N * 4], lb[N * 4];
    fill(a, la, 1.0f, 50);
    fill(b, lb, 1.0f, 50);
    b[5 * 4 + 2] = 2.0f;        /* the reference's peak: 2 (the pipeline matches it) */
    a[5 * 4 + 2] = 2.0f;
    a[3 * 4 + 1] = 1.5f;        /* one channel off by 0.5 */
    a[3 * 4 + 3] = 99.0f;       /* alpha is ignored */
    la[3 * 4 + 0] = 60;         /* one display channel off by 10 */
    la[6 * 4 + 3] = 0;          /* alpha is ignored */
    pg_image_error e;
    pg_error err = {0};
    CHECK(pg_image_error_compute(a, b, la, lb, W, H, 1.0, &e, &err) == PG_OK);
    double mse = 0.25 / (3.0 * N);
    CHECK_MSG(near(e.rmse_linear, sqrt(mse), 1e-12), "rmse_linear %.17g", e.rmse_linear);
    CHECK(e.max_abs_linear == 0.5);
    CHECK(e.peak_linear == 2.0);
    CHECK_MSG(near(e.psnr_linear, 10.0 * log10(4.0 / mse), 1e-12), "psnr_linear %.17g", e.psnr_linear);
    double mse8 = 100.0 / (3.0 * N);
    CHECK_MSG(near(e.rmse_display, sqrt(mse8), 1e-12), "rmse_display %.17g", e.rmse_display);
    CHECK(e.max_abs_display == 10);
    CHECK_MSG(near(e.psnr_display, 10.0 * log10(255.0 * 255.0 / mse8), 1e-12), "psnr_display %.17g", e.psnr_display);
    CHECK(e.over_threshold == 1 && e.share_over_threshold == 1.0 / N);
    /* the threshold is exclusive: a difference equal to it does not count */
    CHECK(pg_image_error_compute(a, b, la, lb, W, H, 10.0, &e, &err) == PG_OK);
    CHECK(e.over_threshold == 0 && e.share_over_threshold == 0);
    CHECK(pg_image_error_compute(a, b, la, lb, W, H, 9.5, &e, &err) == PG_OK);
    CHECK(e.over_threshold == 1);
    /* the metrics are symmetric except the PSNR peak, which is the reference's (b) */
    CHECK(pg_image_error_compute(b, a, lb, la, W, H, 1.0, &e, &err) == PG_OK);
    CHECK(e.peak_linear == 2.0 && e.max_abs_linear == 0.5);
}

static void test_nonfinite(void)
{
    float a[N * 4], b[N * 4];
    uint8_t la[N * 4], lb[N * 4];
    fill(a, la, 1.0f, 0);
    fill(b, lb, 1.0f, 0);
    a[1 * 4 + 0] = NAN;                 /* pixel 1: NaN in a, huge difference elsewhere: excluded */
    a[1 * 4 + 1] = 1000.0f;
    b[2 * 4 + 2] = INFINITY;            /* pixel 2: Inf in b */
    b[2 * 4 + 0] = 5000.0f;
    a[4 * 4 + 1] = -INFINITY;           /* pixel 4: bad in both */
    b[4 * 4 + 2] = NAN;
    a[6 * 4 + 3] = NAN;                 /* alpha: not counted */
    a[7 * 4 + 0] = 1.25f;               /* pixel 7: the only counted difference */
    pg_image_error e;
    pg_error err = {0};
    CHECK(pg_image_error_compute(a, b, la, lb, W, H, 1.0, &e, &err) == PG_OK);
    CHECK_MSG(e.nonfinite_a == 2 && e.nonfinite_b == 2, "nonfinite %llu %llu", (unsigned long long)e.nonfinite_a,
              (unsigned long long)e.nonfinite_b);
    CHECK(e.compared_linear == N - 3);
    CHECK(e.max_abs_linear == 0.25);
    CHECK(e.peak_linear == 1.0);
    CHECK(near(e.rmse_linear, sqrt(0.0625 / (3.0 * (N - 3))), 1e-12));
    CHECK(isfinite(e.psnr_linear));
    /* nothing comparable: linear metrics are NaN, display metrics still computed */
    for (int i = 0; i < N; i++) a[i * 4] = NAN;
    CHECK(pg_image_error_compute(a, b, la, lb, W, H, 1.0, &e, &err) == PG_OK);
    CHECK(e.nonfinite_a == N && e.compared_linear == 0);
    CHECK(isnan(e.rmse_linear) && isnan(e.psnr_linear) && isnan(e.max_abs_linear));
    CHECK(e.rmse_display == 0);
}

static void test_zero_peak(void)
{
    float a[N * 4], b[N * 4];
    uint8_t la[N * 4], lb[N * 4];
    fill(a, la, 0.0f, 0);
    fill(b, lb, 0.0f, 0);
    a[0] = 0.5f; /* the reference is black: PSNR of a non-zero error is -inf */
    pg_image_error e;
    pg_error err = {0};
    CHECK(pg_image_error_compute(a, b, la, lb, W, H, 1.0, &e, &err) == PG_OK);
    CHECK(isinf(e.psnr_linear) && e.psnr_linear < 0);
    CHECK(e.max_abs_linear == 0.5);
}

static void test_share_over_threshold(void)
{
    float a[N * 4], b[N * 4];
    uint8_t la[N * 4], lb[N * 4];
    fill(a, la, 1.0f, 100);
    fill(b, lb, 1.0f, 100);
    /* pixel i differs by i in one channel (channel i % 3), 8-bit */
    for (int i = 0; i < N; i++) la[i * 4 + i % 3] = (uint8_t)(100 + i);
    lb[7 * 4 + 1] = 120;      /* pixel 7: la is 107 in channel 1 (7 % 3), lb 120: diff 13 */
    pg_error err = {0};
    pg_image_error e;
    /* max diffs per pixel: 0 1 2 3 4 5 6 13 */
    CHECK(pg_image_error_compute(a, b, la, lb, W, H, 1.0, &e, &err) == PG_OK);
    CHECK_MSG(e.over_threshold == 6 && e.share_over_threshold == 6.0 / N, "over %llu",
              (unsigned long long)e.over_threshold);
    CHECK(pg_image_error_compute(a, b, la, lb, W, H, 0.0, &e, &err) == PG_OK);
    CHECK(e.over_threshold == 7 && e.share_over_threshold == 7.0 / N);
    CHECK(pg_image_error_compute(a, b, la, lb, W, H, 4.5, &e, &err) == PG_OK);
    CHECK(e.over_threshold == 3 && e.share_over_threshold == 3.0 / N);
    CHECK(pg_image_error_compute(a, b, la, lb, W, H, 13.0, &e, &err) == PG_OK);
    CHECK(e.over_threshold == 0 && e.share_over_threshold == 0);
    CHECK(e.max_abs_display == 13);
    double sum = 0;
    for (int i = 1; i < 7; i++) sum += (double)i * i;
    sum += 13.0 * 13.0;
    CHECK(near(e.rmse_display, sqrt(sum / (3.0 * N)), 1e-12));
}

static void test_bad_args(void)
{
    float a[N * 4], b[N * 4];
    uint8_t la[N * 4], lb[N * 4];
    fill(a, la, 1.0f, 0);
    fill(b, lb, 1.0f, 0);
    pg_image_error e;
    pg_error err = {0};
    CHECK(pg_image_sizes_match("hdr_output", 64, 36, 64, 36, &err) == PG_OK);
    CHECK(pg_image_sizes_match("hdr_output", 64, 36, 32, 36, &err) == PG_ERR_INVALID_ARG);
    CHECK(strstr(err.msg, "hdr_output") && strstr(err.msg, "64x36") && strstr(err.msg, "32x36"));
    CHECK(pg_image_sizes_match("x", 64, 36, 64, 18, &err) == PG_ERR_INVALID_ARG);
    CHECK(pg_image_error_compute(a, b, la, lb, 0, H, 1.0, &e, &err) == PG_ERR_INVALID_ARG);
    CHECK(pg_image_error_compute(a, b, la, lb, W, 0, 1.0, &e, &err) == PG_ERR_INVALID_ARG);
    CHECK(pg_image_error_compute(NULL, b, la, lb, W, H, 1.0, &e, &err) == PG_ERR_INVALID_ARG);
    CHECK(pg_image_error_compute(a, b, la, NULL, W, H, 1.0, &e, &err) == PG_ERR_INVALID_ARG);
    CHECK(pg_image_error_compute(a, b, la, lb, W, H, -1.0, &e, &err) == PG_ERR_INVALID_ARG);
    CHECK(pg_image_error_compute(a, b, la, lb, W, H, NAN, &e, &err) == PG_ERR_INVALID_ARG);
    CHECK(pg_image_error_compute(a, b, la, lb, W, H, 1.0, NULL, &err) == PG_ERR_INVALID_ARG);
}

static void test_heatmap(void)
{
    uint8_t c0[3], c1[3], cm[3];
    pg_colormap(0.0, c0);
    pg_colormap(1.0, c1);
    pg_colormap(0.5, cm);
    float a[N * 4], b[N * 4];
    uint8_t la[N * 4], lb[N * 4], out[N * 4];
    fill(a, la, 1.0f, 0);
    fill(b, lb, 1.0f, 0);
    a[1 * 4 + 2] = 1.5f;    /* error 0.5 = scale */
    a[2 * 4 + 0] = 0.0f;    /* error 1.0 > scale: saturates */
    b[3 * 4 + 1] = 1.25f;   /* error 0.25 = scale / 2 */
    a[4 * 4 + 0] = NAN;     /* non-finite: cyan */
    pg_error_heatmap(a, b, W, H, 0.5, out);
    CHECK(!memcmp(out + 0 * 4, c0, 3) && out[3] == 255);
    CHECK(!memcmp(out + 1 * 4, c1, 3));
    CHECK(!memcmp(out + 2 * 4, c1, 3));
    CHECK(close_rgb(out + 3 * 4, cm)); /* the heatmap uses a 256-entry table: exact at the ends */
    CHECK(out[4 * 4 + 0] == PG_HEATMAP_NONFINITE_R && out[4 * 4 + 1] == PG_HEATMAP_NONFINITE_G &&
          out[4 * 4 + 2] == PG_HEATMAP_NONFINITE_B && out[4 * 4 + 3] == 255);
    CHECK(!memcmp(out + 7 * 4, c0, 3) && out[7 * 4 + 3] == 255);
    /* scale <= 0: the largest finite error (1.0) maps to the end colour */
    CHECK(pg_error_heatmap_scale(a, b, W, H, 0) == 1.0);
    CHECK(pg_error_heatmap_scale(a, b, W, H, 0.5) == 0.5);
    pg_error_heatmap(a, b, W, H, 0, out);
    CHECK(!memcmp(out + 2 * 4, c1, 3));
    CHECK(close_rgb(out + 1 * 4, cm));
    CHECK(!memcmp(out + 0 * 4, c0, 3));
    /* all equal: every pixel the start colour (scale 1e-30) */
    fill(a, la, 1.0f, 0);
    fill(b, lb, 1.0f, 0);
    CHECK(pg_error_heatmap_scale(a, b, W, H, -1) == 1e-30);
    pg_error_heatmap(a, b, W, H, -1, out);
    int all_start = 1;
    for (int i = 0; i < N; i++) all_start &= !memcmp(out + i * 4, c0, 3) && out[i * 4 + 3] == 255;
    CHECK(all_start);
}

static void test_colormap(void)
{
    uint8_t c[3], prev_c[3] = {0, 0, 0};
    double prev = -1.0;
    int strict = 1, never_marker = 1;
    for (int i = 0; i < 256; i++) { /* the 256 colours a heatmap uses */
        pg_colormap(i / 255.0, c);
        double y = luminance(c);
        if (!(y > prev)) {
            strict = 0;
            fprintf(stderr, "colormap luminance not rising at %d: %d %d %d (%g) after %d %d %d (%g)\n", i, c[0],
                    c[1], c[2], y, prev_c[0], prev_c[1], prev_c[2], prev);
        }
        if (c[0] == PG_HEATMAP_NONFINITE_R && c[1] == PG_HEATMAP_NONFINITE_G && c[2] == PG_HEATMAP_NONFINITE_B)
            never_marker = 0;
        prev = y;
        memcpy(prev_c, c, 3);
    }
    CHECK(strict);
    CHECK(never_marker);
    /* finer than 256 steps, 8-bit rounding may dip luminance by one step of one channel, no more */
    int nondecreasing = 1;
    prev = -1;
    for (int i = 0; i <= 4096; i++) {
        pg_colormap(i / 4096.0, c);
        double y = luminance(c);
        if (y < prev - 0.7152 * (srgb_decode(255) - srgb_decode(254))) nondecreasing = 0; /* largest green step */
        if (y > prev) prev = y;
    }
    CHECK(nondecreasing);
    /* dark start, light end; clamping outside [0, 1] and NaN */
    uint8_t lo[3], hi[3];
    pg_colormap(0, lo);
    pg_colormap(1, hi);
    CHECK(luminance(lo) < 0.01 && luminance(hi) > 0.8);
    pg_colormap(-3, c);
    CHECK(!memcmp(c, lo, 3));
    pg_colormap(NAN, c);
    CHECK(!memcmp(c, lo, 3));
    pg_colormap(7, c);
    CHECK(!memcmp(c, hi, 3));
}

static void test_quantile(void)
{
    enum { QW = 100, QH = 2 };
    float *a = calloc(QW * QH * 4, sizeof(float)), *b = calloc(QW * QH * 4, sizeof(float));
    CHECK(a && b);
    if (!a || !b) {
        free(a);
        free(b);
        return;
    }
    CHECK(pg_error_quantile(a, b, QW, QH, 0.99) == 0); /* nothing differs */
    /* row 0: errors 1..100; row 1: equal (left out of the quantile) */
    for (int i = 0; i < QW; i++) a[i * 4 + 1] = (float)(i + 1);
    double q99 = pg_error_quantile(a, b, QW, QH, 0.99);
    double q50 = pg_error_quantile(a, b, QW, QH, 0.5);
    CHECK_MSG(q99 >= 99 && q99 <= 99 * 1.01, "q99 %g", q99);
    CHECK_MSG(q50 >= 50 && q50 <= 50 * 1.01, "q50 %g", q50);
    CHECK(pg_error_quantile(a, b, QW, QH, 1.0) == 100);
    free(a);
    free(b);
}

int main(void)
{
    test_identical();
    test_one_pixel_off();
    test_nonfinite();
    test_zero_peak();
    test_share_over_threshold();
    test_bad_args();
    test_heatmap();
    test_colormap();
    test_quantile();
    return pg_test_finish("test_image_compare");
}
