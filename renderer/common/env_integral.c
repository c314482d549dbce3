/* env_integral.c - the environment light's integral by randomized quasi-Monte Carlo
 * (env_integral.h). */
#include "env_integral.h"

#include "brdf.h"
#include "scene_features.h"

#include <math.h>
#include <stddef.h>

#define EI_PI 3.14159265358979323846
#define EI_MAX_REPLICAS 16u

/* One shading setup: the frame around N, V, the material's per-channel terms. */
typedef struct ei_ctx {
    const pg_environment *env; /* NULL: a unit white environment */
    uint32_t level;
    double rotation, intensity;
    double t[3], b[3], n[3], v[3]; /* tangent frame (world), V (world) */
    double nv;                     /* N.V */
    double alpha;
    double cdiff[3], f0[3];
} ei_ctx;

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void normalize3(double a[3])
{
    double l = sqrt(dot3(a, a));
    if (l > 0)
        for (int k = 0; k < 3; k++) a[k] /= l;
}

static uint64_t splitmix64(uint64_t x)
{
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

/* a uniform number in [0, 1) from the seed and a stream index */
static double hash01(uint64_t seed, uint64_t stream)
{
    return (double)(splitmix64(seed ^ splitmix64(stream)) >> 11) * 0x1.0p-53;
}

static double radical_inverse2(uint32_t i)
{
    i = (i << 16) | (i >> 16);
    i = ((i & 0x55555555u) << 1) | ((i & 0xAAAAAAAAu) >> 1);
    i = ((i & 0x33333333u) << 2) | ((i & 0xCCCCCCCCu) >> 2);
    i = ((i & 0x0F0F0F0Fu) << 4) | ((i & 0xF0F0F0F0u) >> 4);
    i = ((i & 0x00FF00FFu) << 8) | ((i & 0xFF00FF00u) >> 8);
    return (double)i * 0x1.0p-32;
}

/* point i of the n-point Hammersley set, shifted by (s0, s1) modulo 1 */
static void hammersley(uint32_t i, uint32_t n, double s0, double s1, double xi[2])
{
    double a = (i + 0.5) / n + s0, b = radical_inverse2(i) + s1;
    xi[0] = a >= 1 ? a - 1 : a;
    xi[1] = b >= 1 ? b - 1 : b;
}

/* an orthonormal frame (t, b, n) around unit n (Duff et al. 2017) */
static void frame(ei_ctx *c, const double n[3])
{
    double s = n[2] >= 0 ? 1.0 : -1.0, a = -1.0 / (s + n[2]), d = n[0] * n[1] * a;
    double t[3] = {1 + s * n[0] * n[0] * a, s * d, -s * n[0]}, b[3] = {d, s + n[1] * n[1] * a, -n[1]};
    for (int k = 0; k < 3; k++) {
        c->t[k] = t[k];
        c->b[k] = b[k];
        c->n[k] = n[k];
    }
}

static void to_world(const ei_ctx *c, const double l[3], double w[3])
{
    for (int k = 0; k < 3; k++) w[k] = c->t[k] * l[0] + c->b[k] * l[1] + c->n[k] * l[2];
}

static void radiance(const ei_ctx *c, const double w[3], double out[3])
{
    if (!c->env) {
        out[0] = out[1] = out[2] = 1.0;
        return;
    }
    pg_environment_radiance(c->env, c->level, w, c->rotation, c->intensity, out);
}

/* a cosine-weighted direction around N (world) */
static void cosine_dir(const ei_ctx *c, const double xi[2], double w[3])
{
    double r = sqrt(xi[0]), phi = 2 * EI_PI * xi[1];
    double l[3] = {r * cos(phi), r * sin(phi), sqrt(1 - xi[0] > 0 ? 1 - xi[0] : 0)};
    to_world(c, l, w);
}

/* (1 - V.H)^5 for H = normalize(L + V) */
static double schlick_w(const ei_ctx *c, const double l[3])
{
    double h[3] = {l[0] + c->v[0], l[1] + c->v[1], l[2] + c->v[2]};
    normalize3(h);
    double vh = dot3(c->v, h), t = 1 - (vh < 0 ? 0 : vh > 1 ? 1 : vh);
    return t * t * t * t * t;
}

/* A GGX sample: H from D(N.H) N.H, L = reflect(-V, H); returns the weight
 * V_smith 4 (V.H)(N.L) / (N.H) (0 below the horizon), w = (1 - V.H)^5 and L. */
static double ggx_sample(const ei_ctx *c, const double xi[2], double l[3], double *w)
{
    double a2 = c->alpha * c->alpha;
    double ct = sqrt((1 - xi[0]) / (1 + (a2 - 1) * xi[0])), st = sqrt(1 - ct * ct > 0 ? 1 - ct * ct : 0);
    double phi = 2 * EI_PI * xi[1], hl[3] = {st * cos(phi), st * sin(phi), ct}, h[3];
    to_world(c, hl, h);
    double vh = dot3(c->v, h);
    for (int k = 0; k < 3; k++) l[k] = 2 * vh * h[k] - c->v[k];
    double nl = dot3(c->n, l);
    *w = 0;
    if (nl <= 0 || vh <= 0 || ct <= 0) return 0;
    double t = 1 - (vh > 1 ? 1 : vh);
    *w = t * t * t * t * t;
    return pg_brdf_smith_v(nl, c->nv, c->alpha) * 4 * vh * nl / ct;
}

/* One replica's mean of the diffuse estimator (pbr: (1 - F) c_diff L; otherwise base L). */
static void diffuse_replica(const ei_ctx *c, bool pbr, uint32_t n, const double shift[2], double out[3])
{
    double sum[3] = {0, 0, 0};
    for (uint32_t i = 0; i < n; i++) {
        double xi[2], l[3], L[3];
        hammersley(i, n, shift[0], shift[1], xi);
        cosine_dir(c, xi, l);
        radiance(c, l, L);
        double w = pbr ? schlick_w(c, l) : 0;
        for (int k = 0; k < 3; k++) sum[k] += (1 - (c->f0[k] + (1 - c->f0[k]) * w)) * c->cdiff[k] * L[k];
    }
    for (int k = 0; k < 3; k++) out[k] = sum[k] / n;
}

/* One replica's mean of the specular estimator F V_smith 4 (V.H)(N.L) / (N.H) L. */
static void specular_replica(const ei_ctx *c, uint32_t n, const double shift[2], double out[3])
{
    double sum[3] = {0, 0, 0};
    for (uint32_t i = 0; i < n; i++) {
        double xi[2], l[3], L[3], w;
        hammersley(i, n, shift[0], shift[1], xi);
        double g = ggx_sample(c, xi, l, &w);
        if (g <= 0) continue;
        radiance(c, l, L);
        for (int k = 0; k < 3; k++) sum[k] += (c->f0[k] + (1 - c->f0[k]) * w) * g * L[k];
    }
    for (int k = 0; k < 3; k++) out[k] = sum[k] / n;
}

static void setup(ei_ctx *c, const double N[3], const double V[3], const pg_env_surface *s, bool pbr)
{
    double n[3] = {N[0], N[1], N[2]};
    normalize3(n);
    frame(c, n);
    for (int k = 0; k < 3; k++) c->v[k] = V[k];
    normalize3(c->v);
    c->nv = dot3(c->n, c->v);
    double r = s->roughness < PG_PBR_MIN_ROUGHNESS ? PG_PBR_MIN_ROUGHNESS : s->roughness > 1 ? 1 : s->roughness;
    c->alpha = r * r;
    for (int k = 0; k < 3; k++) {
        c->cdiff[k] = pbr ? s->base[k] * (1 - s->metallic) : s->base[k];
        c->f0[k] = pbr ? 0.04 + (s->base[k] - 0.04) * s->metallic : 0;
    }
}

/* mean and standard error of R replica estimates (rgb) */
static void replica_stats(double est[][3], uint32_t R, double out[3], double se[3])
{
    for (int k = 0; k < 3; k++) {
        double m = 0, v = 0;
        for (uint32_t r = 0; r < R; r++) m += est[r][k];
        m /= R;
        for (uint32_t r = 0; r < R; r++) v += (est[r][k] - m) * (est[r][k] - m);
        out[k] = m;
        if (se) se[k] = R > 1 ? sqrt(v / (R - 1) / R) : INFINITY;
    }
}

void pg_env_integral(const pg_environment *env, uint32_t level, double rotation, double intensity,
                     const double N[3], const double V[3], const pg_env_surface *s, uint32_t samples,
                     uint64_t seed, double out[3], double se[3])
{
    const bool pbr = s->model != PG_SHADING_LAMBERT && s->model != PG_SHADING_BLINN_PHONG;
    ei_ctx c = {.env = env, .level = level, .rotation = rotation, .intensity = intensity};
    setup(&c, N, V, s, pbr);
    const uint32_t R = samples < EI_MAX_REPLICAS ? (samples ? samples : 1) : EI_MAX_REPLICAS;
    const uint32_t n = samples / R ? samples / R : 1;
    double est[EI_MAX_REPLICAS][3];
    for (uint32_t r = 0; r < R; r++) {
        double d[3], sp[3] = {0, 0, 0};
        double sd[2] = {hash01(seed, 4 * r), hash01(seed, 4 * r + 1)};
        double ss[2] = {hash01(seed, 4 * r + 2), hash01(seed, 4 * r + 3)};
        if (pbr && c.nv <= 0) {
            d[0] = d[1] = d[2] = 0;
        } else {
            diffuse_replica(&c, pbr, n, sd, d);
            if (pbr) specular_replica(&c, n, ss, sp);
        }
        for (int k = 0; k < 3; k++) est[r][k] = d[k] + sp[k];
    }
    replica_stats(est, R, out, se);
}

/* The LUT's sums over one replica: A, B (GGX sampling) and c (cosine sampling). */
static void lut_replica(const ei_ctx *c, uint32_t n, const double sg[2], const double sd[2], double r[3])
{
    double a = 0, b = 0, cd = 0;
    for (uint32_t i = 0; i < n; i++) {
        double xi[2], l[3], w;
        hammersley(i, n, sg[0], sg[1], xi);
        double g = ggx_sample(c, xi, l, &w);
        a += (1 - w) * g;
        b += w * g;
        hammersley(i, n, sd[0], sd[1], xi);
        cosine_dir(c, xi, l);
        cd += 1 - schlick_w(c, l);
    }
    r[0] = a / n;
    r[1] = b / n;
    r[2] = cd / n;
}

void pg_env_brdf_lut(double n_dot_v, double roughness, uint32_t samples, double ab[2], double *c)
{
    const double N[3] = {0, 0, 1};
    double nv = n_dot_v > 1 ? 1 : n_dot_v, V[3] = {sqrt(1 - nv * nv > 0 ? 1 - nv * nv : 0), 0, nv};
    pg_env_surface s = {.base = {1, 1, 1}, .metallic = 1, .roughness = roughness, .model = PG_SHADING_PBR};
    ei_ctx ctx = {.env = NULL, .level = 0, .rotation = 0, .intensity = 1};
    setup(&ctx, N, V, &s, true);
    const uint32_t R = samples < EI_MAX_REPLICAS ? (samples ? samples : 1) : EI_MAX_REPLICAS;
    const uint32_t n = samples / R ? samples / R : 1;
    double est[EI_MAX_REPLICAS][3], mean[3];
    for (uint32_t r = 0; r < R; r++) {
        double sg[2] = {hash01(0x4C5554u, 4 * r), hash01(0x4C5554u, 4 * r + 1)};
        double sd[2] = {hash01(0x4C5554u, 4 * r + 2), hash01(0x4C5554u, 4 * r + 3)};
        lut_replica(&ctx, n, sg, sd, est[r]);
    }
    replica_stats(est, R, mean, NULL);
    ab[0] = mean[0];
    ab[1] = mean[1];
    if (c) *c = mean[2];
    if (nv <= 0) ab[0] = ab[1] = 0;
}
