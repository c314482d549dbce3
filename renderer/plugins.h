/* plugins.h - `--plugin FILE.so` and a pipeline's "plugins": pass types from shared libraries
 * (core/graph/pass_plugin.h, docs/plugins.md), loaded into the tool's or an embedding session's
 * registry after the built-in ones. */
#ifndef PG_PLUGINS_H
#define PG_PLUGINS_H

#include "pass_api.h"

#define PG_MAX_PLUGINS 8

typedef struct pg_plugins {
    uint32_t n;
    void *handles[PG_MAX_PLUGINS];
    char paths[PG_MAX_PLUGINS][PG_PATH_MAX]; /* each one's real path (a library is loaded once) */
} pg_plugins;

/* Loads each file (a path: "FILE: cannot load: <dlerror>" when it does not load), checks its API
 * version ("FILE: plug-in API version V; this passgraph has 1") and both entry points ("FILE: not
 * a passgraph plug-in: no passgraph_plugin_register"), then lets it register its pass types
 * (their errors prefixed with "FILE: "). Stops at the first failure (PG_ERR_INVALID_ARG or
 * PG_ERR_IO); what was loaded stays in `out` for pg_plugins_close. */
pg_result pg_plugins_load(pg_pass_registry *reg, const char *const *paths, uint32_t n, pg_plugins *out,
                          pg_error *err);
/* The plug-ins a pipeline file lists ("plugins", pipeline.h: resolved and confined by the loader)
 * that are not loaded yet (by real path: one named by --plugin too is loaded once), loaded as
 * above, their errors prefixed "PIPELINE: plugins: ". A pipeline that does not load is left to the
 * caller's session, which reports why. */
pg_result pg_plugins_load_listed(pg_pass_registry *reg, const char *pipeline_path, pg_plugins *out, pg_error *err);
/* Unloads them (after every session using their types is destroyed). */
void pg_plugins_close(pg_plugins *p);

#endif
