/* frame_metrics.c - perceptual metrics, accumulation and flicker of frames (frame_metrics.h). */
#include "frame_metrics.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "image_compare.h"
#include "image_ssim.h"
#include "image_util.h"

pg_result pg_perceptual_compute(const float *hdr_a, const float *hdr_b, const uint8_t *ldr_a, const uint8_t *ldr_b,
                                uint32_t w, uint32_t h, bool with_hdr_flip, float *flip_map, pg_perceptual *out,
                                pg_error *err)
{
    const double t0 = pg_time_s() * 1e3;
    memset(out, 0, sizeof *out);
    out->hdr_flip = out->ssim = NAN;
    pg_result r = pg_flip_ldr(ldr_a, ldr_b, w, h, NULL, flip_map, &out->flip, err);
    if (r) return pg_error_prefix(err, "LDR-FLIP");
    if (with_hdr_flip) {
        if ((r = pg_flip_hdr(hdr_a, hdr_b, w, h, NULL, NULL, &out->hdr, err))) return pg_error_prefix(err, "HDR-FLIP");
        out->hdr_flip = out->hdr.mean;
    }
    if (w >= PG_SSIM_WINDOW && h >= PG_SSIM_WINDOW && (r = pg_ssim(ldr_a, ldr_b, w, h, &out->ssim, err)))
        return pg_error_prefix(err, "SSIM");
    out->cpu_ms = pg_time_s() * 1e3 - t0;
    return PG_OK;
}

static bool rgb_finite(const float *p)
{
    return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

void pg_flicker_add(pg_flicker *f, const float *prev, const float *cur, uint32_t w, uint32_t h)
{
    const size_t px = (size_t)w * h;
    for (size_t i = 0; i < px; i++) {
        const float *a = prev + 4 * i, *b = cur + 4 * i;
        if (!rgb_finite(a) || !rgb_finite(b)) continue;
        for (int c = 0; c < 3; c++) f->sum += fabs((double)b[c] - (double)a[c]);
        f->count += 3;
    }
    f->pairs++;
}

double pg_flicker_value(const pg_flicker *f, const float *ref_hdr, uint32_t w, uint32_t h)
{
    if (!f->pairs || !f->count) return NAN;
    if (f->sum == 0) return 0;
    double s = 0;
    uint64_t n = 0;
    for (size_t i = 0; i < (size_t)w * h; i++) {
        const float *p = ref_hdr + 4 * i;
        if (!rgb_finite(p)) continue;
        s += (double)p[0] + p[1] + p[2];
        n += 3;
    }
    const double mean = n ? s / (double)n : 0;
    return mean > 0 ? f->sum / (double)f->count / mean : NAN;
}

pg_result pg_session_read_images(const pg_session *s, uint32_t w, uint32_t h, float *hdr_out, uint8_t *ldr_out,
                                 pg_error *err)
{
    const pg_pipeline *pl = s->pipeline;
    uint32_t lw, lh, hw, hh;
    pg_format lf, hf;
    const uint8_t *lp = pg_runtime_output(s->runtime, 0, &lw, &lh, &lf);
    if (!lp || (lf != PG_FMT_RGBA8_UNORM && lf != PG_FMT_RGBA8_SRGB))
        return pg_fail(err, PG_ERR_FORMAT, "%s: output '%s' is not an 8-bit RGBA image", pl->path, pl->output);
    const void *hp = pg_runtime_output(s->runtime, 1, &hw, &hh, &hf);
    if (!hp) return pg_fail(err, PG_ERR_NO_OUTPUT, "%s: hdr_output '%s' was not read back", pl->path, pl->hdr_output);
    pg_result r;
    if ((r = pg_image_sizes_match("output", lw, lh, w, h, err)) || (r = pg_image_sizes_match("hdr_output", hw, hh, w, h, err)))
        return r;
    memcpy(ldr_out, lp, (size_t)w * h * 4);
    return pg_hdr_to_float(hp, hf, w, h, hdr_out, err);
}

/* scratch of pg_sample_frames: the sums, the previous and current frame */
typedef struct sample_scratch {
    double *hdr_sum, *ldr_sum;
    float *prev, *cur;
    uint8_t *ldr;
} sample_scratch;

static void scratch_free(sample_scratch *t)
{
    free(t->hdr_sum);
    free(t->ldr_sum);
    free(t->prev);
    free(t->cur);
    free(t->ldr);
}

static void accumulate_add(sample_scratch *t, const float *hdr, const uint8_t *ldr, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        t->hdr_sum[i] += hdr[i];
        t->ldr_sum[i] += ldr[i];
    }
}

pg_result pg_sample_frames(pg_session *s, const pg_frame_info *fi, uint32_t accumulate, uint32_t flicker_frames,
                           const float *hdr0, const uint8_t *ldr0, uint32_t w, uint32_t h, float *hdr_mean,
                           uint8_t *ldr_mean, pg_flicker *fl, uint32_t *frames_rendered, pg_error *err)
{
    const size_t n = (size_t)w * h * 4;
    const uint32_t total = accumulate > flicker_frames ? accumulate : flicker_frames;
    memset(fl, 0, sizeof *fl);
    *frames_rendered = 0;
    if (total <= 1) {
        memcpy(hdr_mean, hdr0, n * sizeof *hdr_mean);
        memcpy(ldr_mean, ldr0, n);
        return PG_OK;
    }
    sample_scratch t = {calloc(n, sizeof(double)), calloc(n, sizeof(double)), malloc(n * sizeof(float)),
                        malloc(n * sizeof(float)), malloc(n)};
    pg_result r = PG_OK;
    if (!t.hdr_sum || !t.ldr_sum || !t.prev || !t.cur || !t.ldr) {
        r = pg_fail(err, PG_ERR_OOM, "out of memory");
        goto out;
    }
    accumulate_add(&t, hdr0, ldr0, n);
    memcpy(t.prev, hdr0, n * sizeof(float));
    pg_frame_info f = *fi;
    for (uint32_t k = 1; k < total; k++) {
        pg_frame_stats st;
        f.sample = fi->sample + k;
        if ((r = pg_session_render(s, &f, true, &st, err))) goto out;
        ++*frames_rendered;
        if ((r = pg_session_read_images(s, w, h, t.cur, t.ldr, err))) goto out;
        if (k < accumulate) accumulate_add(&t, t.cur, t.ldr, n);
        if (k < flicker_frames) pg_flicker_add(fl, t.prev, t.cur, w, h);
        float *swap = t.prev;
        t.prev = t.cur;
        t.cur = swap;
    }
    const uint32_t na = accumulate ? accumulate : 1;
    for (size_t i = 0; i < n; i++) {
        hdr_mean[i] = (float)(t.hdr_sum[i] / na);
        const double v = floor(t.ldr_sum[i] / na + 0.5);
        ldr_mean[i] = (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v);
    }
out:
    scratch_free(&t);
    return r;
}

static pg_result parse_count(const char *opt, const char *v, uint32_t lo, uint32_t hi, const char *expect,
                             uint32_t *out, pg_error *err)
{
    if (!v || !*v) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: missing value", opt);
    errno = 0;
    char *end = (char *)v;
    unsigned long long u = (*v >= '0' && *v <= '9') ? strtoull(v, &end, 10) : 0;
    if (*v < '0' || *v > '9' || errno || *end || u < lo || u > hi)
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s %s: expected %s", opt, v, expect);
    *out = (uint32_t)u;
    return PG_OK;
}

pg_result pg_parse_accumulate(const char *opt, const char *v, uint32_t *out, pg_error *err)
{
    return parse_count(opt, v, 1, PG_ACCUMULATE_MAX, "a whole number of frames in [1, 4096]", out, err);
}

pg_result pg_parse_flicker_frames(const char *opt, const char *v, uint32_t *out, pg_error *err)
{
    pg_result r = parse_count(opt, v, 0, PG_FLICKER_FRAMES_MAX, "0 (off) or a whole number of frames in [2, 1024]",
                              out, err);
    if (!r && *out == 1)
        r = pg_fail(err, PG_ERR_INVALID_ARG, "%s 1: flicker compares consecutive frames: give 0 (off) or at least 2",
                    opt);
    return r;
}

void pg_flip_map_rgba(const float *map, uint32_t w, uint32_t h, uint8_t *rgba)
{
    for (size_t i = 0; i < (size_t)w * h; i++) {
        pg_colormap(map[i], rgba + 4 * i);
        rgba[4 * i + 3] = 255;
    }
}
