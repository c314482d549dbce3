/* image_compare.c - image error metrics and the error heatmap (see image_compare.h). */
#include "image_compare.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static bool rgb_finite(const float *p)
{
    return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

static double psnr(double peak, double mse)
{
    if (mse == 0.0) return INFINITY;
    if (!(peak > 0.0)) return -INFINITY;
    return 10.0 * log10(peak * peak / mse);
}

pg_result pg_image_sizes_match(const char *what, uint32_t wa, uint32_t ha, uint32_t wb, uint32_t hb, pg_error *err)
{
    if (wa == wb && ha == hb) return PG_OK;
    return pg_fail(err, PG_ERR_INVALID_ARG, "%s: sizes differ: %ux%u vs %ux%u", what ? what : "images", wa, ha, wb,
                   hb);
}

pg_result pg_image_error_compute(const float *hdr_a, const float *hdr_b, const uint8_t *ldr_a, const uint8_t *ldr_b,
                                 uint32_t w, uint32_t h, double threshold_8bit, pg_image_error *out, pg_error *err)
{
    if (!out) return pg_fail(err, PG_ERR_INVALID_ARG, "image compare: no output struct");
    memset(out, 0, sizeof *out);
    if (!hdr_a || !hdr_b || !ldr_a || !ldr_b)
        return pg_fail(err, PG_ERR_INVALID_ARG, "image compare: missing image (HDR and display images of both)");
    if (w == 0 || h == 0) return pg_fail(err, PG_ERR_INVALID_ARG, "image compare: empty image %ux%u", w, h);
    if (!isfinite(threshold_8bit) || threshold_8bit < 0)
        return pg_fail(err, PG_ERR_INVALID_ARG, "image compare: threshold %g must be finite and >= 0", threshold_8bit);
    out->width = w;
    out->height = h;
    size_t n = (size_t)w * h;

    /* linear (HDR) */
    double sum_sq = 0, max_abs = 0, peak = -INFINITY;
    uint64_t compared = 0;
    for (size_t i = 0; i < n; i++) {
        const float *a = hdr_a + i * 4, *b = hdr_b + i * 4;
        bool fa = rgb_finite(a), fb = rgb_finite(b);
        if (!fa) out->nonfinite_a++;
        if (!fb) out->nonfinite_b++;
        if (!fa || !fb) continue;
        compared++;
        for (int c = 0; c < 3; c++) {
            double d = fabs((double)a[c] - (double)b[c]);
            sum_sq += d * d;
            if (d > max_abs) max_abs = d;
            if (b[c] > peak) peak = b[c];
        }
    }
    out->compared_linear = compared;
    if (compared) {
        double mse = sum_sq / (3.0 * (double)compared);
        out->rmse_linear = sqrt(mse);
        out->max_abs_linear = max_abs;
        out->peak_linear = peak;
        out->psnr_linear = psnr(peak, mse);
    } else {
        out->rmse_linear = out->max_abs_linear = out->psnr_linear = out->peak_linear = NAN;
    }

    /* display (8-bit) */
    uint64_t sum_sq8 = 0, over = 0;
    int max8 = 0;
    for (size_t i = 0; i < n; i++) {
        const uint8_t *a = ldr_a + i * 4, *b = ldr_b + i * 4;
        int pix_max = 0;
        for (int c = 0; c < 3; c++) {
            int d = abs((int)a[c] - (int)b[c]);
            sum_sq8 += (uint64_t)(d * d);
            if (d > pix_max) pix_max = d;
        }
        if (pix_max > max8) max8 = pix_max;
        if ((double)pix_max > threshold_8bit) over++;
    }
    double mse8 = (double)sum_sq8 / (3.0 * (double)n);
    out->rmse_display = sqrt(mse8);
    out->max_abs_display = max8;
    out->psnr_display = psnr(255.0, mse8);
    out->over_threshold = over;
    out->share_over_threshold = (double)over / (double)n;
    return PG_OK;
}

/* ---- colormap ---- */

/* OKLab -> linear sRGB (Ottosson's published matrices). */
static void oklab_to_linear_srgb(double L, double a, double b, double rgb[3])
{
    double l_ = L + 0.3963377774 * a + 0.2158037573 * b;
    double m_ = L - 0.1055613458 * a - 0.0638541728 * b;
    double s_ = L - 0.0894841775 * a - 1.2914855480 * b;
    double l = l_ * l_ * l_, m = m_ * m_ * m_, s = s_ * s_ * s_;
    rgb[0] = 4.0767416621 * l - 3.3077115913 * m + 0.2309699292 * s;
    rgb[1] = -1.2684380046 * l + 2.6097574011 * m - 0.3413193965 * s;
    rgb[2] = -0.0041960863 * l - 0.7034186147 * m + 1.7076147010 * s;
}

static bool in_gamut(const double rgb[3])
{
    for (int i = 0; i < 3; i++)
        if (rgb[i] < -1e-9 || rgb[i] > 1.0 + 1e-9) return false;
    return true;
}

static uint8_t srgb_encode8(double x)
{
    x = x < 0 ? 0 : x > 1 ? 1 : x;
    double e = x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055;
    return (uint8_t)lrint(e * 255.0);
}

void pg_colormap(double t, uint8_t rgb[3])
{
    if (!(t > 0)) t = 0; /* also NaN */
    if (t > 1) t = 1;
    const double pi = 3.14159265358979323846;
    double L = 0.14 + 0.83 * t;                          /* OKLab lightness, monotone */
    double hue = (-75.0 + 180.0 * t) * pi / 180.0;        /* purple -> red -> orange -> yellow */
    double C = 0.05 + 0.13 * sin(pi * t) + 0.05 * t;      /* most colourful in the middle */
    double ca = cos(hue), sa = sin(hue), lin[3];
    oklab_to_linear_srgb(L, C * ca, C * sa, lin);
    if (!in_gamut(lin)) { /* keep lightness and hue, reduce chroma until it fits in sRGB */
        double lo = 0, hi = C;
        for (int i = 0; i < 40; i++) {
            double mid = 0.5 * (lo + hi);
            oklab_to_linear_srgb(L, mid * ca, mid * sa, lin);
            if (in_gamut(lin)) lo = mid;
            else hi = mid;
        }
        oklab_to_linear_srgb(L, lo * ca, lo * sa, lin);
    }
    for (int i = 0; i < 3; i++) rgb[i] = srgb_encode8(lin[i]);
}

/* ---- heatmap ---- */

/* 256 colours: adjacent 8-bit colormap entries at a finer step can dip in luminance by one
 * rounding step of a channel; at 256 steps luminance strictly rises (tests/test_image_compare.c). */
#define LUT_N 256

/* max over RGB of |a - b|; NaN when either pixel has a non-finite channel. */
static double pixel_error(const float *a, const float *b)
{
    if (!rgb_finite(a) || !rgb_finite(b)) return NAN;
    double m = 0;
    for (int c = 0; c < 3; c++) {
        double d = fabs((double)a[c] - (double)b[c]);
        if (d > m) m = d;
    }
    return m;
}

double pg_error_heatmap_scale(const float *hdr_a, const float *hdr_b, uint32_t w, uint32_t h, double scale)
{
    if (isfinite(scale) && scale > 0) return scale;
    double m = 0;
    for (size_t i = 0; i < (size_t)w * h; i++) {
        double e = pixel_error(hdr_a + i * 4, hdr_b + i * 4);
        if (e > m) m = e; /* NaN compares false */
    }
    return m > 0 ? m : 1e-30;
}

void pg_error_heatmap(const float *hdr_a, const float *hdr_b, uint32_t w, uint32_t h, double scale, uint8_t *out_rgba)
{
    static const uint8_t nonfinite[3] = {PG_HEATMAP_NONFINITE_R, PG_HEATMAP_NONFINITE_G, PG_HEATMAP_NONFINITE_B};
    uint8_t lut[LUT_N][3];
    for (int i = 0; i < LUT_N; i++) pg_colormap((double)i / (LUT_N - 1), lut[i]);
    double s = pg_error_heatmap_scale(hdr_a, hdr_b, w, h, scale);
    for (size_t i = 0; i < (size_t)w * h; i++) {
        double e = pixel_error(hdr_a + i * 4, hdr_b + i * 4);
        const uint8_t *c;
        if (isnan(e)) {
            c = nonfinite;
        } else {
            double t = e / s;
            if (t > 1) t = 1;
            c = lut[(int)lrint(t * (LUT_N - 1))];
        }
        uint8_t *o = out_rgba + i * 4;
        o[0] = c[0];
        o[1] = c[1];
        o[2] = c[2];
        o[3] = 255;
    }
}

#define QBINS 4096
#define QLOG2_RANGE 48.0 /* errors below max * 2^-48 share the first bin */

double pg_error_quantile(const float *hdr_a, const float *hdr_b, uint32_t w, uint32_t h, double q)
{
    size_t n = (size_t)w * h;
    double m = 0;
    for (size_t i = 0; i < n; i++) {
        double e = pixel_error(hdr_a + i * 4, hdr_b + i * 4);
        if (e > m) m = e;
    }
    if (!(m > 0)) return 0;
    if (!(q > 0)) q = 0;
    if (q > 1) q = 1;
    uint64_t *hist = calloc(QBINS, sizeof *hist);
    if (!hist) return m;
    uint64_t count = 0;
    for (size_t i = 0; i < n; i++) {
        double e = pixel_error(hdr_a + i * 4, hdr_b + i * 4);
        if (!(e > 0)) continue;
        double x = (log2(e / m) + QLOG2_RANGE) / QLOG2_RANGE * QBINS; /* 0..QBINS */
        int b = x < 0 ? 0 : x >= QBINS ? QBINS - 1 : (int)x;
        hist[b]++;
        count++;
    }
    double target = q * (double)count, acc = 0, result = m;
    for (int b = 0; b < QBINS; b++) {
        acc += (double)hist[b];
        if (hist[b] && acc >= target) { /* upper edge of the bin */
            result = m * exp2((double)(b + 1) / QBINS * QLOG2_RANGE - QLOG2_RANGE);
            break;
        }
    }
    free(hist);
    return result < m ? result : m;
}
