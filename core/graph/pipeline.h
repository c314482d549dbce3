/* pipeline.h - a render pipeline as described by a JSON file (see pipelines/README.md).
 *
 * pg_pipeline_load() reads a file and its includes, applies --set overrides to the declared
 * parameters, substitutes "$param" references, drops items whose "when" condition is false,
 * and checks everything that needs no pass registry: structure, names, formats, sizes, the
 * output. What needs pass types (unknown type, access vs format, ordering, cycles) is checked by
 * pg_graph_compile(). Every error message starts with "FILE: JSON.PATH: cause" (or
 * "FILE:LINE:COL: cause" for JSON syntax errors).
 *
 * Ownership: the pg_pipeline owns everything it points to, including the cJSON option trees;
 * free it with pg_pipeline_free().
 */
#ifndef PG_PIPELINE_H
#define PG_PIPELINE_H

#include "pg_common.h"

#ifdef __cplusplus
extern "C" {
#endif

struct cJSON;

typedef enum pg_param_type {
    PG_PARAM_INT,
    PG_PARAM_FLOAT,
    PG_PARAM_BOOL,
    PG_PARAM_ENUM,
} pg_param_type;

typedef struct pg_param {
    char name[PG_NAME_MAX];
    pg_param_type type;
    double number;                       /* INT and FLOAT value (INT is integral) */
    bool boolean;                        /* BOOL value */
    char enum_value[PG_NAME_MAX];        /* ENUM value */
    double min, max;                     /* INT/FLOAT bounds (inclusive); -inf/+inf if absent */
    uint32_t n_values;                   /* ENUM choices; INT: the only values it takes (0: any) */
    char values[PG_MAX_ENUM_VALUES][PG_NAME_MAX];
    char description[160];
    bool overridden;                     /* set by --set */
} pg_param;

typedef struct pg_param_override { /* one --set key=value */
    const char *key;
    const char *value;
} pg_param_override;

typedef enum pg_res_kind { PG_RES_IMAGE = 0, PG_RES_BUFFER = 1 } pg_res_kind;

typedef enum pg_extent_mode {
    PG_EXTENT_RELATIVE = 0, /* scale x output size (default scale 1,1) */
    PG_EXTENT_ABSOLUTE = 1, /* fixed width/height in pixels */
} pg_extent_mode;

typedef enum pg_lifetime_kind {
    PG_LIFETIME_TRANSIENT = 0, /* lives within a frame; may alias */
    PG_LIFETIME_PERSISTENT,    /* keeps contents across frames; never aliased */
    PG_LIFETIME_IMPORTED,      /* provided by the application (e.g. a swapchain image) */
} pg_lifetime_kind;

/* A buffer's element count is the product of its terms; a term is a constant or a built-in
 * quantity known only at compile time. */
typedef enum pg_count_term_kind {
    PG_COUNT_CONST = 0,
    PG_COUNT_VAR,      /* a compile variable by name (e.g. "lights"; pg_compile_desc.vars) */
    PG_COUNT_PIXELS,   /* "pixels": output width * height */
} pg_count_term_kind;

typedef struct pg_count_term {
    pg_count_term_kind kind;
    double value;  /* for PG_COUNT_CONST */
    char var[32];  /* for PG_COUNT_VAR: the variable's name (PG_VAR_NAME_MAX) */
} pg_count_term;

typedef struct pg_resource_desc {
    char name[PG_NAME_MAX];
    pg_res_kind kind;
    pg_lifetime_kind lifetime;
    /* images */
    pg_format format;
    pg_extent_mode extent_mode;
    float scale[2];       /* RELATIVE */
    uint32_t size[2];     /* ABSOLUTE */
    /* buffers: bytes = stride * product(count terms) */
    uint32_t stride;
    uint32_t n_count_terms;
    pg_count_term count[PG_MAX_COUNT_TERMS];
    /* "grow": true - the count is only the initial size: a pass writing the buffer may ask the
     * runtime for more after a frame (pg_report_grow); never aliased */
    bool growable;
    /* where it was declared, for error messages */
    char file[PG_PATH_MAX];
    char json_path[PG_JSON_PATH_MAX]; /* e.g. "resources[3]" */
} pg_resource_desc;

/* Which queue a pass asks for (pipeline JSON "queue"; the compiler decides, core/graph/graph_queues.c). */
typedef enum pg_queue_pref {
    PG_QUEUE_PREF_AUTO = 0,
    PG_QUEUE_PREF_GRAPHICS,
    PG_QUEUE_PREF_COMPUTE,
} pg_queue_pref;

typedef struct pg_pass_desc {
    char name[PG_NAME_MAX];
    char type[PG_NAME_MAX];
    uint32_t n_reads, n_writes, n_after;
    char reads[PG_MAX_SLOTS][PG_NAME_MAX];   /* resource names, positional slots of the type */
    char writes[PG_MAX_SLOTS][PG_NAME_MAX];
    char after[PG_MAX_AFTER][PG_NAME_MAX];   /* explicit ordering: run after these passes */
    bool side_effects;                       /* never culled */
    pg_queue_pref queue;                     /* "queue": "auto" (default), "graphics", "compute" */
    struct cJSON *options;                   /* object, "$param" already substituted; never NULL */
    char file[PG_PATH_MAX];
    char json_path[PG_JSON_PATH_MAX];        /* e.g. "passes[2]" */
} pg_pass_desc;

/* An item dropped because its "when" condition was false: reported by --explain. */
typedef struct pg_omitted {
    char what[PG_NAME_MAX + 16]; /* "pass 'x'" / "resource 'y'" */
    char why[160];               /* "when: $gbuffer == float (gbuffer is 'packed')" */
} pg_omitted;

#define PG_MAX_PIPELINE_PLUGINS 4
#define PG_MAX_SOURCE_DIRS 8

typedef struct pg_pipeline {
    char name[PG_NAME_MAX];
    char description[256];
    char path[PG_PATH_MAX];             /* the top-level file */
    uint32_t n_params, n_resources, n_passes, n_omitted;
    pg_param params[PG_MAX_PARAMS];
    pg_resource_desc resources[PG_MAX_RESOURCES];
    pg_pass_desc passes[PG_MAX_PASSES];
    pg_omitted omitted[PG_MAX_PASSES + PG_MAX_RESOURCES];
    char output[PG_NAME_MAX];           /* the final displayable image (required) */
    char hdr_output[PG_NAME_MAX];       /* optional scene-linear HDR image to inspect/read back */
    /* "plugins" (top-level file only): shared libraries of pass types the pipeline needs, resolved
     * against the file's folder and held to the include rules (pipeline_paths.h); loading them is
     * the application's or the library's (renderer/plugins.c), before the pipeline is compiled */
    uint32_t n_plugins;
    char plugins[PG_MAX_PIPELINE_PLUGINS][PG_PATH_MAX];
    /* the folders of the files it was read from (the top-level file's and its includes', real
     * paths, each once; the first PG_MAX_SOURCE_DIRS): what an editor watches for changes */
    uint32_t n_source_dirs;
    char source_dirs[PG_MAX_SOURCE_DIRS][PG_PATH_MAX];
} pg_pipeline;

/* Loads path (and its includes). overrides may be NULL when n_overrides is 0. */
pg_result pg_pipeline_load(const char *path, const pg_param_override *overrides,
                           uint32_t n_overrides, pg_pipeline **out, pg_error *err);
/* Same from a string; virtual_path is used in messages and to resolve relative includes. */
pg_result pg_pipeline_load_string(const char *json_text, const char *virtual_path,
                                  const pg_param_override *overrides, uint32_t n_overrides,
                                  pg_pipeline **out, pg_error *err);
void pg_pipeline_free(pg_pipeline *p);

const pg_resource_desc *pg_pipeline_find_resource(const pg_pipeline *p, const char *name);
/* An image's extent for an output of output_width x output_height: scale (rounded up) or size, at
 * least 1 a side; the compiler refuses a scale out of range and an extent over its limit. */
void pg_resource_extent(const pg_resource_desc *rd, uint32_t output_width, uint32_t output_height, uint64_t *w,
                        uint64_t *h);
const pg_param *pg_pipeline_find_param(const pg_pipeline *p, const char *name);
/* Value of a parameter formatted as text ("16", "0.5", "true", "packed"). */
void pg_param_format(const pg_param *param, char *buf, size_t buf_size);

#ifdef __cplusplus
}
#endif
#endif
