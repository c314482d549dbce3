/* test_numeric.c - the numerical core of clustered shading on the CPU, against double-precision
 * references (no GPU). passes/cluster_math.c computes the same float32 formulas in the same order as
 * shaders/cluster.glsl, octahedral.glsl and depth_reconstruct.glsl, so these bounds are what the
 * shaders compute up to the GPU's own float precision.
 *
 *   1. octahedral normals: ~4M directions (Fibonacci sphere, random, axes, the fold planes x=0,
 *      y=0, z=0 with signed zeros, within 1e-7 rad of +-Z): max angular error per bit depth
 *      (float, unorm16 = the G-buffer format; snorm16, unorm12/10/8, snorm8 for reference), no
 *      NaN, unit results; every code of a 4096x4096 grid of unorm16 codes decodes to a unit vector.
 *   2. position from depth: D32 depth value vs stored float32 view depth, near 1e-3..1, far
 *      1e2..1e6; table of max relative errors; per-sample bounds (formula below).
 *   3. exponential slices: extremes (0, negative, +-Inf, NaN, near, far, cleared depth), near/far
 *      ratios 1..1e60, monotonic sweeps, boundaries vs pg_slice_depth and vs the exact formula.
 *   4. cluster AABBs contain every sampled point of their cluster (exact frustum piece and the
 *      float assignment rule); sphere test has no false negatives against the exact distance from
 *      the sphere centre to the frustum piece (false-positive rate reported).
 *   5. attenuation (shaders/lighting.glsl) vs double: bounded by intensity / dmin^2, finite,
 *      error bound.
 *   6. the pbr BRDF (renderer/common/brdf.c, the twin of lighting.glsl's pg_light_pbr): the closed
 *      forms of its terms (D(N.H = 1) = 1 / (pi a^2), D = 1/pi at a = 1, V = 1/4 head-on, Schlick's
 *      ends), GGX normalization (the projected microfacet area: integral of D (N.H) over the
 *      hemisphere = 1, Walter et al. 2007), energy (the specular lobe with F = 1 reflects <= 1 of
 *      the light, Heitz 2014's height-correlated Smith), reciprocity, float twin vs double, the
 *      lightcut's bound pi D V N.L <= 0.5 / a^3, finite results at the extremes.
 * Prints every measured number next to its bound. Runs in a few seconds. */
#include "brdf.h"
#include "cluster_math.h"
#include "frame.h"
#include "scene.h"
#include "test_util.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* ------------------------------------------------------------------------------------------ */
/* stated bounds                                                                              */

/* Octahedral, max angular error (radians) of decode(encode(n)) over all tested unit directions.
 * float32 (unquantized): a few ulp of the [-1,1] coordinates (measured 3.0e-7). */
#define OCT_FLOAT_MAX_ERR 5e-7
/* b-bit unorm per axis: the code moves e by at most half a step, 1/(2^b - 1), per axis. The map
 * stretches most at the face centres (|n_i| = 1/sqrt(3)), where a move (d, d) in e turns the
 * direction by sqrt(18) * d; so the supremum is sqrt(18) / (2^b - 1): unorm16 6.474e-5 rad
 * (0.0037 deg), unorm8 1.664e-2 rad (0.95 deg), reached where both coordinates round a tie
 * (n = (+-1,+-1,+-1)/sqrt(3) in the lower hemisphere: e = +-2/3 -> 10922.5 / 65535). Bounds: the
 * supremum plus 1% for the float arithmetic. */
#define OCT_UNORM16_MAX_ERR (4.242640687 / 65535.0 * 1.01)
#define OCT_UNORM8_MAX_ERR (4.242640687 / 255.0 * 1.01)
/* Decoded vectors are unit to float rounding. */
#define OCT_UNIT_TOL 1e-6

/* Depth reconstruction. EPS32 = 2^-24 (float ulp of 1, i.e. 2 * unit roundoff).
 * (b) position from a stored float32 view depth: relative error <= 1e-6 (measured ~2e-7). */
#define DEPTH_STORED_MAX_REL 1e-6
/* (a) from a D32 depth value. Rounding the depth d to float moves it by <= 2^-25 and 1/z is linear
 * in d, so the view depth moves by eps = 2^-25 * z * (1/near - 1/far) relative; the arithmetic adds
 * a few ulp. Per-sample bound:  rel <= K * q / (1 - K * q) + C * EPS32,  q = EPS32 * z * (1/near -
 * 1/far), asserted wherever K*q <= 0.5 (beyond it a D32 value cannot resolve the depth at all).
 *   view depth (pg_view_depth_from_depth):        K = 0.5 (quantization alone), C = 4
 *   position via inv_proj (pg_view_pos_from_depth): K = 4 (w = (d + P10)/P14 cancels near d = 1 and
 *       the float projection entries are rounded: a few more roundings of size 1/near), C = 4
 *   position via the view depth (pg_view_pos_from_view_depth(pg_view_depth_from_depth)): K = 0.5,
 *       C = 6. */
#define DEPTH_K_VIEW 0.5
#define DEPTH_C_VIEW 4.0
#define DEPTH_K_INVPROJ 4.0
#define DEPTH_C_INVPROJ 4.0
#define DEPTH_K_VIA_VIEW 0.5
#define DEPTH_C_VIA_VIEW 6.0
#define EPS32 5.9604644775390625e-08 /* 2^-24 */

/* Slices. The float slice math carries an absolute error of about one ulp of log2(far/near) (a
 * few ulp of values up to lr = log2(far/near)), i.e. a relative depth error growing with lr. One
 * tolerance, relative to the depth, for all three slice properties:
 *   SLICE_TOL(lr) = (SLICE_TOL_K * lr + SLICE_TOL_C) * 2^-24
 * - a float slice index may differ from the exact floor(Z * ln(d/n) / ln(f/n)) only for depths
 *   within SLICE_TOL of an exact boundary (measured 0.7-1.0 * lr * 2^-24);
 * - pg_slice_depth(k) is within SLICE_TOL of the exact near*(far/near)^(k/Z) (measured <= 0.7 *
 *   lr * 2^-24 + 1 ulp);
 * - pg_cluster_slice(pg_slice_depth(k) * (1 + tol)) == k and (1 - tol) -> k-1 for every interior k
 *   (measured <= 1.4 * lr * 2^-24, at least 2 ulp).
 * E.g. far/near 1e4 (lr 13.3): 1.8e-6; 1e9 (lr 29.9): 3.8e-6; the brief's 1e-6 holds for
 * far/near <= 2^10.5. */
#define SLICE_TOL_K 2.0
#define SLICE_TOL_C 4.0
#define SLICE_TOL(lr) ((SLICE_TOL_K * ((lr) > 0 ? (lr) : 0) + SLICE_TOL_C) * EPS32)

/* Attenuation: |att_float - att_double| <= ATT_ABS_K * 2^-24 / max(d^2, dmin^2) (absolute, in
 * units of the unattenuated 1/d^2: the falloff 1 - (d/R)^4 cancels as d -> R, so no relative bound
 * on att itself holds there; measured 7.6 ulp). Equivalently the relative error is
 * <= ATT_ABS_K * 2^-24 / falloff, e.g. <= ATT_REL_BOUND (2e-6) where falloff >= 0.5. */
#define ATT_ABS_K 16.0
#define ATT_REL_BOUND 2e-6

/* ------------------------------------------------------------------------------------------ */
/* helpers                                                                                    */

static uint64_t rng_state = 0x243F6A8885A308D3ull;
static uint64_t rng_u64(void)
{
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
static double rng_unit(void) { return (double)(rng_u64() >> 11) * (1.0 / 9007199254740992.0); }
static double rng_range(double a, double b) { return a + (b - a) * rng_unit(); }
static double rng_log(double a, double b) { return a * pow(b / a, rng_unit()); }
static uint32_t rng_below(uint32_t n) { return (uint32_t)(rng_unit() * n); }

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

static bool finite3(pg_vec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }

/* angle between the float input direction (normalized in double) and the decoded direction */
static double angle_err(pg_vec3 a, pg_vec3 b)
{
    double ax = a.x, ay = a.y, az = a.z, bx = b.x, by = b.y, bz = b.z;
    double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
    double s = sqrt(cx * cx + cy * cy + cz * cz), c = ax * bx + ay * by + az * bz;
    return atan2(s, c);
}

/* ------------------------------------------------------------------------------------------ */
/* 1. octahedral                                                                              */

enum { Q_FLOAT, Q_UNORM16, Q_SNORM16, Q_UNORM12, Q_UNORM10, Q_UNORM8, Q_SNORM8, Q_COUNT };
static const char *q_name[Q_COUNT] = {"float32", "unorm16 (pack)", "snorm16", "unorm12",
                                      "unorm10", "unorm8",         "snorm8"};
static const int q_bits[Q_COUNT] = {32, 16, 16, 12, 10, 8, 8};

static float q_unorm(float e, int bits)
{
    float m = (float)((1u << bits) - 1u);
    float c = e * 0.5f + 0.5f;
    c = c > 0.0f ? (c < 1.0f ? c : 1.0f) : 0.0f;
    return roundf(c * m) / m * 2.0f - 1.0f;
}
static float q_snorm(float e, int bits)
{
    float m = (float)((1u << (bits - 1)) - 1u);
    float c = e > -1.0f ? (e < 1.0f ? e : 1.0f) : -1.0f;
    return roundf(c * m) / m;
}

typedef struct oct_stats {
    double max_err[Q_COUNT], sum_err[Q_COUNT];
    pg_vec3 worst[Q_COUNT];
    long n, bad_nan, bad_unit;
} oct_stats;

static void oct_one(oct_stats *st, pg_vec3 n)
{
    pg_vec2 e = pg_oct_encode(n);
    pg_vec3 r[Q_COUNT];
    r[Q_FLOAT] = pg_oct_decode(e);
    r[Q_UNORM16] = pg_oct_unpack_unorm16(pg_oct_pack_unorm16(n));
    r[Q_SNORM16] = pg_oct_decode((pg_vec2){q_snorm(e.x, 16), q_snorm(e.y, 16)});
    r[Q_UNORM12] = pg_oct_decode((pg_vec2){q_unorm(e.x, 12), q_unorm(e.y, 12)});
    r[Q_UNORM10] = pg_oct_decode((pg_vec2){q_unorm(e.x, 10), q_unorm(e.y, 10)});
    r[Q_UNORM8] = pg_oct_decode((pg_vec2){q_unorm(e.x, 8), q_unorm(e.y, 8)});
    r[Q_SNORM8] = pg_oct_decode((pg_vec2){q_snorm(e.x, 8), q_snorm(e.y, 8)});
    st->n++;
    if (!(isfinite(e.x) && isfinite(e.y) && fabsf(e.x) <= 1.0f && fabsf(e.y) <= 1.0f)) st->bad_nan++;
    for (int q = 0; q < Q_COUNT; q++) {
        if (!finite3(r[q])) {
            st->bad_nan++;
            continue;
        }
        double len = sqrt((double)r[q].x * r[q].x + (double)r[q].y * r[q].y + (double)r[q].z * r[q].z);
        if (fabs(len - 1.0) > OCT_UNIT_TOL) st->bad_unit++;
        double a = angle_err(n, r[q]);
        st->sum_err[q] += a;
        if (a > st->max_err[q] || isnan(a)) {
            st->max_err[q] = a;
            st->worst[q] = n;
        }
    }
}

static pg_vec3 dir_d(double x, double y, double z)
{
    double l = sqrt(x * x + y * y + z * z);
    pg_vec3 v = {(float)(x / l), (float)(y / l), (float)(z / l)};
    return v;
}

static void test_octahedral(void)
{
    double t0 = now_s();
    oct_stats st;
    memset(&st, 0, sizeof st);
    long counts[6] = {0};
    /* Fibonacci sphere */
    const long n_fib = 2000000;
    const double golden = M_PI * (3.0 - sqrt(5.0));
    for (long i = 0; i < n_fib; i++) {
        double z = 1.0 - (2.0 * i + 1.0) / n_fib, r = sqrt(1.0 - z * z), ph = golden * i;
        oct_one(&st, dir_d(r * cos(ph), r * sin(ph), z));
    }
    counts[0] = st.n;
    /* uniform random (normalized Gaussians) */
    for (long i = 0; i < 1200000; i++) {
        double u1 = rng_unit() + 1e-300, u2 = rng_unit(), u3 = rng_unit() + 1e-300, u4 = rng_unit();
        double g0 = sqrt(-2 * log(u1)) * cos(2 * M_PI * u2), g1 = sqrt(-2 * log(u1)) * sin(2 * M_PI * u2);
        double g2 = sqrt(-2 * log(u3)) * cos(2 * M_PI * u4);
        oct_one(&st, dir_d(g0, g1, g2));
    }
    counts[1] = st.n;
    /* the 6 axes and 8 diagonals, with both signed zeros */
    const float zs[2] = {0.0f, -0.0f};
    for (int a = 0; a < 3; a++)
        for (int s = -1; s <= 1; s += 2)
            for (int z0 = 0; z0 < 2; z0++)
                for (int z1 = 0; z1 < 2; z1++) {
                    float v[3];
                    v[a] = (float)s;
                    v[(a + 1) % 3] = zs[z0];
                    v[(a + 2) % 3] = zs[z1];
                    pg_vec3 n = {v[0], v[1], v[2]};
                    oct_one(&st, n);
                    pg_vec3 r = pg_oct_decode(pg_oct_encode(n));
                    CHECK_MSG(r.x == n.x && r.y == n.y && r.z == n.z,
                              "axis (%g,%g,%g) -> (%g,%g,%g) must round-trip exactly", n.x, n.y,
                              n.z, r.x, r.y, r.z);
                }
    for (int i = 0; i < 8; i++)
        oct_one(&st, dir_d(i & 1 ? -1 : 1, i & 2 ? -1 : 1, i & 4 ? -1 : 1));
    counts[2] = st.n;
    /* the fold planes x = 0, y = 0, z = 0 (octahedron edges and the hemisphere seam), with +-0 */
    for (long i = 0; i < 300000; i++) {
        double ph = rng_range(0, 2 * M_PI);
        float c = (float)cos(ph), s = (float)sin(ph), zero = (i & 1) ? -0.0f : 0.0f;
        int plane = (int)(i % 3);
        pg_vec3 n = plane == 0 ? (pg_vec3){zero, c, s} : plane == 1 ? (pg_vec3){c, zero, s}
                                                                    : (pg_vec3){c, s, zero};
        oct_one(&st, n);
    }
    counts[3] = st.n;
    /* within 1e-7 rad of +Z and -Z (and exactly at them) */
    for (long i = 0; i < 200000; i++) {
        double th = 1e-7 * rng_unit() * (i % 7 == 0 ? 1e-6 : 1.0), ph = rng_range(0, 2 * M_PI);
        double z = (i & 1) ? -cos(th) : cos(th);
        oct_one(&st, dir_d(sin(th) * cos(ph), sin(th) * sin(ph), z));
    }
    counts[4] = st.n;
    /* near the octahedron's edges and vertices in every octant: two coordinates tiny */
    for (long i = 0; i < 300000; i++) {
        double eps = pow(10.0, -rng_range(1, 9));
        double v[3] = {eps * rng_range(-1, 1), eps * rng_range(-1, 1), eps * rng_range(-1, 1)};
        int a = (int)(i % 3);
        v[a] = (i & 4) ? -1.0 : 1.0;
        if (i & 8) v[(a + 1) % 3] = rng_range(-1, 1); /* near an edge rather than a vertex */
        oct_one(&st, dir_d(v[0], v[1], v[2]));
    }
    counts[5] = st.n;
    printf("octahedral: %ld directions (fibonacci %ld, random %ld, axes/diagonals %ld, fold planes "
           "%ld, near +-Z %ld, near vertices/edges %ld) in %.2f s\n",
           st.n, counts[0], counts[1] - counts[0], counts[2] - counts[1], counts[3] - counts[2],
           counts[4] - counts[3], counts[5] - counts[4], now_s() - t0);
    printf("  %-16s %5s %14s %12s %14s\n", "encoding", "bits", "max err (rad)", "(deg)",
           "mean err (rad)");
    for (int q = 0; q < Q_COUNT; q++)
        printf("  %-16s %2d+%-2d %14.3e %12.3e %14.3e   worst at (%.9g, %.9g, %.9g)\n", q_name[q],
               q_bits[q], q_bits[q], st.max_err[q], st.max_err[q] * 180 / M_PI,
               st.sum_err[q] / st.n, st.worst[q].x, st.worst[q].y, st.worst[q].z);
    printf("  bounds: float32 %.1e, unorm16 %.1e, unorm8 %.1e rad; |len-1| <= %.0e; NaN: %ld, "
           "non-unit: %ld\n",
           OCT_FLOAT_MAX_ERR, OCT_UNORM16_MAX_ERR, OCT_UNORM8_MAX_ERR, OCT_UNIT_TOL, st.bad_nan,
           st.bad_unit);
    CHECK_MSG(st.max_err[Q_FLOAT] <= OCT_FLOAT_MAX_ERR, "float32 %.3e > %.1e", st.max_err[Q_FLOAT],
              OCT_FLOAT_MAX_ERR);
    CHECK_MSG(st.max_err[Q_UNORM16] <= OCT_UNORM16_MAX_ERR, "unorm16 %.3e > %.1e",
              st.max_err[Q_UNORM16], OCT_UNORM16_MAX_ERR);
    CHECK_MSG(st.max_err[Q_UNORM8] <= OCT_UNORM8_MAX_ERR, "unorm8 %.3e > %.1e", st.max_err[Q_UNORM8],
              OCT_UNORM8_MAX_ERR);
    CHECK(st.bad_nan == 0);
    CHECK(st.bad_unit == 0);

    /* degenerate inputs: defined results */
    const pg_vec3 degenerate[] = {{0, 0, 0},           {-0.0f, -0.0f, -0.0f}, {NAN, 0, 0},
                                  {0, NAN, 1},         {INFINITY, 0, 0},      {1, -INFINITY, 0},
                                  {1e-45f, 0, -1e-45f}, {1e30f, 1e30f, -1e30f}};
    for (size_t i = 0; i < sizeof degenerate / sizeof degenerate[0]; i++) {
        pg_vec3 n = degenerate[i];
        pg_vec2 e = pg_oct_encode(n);
        pg_vec3 r = pg_oct_decode(e), r16 = pg_oct_unpack_unorm16(pg_oct_pack_unorm16(n));
        double len = sqrt((double)r.x * r.x + (double)r.y * r.y + (double)r.z * r.z);
        double len16 = sqrt((double)r16.x * r16.x + (double)r16.y * r16.y + (double)r16.z * r16.z);
        CHECK_MSG(isfinite(e.x) && isfinite(e.y) && finite3(r) && finite3(r16) &&
                      fabs(len - 1) <= OCT_UNIT_TOL && fabs(len16 - 1) <= OCT_UNIT_TOL,
                  "degenerate input %zu -> e (%g,%g) r (%g,%g,%g)", i, e.x, e.y, r.x, r.y, r.z);
    }
    pg_vec2 ez = pg_oct_encode((pg_vec3){0, 0, 0});
    pg_vec3 rz = pg_oct_decode(ez);
    CHECK(ez.x == 0 && ez.y == 0 && rz.x == 0 && rz.y == 0 && rz.z == 1);
    pg_vec2 en = pg_oct_encode((pg_vec3){NAN, NAN, NAN});
    CHECK(en.x == 0 && en.y == 0);
    /* tiny but valid vectors still encode their direction (L1 normalization, no length needed) */
    pg_vec3 rt = pg_oct_decode(pg_oct_encode((pg_vec3){1e-40f, 0, -1e-40f}));
    CHECK_MSG(fabsf(rt.x - 0.70710678f) < 1e-6f && fabsf(rt.z + 0.70710678f) < 1e-6f,
              "denormal direction -> (%g,%g,%g)", rt.x, rt.y, rt.z);
    /* decode of out-of-range / non-finite codes */
    const float odd[] = {-1e30f, -2.0f, -1.0f, -0.5f, -0.0f, 0.0f, 0.5f, 1.0f, 2.0f, 1e30f,
                         INFINITY, -INFINITY, NAN};
    int odd_bad = 0;
    for (size_t i = 0; i < sizeof odd / sizeof odd[0]; i++)
        for (size_t j = 0; j < sizeof odd / sizeof odd[0]; j++) {
            pg_vec3 r = pg_oct_decode((pg_vec2){odd[i], odd[j]});
            double len = sqrt((double)r.x * r.x + (double)r.y * r.y + (double)r.z * r.z);
            if (!finite3(r) || fabs(len - 1) > OCT_UNIT_TOL) odd_bad++;
        }
    CHECK_MSG(odd_bad == 0, "%d out-of-range codes decode to non-unit vectors", odd_bad);

    /* every code of a 4096 x 4096 grid of unorm16 codes (0 and 65535 included) */
    double t1 = now_s();
    long grid_bad = 0;
    double grid_max_dev = 0;
    for (uint32_t i = 0; i < 4096; i++) {
        uint32_t ux = (uint32_t)(((uint64_t)i * 65535u + 2047u) / 4095u);
        for (uint32_t j = 0; j < 4096; j++) {
            uint32_t uy = (uint32_t)(((uint64_t)j * 65535u + 2047u) / 4095u);
            pg_vec3 r = pg_oct_unpack_unorm16(ux | (uy << 16));
            double len = sqrt((double)r.x * r.x + (double)r.y * r.y + (double)r.z * r.z);
            double dev = fabs(len - 1);
            if (!finite3(r) || !(dev <= OCT_UNIT_TOL)) grid_bad++;
            if (dev > grid_max_dev) grid_max_dev = dev;
        }
    }
    printf("  4096x4096 unorm16 code grid: %ld not unit/finite, max |len-1| %.2e (%.2f s)\n",
           grid_bad, grid_max_dev, now_s() - t1);
    CHECK(grid_bad == 0);

    /* packUnorm2x16 semantics */
    CHECK(pg_pack_unorm2x16(0.0f, 1.0f) == 0xFFFF0000u);
    CHECK(pg_pack_unorm2x16(-5.0f, 7.0f) == 0xFFFF0000u);
    CHECK(pg_pack_unorm2x16(NAN, 0.25f) == (uint32_t)16384u << 16); /* 16383.75 -> 16384 */
    CHECK(pg_pack_unorm2x16(1.0f / 65535.0f, 0.49f / 65535.0f) == 1u);
    float ux, uy;
    pg_unpack_unorm2x16(0xFFFF0000u, &ux, &uy);
    CHECK(ux == 0.0f && uy == 1.0f);
    long pack_bad = 0;
    for (uint32_t v = 0; v < 65536; v++) {
        float x, y;
        pg_unpack_unorm2x16(v | ((65535u - v) << 16), &x, &y);
        if (pg_pack_unorm2x16(x, y) != (v | ((65535u - v) << 16))) pack_bad++;
    }
    CHECK_MSG(pack_bad == 0, "%ld unorm16 values do not survive unpack -> pack", pack_bad);
}

/* ------------------------------------------------------------------------------------------ */
/* 2. position from depth                                                                     */

typedef struct depth_row {
    double max_view, max_invproj, max_via_view, max_stored;
    double worst_ratio_view, worst_ratio_invproj, worst_ratio_via_view; /* err / bound */
    double limit_zn; /* largest z/near whose view depth error stays <= 1e-3 */
    long asserted, beyond, nonfinite_invproj;
} depth_row;

static double depth_bound(double K, double C, double q)
{
    return K * q / (1.0 - K * q) + C * EPS32;
}

static double rel3(pg_vec3 p, const double ref[3])
{
    double dx = p.x - ref[0], dy = p.y - ref[1], dz = p.z - ref[2];
    return sqrt(dx * dx + dy * dy + dz * dz) / sqrt(ref[0] * ref[0] + ref[1] * ref[1] + ref[2] * ref[2]);
}

static void test_depth(void)
{
    double t0 = now_s();
    const float nears[] = {1e-3f, 1e-2f, 0.1f, 1.0f};
    const float fars[] = {1e2f, 1e4f, 1e6f};
    const float uvs[] = {0.5f / 1920.0f, 0.1f, 0.37f, 0.5f, 0.5f + 0.5f / 1080.0f, 0.73f, 0.9f,
                         1.0f - 0.5f / 1920.0f};
    const int n_uv = (int)(sizeof uvs / sizeof uvs[0]);
    const int n_z = 4000;
    printf("position from depth (fov 60, aspect 16:9, %d view depths log-spaced in [near, far] x "
           "%d uv):\n",
           n_z, n_uv * n_uv);
    printf("  standard Z only (reversed Z is not offered); max relative error:\n");
    printf("  %-7s %-7s %-8s | %-11s %-11s %-11s | %-11s | %-12s %s\n", "near", "far", "far/near",
           "(a) z", "(a) pos/inv", "(a) pos/z", "(b) stored", "z/near @1e-3", "beyond bound range");
    for (size_t ni = 0; ni < sizeof nears / sizeof nears[0]; ni++)
        for (size_t fi = 0; fi < sizeof fars / sizeof fars[0]; fi++) {
            float n = nears[ni], f = fars[fi];
            pg_camera cam = {.position = {0, 0, 0}, .target = {0, 0, -1}, .up = {0, 1, 0},
                             .fov_y_deg = 60, .near_z = n, .far_z = f, .aspect = 16.0f / 9.0f};
            float proj[16], inv[16];
            pg_camera_proj(&cam, proj);
            bool inv_ok = pg_mat4_invert(proj, inv);
            CHECK(inv_ok);
            if (!inv_ok) continue;
            depth_row row;
            memset(&row, 0, sizeof row);
            double dn = n, df = f, inv_nf = 1.0 / dn - 1.0 / df;
            double limit_ok = 0;
            bool limit_broken = false;
            for (int zi = 0; zi < n_z; zi++) {
                double z = dn * pow(df / dn, (double)zi / (n_z - 1));
                if (zi == n_z - 1) z = df;
                /* D32 value: exact in double, rounded to float as a depth buffer stores it */
                double depth_d = df * (z - dn) / (z * (df - dn));
                float depth = (float)depth_d;
                double q = EPS32 * z * inv_nf;
                double zmax_err = 0;
                for (int ui = 0; ui < n_uv; ui++)
                    for (int vi = 0; vi < n_uv; vi++) {
                        pg_vec2 uv = {uvs[ui], uvs[vi]};
                        double ndx = (double)uv.x * 2 - 1, ndy = (double)uv.y * 2 - 1;
                        double ref[3] = {ndx / proj[0] * z, ndy / proj[5] * z, -z};
                        float zr = pg_view_depth_from_depth(depth, n, f);
                        double e_view = fabs(zr - z) / z;
                        pg_vec3 p_inv = pg_view_pos_from_depth(uv, depth, inv);
                        double e_inv = finite3(p_inv) ? rel3(p_inv, ref) : INFINITY;
                        pg_vec3 p_via = pg_view_pos_from_view_depth(uv, zr, proj);
                        double e_via = rel3(p_via, ref);
                        pg_vec3 p_st = pg_view_pos_from_view_depth(uv, (float)z, proj);
                        double e_st = rel3(p_st, ref);
                        if (!finite3(p_inv)) row.nonfinite_invproj++;
                        CHECK_MSG(isfinite(zr) && zr >= n * (1 - 1e-6) && zr <= f,
                                  "view depth %g from depth %.9g outside [near, far]", zr, depth);
                        if (e_view > row.max_view) row.max_view = e_view;
                        if (e_inv > row.max_invproj) row.max_invproj = e_inv;
                        if (e_via > row.max_via_view) row.max_via_view = e_via;
                        if (e_st > row.max_stored) row.max_stored = e_st;
                        if (e_view > zmax_err) zmax_err = e_view;
                        CHECK_MSG(e_st <= DEPTH_STORED_MAX_REL, "stored view depth: rel %.3e", e_st);
                        /* per-sample bounds where the depth buffer still resolves the depth */
                        if (DEPTH_K_INVPROJ * q <= 0.5) {
                            double b_view = depth_bound(DEPTH_K_VIEW, DEPTH_C_VIEW, q);
                            double b_inv = depth_bound(DEPTH_K_INVPROJ, DEPTH_C_INVPROJ, q);
                            double b_via = depth_bound(DEPTH_K_VIA_VIEW, DEPTH_C_VIA_VIEW, q);
                            row.asserted++;
                            if (e_view / b_view > row.worst_ratio_view) row.worst_ratio_view = e_view / b_view;
                            if (e_inv / b_inv > row.worst_ratio_invproj) row.worst_ratio_invproj = e_inv / b_inv;
                            if (e_via / b_via > row.worst_ratio_via_view) row.worst_ratio_via_view = e_via / b_via;
                            CHECK_MSG(e_view <= b_view, "n %g f %g z %g: view depth rel %.3e > %.3e", n, f, z, e_view, b_view);
                            CHECK_MSG(e_inv <= b_inv, "n %g f %g z %g uv (%g,%g): pos/inv_proj rel %.3e > %.3e", n, f, z, uv.x, uv.y, e_inv, b_inv);
                            CHECK_MSG(e_via <= b_via, "n %g f %g z %g: pos via view depth rel %.3e > %.3e", n, f, z, e_via, b_via);
                        } else {
                            row.beyond++;
                        }
                    }
                if (!limit_broken) {
                    if (zmax_err <= 1e-3) limit_ok = z / dn;
                    else limit_broken = true;
                }
            }
            /* depth 1 (cleared or far plane) -> far exactly, depth 0 -> near */
            CHECK(pg_view_depth_from_depth(1.0f, n, f) == f);
            CHECK(fabsf(pg_view_depth_from_depth(0.0f, n, f) - n) <= n * 2e-7f);
            char lim[32];
            if (limit_broken) snprintf(lim, sizeof lim, "%.2e", limit_ok);
            else snprintf(lim, sizeof lim, ">= %.0e", df / dn);
            printf("  %-7g %-7g %-8.0e | %-11.3e %-11.3e %-11.3e | %-11.3e | %-12s %ld of %ld\n", n,
                   f, df / dn, row.max_view, row.max_invproj, row.max_via_view, row.max_stored, lim,
                   row.beyond, row.beyond + row.asserted);
            if (row.nonfinite_invproj)
                printf("    pos via inv_proj: %ld non-finite (depth 1 with far/near > 2^24: w = 0)\n",
                       row.nonfinite_invproj);
            printf("    worst error / bound over %ld bounded samples: z %.4f, pos/inv %.4f, pos/z %.4f\n",
                   row.asserted, row.worst_ratio_view, row.worst_ratio_invproj, row.worst_ratio_via_view);
        }
    printf("  (a) bound per sample: K*q/(1-K*q) + C*2^-24, q = 2^-24 * z * (1/near - 1/far): z K=%.1f "
           "C=%.0f, pos/inv K=%.1f C=%.0f, pos/z K=%.1f C=%.0f; asserted where %.0f*q <= 0.5\n",
           DEPTH_K_VIEW, DEPTH_C_VIEW, DEPTH_K_INVPROJ, DEPTH_C_INVPROJ, DEPTH_K_VIA_VIEW,
           DEPTH_C_VIA_VIEW, DEPTH_K_INVPROJ);
    printf("  (b) bound %.0e relative; %.2f s\n", DEPTH_STORED_MAX_REL, now_s() - t0);

    /* odd depth values stay in [near, far] */
    const float odd[] = {-1.0f, -0.0f, 0.0f, 1e-30f, 0.5f, 0.99999994f, 1.0f, 2.0f, INFINITY,
                         -INFINITY, NAN};
    for (size_t i = 0; i < sizeof odd / sizeof odd[0]; i++) {
        float z = pg_view_depth_from_depth(odd[i], 1e-3f, 1e6f);
        CHECK_MSG(isfinite(z) && z >= 1e-3f * 0.999999f && z <= 1e6f, "depth %g -> view depth %g",
                  odd[i], z);
    }
    CHECK(pg_view_depth_from_depth(NAN, 0.1f, 100.0f) == 100.0f);
}

/* ------------------------------------------------------------------------------------------ */
/* 3. exponential slices                                                                      */

static void test_slices(void)
{
    double t0 = now_s();
    typedef struct { float n, f; } clip;
    const clip clips[] = {{1e-3f, 1e6f}, {1.0f, 1e9f}, {0.1f, 1000.0f}, {0.01f, 100.0f},
                          {1.0f, 2.0f}, {5.0f, 5.0000005f}, {1e-30f, 1e30f},
                          {1.17549435e-38f, 3.40282347e+38f}};
    const uint32_t grids[] = {1, 2, 3, 16, 24, 32, 64, 128, 4096};
    const size_t n_clips = sizeof clips / sizeof clips[0], n_grids = sizeof grids / sizeof grids[0];
    long range_bad = 0, mono_bad = 0, mismatch = 0, extremes = 0, samples = 0, roundtrip_bad = 0;
    printf("slices: Z in {1, 2, 3, 16, 24, 32, 64, 128, 4096}; relative to the depth, per clip:\n");
    printf("  %-22s %6s | %-14s %-14s %-14s | %s\n", "near..far", "lr", "slice!=exact", "slice depth",
           "boundary trip", "tolerance SLICE_TOL(lr)");
    for (size_t ci = 0; ci < n_clips; ci++) {
        float n = clips[ci].n, f = clips[ci].f;
        double dn = n, df = f, lr = log2(df / dn), tol = SLICE_TOL(lr);
        double c_mis = 0, c_dep = 0, c_rt = 0;
        for (size_t gi = 0; gi < n_grids; gi++) {
            uint32_t Z = grids[gi];
            /* extremes: expect 0 (bottom) or Z-1 (top) */
            const struct { float d; int top; } ex[] = {
                {0.0f, 0},     {-0.0f, 0},    {-1.0f, 0},    {-INFINITY, 0}, {NAN, 0},
                {n * 0.5f, 0}, {n, 0},        {-FLT_MAX, 0}, {1e-45f, 0},    {f, 1},
                {2.0f * f, 1}, {INFINITY, 1}, {FLT_MAX, 1},
                {pg_view_depth_from_depth(1.0f, n, f), 1}, /* cleared depth 1 -> far */
            };
            for (size_t i = 0; i < sizeof ex / sizeof ex[0]; i++) {
                uint32_t k = pg_cluster_slice(ex[i].d, n, f, Z);
                uint32_t want = ex[i].top ? Z - 1 : 0;
                extremes++;
                CHECK_MSG(k == want, "near %g far %g Z %u depth %g: slice %u, want %u", n, f, Z,
                          ex[i].d, k, want);
            }
            float above = nextafterf(n, INFINITY), below = nextafterf(f, 0.0f);
            if (above < f) { /* not when far is the float right after near */
                uint32_t ka = pg_cluster_slice(above, n, f, Z), kb = pg_cluster_slice(below, n, f, Z);
                CHECK_MSG(ka == 0 || lr / Z < 4 * tol, "near %g Z %u: just above near -> %u", n, Z, ka);
                CHECK_MSG(kb == Z - 1, "near %g far %g Z %u: just below far -> %u", n, f, Z, kb);
            }
            CHECK(pg_slice_depth(0, n, f, Z) == n && pg_slice_depth(Z, n, f, Z) == f &&
                  pg_slice_depth(Z + 5, n, f, Z) == f);
            /* fine sweep from near/2 to 2*far: in range, monotonic, = exact away from boundaries */
            const int n_sweep = Z >= 1024 ? 200000 : 40000;
            uint32_t prev = 0;
            float prev_d = 0;
            for (int i = 0; i <= n_sweep; i++) {
                double dd = dn * 0.5 * pow(4.0 * df / dn, (double)i / n_sweep);
                float d = (float)dd;
                if (!isfinite(d)) d = FLT_MAX;
                if (d < prev_d) continue;
                uint32_t k = pg_cluster_slice(d, n, f, Z);
                samples++;
                if (k >= Z) range_bad++;
                if (k < prev) mono_bad++;
                prev = k;
                prev_d = d;
                if (d > n && d < f && Z > 1) {
                    double ke = floor(log(d / dn) / log(df / dn) * Z);
                    if (ke > Z - 1) ke = Z - 1;
                    if ((double)k != ke) { /* relative distance to the exact boundary between */
                        double b = dn * pow(df / dn, fmax((double)k, ke) / Z);
                        double rel = fabs(d - b) / b;
                        mismatch++;
                        if (rel > c_mis) c_mis = rel;
                        if (fabs((double)k - ke) > 1 || rel > tol)
                            CHECK_MSG(false, "near %g far %g Z %u depth %.9g: slice %u, exact %.0f",
                                      n, f, Z, d, k, ke);
                    }
                }
            }
            /* boundaries: pg_slice_depth vs exact, and the round trip through pg_cluster_slice */
            float prev_b = n;
            for (uint32_t k = 1; k < Z; k++) {
                float b = pg_slice_depth(k, n, f, Z);
                double be = exp(log(dn) + (log(df) - log(dn)) * k / Z);
                double rel = fabs(b - be) / be;
                if (rel > c_dep) c_dep = rel;
                CHECK_MSG(b >= prev_b, "slice depth not monotonic at k %u", k);
                CHECK_MSG(rel <= tol, "near %g far %g Z %u: slice depth %u rel err %.3e", n, f, Z, k, rel);
                prev_b = b;
                if (lr / Z < 4 * tol) continue; /* slices thinner than the tolerance */
                /* the smallest relative steps from b that land in k (up) and in k-1 (down) */
                float up = b, down = b;
                for (int st = 0; st < 1000 && pg_cluster_slice(up, n, f, Z) < k; st++)
                    up = nextafterf(up, INFINITY);
                for (int st = 0; st < 1000 && pg_cluster_slice(down, n, f, Z) >= k; st++)
                    down = nextafterf(down, 0.0f);
                double gap = fmax(fabs((double)up - b) / b, fabs((double)down - b) / b);
                if (gap > c_rt) c_rt = gap;
                float hi = (float)(b * (1.0 + tol)), lo = (float)(b * (1.0 - tol));
                if (pg_cluster_slice(hi, n, f, Z) != k || pg_cluster_slice(lo, n, f, Z) != k - 1) {
                    roundtrip_bad++;
                    CHECK_MSG(false, "near %g far %g Z %u k %u: slice(%.9g) = %u, slice(%.9g) = %u",
                              n, f, Z, k, hi, pg_cluster_slice(hi, n, f, Z), lo,
                              pg_cluster_slice(lo, n, f, Z));
                }
            }
        }
        char name[64];
        snprintf(name, sizeof name, "%.8g..%.8g", n, f);
        printf("  %-22s %6.1f | %-14.2e %-14.2e %-14.2e | %.2e\n", name, lr, c_mis, c_dep, c_rt, tol);
    }
    /* invalid clip parameters and degenerate grids */
    const float bad_clip[][2] = {{0, 100}, {-1, 100}, {1, 1}, {2, 1}, {NAN, 100}, {1, NAN},
                                 {1, INFINITY}, {1e-40f, 1}, {INFINITY, INFINITY}};
    for (size_t i = 0; i < sizeof bad_clip / sizeof bad_clip[0]; i++) {
        const float ds[] = {-1, 0, 0.5f, 1, 50, 1e30f, INFINITY, NAN};
        for (size_t j = 0; j < sizeof ds / sizeof ds[0]; j++)
            CHECK_MSG(pg_cluster_slice(ds[j], bad_clip[i][0], bad_clip[i][1], 24) == 0,
                      "invalid clip (%g, %g) depth %g -> slice %u", bad_clip[i][0], bad_clip[i][1],
                      ds[j], pg_cluster_slice(ds[j], bad_clip[i][0], bad_clip[i][1], 24));
        float b = pg_slice_depth(3, bad_clip[i][0], bad_clip[i][1], 24);
        CHECK(b == bad_clip[i][0] || (isnan(b) && isnan(bad_clip[i][0])));
    }
    CHECK(pg_cluster_slice(10.0f, 0.1f, 100.0f, 0) == 0);
    CHECK(pg_cluster_slice(10.0f, 0.1f, 100.0f, 1) == 0);
    printf("  %ld extreme inputs (0, -0, <0, -Inf, NaN, near/2, near, far, 2 far, +Inf, FLT_MAX, "
           "denormal, cleared depth), %ld sweep samples: %ld out of [0, Z-1], %ld monotonicity "
           "breaks, %ld differ from exact (all at boundaries), %ld boundary round-trip failures "
           "(%.2f s)\n",
           extremes, samples, range_bad, mono_bad, mismatch, roundtrip_bad, now_s() - t0);
    CHECK(range_bad == 0);
    CHECK(mono_bad == 0);

    /* index, coordinates, sizes */
    pg_uvec3 g = {16, 9, 24};
    CHECK(pg_cluster_index((pg_uvec3){0, 0, 0}, g) == 0);
    CHECK(pg_cluster_index((pg_uvec3){15, 8, 23}, g) == 16 * 9 * 24 - 1);
    CHECK(pg_cluster_index((pg_uvec3){3, 2, 1}, g) == 3 + 16 * (2 + 9 * 1));
    CHECK(pg_cluster_count(g) == 3456);
    pg_vec2 vp = {1920, 1080};
    pg_uvec3 c = pg_cluster_coord((pg_vec2){0.5f, 0.5f}, vp, 0.05f, 0.1f, 100.0f, g);
    CHECK(c.x == 0 && c.y == 0 && c.z == 0);
    c = pg_cluster_coord((pg_vec2){1919.5f, 1079.5f}, vp, 1e9f, 0.1f, 100.0f, g);
    CHECK(c.x == 15 && c.y == 8 && c.z == 23);
    c = pg_cluster_coord((pg_vec2){-3.0f, NAN}, vp, NAN, 0.1f, 100.0f, g);
    CHECK(c.x == 0 && c.y == 0 && c.z == 0);
    c = pg_cluster_coord((pg_vec2){1e30f, INFINITY}, vp, INFINITY, 0.1f, 100.0f, g);
    CHECK(c.x == 15 && c.y == 8 && c.z == 23);
    c = pg_cluster_coord((pg_vec2){120.5f, 119.5f}, vp, 1.0f, 0.1f, 100.0f, g); /* 1920/16 = 120 */
    CHECK(c.x == 1 && c.y == 0);
    c = pg_cluster_coord((pg_vec2){5, 5}, vp, 1.0f, 0.1f, 100.0f, (pg_uvec3){0, 0, 0});
    CHECK(c.x == 0 && c.y == 0 && c.z == 0);
}

/* ------------------------------------------------------------------------------------------ */
/* 4. cluster AABBs and the sphere test                                                       */

typedef struct piece {
    double v[2][4][3]; /* [near/far][corner (x0,y0) (x1,y0) (x1,y1) (x0,y1)][xyz], view space */
} piece;

static void sub3(const double *a, const double *b, double *o)
{
    o[0] = a[0] - b[0];
    o[1] = a[1] - b[1];
    o[2] = a[2] - b[2];
}
static double dot3d(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void cross3d(const double *a, const double *b, double *o)
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}
static double seg_dist(const double *p, const double *a, const double *b)
{
    double ab[3], ap[3];
    sub3(b, a, ab);
    sub3(p, a, ap);
    double l2 = dot3d(ab, ab), t = l2 > 0 ? dot3d(ap, ab) / l2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    double q[3] = {a[0] + ab[0] * t - p[0], a[1] + ab[1] * t - p[1], a[2] + ab[2] * t - p[2]};
    return sqrt(dot3d(q, q));
}

/* exact (double) distance from p to the convex frustum piece; 0 inside */
static double piece_dist(const piece *pc, const double *p)
{
    const double *quads[6][4];
    for (int i = 0; i < 4; i++) {
        quads[0][i] = pc->v[0][i];
        quads[1][i] = pc->v[1][i];
    }
    for (int e = 0; e < 4; e++) {
        quads[2 + e][0] = pc->v[0][e];
        quads[2 + e][1] = pc->v[0][(e + 1) % 4];
        quads[2 + e][2] = pc->v[1][(e + 1) % 4];
        quads[2 + e][3] = pc->v[1][e];
    }
    double cen[3] = {0, 0, 0};
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 4; i++)
            for (int a = 0; a < 3; a++) cen[a] += pc->v[j][i][a] / 8;
    bool inside = true;
    double best = INFINITY;
    for (int fidx = 0; fidx < 6; fidx++) {
        const double *const *q = quads[fidx];
        double e1[3], e2[3], nrm[3];
        sub3(q[1], q[0], e1);
        sub3(q[3], q[0], e2);
        cross3d(e1, e2, nrm);
        double l = sqrt(dot3d(nrm, nrm));
        for (int a = 0; a < 3; a++) nrm[a] /= l;
        double tc[3], tp[3];
        sub3(cen, q[0], tc);
        if (dot3d(nrm, tc) > 0)
            for (int a = 0; a < 3; a++) nrm[a] = -nrm[a]; /* outward */
        sub3(p, q[0], tp);
        double sd = dot3d(nrm, tp);
        if (sd > 0) inside = false;
        /* distance to the face polygon */
        double proj[3] = {p[0] - sd * nrm[0], p[1] - sd * nrm[1], p[2] - sd * nrm[2]};
        int pos = 0, neg = 0;
        for (int i = 0; i < 4; i++) {
            double ed[3], tq[3], cr[3];
            sub3(q[(i + 1) % 4], q[i], ed);
            sub3(proj, q[i], tq);
            cross3d(ed, tq, cr);
            double s = dot3d(cr, nrm);
            if (s > 0) pos++;
            if (s < 0) neg++;
        }
        double d;
        if (pos == 0 || neg == 0) d = fabs(sd);
        else {
            d = INFINITY;
            for (int i = 0; i < 4; i++) {
                double sdist = seg_dist(p, q[i], q[(i + 1) % 4]);
                if (sdist < d) d = sdist;
            }
        }
        if (d < best) best = d;
    }
    return inside ? 0.0 : best;
}

typedef struct cam_setup {
    float proj[16], inv[16];
    float n, f;
    pg_uvec3 grid;
    pg_vec2 vp;
} cam_setup;

static bool random_setup(cam_setup *s)
{
    pg_camera cam = {.position = {0, 0, 0}, .target = {0, 0, -1}, .up = {0, 1, 0}};
    cam.fov_y_deg = (float)rng_range(20, 150);
    cam.aspect = (float)rng_log(0.3, 4.0);
    cam.near_z = (float)rng_log(1e-3, 1.0);
    cam.far_z = (float)(cam.near_z * rng_log(10, 1e7));
    pg_camera_proj(&cam, s->proj);
    if (!pg_mat4_invert(s->proj, s->inv)) return false;
    s->n = cam.near_z;
    s->f = cam.far_z;
    s->grid = (pg_uvec3){1 + rng_below(64), 1 + rng_below(64), 1 + rng_below(128)};
    s->vp = (pg_vec2){(float)(1 + rng_below(4096)), (float)(1 + rng_below(4096))};
    return true;
}

static double exact_boundary(const cam_setup *s, uint32_t k)
{
    if (k == 0) return s->n;
    if (k >= s->grid.z) return s->f;
    return (double)s->n * pow((double)s->f / s->n, (double)k / s->grid.z);
}

static void point_at(const cam_setup *s, double ndx, double ndy, double z, double *o)
{
    o[0] = ndx / s->proj[0] * z;
    o[1] = ndy / s->proj[5] * z;
    o[2] = -z;
}

static bool in_box(const double *p, pg_vec3 mn, pg_vec3 mx)
{
    return p[0] >= mn.x && p[0] <= mx.x && p[1] >= mn.y && p[1] <= mx.y && p[2] >= mn.z && p[2] <= mx.z;
}

/* How far p lies outside the box before its PG_CLUSTER_AABB_PAD growth, relative to the box's
 * largest coordinate magnitude (<= 0: inside the unpadded box). Shows how much of the pad the
 * float rounding actually uses. */
static double unpadded_excursion(const double *p, pg_vec3 mn, pg_vec3 mx)
{
    const double lo[3] = {mn.x, mn.y, mn.z}, hi[3] = {mx.x, mx.y, mx.z};
    double ext = 0;
    for (int a = 0; a < 3; a++) ext = fmax(ext, fmax(fabs(lo[a]), fabs(hi[a])));
    double pad = ext * PG_CLUSTER_AABB_PAD / (1.0 + PG_CLUSTER_AABB_PAD);
    double out = -INFINITY;
    for (int a = 0; a < 3; a++) {
        out = fmax(out, (lo[a] + pad) - p[a]);
        out = fmax(out, p[a] - (hi[a] - pad));
    }
    return out / (ext - pad);
}

static void test_clusters(void)
{
    double t0 = now_s();
    const int n_setups = 400, clusters_per_setup = 40, points_per_cluster = 64;
    const int spheres_per_cluster = 128, grazing_per_cluster = 96;
    long pts = 0, pts_out = 0, assigned = 0, assigned_out = 0;
    long sph = 0, fn = 0, fp = 0, hits = 0, exact_hits = 0, graze = 0, graze_fn = 0, graze_skip = 0;
    double worst_out = 0, pad_used_exact = -INFINITY, pad_used_assigned = -INFINITY;
    for (int si = 0; si < n_setups; si++) {
        cam_setup s;
        if (!random_setup(&s)) {
            CHECK_MSG(false, "setup %d: projection not invertible", si);
            continue;
        }
        /* (1) the float assignment rule: random fragments -> cluster -> inside its box */
        for (int i = 0; i < clusters_per_setup * points_per_cluster / 4; i++) {
            pg_vec2 frag;
            if (i & 1) frag = (pg_vec2){(float)rng_below((uint32_t)s.vp.x) + 0.5f,
                                        (float)rng_below((uint32_t)s.vp.y) + 0.5f};
            else frag = (pg_vec2){(float)rng_range(0, s.vp.x), (float)rng_range(0, s.vp.y)};
            float z;
            if (i & 2) { /* right at a float slice boundary */
                uint32_t k = rng_below(s.grid.z + 1);
                z = pg_slice_depth(k, s.n, s.f, s.grid.z);
                for (int st = (int)rng_below(5); st > 0; st--) z = nextafterf(z, (i & 4) ? INFINITY : 0.0f);
            } else {
                z = (float)rng_log(s.n, s.f);
            }
            if (!(z >= s.n && z <= s.f)) continue;
            pg_uvec3 c = pg_cluster_coord(frag, s.vp, z, s.n, s.f, s.grid);
            pg_vec3 mn, mx;
            pg_cluster_aabb(c, s.grid, s.inv, s.n, s.f, &mn, &mx);
            double p[3];
            point_at(&s, (double)frag.x / s.vp.x * 2 - 1, (double)frag.y / s.vp.y * 2 - 1, z, p);
            assigned++;
            pad_used_assigned = fmax(pad_used_assigned, unpadded_excursion(p, mn, mx));
            if (!in_box(p, mn, mx)) {
                assigned_out++;
                if (assigned_out < 5)
                    fprintf(stderr, "fragment (%g,%g) z %.9g -> cluster (%u,%u,%u) outside its box\n",
                            frag.x, frag.y, z, c.x, c.y, c.z);
            }
        }
        for (int ci = 0; ci < clusters_per_setup; ci++) {
            pg_uvec3 c = {rng_below(s.grid.x), rng_below(s.grid.y), rng_below(s.grid.z)};
            if (ci == 0) c = (pg_uvec3){0, 0, 0};
            if (ci == 1) c = (pg_uvec3){s.grid.x - 1, s.grid.y - 1, s.grid.z - 1};
            pg_vec3 mn, mx;
            pg_cluster_aabb(c, s.grid, s.inv, s.n, s.f, &mn, &mx);
            double x0 = 2.0 * c.x / s.grid.x - 1, x1 = 2.0 * (c.x + 1) / s.grid.x - 1;
            double y0 = 2.0 * c.y / s.grid.y - 1, y1 = 2.0 * (c.y + 1) / s.grid.y - 1;
            double zn = exact_boundary(&s, c.z), zf = exact_boundary(&s, c.z + 1);
            piece pc;
            const double cx[4] = {x0, x1, x1, x0}, cy[4] = {y0, y0, y1, y1};
            for (int j = 0; j < 2; j++)
                for (int i = 0; i < 4; i++) point_at(&s, cx[i], cy[i], j ? zf : zn, pc.v[j][i]);
            /* (2) points of the exact piece (corners, edges, interior) lie in the box */
            double samples[64][3];
            for (int i = 0; i < points_per_cluster; i++) {
                double ux = rng_unit(), uy = rng_unit(), uz = rng_unit();
                if (i < 8) { ux = i & 1; uy = (i >> 1) & 1; uz = (i >> 2) & 1; }
                else if (i < 24) { if (i & 1) ux = (i >> 1) & 1; else uz = (i >> 2) & 1; }
                double z = zn * pow(zf / zn, uz);
                if (uz == 1) z = zf;
                point_at(&s, x0 + (x1 - x0) * ux, y0 + (y1 - y0) * uy, z, samples[i]);
                pts++;
                pad_used_exact = fmax(pad_used_exact, unpadded_excursion(samples[i], mn, mx));
                if (!in_box(samples[i], mn, mx)) {
                    pts_out++;
                    double ext = fmax(fabs(mn.z), fabs(mx.z));
                    double out = 0;
                    const double lo[3] = {mn.x, mn.y, mn.z}, hi[3] = {mx.x, mx.y, mx.z};
                    for (int a = 0; a < 3; a++) {
                        out = fmax(out, lo[a] - samples[i][a]);
                        out = fmax(out, samples[i][a] - hi[a]);
                    }
                    if (out / ext > worst_out) worst_out = out / ext;
                }
            }
            /* (3) grazing spheres: each reaches one sampled point (double distance < r) */
            for (int i = 0; i < grazing_per_cluster; i++) {
                const double *p = samples[rng_below(points_per_cluster)];
                double u[3] = {rng_range(-1, 1), rng_range(-1, 1), rng_range(-1, 1)};
                double ul = sqrt(dot3d(u, u));
                if (ul < 1e-6) continue;
                double scale = fmax(fabs(p[2]), 1e-6);
                float r = (float)(scale * rng_log(1e-6, 10.0));
                double sfac = (i & 1) ? 1.0 - pow(2.0, -(double)(1 + rng_below(40))) : rng_unit();
                pg_vec3 cen = {(float)(p[0] + u[0] / ul * r * sfac), (float)(p[1] + u[1] / ul * r * sfac),
                               (float)(p[2] + u[2] / ul * r * sfac)};
                double dd[3] = {cen.x - p[0], cen.y - p[1], cen.z - p[2]};
                if (!(sqrt(dot3d(dd, dd)) < (double)r)) {
                    graze_skip++; /* the float centre moved out of reach */
                    continue;
                }
                graze++;
                if (!pg_sphere_intersects_aabb(cen, r, mn, mx)) graze_fn++;
            }
            /* (4) random spheres around the cluster vs the exact distance to the piece */
            double ext[3] = {mx.x - mn.x, mx.y - mn.y, mx.z - mn.z};
            double diag = sqrt(dot3d(ext, ext));
            for (int i = 0; i < spheres_per_cluster; i++) {
                pg_vec3 cen = {(float)rng_range(mn.x - ext[0], mx.x + ext[0]),
                               (float)rng_range(mn.y - ext[1], mx.y + ext[1]),
                               (float)rng_range(mn.z - ext[2], mx.z + ext[2])};
                float r = (float)(diag * rng_log(1e-3, 2.0));
                double pd[3] = {cen.x, cen.y, cen.z};
                double dist = piece_dist(&pc, pd);
                bool test = pg_sphere_intersects_aabb(cen, r, mn, mx);
                sph++;
                if (test) hits++;
                if (dist < r) {
                    exact_hits++;
                    if (!test) {
                        fn++;
                        if (fn < 5)
                            fprintf(stderr, "false negative: cluster (%u,%u,%u) dist %.9g r %.9g\n",
                                    c.x, c.y, c.z, dist, r);
                    }
                } else if (test) {
                    fp++;
                }
            }
        }
    }
    printf("cluster AABBs (%d random cameras: fov 20-150, aspect 0.3-4, near 1e-3..1, far/near "
           "10..1e7, grids up to 64x64x128) (%.2f s):\n",
           n_setups, now_s() - t0);
    printf("  exact frustum-piece points outside their box: %ld of %ld (worst %.2e of |z|)\n",
           pts_out, pts, worst_out);
    printf("  fragments assigned by pg_cluster_coord outside their cluster's box: %ld of %ld\n",
           assigned_out, assigned);
    printf("  largest excursion beyond the box before its pad (relative to its largest coordinate): "
           "exact points %.2e, assigned fragments %.2e (pad %.2e)\n",
           pad_used_exact, pad_used_assigned, (double)PG_CLUSTER_AABB_PAD);
    printf("  grazing spheres (reach a sampled point): %ld false negatives of %ld (%ld skipped: the "
           "float centre moved out of reach)\n",
           graze_fn, graze, graze_skip);
    printf("  random spheres vs exact distance to the piece: %ld false negatives of %ld; %ld of %ld "
           "hits are false positives (%.1f%% of hits, AABB looseness, informational)\n",
           fn, sph, fp, hits, hits ? 100.0 * fp / hits : 0.0);
    CHECK(pts_out == 0);
    CHECK(assigned_out == 0);
    CHECK(graze_fn == 0);
    CHECK(fn == 0);
    CHECK(graze > 1000000);

    /* sphere test edge cases */
    pg_vec3 mn = {-1, -1, -1}, mx = {1, 1, 1};
    CHECK(!pg_sphere_intersects_aabb((pg_vec3){0, 0, 0}, 0.0f, mn, mx));
    CHECK(!pg_sphere_intersects_aabb((pg_vec3){0, 0, 0}, -1.0f, mn, mx));
    CHECK(!pg_sphere_intersects_aabb((pg_vec3){0, 0, 0}, NAN, mn, mx));
    CHECK(!pg_sphere_intersects_aabb((pg_vec3){NAN, 0, 0}, 1.0f, mn, mx));
    CHECK(pg_sphere_intersects_aabb((pg_vec3){2, 0, 0}, 1.0f, mn, mx));           /* touching */
    CHECK(!pg_sphere_intersects_aabb((pg_vec3){2.001f, 0, 0}, 1.0f, mn, mx));
    CHECK(pg_sphere_intersects_aabb((pg_vec3){1e30f, 0, 0}, INFINITY, mn, mx));
    CHECK(pg_sphere_intersects_aabb((pg_vec3){0.5f, 0.5f, 0.5f}, 1e-30f, mn, mx)); /* inside */
}

/* ------------------------------------------------------------------------------------------ */
/* 5. attenuation                                                                             */

/* shaders/lighting.glsl pg_accumulate_light_rel's attenuation, float, same order: (d/R)^2 as
 * d^2 * (1/R^2) (1/R^2 capped at FLT_MAX, pg_light_inv_r2), 1/max(d^2, dmin^2) as
 * min((1/d)^2, 1/dmin^2) from one inverse square root (here 1/sqrtf: a GPU's inversesqrt is
 * within a few ulp of it) */
static float att_float(const float L[3], const float P[3], float R, float min_dist)
{
    float Ld[3] = {L[0] - P[0], L[1] - P[1], L[2] - P[2]};
    float d2 = Ld[0] * Ld[0] + Ld[1] * Ld[1] + Ld[2] * Ld[2];
    float R2 = R * R;
    if (!(d2 < R2)) return 0.0f;
    float inv_r2 = 1.0f / R2;
    inv_r2 = inv_r2 < FLT_MAX ? inv_r2 : FLT_MAX;
    float t = d2 * inv_r2;
    float falloff = 1.0f - t * t;
    falloff = falloff > 0.0f ? (falloff < 1.0f ? falloff : 1.0f) : 0.0f;
    float rs = 1.0f / sqrtf(d2);
    float inv_md2 = 1.0f / (min_dist * min_dist);
    return falloff * (rs * rs < inv_md2 ? rs * rs : inv_md2);
}
static double att_double(const float L[3], const float P[3], float R, float min_dist,
                         double *falloff_out, double *denom_out)
{
    double Ld[3] = {(double)L[0] - P[0], (double)L[1] - P[1], (double)L[2] - P[2]};
    double d2 = Ld[0] * Ld[0] + Ld[1] * Ld[1] + Ld[2] * Ld[2];
    double dm = min_dist;
    *denom_out = fmax(d2, dm * dm);
    *falloff_out = 0;
    if (!(d2 < (double)R * R)) return 0.0;
    double x = sqrt(d2) / R;
    double fo = fmin(fmax(1.0 - x * x * x * x, 0.0), 1.0);
    *falloff_out = fo;
    return fo / *denom_out;
}

static void test_attenuation(void)
{
    const float dmin = PG_LIGHT_MIN_DISTANCE;
    const double att_max = 1.0 / ((double)dmin * dmin);
    const float P0[3] = {0, 0, 0};
    /* the extreme cases */
    struct { float L[3], R, intensity; } cases[] = {
        {{0, 0, 0}, 1.0f, 1.0f},                 /* d = 0 */
        {{0, 0, 0}, 0.0f, 1.0f},                 /* R = 0, d = 0 */
        {{1, 0, 0}, 0.0f, 1.0f},                 /* R = 0 */
        {{0, 0, 1e-20f}, 1e6f, 1e6f},            /* R = 1e6, intensity 1e6, on the surface */
        {{0, 1, 0}, 1e6f, 1e6f},
        {{0, 0.999999f, 0}, 1.0f, 1.0f},         /* d just below R */
        {{0, 0, 0.99999994f}, 1.0f, 1.0f},
        {{0, 0, 1.0f}, 1.0f, 1.0f},              /* d = R */
        {{NAN, 0, 0}, 1.0f, 1.0f},
        {{0, 0, 0}, NAN, 1.0f},
        {{INFINITY, 0, 0}, 1.0f, 1.0f},
        {{0, 0, 0}, INFINITY, 1.0f},
        {{1e30f, 0, 0}, 1e38f, 1e6f},
        {{0.005f, 0, 0}, 1e-3f, 1.0f},           /* R < dmin */
    };
    double worst_extreme = 0;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        float a = att_float(cases[i].L, P0, cases[i].R, dmin);
        float contrib = cases[i].intensity * a;
        CHECK_MSG(isfinite(a) && a >= 0 && a <= (float)att_max && isfinite(contrib) &&
                      contrib <= cases[i].intensity / (dmin * dmin),
                  "case %zu: att %g contribution %g", i, a, contrib);
        if (contrib > worst_extreme) worst_extreme = contrib;
    }
    CHECK(att_float(cases[1].L, P0, 0.0f, dmin) == 0.0f);
    CHECK(att_float(cases[7].L, P0, 1.0f, dmin) == 0.0f);
    CHECK(att_float(cases[0].L, P0, 1.0f, dmin) == (float)att_max);
    /* random: relative to the double formula */
    double worst_abs = 0, worst_rel = 0;
    long n = 0, nonfinite = 0;
    for (long i = 0; i < 1000000; i++) {
        float R = (float)rng_log(1e-3, 1e6);
        double dist = R * rng_range(0, 1.2);
        if (i % 5 == 0) dist = R * (1 - rng_log(1e-8, 1e-2));
        if (i % 7 == 0) dist = rng_log(1e-6, 0.02);
        double u[3] = {rng_range(-1, 1), rng_range(-1, 1), rng_range(-1, 1)};
        double ul = sqrt(dot3d(u, u));
        float L[3] = {(float)(u[0] / ul * dist), (float)(u[1] / ul * dist), (float)(u[2] / ul * dist)};
        float a = att_float(L, P0, R, dmin);
        double fo, den;
        double ad = att_double(L, P0, R, dmin, &fo, &den);
        n++;
        if (!isfinite(a) || a < 0 || a > att_max) nonfinite++;
        double err = fabs(a - ad) * den; /* in units of 1/max(d^2, dmin^2) */
        if (err > worst_abs) worst_abs = err;
        if (fo >= 0.5) {
            double rel = fabs(a - ad) / ad;
            if (rel > worst_rel) worst_rel = rel;
        }
    }
    printf("attenuation clamp(1-(d/R)^4,0,1)/max(d^2,dmin^2), dmin %g: extremes max contribution "
           "%.4g (bound intensity/dmin^2 = %.4g for intensity 1e6); %ld random, %ld out of "
           "[0, 1/dmin^2]\n",
           dmin, worst_extreme, 1e6 / ((double)dmin * dmin), n, nonfinite);
    printf("  |float - double| * max(d^2,dmin^2): %.3e = %.2f ulp(1) (bound %.0f); relative where "
           "falloff >= 0.5: %.3e (bound %.0e)\n",
           worst_abs, worst_abs / EPS32, ATT_ABS_K, worst_rel, ATT_REL_BOUND);
    CHECK(nonfinite == 0);
    CHECK(worst_abs <= ATT_ABS_K * EPS32);
    CHECK(worst_rel <= ATT_REL_BOUND);
}

/* ------------------------------------------------------------------------------------------ */
/* 6. the pbr BRDF                                                                             */

/* float twin vs double: relative error of pi f N.L (one light, c = att = 1) where N.L, N.V >= 0.05 */
#define BRDF_TWIN_REL 3e-5
/* energy of the specular lobe with F = 1 (quadrature of a 720 x 720 hemisphere grid): <= 1 + quadrature error */
#define BRDF_ENERGY_TOL 2e-3

static void rand_unit(double o[3])
{
    double z = rng_range(-1, 1), ph = rng_range(0, 2 * M_PI), r = sqrt(1 - z * z);
    o[0] = r * cos(ph);
    o[1] = r * sin(ph);
    o[2] = z;
}

/* a unit vector at angle acos(mu) from N = (0, 0, 1), azimuth ph */
static void dir_mu(double mu, double ph, double o[3])
{
    double s = sqrt(fmax(0, 1 - mu * mu));
    o[0] = s * cos(ph);
    o[1] = s * sin(ph);
    o[2] = mu;
}

/* pi f N.L of the float twin for one channel (c = att = 1, no ambient) */
static float twin_one(const double L[3], const double V[3], const double N[3], float b, float m, float r)
{
    float Lf[3] = {(float)L[0], (float)L[1], (float)L[2]}, Vf[3] = {(float)V[0], (float)V[1], (float)V[2]};
    float Nf[3] = {(float)N[0], (float)N[1], (float)N[2]}, c[3] = {1, 1, 1}, base[3] = {b, b, b}, e[3] = {0, 0, 0};
    float acc[3] = {0, 0, 0}, out[3];
    pg_pbr_light(c, 1.0f, Lf, Nf, Vf, base, m, r, acc);
    pg_pbr_combine(base, m, acc, 0.0f, 1.0f, e, out);
    return out[0];
}

static void test_brdf(void)
{
    printf("pbr BRDF (glTF 2.0 Appendix B: GGX, height-correlated Smith, Schlick):\n");
    /* closed forms */
    const double as[] = {0.01, 0.05, 0.1, 0.3, 0.6, 1.0};
    double worst_cf = 0;
    for (size_t i = 0; i < sizeof as / sizeof as[0]; i++) {
        double a = as[i];
        worst_cf = fmax(worst_cf, fabs(pg_brdf_ggx_d(1, a) * M_PI * a * a - 1));
        worst_cf = fmax(worst_cf, fabs(pg_brdf_smith_v(1, 1, a) - 0.25) * 4);
    }
    for (double t = 0.05; t <= 1.0; t += 0.05) {
        worst_cf = fmax(worst_cf, fabs(pg_brdf_ggx_d(t, 1.0) * M_PI - 1));               /* a = 1: uniform */
        worst_cf = fmax(worst_cf, fabs(pg_brdf_smith_v(t, 0.5, 1.0) * 2 * (t + 0.5) - 1)); /* a = 1: 1/(2(N.L+N.V)) */
    }
    worst_cf = fmax(worst_cf, fabs(pg_brdf_schlick(0.04, 1.0) - 0.04) + fabs(pg_brdf_schlick(0.04, 0.0) - 1.0));
    printf("  closed forms (D(1) = 1/(pi a^2), D = 1/pi and V = 1/(2(N.L+N.V)) at a = 1, V = 1/4 head-on, "
           "Schlick at 0 and 90 deg): worst relative error %.2e (bound 1e-12)\n",
           worst_cf);
    CHECK(worst_cf <= 1e-12);
    /* normalization: integral over the hemisphere of D(h) (N.h) = integral_0^1 pi D du with u = (N.h)^2 */
    double worst_norm = 0;
    for (size_t i = 1; i < sizeof as / sizeof as[0]; i++) {
        const int n = 400000; /* Simpson on u */
        double sum = 0;
        for (int k = 0; k <= n; k++) {
            double u = (double)k / n, w = k == 0 || k == n ? 1 : k % 2 ? 4 : 2;
            sum += w * M_PI * pg_brdf_ggx_d(sqrt(u), as[i]);
        }
        sum /= 3.0 * n;
        worst_norm = fmax(worst_norm, fabs(sum - 1));
    }
    printf("  GGX normalization (integral of D (N.H) over the hemisphere, a = 0.05..1): worst |x - 1| %.2e (bound "
           "1e-6)\n",
           worst_norm);
    CHECK(worst_norm <= 1e-6);
    /* energy: E(V) = integral of D V F=1 (N.L) over L, for a few roughnesses and view angles */
    const double rs[] = {0.3, 0.5, 0.7, 1.0}, mus[] = {1.0, 0.5, 0.1};
    double worst_e = 0, e_smooth = 0;
    for (size_t i = 0; i < 4; i++)
        for (size_t j = 0; j < 3; j++) {
            const int nt = 720, np = 720;
            double a = rs[i] * rs[i], V[3], N[3] = {0, 0, 1}, e = 0;
            dir_mu(mus[j], 0, V);
            for (int it = 0; it < nt; it++) {
                double th = (it + 0.5) * (M_PI / 2) / nt, mu = cos(th);
                for (int ip = 0; ip < np; ip++) {
                    double L[3];
                    dir_mu(mu, (ip + 0.5) * 2 * M_PI / np, L);
                    double h[3] = {L[0] + V[0], L[1] + V[1], L[2] + V[2]}, hl = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
                    double ndh = h[2] / hl;
                    e += pg_brdf_ggx_d(ndh, a) * pg_brdf_smith_v(mu, mus[j], a) * mu * sin(th);
                }
            }
            e *= (M_PI / 2 / nt) * (2 * M_PI / np);
            (void)N;
            worst_e = fmax(worst_e, e);
            if (i == 0 && j == 0) e_smooth = e;
        }
    printf("  specular energy with F = 1 (roughness 0.3..1, N.V 1, 0.5, 0.1): at most %.4f (bound 1 + %.0e); "
           "roughness 0.3 head-on %.4f (>= 0.95: single scattering loses little when smooth)\n",
           worst_e, BRDF_ENERGY_TOL, e_smooth);
    CHECK(worst_e <= 1 + BRDF_ENERGY_TOL);
    CHECK(e_smooth >= 0.95);
    /* float twin vs double, reciprocity, the lightcut's bound, extremes */
    double worst_rel = 0, worst_recip = 0, worst_bound = 0;
    long nonfinite = 0;
    for (int it = 0; it < 200000; it++) {
        double N[3], L[3], V[3];
        rand_unit(N);
        rand_unit(L);
        rand_unit(V);
        double ndl = N[0] * L[0] + N[1] * L[1] + N[2] * L[2], ndv = N[0] * V[0] + N[1] * V[1] + N[2] * V[2];
        float r = (float)rng_range(0.0, 1.0), b = (float)rng_unit(), m = (float)(rng_below(3) == 0 ? rng_below(2) : rng_unit());
        /* the bound, everywhere (grazing and behind included) */
        float Lf[3] = {(float)L[0], (float)L[1], (float)L[2]}, Vf[3] = {(float)V[0], (float)V[1], (float)V[2]};
        float Nf[3] = {(float)N[0], (float)N[1], (float)N[2]}, c[3] = {1, 1, 1};
        /* base 1, metallic 1: the sum is the specular lobe alone (kd = 0, ks = 1); base 1, metallic 0:
         * the diffuse term too */
        float metal[3] = {0, 0, 0}, dielectric[3] = {0, 0, 0}, one[3] = {1, 1, 1};
        if (ndl > 0) pg_pbr_light(c, 1.0f, Lf, Nf, Vf, one, 1.0f, r, metal);
        if (ndl > 0) pg_pbr_light(c, 1.0f, Lf, Nf, Vf, one, 0.0f, r, dielectric);
        float a = pg_pbr_alpha(r);
        double spec = metal[0];
        if (!isfinite(spec) || !isfinite(dielectric[0])) nonfinite++;
        worst_bound = fmax(worst_bound, spec / (0.5 / ((double)a * a * a)));
        if (ndl < 0.05 || ndv < 0.05 || r < 0.05) continue;
        double want = M_PI * pg_brdf_pbr(L, V, N, b, m, r) * ndl;
        float got = twin_one(L, V, N, b, m, r);
        worst_rel = fmax(worst_rel, fabs(got - want) / want);
        /* reciprocity: f(L, V) = f(V, L) */
        float back = twin_one(V, L, N, b, m, r);
        worst_recip = fmax(worst_recip, fabs(got / ndl - back / ndv) / (want / ndl));
    }
    /* at the highlight's peak (H within 0.03 rad of N), where the short form q = |h|^2 - (N.h)^2 (1 - a^2)
     * that the twin and lighting.glsl take for roughness >= 0.5 cancels most: the same bound (smoother
     * surfaces keep the cross product; there the peak's float inputs alone reach 3.5e-5 at roughness
     * 0.05, before and after the short form) */
    double worst_peak = 0;
    for (int it = 0; it < 50000; it++) {
        double N[3], p[3], q[3], H[3], V[3], L[3];
        rand_unit(N);
        rand_unit(p);
        double pn = p[0] * N[0] + p[1] * N[1] + p[2] * N[2], pl = 0;
        for (int k = 0; k < 3; k++) p[k] -= pn * N[k], pl += p[k] * p[k];
        const double th = rng_range(0.0, 0.03), ph = rng_range(0.0, 1.2);
        for (int k = 0; k < 3; k++) H[k] = cos(th) * N[k] + sin(th) * p[k] / sqrt(pl);
        rand_unit(q);
        double qh = q[0] * H[0] + q[1] * H[1] + q[2] * H[2], ql = 0;
        for (int k = 0; k < 3; k++) q[k] -= qh * H[k], ql += q[k] * q[k];
        for (int k = 0; k < 3; k++) V[k] = cos(ph) * H[k] + sin(ph) * q[k] / sqrt(ql);
        for (int k = 0; k < 3; k++) L[k] = 2 * cos(ph) * H[k] - V[k];
        const double ndl = N[0] * L[0] + N[1] * L[1] + N[2] * L[2], ndv = N[0] * V[0] + N[1] * V[1] + N[2] * V[2];
        const float r = (float)rng_range(0.5, 1.0);
        if (ndl < 0.05 || ndv < 0.05) continue;
        const double want = M_PI * pg_brdf_pbr(L, V, N, 1.0, 1.0, r) * ndl;
        worst_peak = fmax(worst_peak, fabs(twin_one(L, V, N, 1.0f, 1.0f, r) - want) / want);
    }
    printf("  float twin vs double at the highlight's peak (50000 random, N.H >= cos 0.03, metal, roughness 0.5..1): "
           "worst relative "
           "%.2e (bound %.0e)\n", worst_peak, BRDF_TWIN_REL);
    CHECK(worst_peak <= BRDF_TWIN_REL);
    /* extremes: roughness 0 (clamped), L = -V, N.V = 0, a light along the surface, tiny N.L */
    const double ex[][9] = {{0, 0, 1, 0, 0, 1, 0, 0, 1},   {0, 0.6, 0.8, 0, -0.6, -0.8, 0, 0, 1},
                            {0, 0, 1, 1, 0, 0, 0, 0, 1},   {1e-30, 0, 1, 0, 1, 0, 0, 0, 1},
                            {1, 0, 1e-7, -1, 0, 1e-7, 0, 0, 1}};
    for (size_t i = 0; i < sizeof ex / sizeof ex[0]; i++)
        for (int ri = 0; ri < 3; ri++) {
            double L[3] = {ex[i][0], ex[i][1], ex[i][2]}, V[3] = {ex[i][3], ex[i][4], ex[i][5]};
            double ll = sqrt(L[0] * L[0] + L[1] * L[1] + L[2] * L[2]), vl = sqrt(V[0] * V[0] + V[1] * V[1] + V[2] * V[2]);
            for (int k = 0; k < 3; k++) {
                L[k] /= ll;
                V[k] /= vl;
            }
            float v = twin_one(L, V, ex[i] + 6, 0.8f, 0.5f, ri == 0 ? 0.0f : ri == 1 ? 0.045f : 1.0f);
            if (!isfinite(v) || v < 0) nonfinite++;
        }
    printf("  float twin vs double (200000 random, N.L and N.V >= 0.05): worst relative %.2e (bound %.0e); "
           "reciprocity %.2e (bound %.0e)\n",
           worst_rel, BRDF_TWIN_REL, worst_recip, 2 * BRDF_TWIN_REL);
    printf("  pi D V N.L / (0.5 / a^3) (the lightcut's bound): at most %.4f (<= 1); non-finite or negative: %ld\n",
           worst_bound, nonfinite);
    CHECK(worst_rel <= BRDF_TWIN_REL);
    CHECK(worst_recip <= 2 * BRDF_TWIN_REL);
    CHECK(worst_bound <= 1.0 + 1e-5);
    CHECK(nonfinite == 0);
}

int main(void)
{
    double t0 = now_s();
    test_octahedral();
    test_depth();
    test_slices();
    test_clusters();
    test_attenuation();
    test_brdf();
    printf("test_numeric: %.2f s\n", now_s() - t0);
    return pg_test_finish("test_numeric");
}
