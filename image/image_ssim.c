/* image_ssim.c - mean SSIM over the valid region (see image_ssim.h). */
#include "image_ssim.h"

#include <math.h>
#include <stdlib.h>

#define SSIM_R (PG_SSIM_WINDOW / 2)
#define SSIM_SIGMA 1.5
#define SSIM_C1 ((0.01 * 255.0) * (0.01 * 255.0))
#define SSIM_C2 ((0.03 * 255.0) * (0.03 * 255.0))

/* the five row-filtered quantities x, y, x^2, y^2, xy: planes of ow * h doubles */
enum { Q_X, Q_Y, Q_XX, Q_YY, Q_XY, Q_COUNT };

static double luma(const uint8_t *p)
{
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

static void gaussian(double g[PG_SSIM_WINDOW])
{
    double sum = 0.0;
    for (int i = -SSIM_R; i <= SSIM_R; i++) {
        g[i + SSIM_R] = exp(-(double)(i * i) / (2.0 * SSIM_SIGMA * SSIM_SIGMA));
        sum += g[i + SSIM_R];
    }
    for (int i = 0; i < PG_SSIM_WINDOW; i++) g[i] /= sum;
}

/* row pass: q[k][y * ow + x] = sum_j g[j] * quantity k at (x + j, y); yrow: scratch of 2 * w doubles */
static void row_pass(const uint8_t *a, const uint8_t *b, uint32_t w, uint32_t h, const double *g, double **q,
                     double *yrow)
{
    uint32_t ow = w - 2 * SSIM_R;
    double *ya = yrow, *yb = yrow + w;
    for (uint32_t y = 0; y < h; y++) {
        for (uint32_t x = 0; x < w; x++) {
            ya[x] = luma(a + 4 * ((size_t)y * w + x));
            yb[x] = luma(b + 4 * ((size_t)y * w + x));
        }
        for (uint32_t x = 0; x < ow; x++) {
            double s[Q_COUNT] = {0};
            for (int j = 0; j < PG_SSIM_WINDOW; j++) {
                double u = ya[x + j], v = yb[x + j];
                s[Q_X] += g[j] * u;
                s[Q_Y] += g[j] * v;
                s[Q_XX] += g[j] * (u * u);
                s[Q_YY] += g[j] * (v * v);
                s[Q_XY] += g[j] * (u * v); /* u * v: symmetric in a and b */
            }
            for (int k = 0; k < Q_COUNT; k++) q[k][(size_t)y * ow + x] = s[k];
        }
    }
}

/* column pass and the SSIM of each valid pixel; acc: scratch of Q_COUNT * ow doubles */
static double col_pass(uint32_t w, uint32_t h, const double *g, double **q, double *acc)
{
    uint32_t ow = w - 2 * SSIM_R, oh = h - 2 * SSIM_R;
    double total = 0.0;
    for (uint32_t y = 0; y < oh; y++) {
        for (size_t i = 0; i < (size_t)Q_COUNT * ow; i++) acc[i] = 0.0;
        for (int j = 0; j < PG_SSIM_WINDOW; j++)
            for (int k = 0; k < Q_COUNT; k++) {
                const double *src = q[k] + (size_t)(y + j) * ow;
                double *d = acc + (size_t)k * ow;
                for (uint32_t x = 0; x < ow; x++) d[x] += g[j] * src[x];
            }
        for (uint32_t x = 0; x < ow; x++) {
            double mx = acc[Q_X * ow + x], my = acc[Q_Y * ow + x];
            double sxx = acc[Q_XX * ow + x] - mx * mx, syy = acc[Q_YY * ow + x] - my * my;
            double sxy = acc[Q_XY * ow + x] - mx * my;
            total += (2.0 * (mx * my) + SSIM_C1) * (2.0 * sxy + SSIM_C2) /
                     ((mx * mx + my * my + SSIM_C1) * (sxx + syy + SSIM_C2));
        }
    }
    return total / ((double)ow * oh);
}

pg_result pg_ssim(const uint8_t *a_rgba8, const uint8_t *b_rgba8, uint32_t w, uint32_t h, double *mean_out,
                  pg_error *err)
{
    if (!a_rgba8 || !b_rgba8) return pg_fail(err, PG_ERR_INVALID_ARG, "SSIM: missing image");
    if (!mean_out) return pg_fail(err, PG_ERR_INVALID_ARG, "SSIM: no output");
    if (w < PG_SSIM_WINDOW || h < PG_SSIM_WINDOW)
        return pg_fail(err, PG_ERR_INVALID_ARG, "SSIM: image %ux%u smaller than the %dx%d window", w, h,
                       PG_SSIM_WINDOW, PG_SSIM_WINDOW);
    uint32_t ow = w - 2 * SSIM_R;
    double g[PG_SSIM_WINDOW];
    gaussian(g);
    double *q[Q_COUNT] = {0};
    double *yrow = malloc(2 * (size_t)w * sizeof(double));
    double *acc = malloc((size_t)Q_COUNT * ow * sizeof(double));
    bool ok = yrow && acc;
    for (int k = 0; k < Q_COUNT; k++) ok = ok && (q[k] = malloc((size_t)ow * h * sizeof(double)));
    pg_result r = PG_OK;
    if (ok) {
        row_pass(a_rgba8, b_rgba8, w, h, g, q, yrow);
        *mean_out = col_pass(w, h, g, q, acc);
    } else {
        r = pg_fail(err, PG_ERR_OOM, "SSIM: out of memory for a %ux%u image", w, h);
    }
    for (int k = 0; k < Q_COUNT; k++) free(q[k]);
    free(yrow);
    free(acc);
    return r;
}
