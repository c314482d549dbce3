/* pg_common.h - results, error messages, formats and limits shared by every passgraph module.
 *
 * Errors are values: every fallible function returns a pg_result and, on failure, fills the
 * caller-owned pg_error with a message that names the file, the JSON path / field and the cause.
 */
#ifndef PG_COMMON_H
#define PG_COMMON_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum pg_result {
    PG_OK = 0,
    PG_ERR_IO,               /* file missing or unreadable */
    PG_ERR_PARSE,            /* malformed JSON / glTF syntax */
    PG_ERR_SCHEMA,           /* well-formed but wrong shape: missing/extra field, wrong type */
    PG_ERR_UNKNOWN_PASS,     /* pass type not in the registry */
    PG_ERR_UNKNOWN_RESOURCE, /* a pass or the output names an undeclared resource */
    PG_ERR_WRITE_CONFLICT,   /* resource written by two passes without ordering */
    PG_ERR_CYCLE,            /* pass dependencies form a cycle */
    PG_ERR_NO_OUTPUT,        /* output missing or unknown */
    PG_ERR_FORMAT,           /* resource format not valid for the access a pass makes */
    PG_ERR_PARAM,            /* bad parameter declaration, value or override */
    PG_ERR_INCLUDE,          /* include missing, cyclic or too deep */
    PG_ERR_LIMIT,            /* a fixed limit (passes, resources, slots...) exceeded */
    PG_ERR_READ_BEFORE_WRITE,/* transient resource read before any pass writes it */
    PG_ERR_GLTF,             /* glTF content invalid (accessors, indices, non-finite data...) */
    PG_ERR_SHADER,           /* GLSL failed to compile */
    PG_ERR_VULKAN,           /* a Vulkan call failed */
    PG_ERR_NO_DEVICE,        /* no suitable Vulkan device */
    PG_ERR_OOM,              /* allocation failed */
    PG_ERR_INVALID_ARG,      /* bad API / command line argument */
    PG_ERR_COUNT
} pg_result;

#define PG_ERROR_MSG_MAX 1024

/* alignment of a member in headers a C++ program may include (C11 _Alignas is no C++ keyword) */
#ifdef __cplusplus
#define PG_ALIGNAS(n) alignas(n)
#else
#define PG_ALIGNAS(n) _Alignas(n)
#endif

typedef struct pg_error {
    pg_result code;
    char msg[PG_ERROR_MSG_MAX];
} pg_error;

/* Fills err (if non-NULL) with code and a printf-style message; returns code. */
pg_result pg_fail(pg_error *err, pg_result code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* Prepends "prefix: " to an existing message (keeps the code). Returns err->code. */
pg_result pg_error_prefix(pg_error *err, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* Stable name of a result code, e.g. "PG_ERR_CYCLE". */
const char *pg_result_name(pg_result r);

/* ---- limits (fixed so the compiled graph is plain data; exceeding one is PG_ERR_LIMIT) ---- */
#define PG_NAME_MAX 64
#define PG_PATH_MAX 512
#define PG_JSON_PATH_MAX 128
#define PG_MAX_PASSES 64
#define PG_MAX_RESOURCES 96
#define PG_MAX_SLOTS 12          /* reads or writes per pass */
#define PG_MAX_PARAMS 48
#define PG_MAX_AFTER 8
#define PG_MAX_ENUM_VALUES 12
#define PG_MAX_COUNT_TERMS 4
#define PG_MAX_EXPLAIN 256       /* explanation lines in a compiled graph */
#define PG_EXPLAIN_MAX 256
#define PG_MAX_BARRIERS_PER_PASS 24

/* ---- formats ---- */
typedef enum pg_format {
    PG_FMT_UNDEFINED = 0,
    PG_FMT_RGBA8_UNORM,
    PG_FMT_RGBA8_SRGB,
    PG_FMT_RGBA16F,
    PG_FMT_RGBA32F,
    PG_FMT_RG16F,
    PG_FMT_RGBA16_UNORM,
    PG_FMT_RG16_UNORM,
    PG_FMT_RG16_SNORM,
    PG_FMT_R32F,
    PG_FMT_R32UI,
    PG_FMT_RG32UI,
    PG_FMT_RGBA32UI,
    PG_FMT_R11G11B10F,
    PG_FMT_D32F,
    PG_FMT_COUNT
} pg_format;

typedef enum pg_format_class {
    PG_FMTCLASS_NONE = 0,
    PG_FMTCLASS_FLOAT = 1u << 0, /* unorm / snorm / float / srgb colour formats */
    PG_FMTCLASS_UINT = 1u << 1,  /* integer colour formats */
    PG_FMTCLASS_DEPTH = 1u << 2,
    PG_FMTCLASS_ANY_COLOR = PG_FMTCLASS_FLOAT | PG_FMTCLASS_UINT,
    PG_FMTCLASS_ANY = PG_FMTCLASS_FLOAT | PG_FMTCLASS_UINT | PG_FMTCLASS_DEPTH
} pg_format_class;

typedef struct pg_format_info {
    const char *name;        /* as written in pipeline JSON, e.g. "rgba16f" */
    uint32_t vk_format;      /* VkFormat value */
    uint32_t bytes_per_pixel;
    pg_format_class fmt_class;
    bool srgb;
    bool storage_ok;         /* usable as a storage image (portable set) */
} pg_format_info;

const pg_format_info *pg_format_get(pg_format f);
/* Returns PG_FMT_UNDEFINED for unknown names. */
pg_format pg_format_from_name(const char *name);

/* ---- small helpers ---- */
/* A name pipelines can write: [A-Za-z0-9_]+, at most PG_NAME_MAX - 1 characters (pass, resource
 * and pass type names). */
bool pg_ident_ok(const char *s);
/* Safe string copy: always NUL-terminates, returns false if truncated. */
bool pg_strlcpy(char *dst, const char *src, size_t dst_size);
/* Reads a whole file into a malloc'd NUL-terminated buffer. */
pg_result pg_read_file(const char *path, char **out_text, size_t *out_size, pg_error *err);
/* The same; a path that is a directory or another non-regular file is refused (PG_ERR_IO) with
 * "PATH: is a directory (expected EXPECTED)" (EXPECTED e.g. "a scenario .json file"; NULL leaves
 * the parenthesis out). */
pg_result pg_read_file_as(const char *path, const char *expected, char **out_text, size_t *out_size,
                          pg_error *err);

/* Where shaders/, pipelines/ and assets/ live: $PASSGRAPH_DATA_DIR, else next to the executable
 * (../share/passgraph for an installed bundle), else the source tree. Never NULL. */
const char *pg_data_dir(void);
/* Joins pg_data_dir() and rel into buf. */
/* Seconds on the monotonic clock (for durations). */
double pg_time_s(void);
void pg_data_path(char *buf, size_t size, const char *rel);

#ifdef __cplusplus
}
#endif
#endif
