/* test_environment.c - the environment light on the CPU (no GPU):
 *   1. scene/environment.c: Radiance HDR files written here (flat, tests/harness/hdr_file.c, and
 *      run-length encoded, stb_image_write) read back exactly; the mip chain (sizes, the box
 *      filter); the solid-angle mean; ids; clamping; every refused file with its code and message;
 *      the default sky (finite, positive, mean = level, brighter up than down);
 *   2. directions: dir <-> uv, the axes of environment.h, bilinear sampling at texel centres, the
 *      rotation's sign;
 *   3. renderer/common/env_integral.c: uniform and half-bright environments with known answers,
 *      the pbr integral against a brute-force quadrature of pg_brdf_pbr, the white furnace, the
 *      split-sum terms (pg_env_brdf_lut) against the furnace.
 * Prints the measured numbers next to their bounds. Runs in well under a second. */
#include "brdf.h"
#include "env_integral.h"
#include "environment_layout.h"
#include "environment.h"
#include "hdr_file.h"
#include "scene_features.h"
#include "test_util.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <stb_image_write.h>

#define PI 3.14159265358979323846

static char g_dir[64];

static const char *tmp_path(const char *name)
{
    static char p[4][256];
    static int k;
    k = (k + 1) % 4;
    snprintf(p[k], sizeof p[k], "%s/%s", g_dir, name);
    return p[k];
}

static int rel_close(double a, double b, double rel)
{
    return fabs(a - b) <= rel * fmax(fabs(a), fabs(b));
}

/* the RGBE-exact test image: multiples of 1/64 up to 200/64 (exact, hdr_file.h) */
static float test_value(uint32_t i, uint32_t j, int c)
{
    return (float)(1 + (i * 7 + j * 13 + (uint32_t)c * 5) % 200) / 64.0f;
}

static float *test_image(uint32_t w, uint32_t h)
{
    float *rgb = malloc(sizeof(float) * 3 * w * h);
    for (uint32_t j = 0; j < h; j++)
        for (uint32_t i = 0; i < w; i++)
            for (int c = 0; c < 3; c++) rgb[3 * (j * w + i) + c] = test_value(i, j, c);
    return rgb;
}

static pg_environment *load_ok(const char *path)
{
    pg_environment *env = NULL;
    pg_error err = {0};
    pg_result r = pg_environment_load(path, &env, &err);
    CHECK_MSG(r == PG_OK && env, "%s: %s", path, err.msg);
    return r == PG_OK ? env : NULL;
}

static const float *texel(const pg_environment *e, uint32_t k, uint32_t i, uint32_t j)
{
    return e->rgba + 4 * (e->offset[k] + (uint64_t)j * e->width[k] + i);
}

/* ------------------------------------------------------------------------------------------ */
/* 1. files                                                                                   */

static void check_levels_64(const pg_environment *e)
{
    static const uint32_t W[] = {64, 32, 16, 8, 4, 2}, H[] = {32, 16, 8, 4, 2, 1};
    CHECK(e->n_levels == 6);
    uint64_t off = 0;
    for (uint32_t k = 0; k < 6 && k < e->n_levels; k++) {
        CHECK(e->width[k] == W[k] && e->height[k] == H[k] && e->offset[k] == off);
        off += (uint64_t)W[k] * H[k];
    }
    CHECK(e->n_texels == 2730 && off == 2730);
    /* level 1: the average of its 4 sources; level 5 (2 x 1): of the 32 x 32 level-0 half */
    int bad1 = 0, bad5 = 0, alpha = 0;
    for (uint32_t j = 0; j < 16; j++)
        for (uint32_t i = 0; i < 32; i++)
            for (int c = 0; c < 3; c++) {
                double s = (double)texel(e, 0, 2 * i, 2 * j)[c] + texel(e, 0, 2 * i + 1, 2 * j)[c] +
                           texel(e, 0, 2 * i, 2 * j + 1)[c] + texel(e, 0, 2 * i + 1, 2 * j + 1)[c];
                bad1 += !rel_close(texel(e, 1, i, j)[c], s / 4, 1e-6);
            }
    for (uint32_t half = 0; half < 2; half++)
        for (int c = 0; c < 3; c++) {
            double s = 0;
            for (uint32_t j = 0; j < 32; j++)
                for (uint32_t i = 0; i < 32; i++) s += texel(e, 0, 32 * half + i, j)[c];
            bad5 += !rel_close(texel(e, 5, half, 0)[c], s / 1024, 1e-5);
        }
    for (uint64_t t = 0; t < e->n_texels; t++) alpha += e->rgba[4 * t + 3] != 1.0f;
    CHECK_MSG(bad1 == 0 && bad5 == 0 && alpha == 0, "level-1 mismatches %d, level-5 %d, alpha != 1: %d", bad1,
              bad5, alpha);
}

static void test_load_exact(void)
{
    const uint32_t w = 64, h = 32;
    float *rgb = test_image(w, h);
    int inexact = 0;
    for (uint32_t t = 0; t < w * h; t++) {
        float q[3];
        pg_test_rgbe_round(rgb + 3 * t, q);
        inexact += memcmp(q, rgb + 3 * t, sizeof q) != 0;
    }
    CHECK_MSG(inexact == 0, "%d test values are not RGBE-exact", inexact);
    const char *path = tmp_path("exact.hdr");
    CHECK(pg_test_write_hdr(path, w, h, rgb) == 0);
    pg_environment *e = load_ok(path);
    if (e) {
        int diff = 0;
        float mx = 0;
        for (uint32_t j = 0; j < h; j++)
            for (uint32_t i = 0; i < w; i++)
                for (int c = 0; c < 3; c++) {
                    diff += texel(e, 0, i, j)[c] != rgb[3 * (j * w + i) + c];
                    mx = fmaxf(mx, rgb[3 * (j * w + i) + c]);
                }
        CHECK_MSG(diff == 0, "%d level-0 components differ from the file", diff);
        CHECK(strcmp(e->source, path) == 0 && e->clamped == 0 && e->max_value == mx && e->id > 0);
        check_levels_64(e);
    }
    pg_environment_free(e);
    free(rgb);
}

/* the run-length encoded twin (stb_image_write writes RLE scanlines for widths 8..32767) */
static void test_load_rle(void)
{
    const uint32_t w = 64, h = 32;
    float *rgb = test_image(w, h);
    const char *path = tmp_path("rle.hdr");
    CHECK(stbi_write_hdr(path, (int)w, (int)h, 3, rgb) != 0);
    pg_environment *e = load_ok(path);
    int diff = 0;
    for (uint32_t t = 0; e && t < w * h; t++)
        for (int c = 0; c < 3; c++) diff += e->rgba[4 * t + c] != rgb[3 * t + c];
    CHECK_MSG(e && diff == 0, "RLE file: %d components differ", diff);
    pg_environment_free(e);
    free(rgb);
}

static void test_uniform_and_ids(void)
{
    const uint32_t w = 64, h = 32;
    float *rgb = malloc(sizeof(float) * 3 * w * h);
    for (uint32_t t = 0; t < 3 * w * h; t++) rgb[t] = 0.75f;
    const char *path = tmp_path("uniform.hdr");
    CHECK(pg_test_write_hdr(path, w, h, rgb) == 0);
    pg_environment *a = load_ok(path), *b = load_ok(path);
    if (a && b) {
        double worst = 0;
        for (int c = 0; c < 3; c++) worst = fmax(worst, fabs(a->mean_radiance[c] - 0.75) / 0.75);
        printf("  uniform 0.75 file: mean radiance relative error %.2e (bound 1e-12)\n", worst);
        CHECK(worst <= 1e-12);
        CHECK(a->id > 0 && b->id > 0 && a->id != b->id);
    }
    pg_environment_free(a);
    pg_environment_free(b);
    free(rgb);
}

static void test_clamping(void)
{
    const uint32_t w = 16, h = 8;
    float *rgb = malloc(sizeof(float) * 3 * w * h);
    for (uint32_t t = 0; t < 3 * w * h; t++) rgb[t] = 1.0f;
    rgb[3 * 37] = 1e10f; /* (1e10, 0, 0): with 1e10's exponent, a 1 beside it would read 0 */
    rgb[3 * 37 + 1] = rgb[3 * 37 + 2] = 0;
    const char *path = tmp_path("huge.hdr");
    CHECK(pg_test_write_hdr(path, w, h, rgb) == 0);
    pg_environment *e = load_ok(path);
    if (e) {
        CHECK_MSG(e->clamped == 1, "clamped %llu (1 expected)", (unsigned long long)e->clamped);
        CHECK(e->rgba[4 * 37] == PG_ENV_MAX_VALUE && e->rgba[4 * 37 + 1] == 0 && e->rgba[4 * 38] == 1.0f && e->max_value == PG_ENV_MAX_VALUE);
    }
    pg_environment_free(e);
    /* from pixels: NaN, infinity, negative -> 0; counted */
    float *px = calloc(4 * w * h, sizeof(float));
    px[0] = NAN;
    px[5] = INFINITY;
    px[10] = -2.0f;
    px[12] = 7e4f;
    px[3] = 5.0f; /* alpha: ignored, not counted */
    pg_error err = {0};
    e = NULL;
    CHECK(pg_environment_from_pixels("pixels", w, h, px, &e, &err) == PG_OK && e);
    if (e) {
        CHECK(e->clamped == 4 && e->rgba[0] == 0 && e->rgba[5] == 0 && e->rgba[10] == 0 && e->rgba[3] == 1.0f);
        CHECK(e->rgba[12] == PG_ENV_MAX_VALUE && e->max_value == PG_ENV_MAX_VALUE);
    }
    pg_environment_free(e);
    free(px);
    free(rgb);
}

static void expect_fail(const char *path, pg_result code, const char *cause)
{
    pg_environment *e = (pg_environment *)1;
    pg_error err = {0};
    pg_result r = pg_environment_load(path, &e, &err);
    CHECK_MSG(r == code && e == NULL && strstr(err.msg, path) && strstr(err.msg, cause),
              "%s: got %s '%s', expected %s with '%s'", path, pg_result_name(r), err.msg, pg_result_name(code),
              cause);
    if (r == PG_OK) pg_environment_free(e);
}

/* a file of n bytes that begins as an HDR of w x h with `pixels` pixel bytes */
static const char *write_cut(const char *name, uint32_t w, uint32_t h, size_t pixels)
{
    char head[128];
    size_t hl = pg_test_hdr_header(head, sizeof head, w, h);
    unsigned char *b = calloc(hl + pixels + 1, 1);
    memcpy(b, head, hl);
    for (size_t i = 0; i < pixels; i += 4) b[hl + i + 3] = b[hl + i] = 128; /* (128, 0, 0, 128) */
    const char *path = tmp_path(name);
    CHECK(pg_test_write_bytes(path, b, hl + pixels) == 0);
    free(b);
    return path;
}

static const char *write_text(const char *name, const char *text)
{
    const char *path = tmp_path(name);
    CHECK(pg_test_write_bytes(path, text, strlen(text)) == 0);
    return path;
}

/* write_cut's flat file of (128, 0, 0, 128) texels (0.5, 0, 0) with extra header lines */
static const char *write_with_header(const char *name, const char *lines, uint32_t w, uint32_t h)
{
    char head[256];
    int hl = snprintf(head, sizeof head, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n%s\n-Y %u +X %u\n", lines, h, w);
    size_t pixels = (size_t)w * h * 4;
    unsigned char *b = calloc((size_t)hl + pixels, 1);
    memcpy(b, head, (size_t)hl);
    for (size_t i = 0; i < pixels; i += 4) b[(size_t)hl + i + 3] = b[(size_t)hl + i] = 128;
    const char *path = tmp_path(name);
    CHECK(pg_test_write_bytes(path, b, (size_t)hl + pixels) == 0);
    free(b);
    return path;
}

/* EXPOSURE= lines: the pixels hold radiance times their product (Radiance's format; ignored, an
 * environment saved with EXPOSURE=10 lit 10 times too bright); a bad value is refused */
static void test_exposure(void)
{
    pg_environment *e = load_ok(write_with_header("exposure.hdr", "EXPOSURE=2\nEXPOSURE= 0.5e1\n", 64, 32));
    CHECK_MSG(e && fabsf(e->rgba[0] - 0.05f) < 1e-7f && e->rgba[1] == 0.0f, "%g", e ? e->rgba[0] : -1.0);
    pg_environment_free(e);
    e = load_ok(write_with_header("exposure_1.hdr", "EXPOSURE=1.0\n", 64, 32));
    CHECK(e && e->rgba[0] == 0.5f);
    pg_environment_free(e);
    expect_fail(write_with_header("exposure_0.hdr", "EXPOSURE=0\n", 64, 32), PG_ERR_PARSE,
                "header line 'EXPOSURE=0': expected a finite number > 0");
    expect_fail(write_with_header("exposure_x.hdr", "EXPOSURE=bright\n", 64, 32), PG_ERR_PARSE,
                "header line 'EXPOSURE=bright'");
}

static void test_errors(void)
{
    expect_fail(tmp_path("missing.hdr"), PG_ERR_IO, "cannot open: No such file or directory");
    expect_fail(g_dir, PG_ERR_IO, "is a directory");
    expect_fail("/dev/null", PG_ERR_IO, "(expected a Radiance .hdr file (or an OpenEXR .exr))"); /* both are read */
    expect_fail(write_text("text.hdr", "hello, world\n"), PG_ERR_PARSE, "not a Radiance HDR file");
    expect_fail(write_text("crlf.hdr", "#?RADIANCE\r\nFORMAT=32-bit_rle_rgbe\r\n\r\n-Y 4 +X 8\r\n"), PG_ERR_PARSE,
                "a Radiance HDR header with CRLF line ends");
    expect_fail(write_cut("header_only.hdr", 64, 32, 0), PG_ERR_PARSE, "truncated");
    expect_fail(write_cut("half.hdr", 64, 32, 64 * 16 * 4), PG_ERR_PARSE, "truncated");
    expect_fail(write_cut("nearly.hdr", 64, 32, 64 * 32 * 4 - 1), PG_ERR_PARSE, "truncated");
    expect_fail(write_text("no_end.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n"), PG_ERR_PARSE, "truncated");
    expect_fail(write_text("xyze.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 4 +X 8\n"), PG_ERR_PARSE,
                "is not 32-bit_rle_rgbe");
    expect_fail(write_text("flip.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n+Y 4 +X 8\n"), PG_ERR_PARSE,
                "-Y HEIGHT +X WIDTH");
    expect_fail(write_text("huge.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1073741823 +X 2147483646\n"),
                PG_ERR_PARSE, "HEIGHT and WIDTH of at most 9 digits"); /* a number too long, not an orientation */
    expect_fail(write_cut("wide.hdr", 64, 16, 64 * 16 * 4), PG_ERR_INVALID_ARG,
                "64 x 16: an equirectangular environment is 2:1 (width = 2 x height)");
    expect_fail(write_cut("ratio.hdr", 300, 100, 300 * 100 * 4), PG_ERR_INVALID_ARG, "is 2:1");
    expect_fail(write_cut("small.hdr", 4, 2, 4 * 2 * 4), PG_ERR_LIMIT, "4 x 2: smaller than 8 x 4");
    expect_fail(write_cut("too_wide.hdr", 32768, 16384, 0), PG_ERR_LIMIT, "wider than 16384");
    /* 2:1 within one texel is accepted */
    pg_environment *e = load_ok(write_cut("odd.hdr", 65, 32, 65 * 32 * 4));
    CHECK(e && e->width[1] == 32 && e->height[1] == 16 && e->rgba[0] == 0.5f);
    pg_environment_free(e);
    /* a PNG renamed .hdr */
    unsigned char png[8 * 4 * 3];
    memset(png, 200, sizeof png);
    CHECK(stbi_write_png(tmp_path("image.hdr"), 8, 4, 3, png, 8 * 3) != 0);
    expect_fail(tmp_path("image.hdr"), PG_ERR_PARSE, "not a Radiance HDR file");
    /* a truncated run-length encoded file */
    float *rgb = test_image(64, 32);
    const char *rle = tmp_path("rle_cut.hdr");
    CHECK(stbi_write_hdr(rle, 64, 32, 3, rgb) != 0);
    free(rgb);
    FILE *f = fopen(rle, "rb+");
    long size = 0;
    if (f && fseek(f, 0, SEEK_END) == 0) size = ftell(f);
    if (f) fclose(f);
    CHECK(size > 1000 && truncate(rle, size / 2) == 0);
    expect_fail(rle, PG_ERR_PARSE, "truncated (the pixels end in row");
    /* from_pixels refuses the same sizes */
    pg_error err = {0};
    float px[4 * 16 * 4] = {0};
    CHECK(pg_environment_from_pixels("mine", 16, 4, px, &e, &err) == PG_ERR_INVALID_ARG && !e &&
          strstr(err.msg, "mine: 16 x 4"));
}

static void test_default_sky(void)
{
    static const float levels[] = {1.0f, 0.37f, 25.0f};
    for (int l = 0; l < 3; l++) {
        pg_environment *e = NULL;
        pg_error err = {0};
        CHECK_MSG(pg_environment_default(levels[l], &e, &err) == PG_OK && e, "%s", err.msg);
        if (!e) continue;
        CHECK(strcmp(e->source, "default") == 0 && e->width[0] == 256 && e->height[0] == 128 && e->n_levels == 8);
        CHECK(e->clamped == 0 && e->id > 0);
        int bad = 0;
        for (uint64_t t = 0; t < e->n_texels; t++)
            for (int c = 0; c < 3; c++) bad += !(isfinite(e->rgba[4 * t + c]) && e->rgba[4 * t + c] > 0);
        CHECK_MSG(bad == 0, "%d components not finite and positive", bad);
        double worst = 0, up[3], down[3], hz[3];
        for (int c = 0; c < 3; c++) worst = fmax(worst, fabs(e->mean_radiance[c] - levels[l]) / levels[l]);
        const double Y[3] = {0, 1, 0}, nY[3] = {0, -1, 0}, X[3] = {1, 0, 0};
        pg_environment_radiance(e, 0, Y, 0, 1, up);
        pg_environment_radiance(e, 0, nY, 0, 1, down);
        pg_environment_radiance(e, 0, X, 0, 1, hz);
        printf("  default sky level %g: mean (%.7g %.7g %.7g), relative error %.1e (bound 1e-6); zenith %.4g, "
               "horizon %.4g, nadir %.4g (green)\n",
               levels[l], e->mean_radiance[0], e->mean_radiance[1], e->mean_radiance[2], worst, up[1], hz[1], down[1]);
        CHECK(worst <= 1e-6);
        for (int c = 0; c < 3; c++) CHECK(up[c] > hz[c] && hz[c] > down[c] && down[c] > 0);
        pg_environment_free(e);
    }
    pg_environment *e = (pg_environment *)1;
    pg_error err = {0};
    CHECK(pg_environment_default(-1.0f, &e, &err) == PG_ERR_INVALID_ARG && !e);
    CHECK(pg_environment_default(NAN, &e, &err) == PG_ERR_INVALID_ARG && !e);
}

/* ------------------------------------------------------------------------------------------ */
/* 2. directions                                                                              */

static double rnd(uint64_t *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*s >> 11) * 0x1.0p-53;
}

static void rand_dir(uint64_t *s, double d[3])
{
    double z = 2 * rnd(s) - 1, phi = 2 * PI * rnd(s), r = sqrt(1 - z * z);
    d[0] = r * cos(phi);
    d[1] = r * sin(phi);
    d[2] = z;
}

static int near3(const double a[3], double x, double y, double z, double tol)
{
    return fabs(a[0] - x) <= tol && fabs(a[1] - y) <= tol && fabs(a[2] - z) <= tol;
}

static void test_directions(void)
{
    uint64_t s = 12345;
    double worst = 0, u, v, d[3], e[3];
    int out_of_range = 0;
    for (int n = 0; n < 200000; n++) {
        rand_dir(&s, d);
        pg_env_dir_to_uv(d, &u, &v);
        out_of_range += !(u >= 0 && u < 1 && v >= 0 && v <= 1);
        pg_env_uv_to_dir(u, v, e);
        for (int k = 0; k < 3; k++) worst = fmax(worst, fabs(e[k] - d[k]));
    }
    printf("  dir -> uv -> dir: worst %.1e (bound 1e-12) over 200000 directions\n", worst);
    CHECK(worst <= 1e-12 && out_of_range == 0);
    pg_env_uv_to_dir(0.5, 0.5, d);
    CHECK(near3(d, 0, 0, -1, 1e-15));
    pg_env_uv_to_dir(0.75, 0.5, d);
    CHECK(near3(d, 1, 0, 0, 1e-15));
    pg_env_uv_to_dir(0.25, 0.5, d);
    CHECK(near3(d, -1, 0, 0, 1e-15));
    pg_env_uv_to_dir(0.3, 0.0, d);
    CHECK(near3(d, 0, 1, 0, 1e-15));
    const double px[3] = {1, 0, 0}, pz[3] = {0, 0, 1}, ny[3] = {0, -1, 0};
    pg_env_dir_to_uv(px, &u, &v);
    CHECK(fabs(u - 0.75) < 1e-15 && fabs(v - 0.5) < 1e-15);
    pg_env_dir_to_uv(pz, &u, &v);
    CHECK(u == 0.0 && fabs(v - 0.5) < 1e-15); /* +Z: the seam, u = 0 (not 1) */
    pg_env_dir_to_uv(ny, &u, &v);
    CHECK(v == 1.0);
}

static void test_texel_centres(void)
{
    float *rgb = test_image(64, 32);
    const char *path = tmp_path("centres.hdr");
    CHECK(pg_test_write_hdr(path, 64, 32, rgb) == 0);
    free(rgb);
    pg_environment *e = load_ok(path);
    if (!e) return;
    double worst = 0;
    for (uint32_t k = 0; k < 3; k++)
        for (uint32_t j = 0; j < e->height[k]; j++)
            for (uint32_t i = 0; i < e->width[k]; i++) {
                double d[3], L[3];
                pg_env_uv_to_dir((i + 0.5) / e->width[k], (j + 0.5) / e->height[k], d);
                pg_environment_radiance(e, k, d, 0, 2.0, L);
                for (int c = 0; c < 3; c++) worst = fmax(worst, fabs(L[c] / (2.0 * texel(e, k, i, j)[c]) - 1));
            }
    printf("  radiance at texel centres (levels 0-2, intensity 2): worst relative %.1e (bound 1e-9)\n", worst);
    CHECK(worst <= 1e-9);
    pg_environment_free(e);
}

/* One bright texel at -Z (the image centre); rotation pi/2 shows it at Ry(pi/2)(-Z) = -X. */
static void test_rotation(void)
{
    const uint32_t w = 64, h = 32;
    float *px = calloc(4 * w * h, sizeof(float));
    for (uint32_t t = 0; t < w * h; t++) px[4 * t] = px[4 * t + 1] = px[4 * t + 2] = 0.01f;
    const uint32_t bi = 31, bj = 15; /* centre u = 31.5 / 64, v = 15.5 / 32: just off -Z */
    for (int c = 0; c < 3; c++) px[4 * (bj * w + bi) + c] = 100.0f;
    pg_environment *e = NULL;
    pg_error err = {0};
    CHECK(pg_environment_from_pixels("one texel", w, h, px, &e, &err) == PG_OK);
    free(px);
    if (!e) return;
    double d0[3], at[3], wrong[3], L[3], L0[3], Lw[3];
    pg_env_uv_to_dir((bi + 0.5) / w, (bj + 0.5) / h, d0);
    const double r = PI / 2; /* Ry(r) d: x' = x cos r + z sin r, z' = -x sin r + z cos r */
    at[0] = d0[0] * cos(r) + d0[2] * sin(r), at[1] = d0[1], at[2] = -d0[0] * sin(r) + d0[2] * cos(r);
    wrong[0] = d0[0] * cos(r) - d0[2] * sin(r), wrong[1] = d0[1], wrong[2] = d0[0] * sin(r) + d0[2] * cos(r);
    pg_environment_radiance(e, 0, at, r, 1, L);
    pg_environment_radiance(e, 0, d0, r, 1, L0);
    pg_environment_radiance(e, 0, wrong, r, 1, Lw);
    printf("  rotation pi/2: at Ry(r) d0 = (%.3f %.3f %.3f): %.4g; at d0: %.4g; at Ry(-r) d0: %.4g\n", at[0], at[1],
           at[2], L[0], L0[0], Lw[0]);
    CHECK(at[0] < -0.99 && rel_close(L[0], 100.0, 1e-9) && L0[0] < 0.02 && Lw[0] < 0.02);
    pg_environment_free(e);
}

/* ------------------------------------------------------------------------------------------ */
/* 3. the integral                                                                            */

static pg_environment *uniform_env(float value)
{
    float *px = malloc(sizeof(float) * 4 * 32 * 16);
    for (int t = 0; t < 4 * 32 * 16; t++) px[t] = value;
    pg_environment *e = NULL;
    pg_error err = {0};
    CHECK(pg_environment_from_pixels("uniform", 32, 16, px, &e, &err) == PG_OK);
    free(px);
    return e;
}

/* the hemisphere integral of pg_brdf_pbr x cos by the midpoint rule on a theta x phi grid */
static double quadrature(double nv, double b, double m, double rough)
{
    const int nt = 600, np = 1200;
    const double N[3] = {0, 0, 1}, V[3] = {sqrt(1 - nv * nv), 0, nv};
    double sum = 0;
    for (int i = 0; i < nt; i++) {
        double t = (i + 0.5) * (PI / 2) / nt, st = sin(t), ct = cos(t), row = 0;
        for (int k = 0; k < np; k++) {
            double p = (k + 0.5) * 2 * PI / np, L[3] = {st * cos(p), st * sin(p), ct};
            row += pg_brdf_pbr(L, V, N, b, m, rough);
        }
        sum += row * ct * st;
    }
    return sum * (PI / 2 / nt) * (2 * PI / np);
}

/* a unit vector at angle acos(nv) from N (unit), in some plane */
static void view_at(const double N[3], double nv, double V[3])
{
    double t[3] = {N[1] * 0.3 - N[2] * 0.9, N[2] * 0.2 - N[0] * 0.3, N[0] * 0.9 - N[1] * 0.2}; /* N x (0.2,0.9,0.3) */
    double l = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]), s = sqrt(1 - nv * nv);
    for (int k = 0; k < 3; k++) V[k] = nv * N[k] + s * t[k] / l;
}

static void test_integral_uniform(void)
{
    const double Lc = 2.0;
    pg_environment *e = uniform_env((float)Lc);
    if (!e) return;
    double N[3] = {0.3, 0.9, 0.2}, V[3], out[3], se[3];
    double nl = sqrt(0.94);
    for (int k = 0; k < 3; k++) N[k] /= nl;
    view_at(N, 0.7, V);
    pg_env_surface lam = {.base = {0.2, 0.5, 0.8}, .model = PG_SHADING_LAMBERT};
    pg_env_integral(e, 0, 0.7, 1.0, N, V, &lam, 4096, 1, out, se);
    double worst = 0;
    for (int c = 0; c < 3; c++) worst = fmax(worst, fabs(out[c] - lam.base[c] * Lc));
    printf("  uniform Lc = 2, lambert: worst |out - base Lc| %.1e (bound 1e-9)\n", worst);
    CHECK(worst <= 1e-9);
    lam.model = PG_SHADING_BLINN_PHONG;
    pg_env_integral(e, 0, 0, 0.5, N, V, &lam, 4096, 2, out, se);
    CHECK(fabs(out[1] - 0.5 * Lc * 0.5) <= 1e-9);

    pg_env_surface pbr = {.base = {0.5, 0.5, 0.5}, .metallic = 0, .roughness = 1, .model = PG_SHADING_PBR};
    static const double nvs[] = {1.0, 0.5, 0.1};
    for (int i = 0; i < 3; i++) {
        view_at(N, nvs[i], V);
        pg_env_integral(e, 0, 0, 1.0, N, V, &pbr, 1 << 16, 7 + i, out, se);
        double q = Lc * quadrature(nvs[i], 0.5, 0, 1);
        double bound = 4 * se[0] + 1e-3 * q;
        printf("  pbr b 0.5 m 0 r 1, n.v %.1f: MC %.6f +- %.1e, quadrature %.6f, |d| %.1e (bound %.1e)\n", nvs[i],
               out[0], se[0], q, fabs(out[0] - q), bound);
        CHECK(fabs(out[0] - q) <= bound && se[0] > 0);
        CHECK(out[0] == out[1] && out[1] == out[2]);
    }
    pg_environment_free(e);
}

static void test_furnace_and_lut(void)
{
    pg_environment *e = uniform_env(1.0f);
    if (!e) return;
    const double N[3] = {0, 1, 0}, V0[3] = {0, 1, 0};
    pg_env_surface metal = {.base = {1, 1, 1}, .metallic = 1, .roughness = 0.2, .model = PG_SHADING_PBR};
    double out[3], se[3], ab[2], c;
    pg_env_integral(e, 0, 0, 1.0, N, V0, &metal, 1 << 16, 3, out, se);
    printf("  white furnace (metal, roughness 0.2, n.v 1): %.6f +- %.1e (bounds [0.93, 1])\n", out[0], se[0]);
    CHECK(out[0] >= 0.93 && out[0] <= 1.0);

    pg_env_brdf_lut(1.0, 0.045, 1 << 16, ab, &c);
    printf("  LUT r 0.045, n.v 1: A %.6f B %.6f, A + B %.6f (|1 - (A+B)| <= 1e-2), c %.6f\n", ab[0], ab[1],
           ab[0] + ab[1], c);
    CHECK(fabs(ab[0] + ab[1] - 1) <= 1e-2);
    CHECK(c > 0.9 && c <= 1.0);
    double prev = INFINITY;
    int monotonic = 1;
    printf("  LUT n.v 0.5, A + B at roughness 0.2..1:");
    for (int i = 1; i <= 5; i++) {
        pg_env_brdf_lut(0.5, 0.2 * i, 1 << 16, ab, NULL);
        printf(" %.5f", ab[0] + ab[1]);
        monotonic &= ab[0] + ab[1] < prev;
        prev = ab[0] + ab[1];
    }
    printf(" (decreasing)\n");
    CHECK(monotonic);

    static const struct { double r, nv; } cases[] = {{0.2, 1.0}, {0.5, 0.5}, {0.8, 0.3}};
    for (int i = 0; i < 3; i++) {
        double V[3];
        view_at(N, cases[i].nv, V);
        metal.roughness = cases[i].r;
        pg_env_integral(e, 0, 0, 1.0, N, V, &metal, 1 << 14, 11 + i, out, se);
        pg_env_brdf_lut(cases[i].nv, cases[i].r, 1 << 18, ab, NULL);
        printf("  F0 = 1, r %.1f n.v %.1f: LUT A + B %.6f, furnace %.6f +- %.1e (|d| %.1e, bound 3 se)\n",
               cases[i].r, cases[i].nv, ab[0] + ab[1], out[0], se[0], fabs(ab[0] + ab[1] - out[0]));
        CHECK(fabs(ab[0] + ab[1] - out[0]) <= 3 * se[0]);
    }
    pg_environment_free(e);
}

/* Rows 0..h/2 bright (1), the rest 0: every direction above the horizon reads 1 (bilinear reads
 * rows <= h/2 there), so lambert with N = +Y gives base exactly. */
static void test_half_bright(void)
{
    const uint32_t w = 32, h = 16;
    float *px = calloc(4 * w * h, sizeof(float));
    for (uint32_t j = 0; j <= h / 2; j++)
        for (uint32_t i = 0; i < w; i++)
            for (int c = 0; c < 3; c++) px[4 * (j * w + i) + c] = 1.0f;
    pg_environment *e = NULL;
    pg_error err = {0};
    CHECK(pg_environment_from_pixels("half", w, h, px, &e, &err) == PG_OK);
    free(px);
    if (!e) return;
    double want = (1 - cos(PI * (h / 2 + 1) / h)) / 2, N[3] = {0, 1, 0}, V[3] = {0.6, 0.8, 0}, out[3], se[3];
    CHECK(fabs(e->mean_radiance[0] - want) <= 1e-12);
    pg_env_surface lam = {.base = {0.3, 0.6, 0.9}, .model = PG_SHADING_LAMBERT};
    pg_env_integral(e, 0, 1.1, 1.0, N, V, &lam, 4096, 5, out, se);
    CHECK(fabs(out[0] - 0.3) <= 1e-12 && fabs(out[1] - 0.6) <= 1e-12 && fabs(out[2] - 0.9) <= 1e-12);
    CHECK(se[0] <= 1e-12);
    pg_environment_free(e);
}

/* The value of `const uint NAME = VALUE u` in shaders/environment.glsl; -1 when absent. */
static long glsl_const(const char *text, const char *name)
{
    char key[64];
    snprintf(key, sizeof key, "%s = ", name);
    const char *p = strstr(text, key);
    return p ? strtol(p + strlen(key), NULL, 10) : -1;
}

/* renderer/common/environment_layout.h mirrors the filtered layout of shaders/environment.glsl: a
 * mismatch would make environment_filter write (or the shading passes read) past the buffer the
 * pipeline declares. */
static void test_layout_mirror(void)
{
    char path[512];
    snprintf(path, sizeof path, "%s/../shaders/environment.glsl", PG_TEST_DIR);
    FILE *f = fopen(path, "rb");
    CHECK_MSG(f != NULL, "cannot open %s", path);
    if (!f) return;
    static char text[32768];
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = 0;
    const struct { const char *name; long c; } k[] = {
        {"PG_ENV_IRR_W", PG_ENV_IRR_W}, {"PG_ENV_IRR_H", PG_ENV_IRR_H}, {"PG_ENV_IRR_OFF", PG_ENV_IRR_OFF},
        {"PG_ENV_LUT_N", PG_ENV_LUT_N}, {"PG_ENV_LUT_OFF", PG_ENV_LUT_OFF}, {"PG_ENV_SPEC_W", PG_ENV_SPEC_W},
        {"PG_ENV_SPEC_H", PG_ENV_SPEC_H}, {"PG_ENV_SPEC_LEVELS", PG_ENV_SPEC_LEVELS},
        {"PG_ENV_SPEC_OFF", PG_ENV_SPEC_OFF}, {"PG_ENV_TEXELS", PG_ENV_TEXELS}};
    for (size_t i = 0; i < sizeof k / sizeof k[0]; i++)
        CHECK_MSG(glsl_const(text, k[i].name) == k[i].c, "%s: environment.glsl %ld, environment_layout.h %ld",
                  k[i].name, glsl_const(text, k[i].name), k[i].c);
    /* the level sizes: (256 >> k) x (128 >> k), at least 64 x 32, summed from PG_ENV_SPEC_OFF */
    long min_w = glsl_const(text, "PG_ENV_SPEC_MIN_W"), total = PG_ENV_SPEC_OFF;
    for (uint32_t lv = 0; lv < PG_ENV_SPEC_LEVELS; lv++) {
        long w = (long)(PG_ENV_SPEC_W >> lv), h = (long)(PG_ENV_SPEC_H >> lv);
        total += (w > min_w ? w : min_w) * (h > min_w / 2 ? h : min_w / 2);
    }
    CHECK_MSG(min_w > 0 && total == PG_ENV_TEXELS, "the specular levels sum to %ld texels, PG_ENV_TEXELS %u", total,
              PG_ENV_TEXELS);
}

int main(void)
{
    snprintf(g_dir, sizeof g_dir, "/tmp/pg_test_environment_XXXXXX");
    if (!mkdtemp(g_dir)) return pg_test_skip("test_environment", "mkdtemp failed");
    test_layout_mirror();
    test_load_exact();
    test_load_rle();
    test_uniform_and_ids();
    test_clamping();
    test_errors();
    test_exposure();
    test_default_sky();
    test_directions();
    test_texel_centres();
    test_rotation();
    test_integral_uniform();
    test_furnace_and_lut();
    test_half_bright();
    static const char *files[] = {"exact.hdr", "rle.hdr", "uniform.hdr", "huge.hdr", "text.hdr", "header_only.hdr",
                                  "half.hdr", "nearly.hdr", "no_end.hdr", "xyze.hdr", "flip.hdr", "wide.hdr",
                                  "ratio.hdr", "small.hdr", "too_wide.hdr", "odd.hdr", "image.hdr", "rle_cut.hdr", "centres.hdr",
                                  "exposure.hdr", "exposure_1.hdr", "exposure_0.hdr", "exposure_x.hdr", "crlf.hdr"};
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) unlink(tmp_path(files[i]));
    CHECK(rmdir(g_dir) == 0);
    return pg_test_finish("test_environment");
}
