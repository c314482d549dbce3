/* image_util.h - read-back pixel helpers: half floats, non-finite counts, PNG output, image
 * statistics used by the tests and the render summary. */
#ifndef PG_IMAGE_UTIL_H
#define PG_IMAGE_UTIL_H

#include "pg_common.h"

#ifdef __cplusplus
extern "C" {
#endif

float pg_half_to_float(uint16_t h);
/* Converts w*h pixels of an rgba16f / rgba32f image to rgba32f (out has w*h*4 floats). */
pg_result pg_hdr_to_float(const void *pixels, pg_format fmt, uint32_t w, uint32_t h, float *out, pg_error *err);
/* Pixels with any NaN or Inf channel among the RGB channels. */
uint64_t pg_count_nonfinite(const float *rgba, uint32_t w, uint32_t h);
pg_result pg_write_png(const char *path, const uint8_t *rgba, uint32_t w, uint32_t h, pg_error *err);

/* 8-bit image files by extension (case-insensitive): .png -> PNG, .jpg/.jpeg -> JPEG (stb,
 * quality 95, alpha dropped), .exr -> OpenEXR (written by core/image/exr.c, not pg_write_image). */
typedef enum pg_image_kind { PG_IMAGE_UNKNOWN = 0, PG_IMAGE_PNG, PG_IMAGE_JPEG, PG_IMAGE_EXR } pg_image_kind;
pg_image_kind pg_image_kind_of(const char *path);
/* PG_OK for .png/.jpg/.jpeg (and .exr when allow_exr); else PG_ERR_INVALID_ARG naming the path,
 * the extension and the accepted ones: "x.bmp: unsupported image extension '.bmp' (accepted:
 * .png, .jpg, .jpeg)", "x: no file extension (accepted: ...)". */
pg_result pg_image_path_check(const char *path, bool allow_exr, pg_error *err);
/* Writes a PNG or a JPEG by the extension (refused as pg_image_path_check(path, false)). */
pg_result pg_write_image(const char *path, const uint8_t *rgba, uint32_t w, uint32_t h, pg_error *err);

typedef struct pg_image_stats {
    double mean_luma;        /* 0..255 for 8-bit */
    double lit_fraction;     /* pixels with luma > 8/255 */
    uint32_t distinct_colors_sampled; /* distinct RGB values among a 64x64 sample grid */
} pg_image_stats;
pg_image_stats pg_rgba8_stats(const uint8_t *rgba, uint32_t w, uint32_t h);

#ifdef __cplusplus
}
#endif
#endif
