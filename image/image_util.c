#include "image_util.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <stb_image_write.h>

float pg_half_to_float(uint16_t h)
{
    uint32_t sign = (uint32_t)(h >> 15) << 31;
    uint32_t exp = (h >> 10) & 0x1f;
    uint32_t mant = h & 0x3ff;
    uint32_t bits;
    if (exp == 0) {
        if (mant == 0) {
            bits = sign;
        } else { /* subnormal */
            float f = ldexpf((float)mant, -24);
            return sign ? -f : f;
        }
    } else if (exp == 31) {
        bits = sign | 0x7f800000u | (mant << 13);
    } else {
        bits = sign | ((exp + 112) << 23) | (mant << 13);
    }
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

pg_result pg_hdr_to_float(const void *pixels, pg_format fmt, uint32_t w, uint32_t h, float *out, pg_error *err)
{
    size_t n = (size_t)w * h * 4;
    if (fmt == PG_FMT_RGBA32F) {
        memcpy(out, pixels, n * sizeof(float));
    } else if (fmt == PG_FMT_RGBA16F) {
        const uint16_t *p = pixels;
        for (size_t i = 0; i < n; i++) out[i] = pg_half_to_float(p[i]);
    } else {
        return pg_fail(err, PG_ERR_FORMAT, "HDR read-back supports rgba16f and rgba32f, not %s",
                       pg_format_get(fmt)->name);
    }
    return PG_OK;
}

uint64_t pg_count_nonfinite(const float *rgba, uint32_t w, uint32_t h)
{
    uint64_t bad = 0;
    for (size_t i = 0; i < (size_t)w * h; i++)
        if (!isfinite(rgba[i * 4]) || !isfinite(rgba[i * 4 + 1]) || !isfinite(rgba[i * 4 + 2])) bad++;
    return bad;
}

/* stb's encoder writes through this: the first failed fwrite's errno is kept (stbi_write_png and
 * stbi_write_jpg ignore write and close errors, so a full disk gave a truncated file and success) */
typedef struct image_sink {
    FILE *f;
    int error; /* errno of the first failed write, 0 while none */
} image_sink;

static void sink_write(void *ctx, void *data, int size)
{
    image_sink *s = ctx;
    if (s->error || size <= 0) return;
    errno = 0;
    if (fwrite(data, 1, (size_t)size, s->f) != (size_t)size) s->error = errno ? errno : EIO;
}

/* kind: "PNG" or "JPEG" */
static pg_result write_encoded(const char *path, const char *kind, const uint8_t *rgba, uint32_t w, uint32_t h,
                               pg_error *err)
{
    if (w == 0 || h == 0 || w > 0x7fffffffu / 4 || h > 0x7fffffffu)
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s: cannot write a %ux%u %s", path, w, h, kind);
    image_sink s = {fopen(path, "wb"), 0};
    if (!s.f) return pg_fail(err, PG_ERR_IO, "%s: cannot write %s: %s", path, kind, strerror(errno));
    const int ok = kind[0] == 'P' ? stbi_write_png_to_func(sink_write, &s, (int)w, (int)h, 4, rgba, (int)(w * 4))
                                  : stbi_write_jpg_to_func(sink_write, &s, (int)w, (int)h, 4, rgba, 95);
    errno = 0;
    if (fflush(s.f) != 0 && !s.error) s.error = errno ? errno : EIO;
    if (fclose(s.f) != 0 && !s.error) s.error = errno ? errno : EIO;
    if (s.error) return pg_fail(err, PG_ERR_IO, "%s: cannot write %s: %s", path, kind, strerror(s.error));
    if (!ok) return pg_fail(err, PG_ERR_IO, "%s: cannot write %s: the encoder failed (out of memory?)", path, kind);
    return PG_OK;
}

pg_result pg_write_png(const char *path, const uint8_t *rgba, uint32_t w, uint32_t h, pg_error *err)
{
    return write_encoded(path, "PNG", rgba, w, h, err);
}

pg_image_kind pg_image_kind_of(const char *path)
{
    const char *dot = strrchr(path, '.');
    const char *slash = strrchr(path, '/');
    if (!dot || (slash && dot < slash)) return PG_IMAGE_UNKNOWN;
    if (!strcasecmp(dot, ".png")) return PG_IMAGE_PNG;
    if (!strcasecmp(dot, ".jpg") || !strcasecmp(dot, ".jpeg")) return PG_IMAGE_JPEG;
    if (!strcasecmp(dot, ".exr")) return PG_IMAGE_EXR;
    return PG_IMAGE_UNKNOWN;
}

pg_result pg_image_path_check(const char *path, bool allow_exr, pg_error *err)
{
    pg_image_kind k = pg_image_kind_of(path);
    if (k == PG_IMAGE_PNG || k == PG_IMAGE_JPEG || (k == PG_IMAGE_EXR && allow_exr)) return PG_OK;
    const char *dot = strrchr(path, '.');
    const char *slash = strrchr(path, '/');
    const char *accepted = allow_exr ? ".png, .jpg, .jpeg, .exr" : ".png, .jpg, .jpeg";
    if (!dot || (slash && dot < slash))
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s: no file extension (accepted: %s)", path, accepted);
    return pg_fail(err, PG_ERR_INVALID_ARG, "%s: unsupported image extension '%s' (accepted: %s)", path, dot,
                   accepted);
}

pg_result pg_write_image(const char *path, const uint8_t *rgba, uint32_t w, uint32_t h, pg_error *err)
{
    pg_result r = pg_image_path_check(path, false, err);
    if (r) return r;
    if (pg_image_kind_of(path) == PG_IMAGE_JPEG) {
        /* JPEG has no alpha: the RGB channels, quality 95 */
        return write_encoded(path, "JPEG", rgba, w, h, err);
    }
    return pg_write_png(path, rgba, w, h, err);
}

pg_image_stats pg_rgba8_stats(const uint8_t *rgba, uint32_t w, uint32_t h)
{
    pg_image_stats s = {0};
    double sum = 0;
    uint64_t lit = 0;
    for (size_t i = 0; i < (size_t)w * h; i++) {
        const uint8_t *p = rgba + i * 4;
        double l = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
        sum += l;
        if (l > 8.0) lit++;
    }
    size_t n = (size_t)w * h;
    s.mean_luma = n ? sum / n : 0;
    s.lit_fraction = n ? (double)lit / n : 0;
    uint32_t seen[4096];
    uint32_t n_seen = 0;
    for (uint32_t y = 0; y < 64; y++)
        for (uint32_t x = 0; x < 64; x++) {
            uint32_t px = (uint32_t)((x + 0.5) * w / 64), py = (uint32_t)((y + 0.5) * h / 64);
            const uint8_t *p = rgba + ((size_t)py * w + px) * 4;
            uint32_t c = (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2];
            bool found = false;
            for (uint32_t k = 0; k < n_seen && !found; k++) found = seen[k] == c;
            if (!found && n_seen < 4096) seen[n_seen++] = c;
        }
    s.distinct_colors_sampled = n_seen;
    return s;
}
