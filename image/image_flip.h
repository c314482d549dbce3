/* image_flip.h - the FLIP perceptual image difference (pure CPU, no Vulkan), written from the papers:
 *   LDR-FLIP: Andersson, Nilsson, Akenine-Moller, Oskarsson, Astrom, Fairchild, "FLIP: A Difference
 *             Evaluator for Alternating Images", HPG 2020;
 *   HDR-FLIP: Andersson, Nilsson, Shirley, Akenine-Moller, "Visualizing Errors in Rendered High
 *             Dynamic Range Images", Eurographics 2021 (short paper),
 * with NVlabs/flip's Python version read (not copied) for the details the papers leave open.
 *
 * LDR-FLIP, per pixel, for a test and a reference image viewed at ppd pixels per degree:
 * - sRGB -> linear RGB -> XYZ (sRGB primaries, D65 white = XYZ of linear (1,1,1)) -> YCxCz
 *   (Y = 116 Y/Yn - 16, Cx = 500 (X/Xn - Y/Yn), Cz = 200 (Y/Yn - Z/Zn)).
 * - Colour: each YCxCz channel is filtered with its contrast sensitivity function, a sum of Gaussians
 *   s(r) = a1 sqrt(pi/b1) exp(-pi^2 r^2/b1) + a2 sqrt(pi/b2) exp(-pi^2 r^2/b2), r in degrees:
 *   achromatic (a1, b1) = (1, 0.0047); red-green (1, 0.0053); blue-yellow (34.1, 0.04) + (13.5, 0.025).
 *   Kernel radius ceil(3 sqrt(0.04 / (2 pi^2)) ppd) pixels (10 at the default ppd), weights
 *   normalised to sum 1, image borders replicated. Each Gaussian is separable, so the 2D kernels are
 *   applied as row and column passes (exactly the same sums, in another order). The filtered image
 *   goes back to linear RGB, is clamped to [0, 1], then to CIELAB, Hunt-adjusted (a* and b* scaled by
 *   0.01 L*), and the two images' HyAB distance |dL| + sqrt(da^2 + db^2) is raised to qc = 0.7.
 *   Redistribution with cmax = HyAB(pure green, pure blue)^qc (Hunt-adjusted, linear (0,1,0) vs
 *   (0,0,1): the largest colour error, which maps to 1), pc = 0.4, pt = 0.95: e < pc cmax maps to
 *   (pt / (pc cmax)) e, otherwise pt + (e - pc cmax) / (cmax - pc cmax) (1 - pt); clamped to <= 1.
 * - Features on the unfiltered achromatic channel Y/Yn in [0, 1]: Gaussian sigma = 0.5 * 0.082 * ppd
 *   pixels, radius ceil(3 sigma); edge kernel -x g, point kernel (x^2/sigma^2 - 1) g, each with its
 *   positive weights normalised to sum 1 and its negative weights to -1, applied by pairs of taps
 *   (k_j (s_j - s_-j) for the edge, k_j ((s_j - s_0) + (s_-j - s_0)) for the point) so that a flat
 *   region gives exactly 0 in float too; edge (point) strength =
 *   the length of the (x, y) responses. Feature error f = (max(|dedge|, |dpoint|) / sqrt(2))^qf, qf = 0.5.
 * - FLIP = colour_error^(1 - f), in [0, 1].
 *
 * HDR-FLIP: the reference's luminance (0.2126 R + 0.7152 G + 0.0722 B) gives the exposures, with
 * the ACES fit of Narkowicz (as HDR-FLIP uses it, the 0.6 pre-scale folded in: t(x) = (0.9036 x^2 +
 * 0.018 x) / (0.8748 x^2 + 0.354 x + 0.14)): x85 solves t(x) = 0.85 (x85 = 2.1189...), start =
 * log2(x85 / Y_max), stop = log2(x85 / Y_median) (the median of an even count is the mean of the two
 * middle values); exposures = max(2, ceil(stop - start)), evenly spaced from start to stop. At each
 * exposure c both images are scaled by 2^c, tone mapped, clamped to [0, 1] and compared with LDR-FLIP
 * as linear display images (the sRGB encoding and decoding the paper's pipeline passes through
 * cancel; there is no 8-bit rounding in between). The HDR-FLIP map is the per-pixel maximum.
 * Special cases: negative values are taken as 0 (as the tone mapper clips them); a pixel with a NaN
 * or Inf in R, G or B is taken as black and counted (pg_flip_hdr_stats); a reference whose largest
 * luminance is 0 gives start = stop = 0; a reference whose median luminance is 0 (more than half of
 * it black) uses the median of its positive luminances for the stop exposure (the papers' formula
 * would give +inf; this is passgraph's choice).
 *
 * Published anchors this implementation checks (tests/unit/test_image_metrics.c): the green/blue
 * normalisation (flat pure green vs flat pure blue gives 1), the constants above, identical images
 * give 0. tests/oracle/ (metrics_oracle) compares every pixel with an independent numpy
 * implementation of these papers and conventions (docs/accuracy.md states the agreement). NVlabs/flip
 * also publishes results for its example images (HDR: start -12.5423, stop 0.9427, 14 exposures,
 * mean 0.283478); those images are not available here, so those values are NOT checked.
 */
#ifndef PG_IMAGE_FLIP_H
#define PG_IMAGE_FLIP_H

#include "pg_common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The default observer: 0.7 m from a 0.7 m wide monitor of 3840 pixels: 3840 * pi / 180 ppd. */
#define PG_FLIP_DEFAULT_PPD 67.02064327658226

typedef struct pg_flip_opts {
    double ppd; /* pixels per degree of visual angle; <= 0 (or not finite): PG_FLIP_DEFAULT_PPD */
    uint32_t threads; /* 0: one per online CPU; at most 64, and one per 16 rows of the image. The map
                       * is the same bits for any count (each thread computes whole rows of each step) */
} pg_flip_opts;

/* LDR-FLIP of two w*h RGBA8 sRGB-encoded display images (alpha ignored). o may be NULL (defaults).
 * map_out: w*h floats in [0, 1] (row-major), may be NULL; mean_out: the mean over all pixels, may be
 * NULL. PG_ERR_INVALID_ARG for a NULL image or a zero size, PG_ERR_OOM when memory runs out. */
pg_result pg_flip_ldr(const uint8_t *test_rgba8, const uint8_t *ref_rgba8, uint32_t w, uint32_t h,
                      const pg_flip_opts *o, float *map_out, double *mean_out, pg_error *err);

typedef struct pg_flip_hdr_stats {
    double mean;                           /* mean of the HDR-FLIP map */
    double start_exposure, stop_exposure;  /* in stops (the images are scaled by 2^c) */
    uint32_t exposures;                    /* LDR-FLIP evaluations, >= 2 */
    uint64_t nonfinite_test, nonfinite_ref; /* pixels with a NaN/Inf in R, G or B (taken as black) */
} pg_flip_hdr_stats;

/* HDR-FLIP of two w*h RGBA32F scene-linear images (alpha ignored); the exposures come from the
 * reference. o may be NULL; map_out: w*h floats in [0, 1], may be NULL; stats may be NULL. Errors
 * as pg_flip_ldr. Costs about `exposures` LDR-FLIP evaluations. */
pg_result pg_flip_hdr(const float *test_rgba32f, const float *ref_rgba32f, uint32_t w, uint32_t h,
                      const pg_flip_opts *o, float *map_out, pg_flip_hdr_stats *stats, pg_error *err);

/* A FLIP map is shown with passgraph's own colormap (pg_colormap, image_compare.h) over [0, 1]. */

#ifdef __cplusplus
}
#endif
#endif
