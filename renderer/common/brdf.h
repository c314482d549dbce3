/* brdf.h - the C twin of the pbr light model of shaders/lighting.glsl (the glTF 2.0 metallic-roughness
 * BRDF of the specification's Appendix B: GGX distribution, height-correlated Smith visibility,
 * Schlick Fresnel, the diffuse/metal mix), in float with the shader's operations in the shader's
 * order, and its terms in double for the checks (tests/unit/test_numeric.c) and the CPU evaluations
 * the GPU tests compare the reference with (tests/gpu/test_gpu_pbr.c).
 *
 * Units: a light's colour c is colour x intensity / pi (Light.color); a light adds
 * pi f(L, V) x c x N.L x att, att its distance attenuation (window / max(d^2, dmin^2)). */
#ifndef PG_BRDF_H
#define PG_BRDF_H

#ifdef __cplusplus
extern "C" {
#endif

#define PG_PBR_MIN_ROUGHNESS 0.045f /* lighting.glsl's clamp: roughness 0 would be a mirror */
#define PG_PBR_FAST_Q_A2 0.0625f  /* lighting.glsl's: a^2 from which q = |h|^2 - (N.h)^2 (1 - a^2) */

/* a = clamp(roughness, PG_PBR_MIN_ROUGHNESS, 1)^2 */
float pg_pbr_alpha(float roughness);
/* pg_light_pbr of lighting.glsl: adds to the light sum acc one light of colour c from unit direction
 * L (N.L > 0) with attenuation att, at a point of unit normal N seen from unit direction V, of base
 * colour, metallic and roughness: c (kd (1 - w) N.L att + ks (1 - w) S + w S), S = pi D V N.L att,
 * w = (1 - V.H)^5, kd = c_diff (1 - F0), ks = F0. With base 1 and metallic 1 it adds c S. */
void pg_pbr_light(const float c[3], float att, const float L[3], const float N[3], const float V[3],
                  const float base[3], float metallic, float roughness, float acc[3]);
/* pg_shade_combine of lighting.glsl with PG_PBR: base colour, metallic, the light sum, ambient x
 * occlusion, emissive -> the pixel's colour. */
void pg_pbr_combine(const float base[3], float metallic, const float acc[3], float ambient, float occlusion,
                    const float emissive[3], float out[3]);

/* The terms in double, as the specification writes them (a = alpha = roughness^2, unclamped). */
double pg_brdf_ggx_d(double n_dot_h, double a);               /* D: a^2 / (pi ((N.H)^2 (a^2 - 1) + 1)^2) */
double pg_brdf_smith_v(double n_dot_l, double n_dot_v, double a); /* V: height-correlated Smith / (4 N.L N.V) */
double pg_brdf_schlick(double f0, double v_dot_h);            /* F0 + (1 - F0) (1 - V.H)^5 */
/* The whole BRDF f(L, V) for one channel (base colour b, metallic m, roughness r; unit vectors). */
double pg_brdf_pbr(const double L[3], const double V[3], const double N[3], double b, double m, double r);

#ifdef __cplusplus
}
#endif
#endif
