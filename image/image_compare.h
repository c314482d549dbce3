/* image_compare.h - image error between a pipeline's frame and a reference frame (pure CPU, no
 * Vulkan): RMSE / PSNR / max abs over the scene-linear HDR images and over the 8-bit display
 * images, the share of pixels visibly different, and an error heatmap.
 *
 * Conventions (image a is the pipeline under test, image b the reference):
 * - Only the R, G, B channels count; alpha is ignored.
 * - Linear metrics: over the pixels whose R, G, B are finite in BOTH HDR images; a pixel with a
 *   NaN or Inf channel (RGB) is excluded and counted in nonfinite_a / nonfinite_b (a pixel bad in
 *   both is counted in both). MSE is the mean of the squared channel differences.
 *   PSNR_linear = 10 * log10(peak^2 / MSE) with peak = the largest R, G or B value of the
 *   reference (b) over the compared pixels (peak_linear). MSE = 0 gives +inf (printed "inf");
 *   MSE > 0 with peak <= 0 gives -inf. No compared pixel at all: rmse / max abs / PSNR are NaN.
 * - Display metrics: over every pixel, in 0..255 units; PSNR_display = 10*log10(255^2 / MSE).
 * - share_over_threshold: fraction of pixels whose max over RGB of |display a - display b| is
 *   strictly greater than the threshold (8-bit units; threshold 1 tolerates one step of rounding).
 */
#ifndef PG_IMAGE_COMPARE_H
#define PG_IMAGE_COMPARE_H

#include "pg_common.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pg_image_error {
    double rmse_linear, psnr_linear, max_abs_linear;    /* over RGB of the HDR (scene-linear) images */
    double rmse_display, psnr_display, max_abs_display; /* over RGB of the 8-bit display images, 0..255 units */
    double share_over_threshold;  /* fraction of pixels whose max |display diff| over RGB > threshold */
    uint64_t nonfinite_a, nonfinite_b; /* pixels with NaN/Inf (RGB) in either HDR */
    uint32_t width, height;
    double peak_linear;           /* PSNR_linear's peak: max RGB of the reference (b) */
    uint64_t compared_linear;     /* pixels that entered the linear metrics */
    uint64_t over_threshold;      /* pixels counted in share_over_threshold */
} pg_image_error;

/* hdr_a/hdr_b: w*h RGBA32F pixels; ldr_a/ldr_b: w*h RGBA8 pixels (display images, any encoding:
 * compared as stored). threshold_8bit must be finite and >= 0. PG_ERR_INVALID_ARG for a NULL
 * image, a zero size or a bad threshold. The caller checks that the images have one size
 * (pg_image_sizes_match). */
pg_result pg_image_error_compute(const float *hdr_a, const float *hdr_b, const uint8_t *ldr_a, const uint8_t *ldr_b,
                                 uint32_t w, uint32_t h, double threshold_8bit, pg_image_error *out, pg_error *err);

/* PG_OK when (wa, ha) == (wb, hb); otherwise PG_ERR_INVALID_ARG with a message naming both sizes,
 * prefixed by what (e.g. "HDR output"). */
pg_result pg_image_sizes_match(const char *what, uint32_t wa, uint32_t ha, uint32_t wb, uint32_t hb, pg_error *err);

/* The heatmap colormap, passgraph's own: a dark-to-light ramp built in OKLab (lightness rising
 * linearly from 0.14 to 0.97, hue turning purple -> red -> orange -> yellow, chroma reduced to stay
 * inside sRGB), so perceived lightness rises monotonically with t. t is clamped to [0, 1]
 * (NaN -> 0). Writes sRGB-encoded 8-bit R, G, B. */
void pg_colormap(double t, uint8_t rgb[3]);

/* Colour a heatmap gives pixels whose error is not finite (NaN/Inf in either HDR): pure cyan,
 * which the colormap never produces. */
#define PG_HEATMAP_NONFINITE_R 0
#define PG_HEATMAP_NONFINITE_G 255
#define PG_HEATMAP_NONFINITE_B 255

/* Heatmap of the per-pixel error max over RGB of |a - b| (linear HDR), mapped with pg_colormap over
 * [0, scale]; errors above scale saturate. scale <= 0 (or not finite): the largest finite error
 * (1e-30 if every error is 0). out_rgba: w*h*4 bytes (caller-allocated), alpha 255. */
void pg_error_heatmap(const float *hdr_a, const float *hdr_b, uint32_t w, uint32_t h, double scale, uint8_t *out_rgba);
/* The q-quantile (q in [0, 1]) of the per-pixel errors (max over RGB of |a - b|) of the pixels that
 * differ (error > 0, finite), to within 1% (log-spaced histogram); 0 when no pixel differs. A
 * heatmap scale that a few extreme pixels do not wash out: HDR errors are heavy-tailed. */
double pg_error_quantile(const float *hdr_a, const float *hdr_b, uint32_t w, uint32_t h, double q);
/* The scale pg_error_heatmap uses for a given scale argument (for reporting). */
double pg_error_heatmap_scale(const float *hdr_a, const float *hdr_b, uint32_t w, uint32_t h, double scale);

#ifdef __cplusplus
}
#endif
#endif
