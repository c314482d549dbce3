/* fuzz_hdr.c - libFuzzer target for pg_environment_load (scene/environment.c: the Radiance HDR
 * header and row checks, stb_image's decoder, image/exr.c's OpenEXR reader, the levels, the
 * clamping, the sampling tables).
 *
 * Each input is written to a private temporary directory as input.exr when it starts with
 * OpenEXR's magic number (76 2f 31 01), else as input.hdr, and loaded from there.
 * Invariants checked on an environment that loads (abort = a finding): 2:1 within a texel, at least
 * 8 x 4, levels halving down to 1 texel wide or tall inside n_texels; every texel finite, >= 0 and
 * <= PG_ENV_MAX_VALUE with alpha 1; the mean radiance finite; the sampling tables (when present)
 * non-decreasing from 0 to 1. On failure: result code in range, err.code equal, a non-empty message
 * naming the file. ASan/UBSan/LSan catch the rest. */
#include "environment.h"

#include <math.h>
#include <stdbool.h>
#include <stdint.h>

#include "fuzz_common.h"

static char g_hdr[512], g_exr[512];

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    const char *dir = fuzz_dir("hdr");
    snprintf(g_hdr, sizeof g_hdr, "%s/input.hdr", dir);
    snprintf(g_exr, sizeof g_exr, "%s/input.exr", dir);
    return 0;
}

static void check_cdf(const float *c, uint64_t n, const char *what)
{
    if (c[0] != 0.0f || c[n] != 1.0f) fuzz_die("%s: runs from %g to %g", what, c[0], c[n]);
    for (uint64_t i = 0; i < n; i++)
        if (!(c[i + 1] >= c[i])) fuzz_die("%s: decreases at %llu", what, (unsigned long long)i);
}

static void check_env(const pg_environment *e)
{
    const uint32_t w = e->width[0], h = e->height[0];
    if (w < 8 || h < 4 || w > PG_ENV_MAX_WIDTH || (w > 2 * h ? w - 2 * h : 2 * h - w) > 1)
        fuzz_die("level 0 is %u x %u", w, h);
    uint64_t off = 0;
    for (uint32_t k = 0; k < e->n_levels; k++) {
        if (e->offset[k] != off) fuzz_die("level %u at %llu, expected %llu", k, (unsigned long long)e->offset[k],
                                          (unsigned long long)off);
        off += (uint64_t)e->width[k] * e->height[k];
    }
    if (off != e->n_texels || e->n_levels < 1 || (e->width[e->n_levels - 1] > 1 && e->height[e->n_levels - 1] > 1))
        fuzz_die("%u levels, %llu texels", e->n_levels, (unsigned long long)e->n_texels);
    for (uint64_t i = 0; i < e->n_texels; i++)
        for (int c = 0; c < 4; c++) {
            float v = e->rgba[4 * i + c];
            if (!(v >= 0.0f) || v > (c == 3 ? 1.0f : PG_ENV_MAX_VALUE) || (c == 3 && v != 1.0f))
                fuzz_die("texel %llu channel %d is %g", (unsigned long long)i, c, v);
        }
    for (int c = 0; c < 3; c++)
        if (!isfinite(e->mean_radiance[c])) fuzz_die("mean radiance %g", e->mean_radiance[c]);
    if (e->cdf) {
        check_cdf(e->cdf, h, "marginal");
        for (uint32_t j = 0; j < h; j++) check_cdf(e->cdf + h + 1 + (uint64_t)j * (w + 1), w, "row");
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const uint8_t exr_magic[4] = {0x76, 0x2f, 0x31, 0x01};
    const bool exr = size >= 4 && memcmp(data, exr_magic, 4) == 0;
    const char *g_path = exr ? g_exr : g_hdr;
    fuzz_write(g_path, data, size);
    pg_environment *e = (pg_environment *)g_path; /* any non-NULL value: must be reset */
    pg_error err = {0};
    pg_result r = pg_environment_load(g_path, &e, &err);
    if ((int)r < 0 || r >= PG_ERR_COUNT) fuzz_die("result %d out of range", (int)r);
    if ((r == PG_OK) != (e != NULL)) fuzz_die("result %s, environment %p", pg_result_name(r), (void *)e);
    if (r != PG_OK) {
        if (!memchr(err.msg, 0, sizeof err.msg)) fuzz_die("message not terminated");
        if (err.code != r || !err.msg[0] || !strstr(err.msg, exr ? "input.exr" : "input.hdr"))
            fuzz_die("returned %s, err.code %s, message '%s'", pg_result_name(r), pg_result_name(err.code), err.msg);
    } else {
        check_env(e);
    }
    pg_environment_free(e);
    unlink(g_path);
    return 0;
}
