/* environment.c - the environment light's image (environment.h): Radiance HDR files through
 * stb_image (stbi_loadf), the neutral default sky, the box-filtered mip chain and its statistics.
 *
 * stb_image reads past the end of a truncated HDR file as if it went on with zero bytes, so the
 * header and the scanlines (flat or run-length encoded) are walked here first, with stb_image's
 * own rules, and a file whose pixels end early is refused before it is decoded. */
#include "environment.h"

#include <limits.h>
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>

#define ENV_MIN_WIDTH 8
#define ENV_MIN_HEIGHT 4
#define ENV_PI 3.14159265358979323846

/* the next id (pg_environment.id): 1 for the first environment of the process */
static _Atomic uint64_t g_next_id = 1;

typedef unsigned long long ull;

/* ------------------------------------------------------------------------------------------ */
/* sizes, levels, values                                                                      */

static pg_result check_size(const char *src, uint64_t w, uint64_t h, pg_error *err)
{
    if (w > PG_ENV_MAX_WIDTH)
        return pg_fail(err, PG_ERR_LIMIT, "%s: %llu x %llu: wider than %d texels", src, (ull)w, (ull)h,
                       PG_ENV_MAX_WIDTH);
    if (w < ENV_MIN_WIDTH || h < ENV_MIN_HEIGHT)
        return pg_fail(err, PG_ERR_LIMIT, "%s: %llu x %llu: smaller than %d x %d", src, (ull)w, (ull)h,
                       ENV_MIN_WIDTH, ENV_MIN_HEIGHT);
    if (w + 1 < 2 * h || w > 2 * h + 1) /* 2:1 within one texel */
        return pg_fail(err, PG_ERR_INVALID_ARG,
                       "%s: %llu x %llu: an equirectangular environment is 2:1 (width = 2 x height)", src,
                       (ull)w, (ull)h);
    return PG_OK;
}

/* Level sizes and offsets (environment.h "Levels"); false when the texels cannot be addressed. */
static bool plan_levels(pg_environment *e, uint32_t w, uint32_t h)
{
    uint64_t off = 0;
    uint32_t n = 0;
    for (;;) {
        e->width[n] = w;
        e->height[n] = h;
        e->offset[n] = off;
        off += (uint64_t)w * h;
        n++;
        if (w == 1 || h == 1 || n == PG_ENV_MAX_LEVELS) break;
        w = w / 2 > 0 ? w / 2 : 1;
        h = h / 2 > 0 ? h / 2 : 1;
    }
    e->n_levels = n;
    e->n_texels = off;
    return off <= SIZE_MAX / (4 * sizeof(float));
}

/* One level-0 component: non-finite or negative -> 0, above PG_ENV_MAX_VALUE -> it; counted. */
static float clean_value(float x, uint64_t *clamped)
{
    if (!isfinite(x) || x < 0.0f) {
        (*clamped)++;
        return 0.0f;
    }
    if (x > PG_ENV_MAX_VALUE) {
        (*clamped)++;
        return PG_ENV_MAX_VALUE;
    }
    return x;
}

static void clean_level0(pg_environment *e)
{
    uint64_t n = (uint64_t)e->width[0] * e->height[0];
    float mx = 0.0f;
    for (uint64_t t = 0; t < n; t++) {
        float *p = e->rgba + 4 * t;
        for (int c = 0; c < 3; c++) {
            p[c] = clean_value(p[c], &e->clamped);
            if (p[c] > mx) mx = p[c];
        }
        p[3] = 1.0f;
    }
    e->max_value = mx;
}

/* Level k+1 from level k: each texel the plain average of the level-k texels its index range
 * covers (i * w_k / w_{k+1} .. (i + 1) * w_k / w_{k+1} - 1, the same for rows). */
static void downsample(pg_environment *e, uint32_t k)
{
    const uint64_t w0 = e->width[k], h0 = e->height[k], w1 = e->width[k + 1], h1 = e->height[k + 1];
    const float *src = e->rgba + 4 * e->offset[k];
    float *dst = e->rgba + 4 * e->offset[k + 1];
    for (uint64_t j1 = 0; j1 < h1; j1++) {
        uint64_t ja = j1 * h0 / h1, jb = (j1 + 1) * h0 / h1;
        for (uint64_t i1 = 0; i1 < w1; i1++) {
            uint64_t ia = i1 * w0 / w1, ib = (i1 + 1) * w0 / w1;
            double acc[3] = {0, 0, 0};
            for (uint64_t j = ja; j < jb; j++)
                for (uint64_t i = ia; i < ib; i++)
                    for (int c = 0; c < 3; c++) acc[c] += src[4 * (j * w0 + i) + c];
            double n = (double)((jb - ja) * (ib - ia));
            float *d = dst + 4 * (j1 * w1 + i1);
            for (int c = 0; c < 3; c++) d[c] = (float)(acc[c] / n);
            d[3] = 1.0f;
        }
    }
}

/* mean_radiance = sum over level-0 texels of rgb x solid angle / (4 pi); the solid angle of row j
 * is (2 pi / w)(cos(pi j / h) - cos(pi (j + 1) / h)), so the weight is that difference / (2 w). */
static void compute_mean(pg_environment *e)
{
    const uint32_t w = e->width[0], h = e->height[0];
    double sum[3] = {0, 0, 0};
    for (uint32_t j = 0; j < h; j++) {
        double row[3] = {0, 0, 0};
        const float *p = e->rgba + 4 * (uint64_t)j * w;
        for (uint32_t i = 0; i < w; i++)
            for (int c = 0; c < 3; c++) row[c] += p[4 * i + c];
        double wt = (cos(ENV_PI * j / h) - cos(ENV_PI * (j + 1) / h)) / (2.0 * w);
        for (int c = 0; c < 3; c++) sum[c] += row[c] * wt;
    }
    for (int c = 0; c < 3; c++) e->mean_radiance[c] = sum[c];
}

/* Running sums of n weights into cdf[0..n] (cdf[0] = 0), normalized to end at 1; a row of zeros
 * becomes uniform. Returns the total. */
static double cdf_row(const double *wt, uint32_t n, float *cdf)
{
    double total = 0;
    for (uint32_t i = 0; i < n; i++) total += wt[i];
    double run = 0;
    cdf[0] = 0;
    for (uint32_t i = 0; i < n; i++) {
        run += total > 0 ? wt[i] : 1.0;
        cdf[i + 1] = (float)(run / (total > 0 ? total : (double)n));
    }
    cdf[n] = 1;
    return total;
}

/* The importance-sampling tables of level 0 (environment.h: cdf); false when out of memory. */
static bool build_cdf(pg_environment *e)
{
    const uint32_t w = e->width[0], h = e->height[0];
    e->n_cdf = (uint64_t)h + 1 + (uint64_t)h * (w + 1);
    e->cdf = malloc(e->n_cdf * sizeof(float));
    double *wt = malloc(sizeof(double) * (w > h ? w : h)), *rows = malloc(sizeof(double) * h);
    if (!e->cdf || !wt || !rows) {
        free(wt);
        free(rows);
        return false;
    }
    for (uint32_t j = 0; j < h; j++) {
        const float *p = e->rgba + 4 * (uint64_t)j * w;
        double s = sin(ENV_PI * (j + 0.5) / h);
        for (uint32_t i = 0; i < w; i++)
            wt[i] = s * (0.2126 * p[4 * i] + 0.7152 * p[4 * i + 1] + 0.0722 * p[4 * i + 2]);
        rows[j] = cdf_row(wt, w, e->cdf + h + 1 + (uint64_t)j * (w + 1));
    }
    double total = cdf_row(rows, h, e->cdf);
    free(wt);
    free(rows);
    if (!(total > 0)) { /* black: nothing to sample by */
        free(e->cdf);
        e->cdf = NULL;
        e->n_cdf = 0;
    }
    return true;
}

/* Builds the environment from w x h level-0 RGBA floats (copied): the checks, the levels, the
 * clamping, the statistics and a new id. */
static pg_result env_build(const char *source, uint32_t w, uint32_t h, const float *rgba, pg_environment **out,
                           pg_error *err)
{
    *out = NULL;
    pg_result r = check_size(source, w, h, err);
    if (r != PG_OK) return r;
    pg_environment *e = calloc(1, sizeof *e);
    if (!e) return pg_fail(err, PG_ERR_OOM, "%s: out of memory", source);
    pg_strlcpy(e->source, source, sizeof e->source);
    if (!plan_levels(e, w, h)) {
        pg_result lim = pg_fail(err, PG_ERR_LIMIT, "%s: %u x %u: too many texels to address", source, w, h);
        free(e);
        return lim;
    }
    e->rgba = malloc((size_t)e->n_texels * 4 * sizeof(float));
    if (!e->rgba) {
        pg_result oom = pg_fail(err, PG_ERR_OOM, "%s: out of memory for %llu texels", source, (ull)e->n_texels);
        free(e);
        return oom;
    }
    memcpy(e->rgba, rgba, (size_t)w * h * 4 * sizeof(float));
    clean_level0(e);
    for (uint32_t k = 0; k + 1 < e->n_levels; k++) downsample(e, k);
    compute_mean(e);
    if (!build_cdf(e)) {
        pg_result oom = pg_fail(err, PG_ERR_OOM, "%s: out of memory for the sampling tables", source);
        pg_environment_free(e);
        return oom;
    }
    e->id = atomic_fetch_add(&g_next_id, 1);
    *out = e;
    return PG_OK;
}

pg_result pg_environment_from_pixels(const char *source, uint32_t w, uint32_t h, const float *rgba,
                                     pg_environment **out, pg_error *err)
{
    if (!source) source = "pixels";
    if (!rgba || !out) {
        if (out) *out = NULL;
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s: no pixels", source);
    }
    return env_build(source, w, h, rgba, out, err);
}

void pg_environment_free(pg_environment *env)
{
    if (!env) return;
    free(env->rgba);
    free(env->cdf);
    free(env);
}

/* ------------------------------------------------------------------------------------------ */
/* Radiance HDR files                                                                         */

typedef struct hdr_info {
    uint64_t w, h;
    size_t data;     /* offset of the first pixel byte */
    double exposure; /* the product of the header's EXPOSURE= values (1 without): the pixels hold
                      * radiance times it (Radiance's file format), so they are divided by it */
} hdr_info;

/* "EXPOSURE=x" (l bytes at b): x multiplied into *exposure; a value that is not a finite number > 0
 * is refused */
static pg_result parse_exposure(const char *path, const unsigned char *b, size_t l, double *exposure, pg_error *err)
{
    char v[64];
    size_t k = l - 9 < sizeof v - 1 ? l - 9 : sizeof v - 1;
    memcpy(v, b + 9, k);
    v[k] = 0;
    char *end = NULL;
    double x = strtod(v, &end);
    while (end && (*end == ' ' || *end == '\t' || *end == '\r')) end++;
    if (end == v || !end || *end || !isfinite(x) || !(x > 0) || !isfinite(*exposure * x) || !(*exposure * x > 0))
        return pg_fail(err, PG_ERR_PARSE, "%s: header line 'EXPOSURE=%s': expected a finite number > 0", path, v);
    *exposure *= x;
    return PG_OK;
}

/* The line at *pos (without its '\n'); false when no '\n' comes before n. */
static bool next_line(const unsigned char *b, size_t n, size_t *pos, size_t *start, size_t *len)
{
    const unsigned char *nl = *pos < n ? memchr(b + *pos, '\n', n - *pos) : NULL;
    if (!nl) return false;
    *start = *pos;
    *len = (size_t)(nl - (b + *pos));
    *pos += *len + 1;
    return true;
}

/* 1..9 decimal digits at *p */
static bool parse_count(const char **p, uint64_t *v)
{
    const char *s = *p;
    uint64_t x = 0;
    while (*s >= '0' && *s <= '9' && s - *p < 9) x = x * 10 + (uint64_t)(*s++ - '0');
    if (s == *p || (*s >= '0' && *s <= '9')) return false;
    *v = x;
    *p = s;
    return true;
}

/* "-Y H +X W", the one orientation stb_image reads */
static pg_result parse_resolution(const char *path, const unsigned char *line, size_t len, hdr_info *hi,
                                  pg_error *err)
{
    char s[64];
    if (len >= sizeof s) return pg_fail(err, PG_ERR_PARSE, "%s: the image size line is too long", path);
    memcpy(s, line, len);
    s[len] = 0;
    const char *p = s;
    bool ok = strncmp(p, "-Y ", 3) == 0 && (p += 3, parse_count(&p, &hi->h));
    if (ok) {
        while (*p == ' ') p++;
        ok = strncmp(p, "+X ", 3) == 0 && (p += 3, parse_count(&p, &hi->w));
        while (ok && *p == ' ') p++;
        ok = ok && *p == 0;
    }
    if (!ok)
        return pg_fail(err, PG_ERR_PARSE, "%s: image size line '%s' is not '-Y HEIGHT +X WIDTH' (the only "
                       "orientation read; HEIGHT and WIDTH of at most 9 digits)", path, s);
    return PG_OK;
}

static pg_result parse_header(const char *path, const unsigned char *b, size_t n, hdr_info *hi, pg_error *err)
{
    static const char fmt[] = "FORMAT=32-bit_rle_rgbe";
    size_t pos = 0, s = 0, l = 0;
    bool format = false;
    if (!next_line(b, n, &pos, &s, &l)) return pg_fail(err, PG_ERR_PARSE, "%s: truncated (in the header)", path);
    for (;;) {
        if (!next_line(b, n, &pos, &s, &l))
            return pg_fail(err, PG_ERR_PARSE, "%s: truncated (the header has no end)", path);
        if (l == 0) break;
        if (l == sizeof fmt - 1 && memcmp(b + s, fmt, l) == 0)
            format = true;
        else if (l >= 9 && memcmp(b + s, "EXPOSURE=", 9) == 0) {
            pg_result r = parse_exposure(path, b + s, l, &hi->exposure, err);
            if (r != PG_OK) return r;
        }
        else if (l >= 7 && memcmp(b + s, "FORMAT=", 7) == 0)
            return pg_fail(err, PG_ERR_PARSE, "%s: pixel format '%.*s' is not 32-bit_rle_rgbe", path,
                           (int)(l > 64 ? 64 : l), (const char *)b + s);
    }
    if (!format) return pg_fail(err, PG_ERR_PARSE, "%s: no %s line in the header", path, fmt);
    if (!next_line(b, n, &pos, &s, &l))
        return pg_fail(err, PG_ERR_PARSE, "%s: truncated (no image size line)", path);
    pg_result r = parse_resolution(path, b + s, l, hi, err);
    hi->data = pos;
    return r;
}

static pg_result truncated_row(const char *path, uint64_t j, uint64_t h, pg_error *err)
{
    return pg_fail(err, PG_ERR_PARSE, "%s: truncated (the pixels end in row %llu of %llu)", path, (ull)j + 1,
                   (ull)h);
}

/* One run-length encoded scanline at *pos (row j), as stb_image decodes it: 2, 2, the width in
 * two bytes, then per channel runs (count > 128: count - 128 copies of one byte) and dumps
 * (count bytes), never 0 and never past the row's end. */
static pg_result check_rle_row(const char *path, const unsigned char *b, size_t n, size_t *pos,
                               const hdr_info *hi, uint64_t j, pg_error *err)
{
    size_t p = *pos;
    if (n - p < 4) return truncated_row(path, j, hi->h, err);
    if (b[p] != 2 || b[p + 1] != 2 || (b[p + 2] & 0x80))
        return pg_fail(err, PG_ERR_PARSE, "%s: row %llu is not run-length encoded (row 1 is)", path, (ull)j + 1);
    if ((((uint64_t)b[p + 2] << 8) | b[p + 3]) != hi->w)
        return pg_fail(err, PG_ERR_PARSE, "%s: row %llu: scanline length %u, the image is %llu wide", path,
                       (ull)j + 1, ((unsigned)b[p + 2] << 8) | b[p + 3], (ull)hi->w);
    p += 4;
    for (int k = 0; k < 4; k++) {
        for (uint64_t i = 0; i < hi->w;) {
            if (p >= n) return truncated_row(path, j, hi->h, err);
            unsigned c = b[p++];
            size_t bytes = c > 128 ? 1 : c;
            c = c > 128 ? c - 128 : c;
            if (c == 0 || c > hi->w - i)
                return pg_fail(err, PG_ERR_PARSE, "%s: row %llu: bad run-length data", path, (ull)j + 1);
            if (n - p < bytes) return truncated_row(path, j, hi->h, err);
            p += bytes;
            i += c;
        }
    }
    *pos = p;
    return PG_OK;
}

/* The pixels are all there: flat (w x h x 4 bytes) unless the first row starts a run-length
 * encoded scanline (stb_image's rule: only for widths 8..32767). */
static pg_result check_pixels(const char *path, const unsigned char *b, size_t n, const hdr_info *hi, pg_error *err)
{
    size_t p = hi->data;
    bool rle = hi->w >= 8 && hi->w < 32768 && n - p >= 3 && b[p] == 2 && b[p + 1] == 2 && !(b[p + 2] & 0x80);
    if (!rle) {
        uint64_t need = hi->w * hi->h * 4;
        if (n - p < need)
            return pg_fail(err, PG_ERR_PARSE, "%s: truncated (%llu of the %llu pixel bytes of %llu x %llu)", path,
                           (ull)(n - p), (ull)need, (ull)hi->w, (ull)hi->h);
        return PG_OK;
    }
    for (uint64_t j = 0; j < hi->h; j++) {
        pg_result r = check_rle_row(path, b, n, &p, hi, j, err);
        if (r != PG_OK) return r;
    }
    return PG_OK;
}

static pg_result decode_hdr(const char *path, const unsigned char *b, size_t n, pg_environment **out, pg_error *err)
{
    if (n > INT_MAX) return pg_fail(err, PG_ERR_LIMIT, "%s: larger than 2 GiB", path);
    if (!stbi_is_hdr_from_memory(b, (int)n)) {
        if ((n >= 12 && !memcmp(b, "#?RADIANCE\r\n", 12)) || (n >= 8 && !memcmp(b, "#?RGBE\r\n", 8)))
            return pg_fail(err, PG_ERR_PARSE, "%s: a Radiance HDR header with CRLF line ends (Windows text); the "
                           "format's lines end in LF alone", path);
        return pg_fail(err, PG_ERR_PARSE, "%s: not a Radiance HDR file", path);
    }
    hdr_info hi = {0, 0, 0, 1.0};
    pg_result r = parse_header(path, b, n, &hi, err);
    if (r == PG_OK) r = check_size(path, hi.w, hi.h, err);
    if (r == PG_OK) r = check_pixels(path, b, n, &hi, err);
    if (r != PG_OK) return r;
    int w = 0, h = 0, comp = 0;
    float *px = stbi_loadf_from_memory(b, (int)n, &w, &h, &comp, 4);
    if (!px) {
        const char *why = stbi_failure_reason();
        return pg_fail(err, PG_ERR_PARSE, "%s: cannot decode (%s)", path, why ? why : "unknown reason");
    }
    if ((uint64_t)w != hi.w || (uint64_t)h != hi.h)
        r = pg_fail(err, PG_ERR_PARSE, "%s: decoded %d x %d, the header says %llu x %llu", path, w, h, (ull)hi.w,
                    (ull)hi.h);
    else {
        if (hi.exposure != 1.0) /* radiance = the stored value / EXPOSURE */
            for (size_t i = 0; i < (size_t)w * (size_t)h * 4; i += 4)
                for (int c = 0; c < 3; c++) px[i + c] = (float)(px[i + c] / hi.exposure);
        r = env_build(path, (uint32_t)w, (uint32_t)h, px, out, err);
    }
    stbi_image_free(px);
    return r;
}

pg_result pg_environment_load(const char *path, pg_environment **out, pg_error *err)
{
    *out = NULL;
    char *buf = NULL;
    size_t size = 0;
    pg_result r = pg_read_file_as(path, "a Radiance .hdr file (or an OpenEXR .exr)", &buf, &size, err);
    if (r != PG_OK) return r;
    r = decode_hdr(path, (const unsigned char *)buf, size, out, err);
    free(buf);
    return r;
}

/* ------------------------------------------------------------------------------------------ */
/* the default sky                                                                            */

/* The neutral default sky, before scaling, toward a direction with y = cos(theta), channel c:
 *   sky(y)  = T_sky[c] (1 + 2 max(y, 0))   the CIE standard overcast sky's gradation (the zenith
 *                                          3 x the horizon), slightly cool
 *   ground  = 0.2 T_ground[c]              a dim warm-grey ground
 *   L(y)    = ground + (sky(y) - ground) s(y),   s = smoothstep(-0.08, 0.08, y)
 * with T_sky = (0.94, 0.98, 1.06), T_ground = (1.05, 1.0, 0.93); no sun, the same at every phi.
 * Each texel takes L at its centre; then channel c is multiplied by level / M[c], M[c] = the
 * solid-angle mean of the unscaled image (compute_mean's formula), so that its mean radiance is
 * `level` per channel (to float rounding). */
static void sky_row(double y, double out[3])
{
    static const double t_sky[3] = {0.94, 0.98, 1.06}, t_ground[3] = {1.05, 1.0, 0.93};
    double s = (y + 0.08) / 0.16;
    s = s < 0 ? 0 : s > 1 ? 1 : s;
    s = s * s * (3 - 2 * s);
    for (int c = 0; c < 3; c++) {
        double sky = t_sky[c] * (1 + 2 * (y > 0 ? y : 0)), ground = 0.2 * t_ground[c];
        out[c] = ground + (sky - ground) * s;
    }
}

#define SKY_W 256
#define SKY_H 128

pg_result pg_environment_default(float level, pg_environment **out, pg_error *err)
{
    *out = NULL;
    if (!isfinite(level) || level < 0.0f)
        return pg_fail(err, PG_ERR_INVALID_ARG, "default: sky level %g is not a finite value >= 0", (double)level);
    double row[SKY_H][3], mean[3] = {0, 0, 0};
    for (int j = 0; j < SKY_H; j++) {
        sky_row(cos(ENV_PI * (j + 0.5) / SKY_H), row[j]);
        double wt = (cos(ENV_PI * j / SKY_H) - cos(ENV_PI * (j + 1) / SKY_H)) / 2.0; /* w texels x 1/(2w) */
        for (int c = 0; c < 3; c++) mean[c] += row[j][c] * wt;
    }
    float *px = malloc((size_t)SKY_W * SKY_H * 4 * sizeof(float));
    if (!px) return pg_fail(err, PG_ERR_OOM, "default: out of memory");
    for (int j = 0; j < SKY_H; j++)
        for (int i = 0; i < SKY_W; i++) {
            float *p = px + 4 * ((size_t)j * SKY_W + i);
            for (int c = 0; c < 3; c++) p[c] = (float)(row[j][c] * (level / mean[c]));
            p[3] = 1.0f;
        }
    pg_result r = env_build("default", SKY_W, SKY_H, px, out, err);
    free(px);
    return r;
}

/* ------------------------------------------------------------------------------------------ */
/* directions and sampling                                                                    */

void pg_env_dir_to_uv(const double d[3], double *u, double *v)
{
    double y = d[1] < -1 ? -1 : d[1] > 1 ? 1 : d[1];
    double uu = 0.5 + atan2(d[0], -d[2]) / (2 * ENV_PI);
    *u = uu >= 1.0 ? uu - 1.0 : uu;
    *v = acos(y) / ENV_PI;
}

void pg_env_uv_to_dir(double u, double v, double d[3])
{
    double phi = 2 * ENV_PI * (u - 0.5), theta = ENV_PI * v;
    d[0] = sin(theta) * sin(phi);
    d[1] = cos(theta);
    d[2] = -sin(theta) * cos(phi);
}

void pg_environment_radiance(const pg_environment *env, uint32_t level, const double d[3], double rotation,
                             double intensity, double out[3])
{
    if (level >= env->n_levels) level = env->n_levels - 1;
    const double cr = cos(rotation), sr = sin(rotation);
    const double q[3] = {d[0] * cr - d[2] * sr, d[1], d[0] * sr + d[2] * cr}; /* Ry(-rotation) d */
    double u, v;
    pg_env_dir_to_uv(q, &u, &v);
    const uint32_t w = env->width[level], h = env->height[level];
    double x = u * w - 0.5, y = v * h - 0.5;
    y = y < 0 ? 0 : y > h - 1 ? h - 1 : y;
    double xf = floor(x);
    double fx = x - xf, fy = y - floor(y);
    int64_t i0 = ((int64_t)xf % (int64_t)w + w) % w, i1 = (i0 + 1) % w;
    uint32_t j0 = (uint32_t)y, j1 = j0 + 1 < h ? j0 + 1 : h - 1;
    const float *p = env->rgba + 4 * env->offset[level];
    const float *a = p + 4 * ((uint64_t)j0 * w + i0), *b = p + 4 * ((uint64_t)j0 * w + i1);
    const float *c = p + 4 * ((uint64_t)j1 * w + i0), *e = p + 4 * ((uint64_t)j1 * w + i1);
    for (int k = 0; k < 3; k++) {
        double top = a[k] + (b[k] - (double)a[k]) * fx, bottom = c[k] + (e[k] - (double)c[k]) * fx;
        out[k] = (top + (bottom - top) * fy) * intensity;
    }
}
