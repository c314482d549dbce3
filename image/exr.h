/* exr.h - OpenEXR files for linear HDR images, through OpenEXRCore's C API (Debian
 * libopenexr-dev 3.1, <openexr.h>).
 *
 * Images are w x h RGBA, 4 interleaved floats a pixel, row 0 at the top (the EXR data window
 * (0,0)-(w-1,h-1), INCREASING_Y). Written as one scanline part with channels R, G, B, A, ZIP
 * compression (lossless), as 16-bit half or 32-bit float. Errors name the file and OpenEXR's
 * reason; a half-written file is not left behind (OpenEXR writes to a temporary file and renames
 * it on success).
 */
#ifndef PG_EXR_H
#define PG_EXR_H

#include "pg_common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* half: store 16-bit half floats (values beyond +-65504 become +-inf, as in any half image);
 * else 32-bit floats (exact). */
pg_result pg_exr_write_rgba(const char *path, const float *rgba, uint32_t w, uint32_t h, bool half,
                            pg_error *err);
/* Reads the first part of a scanline EXR with R, G, B (and optionally A: else 1) channels of any
 * pixel type into *rgba (malloc'd, w*h*4 floats; free() it). The data window's origin becomes
 * pixel (0,0). */
pg_result pg_exr_read_rgba(const char *path, float **rgba, uint32_t *w, uint32_t *h, pg_error *err);
/* The same, refusing an image wider or taller than max_side (PG_ERR_LIMIT) from its header,
 * before its pixels are allocated (a small compressed file may announce 65536 x 32768: 32 GiB) */
pg_result pg_exr_read_rgba_within(const char *path, uint32_t max_side, float **rgba, uint32_t *w, uint32_t *h,
                                  pg_error *err);

/* IEEE half <-> float (round to nearest even; overflow to inf; NaN stays NaN). */
uint16_t pg_float_to_half(float f);

#ifdef __cplusplus
}
#endif
#endif
