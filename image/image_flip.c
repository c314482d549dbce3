/* image_flip.c - LDR-FLIP and HDR-FLIP on the CPU (see image_flip.h for the method and constants).
 *
 * Layout: every image is held as float planes (one per channel, row-major). The spatial filters are
 * separable: a row pass into a scratch plane, then a column pass, both with replicated borders.
 * Threads: each step of the method (a colour conversion, a row pass, a column pass, the per-pixel
 * error) runs on bands of rows in parallel (flip_run), one band a thread; a step only reads what
 * earlier steps wrote, and every value is computed by the same operations whatever the band, so
 * the map is the same bits for any thread count (test_image_metrics checks it). */
#include "image_flip.h"

#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* linear sRGB -> XYZ from the sRGB primaries and the D65 white (x, y) = (0.3127, 0.3290) */
static const double RGB2XYZ[3][3] = {
    {0.4123907992659595, 0.35758433938387796, 0.1804807884018343},
    {0.21263900587151036, 0.7151686787677559, 0.07219231536073371},
    {0.01933081871559185, 0.11919477979462599, 0.9505321522496606},
};
/* its inverse */
static const double XYZ2RGB[3][3] = {
    {3.240969941905, -1.537383177570, -0.498610760293},
    {-0.969243636281, 1.875967501508, 0.041555057407},
    {0.055630079697, -0.203976958889, 1.056971514243},
};
/* the reference white: XYZ of linear RGB (1, 1, 1) (the row sums above) */
static const double WHITE[3] = {0.9504559270516717, 1.0, 1.0890577507598784};

#define FLIP_QC 0.7
#define FLIP_QF 0.5
#define FLIP_PC 0.4
#define FLIP_PT 0.95
#define FLIP_EDGE_W 0.082 /* peak-to-trough of the edge detector, degrees (2 sigma) */

/* the contrast sensitivity functions: (a1, b1, a2, b2) per YCxCz channel */
static const double CSF[3][4] = {
    {1.0, 0.0047, 0.0, 1e-5},    /* achromatic */
    {1.0, 0.0053, 0.0, 1e-5},    /* red-green */
    {34.1, 0.04, 13.5, 0.025},   /* blue-yellow */
};
#define CSF_MAX_B 0.04

/* ---- small helpers -------------------------------------------------------------------------- */

static double ppd_of(const pg_flip_opts *o)
{
    return (o && isfinite(o->ppd) && o->ppd > 0) ? o->ppd : PG_FLIP_DEFAULT_PPD;
}

static double lab_f(double t)
{
    const double d = 6.0 / 29.0;
    return t > d * d * d ? cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
}

/* linear RGB -> Hunt-adjusted L*a*b* */
static void rgb_to_hunt_lab(const double rgb[3], double lab[3])
{
    double f[3];
    for (int i = 0; i < 3; i++) {
        double v = RGB2XYZ[i][0] * rgb[0] + RGB2XYZ[i][1] * rgb[1] + RGB2XYZ[i][2] * rgb[2];
        f[i] = lab_f(v / WHITE[i]);
    }
    double L = 116.0 * f[1] - 16.0;
    lab[0] = L;
    lab[1] = 0.01 * L * 500.0 * (f[0] - f[1]);
    lab[2] = 0.01 * L * 200.0 * (f[1] - f[2]);
}

static double hyab(const double a[3], const double b[3])
{
    double da = a[1] - b[1], db = a[2] - b[2];
    return fabs(a[0] - b[0]) + sqrt(da * da + db * db);
}

/* cmax: the largest colour error, HyAB(green, blue)^qc */
static double flip_cmax(void)
{
    const double g[3] = {0, 1, 0}, b[3] = {0, 0, 1};
    double lg[3], lb[3];
    rgb_to_hunt_lab(g, lg);
    rgb_to_hunt_lab(b, lb);
    return pow(hyab(lg, lb), FLIP_QC);
}

/* ---- separable filtering ---------------------------------------------------------------------- */

typedef struct flip_kernel {
    int r;         /* taps -r..r */
    float *k;      /* 2r+1 weights */
    int shape;     /* FLIP_KERNEL_ANY, or a feature detector (weights summing to 0), applied by
                    * pairs of taps so that a flat region gives exactly 0 in float too (as in exact
                    * arithmetic): FLIP_KERNEL_ODD (k_-j = -k_j): sum_j>0 k_j (s_j - s_-j);
                    * FLIP_KERNEL_EVEN (k_-j = k_j): sum_j>0 k_j ((s_j - s_0) + (s_-j - s_0)) */
} flip_kernel;
enum { FLIP_KERNEL_ANY, FLIP_KERNEL_ODD, FLIP_KERNEL_EVEN };

/* d[x] (+)= weight x the zero-sum kernel k at the samples at[j][x], j = -r..r (at: r + j) */
static void conv_paired(float *d, const float *const *at, uint32_t w, const flip_kernel *k, float weight)
{
    const int r = k->r;
    const float *c = at[r];
    for (int j = 1; j <= r; j++) {
        const float kj = weight * k->k[r + j];
        const float *a = at[r + j], *b = at[r - j];
        if (k->shape == FLIP_KERNEL_ODD)
            for (uint32_t x = 0; x < w; x++) d[x] += kj * (a[x] - b[x]);
        else
            for (uint32_t x = 0; x < w; x++) d[x] += kj * ((a[x] - c[x]) + (b[x] - c[x]));
    }
}

/* rows [y0, y1) of dst = src correlated with k along rows; pad: scratch of w + 2r floats, at: of
 * 2r + 1 pointers */
static void conv_rows(const float *src, float *dst, uint32_t w, uint32_t y0, uint32_t y1, const flip_kernel *k,
                      float *pad, const float **at)
{
    int r = k->r;
    size_t n = (size_t)w + 2 * (size_t)r;
    for (uint32_t y = y0; y < y1; y++) {
        const float *s = src + (size_t)y * w;
        float *d = dst + (size_t)y * w;
        for (size_t i = 0; i < n; i++) {
            long x = (long)i - r;
            pad[i] = s[x < 0 ? 0 : (x >= (long)w ? (long)w - 1 : x)];
        }
        for (uint32_t x = 0; x < w; x++) d[x] = 0.0f;
        if (k->shape != FLIP_KERNEL_ANY) {
            for (int j = 0; j <= 2 * r; j++) at[j] = pad + j;
            conv_paired(d, at, w, k, 1.0f);
            continue;
        }
        for (int j = 0; j <= 2 * r; j++) {
            float kj = k->k[j];
            const float *p = pad + j;
            for (uint32_t x = 0; x < w; x++) d[x] += kj * p[x];
        }
    }
}

/* rows [y0, y1) of dst = src (h rows) correlated with k along columns (replicated borders);
 * dst += weight * result when accumulate, else dst = weight * result; at: scratch of 2r + 1 pointers */
static void conv_cols(const float *src, float *dst, uint32_t w, uint32_t h, uint32_t y0, uint32_t y1,
                      const flip_kernel *k, float weight, bool accumulate, const float **at)
{
    int r = k->r;
    for (uint32_t y = y0; y < y1; y++) {
        float *d = dst + (size_t)y * w;
        if (!accumulate)
            for (uint32_t x = 0; x < w; x++) d[x] = 0.0f;
        for (int j = -r; j <= r; j++) {
            long yy = (long)y + j;
            yy = yy < 0 ? 0 : (yy >= (long)h ? (long)h - 1 : yy);
            at[j + r] = src + (size_t)yy * w;
        }
        if (k->shape != FLIP_KERNEL_ANY) {
            conv_paired(d, at, w, k, weight);
            continue;
        }
        for (int j = 0; j <= 2 * r; j++) {
            const float *s = at[j];
            float kj = weight * k->k[j];
            for (uint32_t x = 0; x < w; x++) d[x] += kj * s[x];
        }
    }
}

/* the 1D Gaussian exp(-pi^2 (x/ppd)^2 / b) over -r..r, normalised to sum 1; returns its raw sum */
static double csf_kernel(double b, double ppd, flip_kernel *k)
{
    double sum = 0.0;
    for (int i = -k->r; i <= k->r; i++) {
        double x = i / ppd;
        double v = exp(-M_PI * M_PI * x * x / b);
        k->k[i + k->r] = (float)v;
        sum += v;
    }
    for (int i = 0; i <= 2 * k->r; i++) k->k[i] = (float)(k->k[i] / sum);
    return sum;
}

/* positive weights to sum 1, negative ones to -1 */
static void normalise_signed(flip_kernel *k)
{
    double pos = 0.0, neg = 0.0;
    for (int i = 0; i <= 2 * k->r; i++) {
        if (k->k[i] > 0) pos += k->k[i];
        else neg -= k->k[i];
    }
    for (int i = 0; i <= 2 * k->r; i++) {
        if (k->k[i] > 0 && pos > 0) k->k[i] = (float)(k->k[i] / pos);
        else if (k->k[i] < 0 && neg > 0) k->k[i] = (float)(k->k[i] / neg);
    }
}

/* the feature kernels: g (sum 1), its first derivative -x g and second (x^2/s^2 - 1) g */
static void feature_kernels(double ppd, flip_kernel *g, flip_kernel *d1, flip_kernel *d2)
{
    double sd = 0.5 * FLIP_EDGE_W * ppd, sum = 0.0;
    for (int i = -g->r; i <= g->r; i++) {
        double v = exp(-(double)i * i / (2.0 * sd * sd));
        g->k[i + g->r] = (float)v;
        d1->k[i + g->r] = (float)(-i * v);
        d2->k[i + g->r] = (float)(((double)i * i / (sd * sd) - 1.0) * v);
        sum += v;
    }
    for (int i = 0; i <= 2 * g->r; i++) g->k[i] = (float)(g->k[i] / sum);
    normalise_signed(d1);
    normalise_signed(d2);
}

/* ---- the LDR-FLIP core ------------------------------------------------------------------------ */

#define FLIP_MAX_THREADS 64
#define FLIP_MIN_BAND_ROWS 16 /* fewer rows a thread are not worth one */

/* a thread's rows [y0, y1) and its scratch for the filters */
typedef struct flip_band {
    uint32_t y0, y1;
    float *pad;           /* row scratch (conv_rows) */
    const float **at;     /* a filter's 2r + 1 source rows (conv_rows, conv_cols) */
} flip_band;

typedef struct flip_ctx {
    uint32_t w, h;
    double cmax;
    flip_kernel csf[3][2];   /* per channel: the two Gaussians (the second unused when a2 = 0) */
    float csf_w[3][2];       /* their weights in the normalised 2D kernel */
    flip_kernel fg, fd1, fd2; /* feature kernels */
    uint32_t bands;
    flip_band *band;
    float *plane[2][5];       /* per image: Y, Cx, Cz planes, then edge and point strengths */
    float *tmp[3];            /* scratch planes */
    float *kbuf;
} flip_ctx;

static void ctx_free(flip_ctx *c)
{
    for (uint32_t i = 0; c->band && i < c->bands; i++) {
        free(c->band[i].pad);
        free(c->band[i].at);
    }
    free(c->band);
    for (int i = 0; i < 2; i++)
        for (int p = 0; p < 5; p++) free(c->plane[i][p]);
    for (int i = 0; i < 3; i++) free(c->tmp[i]);
    free(c->kbuf);
    memset(c, 0, sizeof *c);
}

static void ctx_kernels(flip_ctx *c, double ppd, int rc, int rf)
{
    float *kb = c->kbuf;
    for (int ch = 0; ch < 3; ch++) {
        double total = 0.0, part[2];
        for (int t = 0; t < 2; t++) {
            flip_kernel *k = &c->csf[ch][t];
            k->r = rc;
            k->k = kb;
            kb += 2 * rc + 1;
            double a = CSF[ch][2 * t], b = CSF[ch][2 * t + 1];
            double s = csf_kernel(b, ppd, k);
            /* 2D sum of a sqrt(pi/b) g(x) g(y) */
            part[t] = a * sqrt(M_PI / b) * s * s;
            total += part[t];
        }
        for (int t = 0; t < 2; t++) c->csf_w[ch][t] = (float)(part[t] / total);
    }
    flip_kernel *fk[3] = {&c->fg, &c->fd1, &c->fd2};
    for (int i = 0; i < 3; i++) {
        fk[i]->r = rf;
        fk[i]->k = kb;
        kb += 2 * rf + 1;
    }
    feature_kernels(ppd, &c->fg, &c->fd1, &c->fd2);
    c->fd1.shape = FLIP_KERNEL_ODD;
    c->fd2.shape = FLIP_KERNEL_EVEN;
}

/* how many threads: opts' count, or one per online CPU; at most one per FLIP_MIN_BAND_ROWS rows */
static uint32_t flip_threads(const pg_flip_opts *o, uint32_t h)
{
    long t = o && o->threads ? (long)o->threads : sysconf(_SC_NPROCESSORS_ONLN);
    long most = (long)(h / FLIP_MIN_BAND_ROWS);
    if (t > most) t = most;
    if (t > FLIP_MAX_THREADS) t = FLIP_MAX_THREADS;
    return t < 1 ? 1 : (uint32_t)t;
}

static pg_result ctx_init(flip_ctx *c, uint32_t w, uint32_t h, const pg_flip_opts *o, pg_error *err)
{
    double ppd = ppd_of(o);
    memset(c, 0, sizeof *c);
    c->w = w;
    c->h = h;
    c->cmax = flip_cmax();
    int rc = (int)ceil(3.0 * sqrt(CSF_MAX_B / (2.0 * M_PI * M_PI)) * ppd);
    int rf = (int)ceil(3.0 * 0.5 * FLIP_EDGE_W * ppd);
    if (rc < 1) rc = 1;
    if (rf < 1) rf = 1;
    if (rc > 1 << 20 || rf > 1 << 20)
        return pg_fail(err, PG_ERR_INVALID_ARG, "FLIP: ppd %g gives a filter radius too large", ppd);
    size_t n = (size_t)w * h, rmax = (size_t)(rc > rf ? rc : rf);
    c->bands = flip_threads(o, h);
    c->band = calloc(c->bands, sizeof *c->band);
    c->kbuf = malloc((6 * (2 * (size_t)rc + 1) + 3 * (2 * (size_t)rf + 1)) * sizeof(float));
    bool ok = c->band && c->kbuf;
    for (uint32_t i = 0; ok && i < c->bands; i++) {
        flip_band *b = &c->band[i];
        b->y0 = (uint32_t)((uint64_t)h * i / c->bands);
        b->y1 = (uint32_t)((uint64_t)h * (i + 1) / c->bands);
        b->pad = malloc(((size_t)w + 2 * rmax) * sizeof(float));
        b->at = malloc((2 * rmax + 1) * sizeof *b->at);
        ok = b->pad && b->at;
    }
    for (int i = 0; i < 2; i++)
        for (int p = 0; p < 5; p++) ok = ok && (c->plane[i][p] = malloc(n * sizeof(float)));
    for (int i = 0; i < 3; i++) ok = ok && (c->tmp[i] = malloc(n * sizeof(float)));
    if (!ok) {
        ctx_free(c);
        return pg_fail(err, PG_ERR_OOM, "FLIP: out of memory for a %ux%u image", w, h);
    }
    ctx_kernels(c, ppd, rc, rf);
    return PG_OK;
}

/* ---- steps on bands of rows ------------------------------------------------------------------- */

/* what a step works on (each step reads the fields it needs) */
typedef struct flip_step {
    int i;                    /* image */
    const flip_kernel *k;     /* rows, cols: the filter, its weight, and whether the column pass adds to */
    float weight;             /* what is in out (an earlier Gaussian of the same CSF) */
    bool add;
    const float *in;          /* rows, cols: source plane; ycxcz: linear RGB (3 floats a pixel) */
    float *out;               /* rows, cols: destination plane */
    const float *src[2];      /* tone_map: the two clean images */
    float *dst[2];            /* tone_map: their tone-mapped copies; combine, max_into: the maps */
    double scale;             /* tone_map: 2^exposure */
} flip_step;

typedef void (*flip_step_fn)(flip_ctx *c, const flip_band *b, const flip_step *s);

typedef struct flip_job {
    flip_ctx *c;
    const flip_band *b;
    const flip_step *s;
    flip_step_fn fn;
} flip_job;

static void *flip_job_run(void *p)
{
    flip_job *j = p;
    j->fn(j->c, j->b, j->s);
    return NULL;
}

/* fn on every band, in parallel; returns when all are done (a band whose thread cannot be started
 * runs on this one) */
static void flip_run(flip_ctx *c, flip_step_fn fn, const flip_step *s)
{
    pthread_t th[FLIP_MAX_THREADS];
    bool started[FLIP_MAX_THREADS] = {false};
    flip_job jobs[FLIP_MAX_THREADS];
    for (uint32_t i = 1; i < c->bands; i++) {
        jobs[i] = (flip_job){c, &c->band[i], s, fn};
        started[i] = pthread_create(&th[i], NULL, flip_job_run, &jobs[i]) == 0;
    }
    fn(c, &c->band[0], s);
    for (uint32_t i = 1; i < c->bands; i++) {
        if (started[i]) pthread_join(th[i], NULL);
        else fn(c, &c->band[i], s);
    }
}

/* linear RGB (3 floats a pixel, in [0, 1]) -> the Y, Cx, Cz planes of image i */
static void step_ycxcz(flip_ctx *c, const flip_band *b, const flip_step *s)
{
    float *Y = c->plane[s->i][0], *Cx = c->plane[s->i][1], *Cz = c->plane[s->i][2];
    for (size_t p = (size_t)b->y0 * c->w; p < (size_t)b->y1 * c->w; p++) {
        const float *v = s->in + 3 * p;
        double xyz[3];
        for (int k = 0; k < 3; k++)
            xyz[k] = (RGB2XYZ[k][0] * v[0] + RGB2XYZ[k][1] * v[1] + RGB2XYZ[k][2] * v[2]) / WHITE[k];
        Y[p] = (float)(116.0 * xyz[1] - 16.0);
        Cx[p] = (float)(500.0 * (xyz[0] - xyz[1]));
        Cz[p] = (float)(200.0 * (xyz[1] - xyz[2]));
    }
}

/* out = in filtered by k along rows */
static void step_rows(flip_ctx *c, const flip_band *b, const flip_step *s)
{
    conv_rows(s->in, s->out, c->w, b->y0, b->y1, s->k, b->pad, b->at);
}

/* out (+)= weight x in filtered by k along columns */
static void step_cols(flip_ctx *c, const flip_band *b, const flip_step *s)
{
    conv_cols(s->in, s->out, c->w, c->h, b->y0, b->y1, s->k, s->weight, s->add, b->at);
}

static void run_rows(flip_ctx *c, const float *in, float *out, const flip_kernel *k)
{
    flip_step s = {.k = k, .in = in, .out = out};
    flip_run(c, step_rows, &s);
}

static void run_cols(flip_ctx *c, const float *in, float *out, const flip_kernel *k, float weight, bool add)
{
    flip_step s = {.k = k, .weight = weight, .add = add, .in = in, .out = out};
    flip_run(c, step_cols, &s);
}

/* the achromatic channel Y / Yn in [0, 1] of image i into tmp[2] */
static void step_feat_y(flip_ctx *c, const flip_band *b, const flip_step *s)
{
    float *y = c->tmp[2];
    for (size_t p = (size_t)b->y0 * c->w; p < (size_t)b->y1 * c->w; p++) y[p] = (c->plane[s->i][0][p] + 16.0f) / 116.0f;
}

/* edge y and point y from the rows filtered by g (tmp[0]), and the strengths: the length of the
 * (x, y) responses */
static void step_feat_strengths(flip_ctx *c, const flip_band *b, const flip_step *s)
{
    float *e = c->plane[s->i][3], *pt = c->plane[s->i][4], *q = c->tmp[1];
    size_t p0 = (size_t)b->y0 * c->w, p1 = (size_t)b->y1 * c->w;
    conv_cols(c->tmp[0], q, c->w, c->h, b->y0, b->y1, &c->fd1, 1.0f, false, b->at);
    for (size_t p = p0; p < p1; p++) e[p] = sqrtf(e[p] * e[p] + q[p] * q[p]);
    conv_cols(c->tmp[0], q, c->w, c->h, b->y0, b->y1, &c->fd2, 1.0f, false, b->at);
    for (size_t p = p0; p < p1; p++) pt[p] = sqrtf(pt[p] * pt[p] + q[p] * q[p]);
}

/* edge and point strengths of image i from its (unfiltered) achromatic channel */
static void features(flip_ctx *c, int i)
{
    flip_step s = {.i = i};
    float *y = c->tmp[2], *a = c->tmp[0];
    flip_run(c, step_feat_y, &s);
    run_rows(c, y, a, &c->fd1);
    run_cols(c, a, c->plane[i][3], &c->fg, 1.0f, false); /* edge x */
    run_rows(c, y, a, &c->fd2);
    run_cols(c, a, c->plane[i][4], &c->fg, 1.0f, false); /* point x */
    run_rows(c, y, a, &c->fg);
    flip_run(c, step_feat_strengths, &s);
}

/* the filtered channel (tmp[1]) back into its plane s->out (its rows are no longer read) */
static void step_store(flip_ctx *c, const flip_band *b, const flip_step *s)
{
    size_t p0 = (size_t)b->y0 * c->w;
    memcpy(s->out + p0, c->tmp[1] + p0, ((size_t)b->y1 * c->w - p0) * sizeof(float));
}

/* filter the Y, Cx, Cz planes of image i with the CSFs (in place) */
static void csf_filter(flip_ctx *c, int i)
{
    for (int ch = 0; ch < 3; ch++) {
        bool any = false;
        for (int t = 0; t < 2; t++) {
            if (CSF[ch][2 * t] == 0.0) continue;
            run_rows(c, c->plane[i][ch], c->tmp[0], &c->csf[ch][t]);
            run_cols(c, c->tmp[0], c->tmp[1], &c->csf[ch][t], c->csf_w[ch][t], any);
            any = true;
        }
        flip_step s = {.out = c->plane[i][ch]};
        flip_run(c, step_store, &s);
    }
}

/* the filtered YCxCz planes of image i -> clamped linear RGB -> Hunt-adjusted L*a*b* (in place) */
static void step_hunt_lab(flip_ctx *c, const flip_band *b, const flip_step *s)
{
    float *P0 = c->plane[s->i][0], *P1 = c->plane[s->i][1], *P2 = c->plane[s->i][2];
    for (size_t p = (size_t)b->y0 * c->w; p < (size_t)b->y1 * c->w; p++) {
        double yy = (P0[p] + 16.0) / 116.0;
        double xyz[3] = {(yy + P1[p] / 500.0) * WHITE[0], yy * WHITE[1], (yy - P2[p] / 200.0) * WHITE[2]};
        double rgb[3], lab[3];
        for (int k = 0; k < 3; k++) {
            double v = XYZ2RGB[k][0] * xyz[0] + XYZ2RGB[k][1] * xyz[1] + XYZ2RGB[k][2] * xyz[2];
            rgb[k] = v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v);
        }
        rgb_to_hunt_lab(rgb, lab);
        P0[p] = (float)lab[0];
        P1[p] = (float)lab[1];
        P2[p] = (float)lab[2];
    }
}

static double redistribute(double e, double cmax)
{
    double pccmax = FLIP_PC * cmax;
    double v = e < pccmax ? (FLIP_PT / pccmax) * e : FLIP_PT + (e - pccmax) / (cmax - pccmax) * (1.0 - FLIP_PT);
    return v > 1.0 ? 1.0 : v;
}

/* the per-pixel FLIP of the two images' Lab planes and feature strengths into dst[0] */
static void step_combine(flip_ctx *c, const flip_band *b, const flip_step *s)
{
    float *map = s->dst[0];
    for (size_t p = (size_t)b->y0 * c->w; p < (size_t)b->y1 * c->w; p++) {
        double lt[3] = {c->plane[0][0][p], c->plane[0][1][p], c->plane[0][2][p]};
        double lr[3] = {c->plane[1][0][p], c->plane[1][1][p], c->plane[1][2][p]};
        double ec = redistribute(pow(hyab(lt, lr), FLIP_QC), c->cmax);
        double de = fabs((double)c->plane[0][3][p] - c->plane[1][3][p]);
        double dp = fabs((double)c->plane[0][4][p] - c->plane[1][4][p]);
        double ef = pow((de > dp ? de : dp) / sqrt(2.0), FLIP_QF);
        map[p] = (float)pow(ec, 1.0 - ef);
    }
}

/* LDR-FLIP of two linear RGB images (3 floats a pixel, in [0, 1]); map: w*h floats */
static void flip_linear(flip_ctx *c, const float *test_rgb, const float *ref_rgb, float *map)
{
    const float *src[2] = {test_rgb, ref_rgb};
    for (int i = 0; i < 2; i++) {
        flip_step s = {.i = i, .in = src[i]};
        flip_run(c, step_ycxcz, &s);
        features(c, i);
        csf_filter(c, i);
        flip_run(c, step_hunt_lab, &s);
    }
    flip_step s = {.dst = {map, NULL}};
    flip_run(c, step_combine, &s);
}

static pg_result check_args(const void *a, const void *b, uint32_t w, uint32_t h, const char *what, pg_error *err)
{
    if (!a || !b)
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s: missing image (%s is NULL)", what, a ? "reference" : "test");
    if (w == 0 || h == 0) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: empty image %ux%u", what, w, h);
    if ((uint64_t)w * h > ((uint64_t)1 << 40))
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s: image %ux%u too large", what, w, h);
    return PG_OK;
}

static double map_mean(const float *map, size_t n)
{
    double s = 0.0;
    for (size_t p = 0; p < n; p++) s += map[p];
    return s / (double)n;
}

pg_result pg_flip_ldr(const uint8_t *test_rgba8, const uint8_t *ref_rgba8, uint32_t w, uint32_t h,
                      const pg_flip_opts *o, float *map_out, double *mean_out, pg_error *err)
{
    pg_result r = check_args(test_rgba8, ref_rgba8, w, h, "LDR-FLIP", err);
    if (r != PG_OK) return r;
    size_t n = (size_t)w * h;
    float lut[256];
    for (int i = 0; i < 256; i++) {
        double x = i / 255.0;
        lut[i] = (float)(x <= 0.04045 ? x / 12.92 : pow((x + 0.055) / 1.055, 2.4));
    }
    flip_ctx c;
    r = ctx_init(&c, w, h, o, err);
    if (r != PG_OK) return r;
    float *rgb[2] = {malloc(n * 3 * sizeof(float)), malloc(n * 3 * sizeof(float))};
    float *map = map_out ? map_out : malloc(n * sizeof(float));
    if (!rgb[0] || !rgb[1] || !map) {
        r = pg_fail(err, PG_ERR_OOM, "LDR-FLIP: out of memory for a %ux%u image", w, h);
    } else {
        const uint8_t *src[2] = {test_rgba8, ref_rgba8};
        for (int i = 0; i < 2; i++)
            for (size_t p = 0; p < n; p++)
                for (int k = 0; k < 3; k++) rgb[i][3 * p + k] = lut[src[i][4 * p + k]];
        flip_linear(&c, rgb[0], rgb[1], map);
        if (mean_out) *mean_out = map_mean(map, n);
    }
    if (map != map_out) free(map);
    free(rgb[0]);
    free(rgb[1]);
    ctx_free(&c);
    return r;
}

/* ---- HDR-FLIP ------------------------------------------------------------------------------- */

/* the ACES fit (Narkowicz) as HDR-FLIP uses it: the 0.6 pre-exposure folded into the coefficients */
static const double ACES_K[6] = {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0.0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};

static double aces(double x)
{
    double num = ACES_K[0] * x * x + ACES_K[1] * x + ACES_K[2];
    double den = ACES_K[3] * x * x + ACES_K[4] * x + ACES_K[5];
    double v = isinf(x) ? 1.0 : num / den;
    return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v);
}

/* the x > 0 where the tone mapper gives t */
static double aces_inverse(double t)
{
    double a = ACES_K[0] - t * ACES_K[3], b = ACES_K[1] - t * ACES_K[4], c = ACES_K[2] - t * ACES_K[5];
    return (-b + sqrt(b * b - 4.0 * a * c)) / (2.0 * a);
}

/* the k-th smallest of v[0..n) (reorders v) */
static float select_kth(float *v, size_t n, size_t k)
{
    size_t lo = 0, hi = n - 1;
    while (lo < hi) {
        float pivot = v[lo + (hi - lo) / 2];
        size_t i = lo, j = hi;
        while (i <= j) {
            while (v[i] < pivot) i++;
            while (v[j] > pivot) j--;
            if (i <= j) {
                float t = v[i];
                v[i] = v[j];
                v[j] = t;
                i++;
                if (j == 0) break;
                j--;
            }
        }
        if (k <= j) hi = j;
        else if (k >= i) lo = i;
        else return v[k];
    }
    return v[k];
}

/* the median of v[0..n), n > 0 (reorders v) */
static double median(float *v, size_t n)
{
    size_t k = n / 2;
    double hi = select_kth(v, n, k);
    if (n % 2) return hi;
    /* v[0..k) now holds the k smallest: the largest of them is the lower middle value */
    float lo = v[0];
    for (size_t i = 1; i < k; i++) lo = v[i] > lo ? v[i] : lo;
    return 0.5 * (lo + hi);
}

/* start and stop exposures from the reference's luminances lum[0..n) (nonnegative; reorders lum) */
static void exposures(float *lum, size_t n, double *start, double *stop)
{
    float ymax = 0.0f;
    for (size_t p = 0; p < n; p++) ymax = lum[p] > ymax ? lum[p] : ymax;
    *start = *stop = 0.0;
    if (!(ymax > 0.0f)) return;
    double x85 = aces_inverse(0.85);
    *start = log2(x85 / ymax);
    double ymed = median(lum, n);
    if (!(ymed > 0.0)) { /* more than half black: the median of the positive values */
        size_t m = 0;
        for (size_t p = 0; p < n; p++)
            if (lum[p] > 0.0f) lum[m++] = lum[p];
        ymed = median(lum, m);
    }
    *stop = log2(x85 / ymed);
}

/* clean copies (3 floats a pixel: nonnegative, non-finite pixels black) of an RGBA32F image */
static uint64_t hdr_clean(const float *src, float *dst, size_t n)
{
    uint64_t bad = 0;
    for (size_t p = 0; p < n; p++) {
        const float *s = src + 4 * p;
        bool fin = isfinite(s[0]) && isfinite(s[1]) && isfinite(s[2]);
        bad += !fin;
        for (int k = 0; k < 3; k++) dst[3 * p + k] = fin && s[k] > 0.0f ? s[k] : 0.0f;
    }
    return bad;
}

/* both clean images scaled by 2^exposure and tone mapped (3 floats a pixel) */
static void step_tone_map(flip_ctx *c, const flip_band *b, const flip_step *s)
{
    for (int k = 0; k < 2; k++)
        for (size_t i = 3 * (size_t)b->y0 * c->w; i < 3 * (size_t)b->y1 * c->w; i++)
            s->dst[k][i] = (float)aces(s->scale * s->src[k][i]);
}

/* dst[0] = max(dst[0], dst[1]) per pixel */
static void step_max_into(flip_ctx *c, const flip_band *b, const flip_step *s)
{
    float *m = s->dst[0];
    const float *v = s->dst[1];
    for (size_t p = (size_t)b->y0 * c->w; p < (size_t)b->y1 * c->w; p++) m[p] = v[p] > m[p] ? v[p] : m[p];
}

typedef struct hdr_bufs {
    float *clean[2], *tm[2], *map, *ldr;
} hdr_bufs;

static void hdr_free(hdr_bufs *b, float *map_out)
{
    for (int i = 0; i < 2; i++) {
        free(b->clean[i]);
        free(b->tm[i]);
    }
    if (b->map != map_out) free(b->map);
    free(b->ldr);
}

pg_result pg_flip_hdr(const float *test_rgba32f, const float *ref_rgba32f, uint32_t w, uint32_t h,
                      const pg_flip_opts *o, float *map_out, pg_flip_hdr_stats *stats, pg_error *err)
{
    pg_result r = check_args(test_rgba32f, ref_rgba32f, w, h, "HDR-FLIP", err);
    if (r != PG_OK) return r;
    size_t n = (size_t)w * h;
    flip_ctx c;
    r = ctx_init(&c, w, h, o, err);
    if (r != PG_OK) return r;
    hdr_bufs b = {0};
    for (int i = 0; i < 2; i++) {
        b.clean[i] = malloc(3 * n * sizeof(float));
        b.tm[i] = malloc(3 * n * sizeof(float));
    }
    b.map = map_out ? map_out : malloc(n * sizeof(float));
    b.ldr = malloc(n * sizeof(float));
    if (!b.clean[0] || !b.clean[1] || !b.tm[0] || !b.tm[1] || !b.map || !b.ldr) {
        hdr_free(&b, map_out);
        ctx_free(&c);
        return pg_fail(err, PG_ERR_OOM, "HDR-FLIP: out of memory for a %ux%u image", w, h);
    }
    pg_flip_hdr_stats st = {0};
    st.nonfinite_test = hdr_clean(test_rgba32f, b.clean[0], n);
    st.nonfinite_ref = hdr_clean(ref_rgba32f, b.clean[1], n);
    /* the reference's luminance, in the map's buffer until the first exposure overwrites it */
    for (size_t p = 0; p < n; p++) {
        const float *v = b.clean[1] + 3 * p;
        double y = 0.2126 * v[0] + 0.7152 * v[1] + 0.0722 * v[2];
        b.ldr[p] = (float)(y < FLT_MAX ? y : FLT_MAX);
    }
    exposures(b.ldr, n, &st.start_exposure, &st.stop_exposure);
    double span = st.stop_exposure - st.start_exposure;
    double count = ceil(span);
    st.exposures = count > 2.0 ? (uint32_t)count : 2;
    double step = span / (st.exposures - 1);
    for (uint32_t e = 0; e < st.exposures; e++) {
        flip_step ts = {.src = {b.clean[0], b.clean[1]}, .dst = {b.tm[0], b.tm[1]},
                        .scale = exp2(st.start_exposure + e * step)};
        flip_run(&c, step_tone_map, &ts);
        flip_linear(&c, b.tm[0], b.tm[1], e == 0 ? b.map : b.ldr);
        flip_step ms = {.dst = {b.map, b.ldr}};
        if (e > 0) flip_run(&c, step_max_into, &ms);
    }
    st.mean = map_mean(b.map, n);
    if (stats) *stats = st;
    hdr_free(&b, map_out);
    ctx_free(&c);
    return PG_OK;
}
