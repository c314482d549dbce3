/* pg_cache.h - the on-disk caches: SPIR-V per shader variant (core/vk/shader.c) and the Vulkan
 * pipeline cache per device (core/vk/vk_context.c).
 *
 * Folder: $PASSGRAPH_CACHE_DIR, else $XDG_CACHE_HOME/passgraph, else $HOME/.cache/passgraph.
 * Off: pg_cache_set_enabled(false) (the tools' --no-shader-cache) or PASSGRAPH_NO_SHADER_CACHE set
 * to anything but "" or "0"; then every shader is compiled by glslang and no pipeline cache is
 * used. A cache file that is corrupt or made for another device/compiler is ignored with a note on
 * stderr; a cache that cannot be written is a note, never an error.
 */
#ifndef PG_CACHE_H
#define PG_CACHE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

bool pg_cache_enabled(void);
void pg_cache_set_enabled(bool on);
/* The cache folder (not created); false when none can be named (no variable set). */
bool pg_cache_dir(char *buf, size_t size);
/* Creates dir and its parents (mode 0755); true when it exists afterwards. */
bool pg_cache_mkdirs(const char *dir);
/* Prints "passgraph: note: ..." to stderr. */
void pg_cache_note(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
/* A 128-bit hash (two independent 64-bit lanes), chained through h. */
typedef struct pg_hash128 {
    uint64_t a, b;
} pg_hash128;
pg_hash128 pg_hash128_init(void);
void pg_hash128_add(pg_hash128 *h, const void *data, size_t n);
/* Writes head then body to path through a temporary file and rename (readers never see half a
 * file). false (with a note) on failure. */
bool pg_cache_write(const char *path, const void *head, size_t head_bytes, const void *body, size_t body_bytes);
/* Reads a whole file (malloc'd; NULL when absent or unreadable). */
void *pg_cache_read(const char *path, size_t *bytes);

/* SPIR-V cache counters since start (or since pg_shader_cache_forget). */
typedef struct pg_shader_cache_stats {
    uint32_t compiled;    /* variants glslang compiled */
    uint32_t memory_hits; /* served from this process's memory */
    uint32_t disk_hits;   /* loaded from a .spv file */
    uint32_t disk_writes; /* .spv files written */
    uint32_t rejected;    /* .spv files ignored as corrupt */
    double compile_ms;    /* wall time in glslang (preprocess, parse, link, SPIR-V) */
    double lookup_ms;     /* wall time finding variants in the caches (hits and misses) */
} pg_shader_cache_stats;
void pg_shader_cache_stats_get(pg_shader_cache_stats *out);
/* Empties the in-memory cache and zeroes the counters (tests: "a new process"). */
void pg_shader_cache_forget(void);

#ifdef __cplusplus
}
#endif
#endif
