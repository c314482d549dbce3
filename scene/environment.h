/* environment.h - an environment light: distant radiance from every direction, stored as an
 * equirectangular (latitude-longitude) image with its box-filtered mip chain, read from a Radiance
 * HDR file (stb_image's stbi_loadf) or generated (the neutral default sky).
 *
 * Directions (world space, +Y up): texel (i, j) of a level w x h covers
 *   u in [i/w, (i+1)/w), v in [j/h, (j+1)/h); its centre is u = (i + 0.5)/w, v = (j + 0.5)/h;
 *   phi = 2 pi (u - 0.5), theta = pi v,
 *   d = (sin(theta) sin(phi), cos(theta), -sin(theta) cos(phi))
 * so v = 0 is straight up, the image centre (u = v = 0.5) looks down -Z and u grows toward +X.
 * The inverse: u = 0.5 + atan2(d.x, -d.z) / (2 pi), v = acos(clamp(d.y, -1, 1)) / pi.
 * A rotation r (radians, about +Y, the viewer's knob) turns the environment: the radiance from
 * direction d is the stored radiance of Ry(-r) d, Ry(a) = rotation by a about +Y (right-handed:
 * x' = x cos a + z sin a, z' = -x sin a + z cos a).
 * Sampling (pg_environment_radiance, and the shaders' twin in shaders/environment.glsl): bilinear
 * between texel centres, u wrapping around, v clamped to the first/last row's centre.
 *
 * Levels: level 0 is the file; level k+1 is max(1, w/2) x max(1, h/2) of level k, each texel the
 * plain average of the level-k texels whose index range it covers (i * w_k / w_{k+1} ..
 * (i + 1) * w_k / w_{k+1} - 1 in integer arithmetic, the same for rows); levels continue until
 * the last is 1 texel wide or tall, at most PG_ENV_MAX_LEVELS.
 * Values: linear RGB in scene-linear units (the file's), alpha 1. NaN, infinite or negative
 * components read as 0; components above PG_ENV_MAX_VALUE are clamped to it (counted in
 * `clamped`, which the tools report in one line).
 *
 * Ownership: a pg_environment owns its pixels; free with pg_environment_free(). */
#ifndef PG_ENVIRONMENT_H
#define PG_ENVIRONMENT_H

#include "pg_common.h"

#ifdef __cplusplus
extern "C" {
#endif

#define PG_ENV_MAX_LEVELS 16
#define PG_ENV_MAX_WIDTH 16384       /* larger files are refused (PG_ERR_LIMIT) */
#define PG_ENV_MAX_VALUE 65000.0f    /* shaders/common.glsl PG_HDR_MAX */
#define PG_DEFAULT_SKY_LEVEL 0.25f   /* the tools' neutral sky: mean radiance (app/app.c) */

typedef struct pg_environment {
    char source[PG_PATH_MAX];        /* the file as given, or "default" (the neutral sky) */
    uint32_t n_levels;
    uint32_t width[PG_ENV_MAX_LEVELS], height[PG_ENV_MAX_LEVELS];
    uint64_t offset[PG_ENV_MAX_LEVELS]; /* first texel of each level in rgba (texels, not floats) */
    uint64_t n_texels;               /* all levels */
    float *rgba;                     /* n_texels x 4 floats, levels one after the other, rows top
                                        (v = 0) first */
    uint64_t clamped;                /* level-0 components replaced (non-finite, negative, too large) */
    float max_value;                 /* largest level-0 component after clamping */
    double mean_radiance[3];         /* solid-angle weighted mean radiance of level 0 (= irradiance
                                        of a uniform environment / pi) */
    /* Importance sampling of level 0 (the reference's Monte Carlo, reference_lighting.comp): texel
     * (i, j) is drawn with probability proportional to its Rec.709 luminance x sin(theta_j) (theta_j
     * at the row's centre); cdf holds the rows' marginal CDF (h + 1 floats, 0 .. 1) and then each
     * row's conditional CDF (w + 1 floats, 0 .. 1; a black row uniform). A direction drawn uniformly
     * in (u, v) within the texel has the solid-angle density p_ij w h / (2 pi^2 sin(theta)).
     * NULL (n_cdf 0) when level 0 is black. */
    float *cdf;
    uint64_t n_cdf;
    uint64_t id;                     /* unique per loaded or generated environment in this process
                                        (> 0): what the GPU filter remembers it filtered */
} pg_environment;

/* Reads a Radiance HDR (.hdr, RGBE) file. Errors name the file and the cause: missing or
 * unreadable (PG_ERR_IO), not an HDR file or truncated (PG_ERR_PARSE), width not twice the height
 * within one texel (PG_ERR_INVALID_ARG: "equirectangular images are 2:1"), wider than
 * PG_ENV_MAX_WIDTH or smaller than 8 x 4 (PG_ERR_LIMIT). */
pg_result pg_environment_load(const char *path, pg_environment **out, pg_error *err);
/* The neutral default sky (source "default"): 256 x 128, a smooth sky brighter toward the zenith
 * over a dim grey ground, no sun; mean radiance `level` per channel (the solid-angle mean). */
pg_result pg_environment_default(float level, pg_environment **out, pg_error *err);
/* Builds an environment from level-0 pixels (w x h x 4 floats, copied; alpha ignored): the levels,
 * the clamping, the statistics and a new id. source names it in messages. */
pg_result pg_environment_from_pixels(const char *source, uint32_t w, uint32_t h, const float *rgba,
                                     pg_environment **out, pg_error *err);
void pg_environment_free(pg_environment *env);

/* Direction <-> equirect coordinates as above (unit d; u in [0, 1), v in [0, 1]). */
void pg_env_dir_to_uv(const double d[3], double *u, double *v);
void pg_env_uv_to_dir(double u, double v, double d[3]);
/* Bilinear radiance of level `level` toward world direction d (unit), with rotation r (radians,
 * about +Y, as above), times intensity: out = rgb. */
void pg_environment_radiance(const pg_environment *env, uint32_t level, const double d[3], double rotation,
                             double intensity, double out[3]);

#ifdef __cplusplus
}
#endif
#endif
