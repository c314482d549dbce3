/* environment_layout.h - the filtered environment's layout (the graph resource "environment",
 * vec4 elements), mirroring shaders/environment.glsl: the diffuse table, the split-sum table and
 * the prefiltered levels. tests/unit/test_environment.c (test_layout_mirror) checks the two agree. */
#ifndef PG_ENVIRONMENT_LAYOUT_H
#define PG_ENVIRONMENT_LAYOUT_H

#define PG_ENV_IRR_W 32u
#define PG_ENV_IRR_H 16u
#define PG_ENV_LUT_N 32u
#define PG_ENV_SPEC_W 256u
#define PG_ENV_SPEC_H 128u
#define PG_ENV_SPEC_LEVELS 9u
#define PG_ENV_IRR_OFF 0u
#define PG_ENV_LUT_OFF (PG_ENV_IRR_OFF + PG_ENV_IRR_W * PG_ENV_IRR_H)
#define PG_ENV_SPEC_OFF (PG_ENV_LUT_OFF + PG_ENV_LUT_N * PG_ENV_LUT_N)
/* every element: the specular levels are (W >> k) x (H >> k), at least 64 x 32, k < PG_ENV_SPEC_LEVELS */
#define PG_ENV_TEXELS (PG_ENV_SPEC_OFF + 32768u + 8192u + 7u * 2048u)
#define PG_ENV_BYTES (16ull * PG_ENV_TEXELS)

#endif
