/* brdf.c - the C twin of the pbr light model (brdf.h). */
#include "brdf.h"

#include <math.h>

static float dotf(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static float clampf(float x, float lo, float hi)
{
    return x < lo ? lo : x > hi ? hi : x;
}

/* the material's colours of one channel: F0 = mix(0.04, base, metallic), c_diff = base (1 - metallic) */
static float pbr_f0(float base, float metallic)
{
    return 0.04f + (base - 0.04f) * metallic;
}

static float pbr_cdiff(float base, float metallic)
{
    return base * (1.0f - metallic);
}

float pg_pbr_alpha(float roughness)
{
    float r = clampf(roughness, PG_PBR_MIN_ROUGHNESS, 1.0f);
    return r * r;
}

void pg_pbr_light(const float c[3], float att, const float L[3], const float N[3], const float V[3],
                  const float base[3], float metallic, float roughness, float acc[3])
{
    float a = pg_pbr_alpha(roughness);
    float a2 = a * a;
    float ndl = fmaxf(dotf(N, L), 0.0f);
    float ndv = fmaxf(dotf(N, V), 0.0f);
    float h[3] = {L[0] + V[0], L[1] + V[1], L[2] + V[2]};
    float nh = dotf(N, h), hh = dotf(h, h), b2 = 1.0f - a2;
    float q;
    if (a2 >= PG_PBR_FAST_Q_A2) {
        q = fmaxf(hh - nh * nh * b2, a2 * hh);
    } else {
        float nxh[3] = {N[1] * h[2] - N[2] * h[1], N[2] * h[0] - N[0] * h[2], N[0] * h[1] - N[1] * h[0]};
        q = dotf(nxh, nxh) + nh * nh * a2;
    }
    float num = a * hh;
    float den = ndl * sqrtf(ndv * ndv * b2 + a2) + ndv * sqrtf(ndl * ndl * b2 + a2);
    float qd = q * q * den;
    float spec = qd > 0.0f ? 0.5f * ndl * att * num * num / qd : 0.0f;
    float t = 1.0f - fminf(sqrtf(fmaxf(0.5f * dotf(V, h), 0.0f)), 1.0f);
    float t2 = t * t;
    float w = t2 * t2 * t;
    float dw = ndl * att, sw = spec * w;
    for (int i = 0; i < 3; i++) {
        float f0 = pbr_f0(base[i], metallic);
        float kd = pbr_cdiff(base[i], metallic) * (1.0f - f0);
        acc[i] += c[i] * (kd * (dw - dw * w) + f0 * (spec - sw) + sw);
    }
}

void pg_pbr_combine(const float base[3], float metallic, const float acc[3], float ambient, float occlusion,
                    const float emissive[3], float out[3])
{
    for (int i = 0; i < 3; i++) {
        float f0 = pbr_f0(base[i], metallic), cdiff = pbr_cdiff(base[i], metallic);
        out[i] = acc[i] + (cdiff + f0) * (ambient * occlusion) + emissive[i];
    }
}

double pg_brdf_ggx_d(double n_dot_h, double a)
{
    if (n_dot_h <= 0) return 0;
    double a2 = a * a, q = n_dot_h * n_dot_h * (a2 - 1) + 1;
    return a2 / (M_PI * q * q);
}

double pg_brdf_smith_v(double n_dot_l, double n_dot_v, double a)
{
    double a2 = a * a;
    double gv = n_dot_l * sqrt(n_dot_v * n_dot_v * (1 - a2) + a2);
    double gl = n_dot_v * sqrt(n_dot_l * n_dot_l * (1 - a2) + a2);
    return gv + gl > 0 ? 0.5 / (gv + gl) : 0;
}

double pg_brdf_schlick(double f0, double v_dot_h)
{
    return f0 + (1 - f0) * pow(1 - v_dot_h, 5);
}


double pg_brdf_pbr(const double L[3], const double V[3], const double N[3], double b, double m, double r)
{
    double ndl = N[0] * L[0] + N[1] * L[1] + N[2] * L[2], ndv = N[0] * V[0] + N[1] * V[1] + N[2] * V[2];
    if (ndl <= 0 || ndv <= 0) return 0;
    double h[3] = {L[0] + V[0], L[1] + V[1], L[2] + V[2]};
    double hl = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    for (int k = 0; k < 3; k++) h[k] /= hl;
    double ndh = N[0] * h[0] + N[1] * h[1] + N[2] * h[2], vdh = V[0] * h[0] + V[1] * h[1] + V[2] * h[2];
    double a = r * r, f0 = 0.04 + (b - 0.04) * m, cdiff = b * (1 - m);
    double F = pg_brdf_schlick(f0, vdh);
    return (1 - F) * cdiff / M_PI + F * pg_brdf_ggx_d(ndh, a) * pg_brdf_smith_v(ndl, ndv, a);
}
