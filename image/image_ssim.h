/* image_ssim.h - SSIM (Wang, Bovik, Sheikh, Simoncelli, "Image Quality Assessment: From Error
 * Visibility to Structural Similarity", IEEE TIP 2004) of two display images; pure CPU, no Vulkan.
 *
 * - Computed on one channel: Y = 0.2126 R + 0.7152 G + 0.0722 B of the sRGB-ENCODED 8-bit values
 *   (no decoding; range 0..255). Alpha is ignored.
 * - Local statistics (means, variances, covariance) over an 11x11 Gaussian window, sigma 1.5,
 *   weights normalised to sum 1, applied as two separable passes.
 * - SSIM = (2 mx my + C1)(2 sxy + C2) / ((mx^2 + my^2 + C1)(sx^2 + sy^2 + C2)),
 *   C1 = (K1 L)^2, C2 = (K2 L)^2, K1 = 0.01, K2 = 0.03, L = 255.
 * - The mean is over the pixels where the whole window fits inside the image ("valid" region:
 *   (w - 10) x (h - 10) pixels, as the paper's reference code): no border handling. Images narrower
 *   or lower than 11 pixels are refused (PG_ERR_INVALID_ARG).
 * SSIM is symmetric in a and b, at most 1, and 1 for identical images.
 */
#ifndef PG_IMAGE_SSIM_H
#define PG_IMAGE_SSIM_H

#include "pg_common.h"

#ifdef __cplusplus
extern "C" {
#endif

#define PG_SSIM_WINDOW 11 /* the window's side; the smallest image side SSIM accepts */

/* Mean SSIM of two w*h RGBA8 images (see above) into *mean_out. PG_ERR_INVALID_ARG for a NULL
 * image or output, or a side < PG_SSIM_WINDOW; PG_ERR_OOM when memory runs out. */
pg_result pg_ssim(const uint8_t *a_rgba8, const uint8_t *b_rgba8, uint32_t w, uint32_t h, double *mean_out,
                  pg_error *err);

#ifdef __cplusplus
}
#endif
#endif
