/* ocio.h - OpenColorIO behind a C interface (core/color/ocio_shim.cpp is the only C++ that sees OCIO).
 *
 * A config is opened once and asked for its displays and views; for one (display, view) it makes
 *   - a GPU shader description: Vulkan GLSL text defining `vec4 FUNCTION(vec4 scene_linear)` with
 *     every LUT sampler at layout(set = desc.set, binding = desc.first_binding + k), plus the list
 *     of LUT textures (dimensions, channels, filtering, float data) the caller uploads;
 *   - a CPU processor that applies the same transform to float RGB / RGBA pixels (the reference
 *     the GPU output is tested against).
 * The source colour space is always the config's `scene_linear` role (what passgraph renders).
 *
 * Errors are values: no C++ exception leaves the shim. Messages name the config file:
 *   "assets/ocio/config.ocio: cannot open OCIO config: No such file or directory"
 *   "my.ocio: OCIO config error: ... (yaml-cpp: error at line 3, column 1 ...)"
 *   "assets/ocio/config.ocio: unknown view 'Filmic' of display 'sRGB' (views: Standard, Filmic (ACES), Raw)"
 * Ownership: every object returned is owned by the caller and freed with its _free/_close
 * function (NULL is accepted); strings returned by the getters live as long as their object.
 */
#ifndef PG_OCIO_H
#define PG_OCIO_H

#include <stddef.h>

#include "pg_common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Where the shipped config lives, relative to the data folder (pg_data_path). */
#define PG_OCIO_SHIPPED_CONFIG "assets/ocio/config.ocio"

typedef struct pg_ocio_config pg_ocio_config;

/* The config file to use: `setting` when non-empty (an application setting such as
 * --ocio-config), else $OCIO when set and non-empty, else the shipped config. */
void pg_ocio_resolve_path(const char *setting, char *buf, size_t size);

/* Opens and validates a config. path NULL or "": pg_ocio_resolve_path(NULL). The config must
 * define the scene_linear role and at least one display. */
pg_result pg_ocio_open(const char *path, pg_ocio_config **out, pg_error *err);
void pg_ocio_close(pg_ocio_config *cfg);
const char *pg_ocio_config_path(const pg_ocio_config *cfg);

/* Active displays, in config order; the default display is the first unless the config says. */
uint32_t pg_ocio_num_displays(const pg_ocio_config *cfg);
const char *pg_ocio_display(const pg_ocio_config *cfg, uint32_t index); /* NULL if out of range */
const char *pg_ocio_default_display(const pg_ocio_config *cfg);
/* Active views of a display (0 / NULL for an unknown display). */
uint32_t pg_ocio_num_views(const pg_ocio_config *cfg, const char *display);
const char *pg_ocio_view(const pg_ocio_config *cfg, const char *display, uint32_t index);
const char *pg_ocio_default_view(const pg_ocio_config *cfg, const char *display);
/* True when display (NULL/"": the default) has a view called name. */
bool pg_ocio_has_view(const pg_ocio_config *cfg, const char *display, const char *name);

/* Resolves a (display, view) choice: NULL or "" takes the config's default. Unknown names are
 * PG_ERR_INVALID_ARG with the file and the available names. display_out / view_out (may be NULL)
 * receive the resolved names. */
pg_result pg_ocio_resolve(const pg_ocio_config *cfg, const char *display, const char *view, char *display_out,
                          size_t display_size, char *view_out, size_t view_size, pg_error *err);

/* ---- GPU shader ---- */
typedef enum pg_ocio_tex_dim {
    PG_OCIO_TEX_1D = 1,   /* sampler1D: width texels (height 1) */
    PG_OCIO_TEX_2D = 2,   /* sampler2D: a 1D LUT wrapped into rows, width x height */
    PG_OCIO_TEX_3D = 3,   /* sampler3D: width = height = depth = edge length */
} pg_ocio_tex_dim;

typedef struct pg_ocio_texture {
    char sampler[PG_NAME_MAX];  /* the GLSL sampler name */
    pg_ocio_tex_dim dim;
    uint32_t width, height, depth;
    uint32_t channels;          /* 1 (red only) or 3 (RGB) */
    bool linear;                /* linear filtering; false: nearest (OCIO interpolates itself) */
    uint32_t binding;           /* layout(binding = ...) given in the GLSL */
    const float *values;        /* width*height*depth*channels floats, x fastest; owned by the shader */
} pg_ocio_texture;

typedef struct pg_ocio_shader_desc {
    const char *display, *view;  /* NULL/"": the config's defaults */
    const char *function_name;   /* NULL: "ocio_display" */
    uint32_t set;                /* descriptor set of the LUT samplers */
    uint32_t first_binding;      /* binding of the first LUT sampler; the others follow */
} pg_ocio_shader_desc;

typedef struct pg_ocio_shader {
    char display[PG_NAME_MAX * 2], view[PG_NAME_MAX * 2]; /* resolved names */
    char *glsl;                  /* NUL-terminated Vulkan GLSL (no #version line) */
    uint32_t n_textures;
    pg_ocio_texture *textures;
} pg_ocio_shader;

/* Fails (PG_ERR_INVALID_ARG) when the processor needs uniforms (OCIO dynamic properties), which
 * passgraph does not support. */
pg_result pg_ocio_shader_create(const pg_ocio_config *cfg, const pg_ocio_shader_desc *desc, pg_ocio_shader **out,
                                pg_error *err);
void pg_ocio_shader_free(pg_ocio_shader *s);

/* ---- CPU processor (the reference) ---- */
typedef struct pg_ocio_cpu pg_ocio_cpu;
pg_result pg_ocio_cpu_create(const pg_ocio_config *cfg, const char *display, const char *view, pg_ocio_cpu **out,
                             pg_error *err);
/* In place: n pixels of `channels` (3 = RGB, 4 = RGBA) interleaved floats. */
void pg_ocio_cpu_apply(const pg_ocio_cpu *p, float *pixels, size_t n, uint32_t channels);
void pg_ocio_cpu_free(pg_ocio_cpu *p);

/* OCIO's version string ("2.1.2"). */
const char *pg_ocio_version(void);

#ifdef __cplusplus
}
#endif
#endif
