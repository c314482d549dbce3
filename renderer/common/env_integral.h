/* env_integral.h - the environment light's integral on the CPU, in double precision, by Monte
 * Carlo: the ground truth the GPU tests compare the filtered environment's shading with.
 *
 * Estimators (randomized quasi-Monte Carlo): each estimator draws `samples` points of a 2D
 * Hammersley set split into R = min(16, samples) replicas of n = samples / R points (so R n <=
 * samples are used), each replica shifted by its own Cranley-Patterson rotation drawn from the
 * seed (splitmix64). Each replica is an unbiased estimate; the result is their mean and the
 * standard error is the replicas' sample standard deviation / sqrt(R) (an honest error of the
 * randomized estimate, much smaller than plain Monte Carlo's for smooth integrands). The same
 * seed gives the same numbers.
 *
 * The integrand (outgoing radiance toward V at a point of normal N, L(w) = pg_environment_radiance):
 *   lambert, blinn_phong: the diffuse part only, base / pi x integral of L(w) N.w dw: L sampled
 *     cosine-weighted around N, each sample weighs base x L(w).
 *   pbr: the glTF 2.0 metallic-roughness BRDF (specification Appendix B; renderer/common/brdf.h)
 *     f = (1 - F) c_diff / pi + F D V_smith, F = F0 + (1 - F0)(1 - V.H)^5 per channel,
 *     c_diff = base (1 - metallic), F0 = mix(0.04, base, metallic),
 *     alpha = clamp(roughness, PG_PBR_MIN_ROUGHNESS, 1)^2 (pg_pbr_alpha's clamp),
 *     as the sum of two independent estimators:
 *       diffuse:  L cosine-weighted around N; weight (1 - F(H)) c_diff L(w), H = normalize(L + V);
 *       specular: H drawn from D(N.H) N.H, L = reflect(-V, H) (pdf D N.H / (4 V.H)); weight
 *                 F V_smith 4 (V.H)(N.L) / (N.H) L(w); samples with N.L <= 0 weigh 0.
 *     With N.V <= 0 the pbr result is 0 (as pg_brdf_pbr).
 * N and V are unit vectors in world space (V from the surface toward the eye). */
#ifndef PG_ENV_INTEGRAL_H
#define PG_ENV_INTEGRAL_H

#include "environment.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pg_env_surface {
    double base[3];             /* base colour (lambert, blinn_phong: the albedo) */
    double metallic, roughness; /* pbr only */
    int model;                  /* PG_SHADING_LAMBERT, PG_SHADING_BLINN_PHONG, PG_SHADING_PBR
                                   (scene/scene_features.h); any other value is treated as pbr */
} pg_env_surface;

/* Outgoing radiance toward V at a point of normal N lit by env (level `level`, rotation and
 * intensity as pg_environment_radiance): out = the estimate (rgb); se = its standard error (rgb;
 * may be NULL). samples per estimator (>= 1; 0 is taken as 1); seed makes it deterministic. */
void pg_env_integral(const pg_environment *env, uint32_t level, double rotation, double intensity,
                     const double N[3], const double V[3], const pg_env_surface *s, uint32_t samples,
                     uint64_t seed, double out[3], double se[3]);

/* The split-sum terms for a unit white environment, V at angle acos(n_dot_v) from N (n_dot_v in
 * (0, 1]), alpha = clamp(roughness, PG_PBR_MIN_ROUGHNESS, 1)^2, w = (1 - V.H)^5:
 *   ab[0] = A = integral of (1 - w) D V_smith N.L dL,  ab[1] = B = integral of w D V_smith N.L dL
 *     (so the specular split-sum of a white environment is F0 A + B), by the GGX sampling above;
 *   *c = the cosine-weighted average of (1 - w) over L's hemisphere (the pbr diffuse term of an
 *     environment of irradiance E is c_diff (1 - F0) c E / pi in the split-sum); c may be NULL.
 * samples as pg_env_integral; a fixed seed. */
void pg_env_brdf_lut(double n_dot_v, double roughness, uint32_t samples, double ab[2], double *c);

#ifdef __cplusplus
}
#endif
#endif
