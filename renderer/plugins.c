/* plugins.c - loading pass-type plug-ins (plugins.h). */
#include "plugins.h"
#include "pass_plugin.h"
#include "pipeline.h"

#include <dlfcn.h>
#include <limits.h>
#include <stdlib.h>
#include <stdio.h>
#include <errno.h>
#include <string.h>
#include <sys/stat.h>

/* The plug-in's symbols, API version and registration (the types it adds: reg->types[before..]) */
static pg_result register_types(pg_pass_registry *reg, void *h, const char *path, uint32_t before, pg_error *err)
{
    pg_plugin_version_fn version;
    pg_plugin_register_fn reg_fn;
    void *v = dlsym(h, PG_PLUGIN_VERSION_SYMBOL), *r = dlsym(h, PG_PLUGIN_REGISTER_SYMBOL);
    if (!v || !r)
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s: not a passgraph plug-in: no %s", path,
                       !v ? PG_PLUGIN_VERSION_SYMBOL : PG_PLUGIN_REGISTER_SYMBOL);
    memcpy(&version, &v, sizeof version); /* object pointer -> function pointer, as POSIX allows */
    memcpy(&reg_fn, &r, sizeof reg_fn);
    const uint32_t got = version();
    if (got != PG_PLUGIN_API_VERSION)
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s: plug-in API version %u; this passgraph has %u (rebuild the "
                                                "plug-in against this passgraph's headers)",
                       path, got, PG_PLUGIN_API_VERSION);
    pg_error e = {0};
    pg_result rr = reg_fn(reg, &e);
    if (rr) return pg_fail(err, rr, "%s: %s", path, e.msg[0] ? e.msg : "registration failed");
    if (reg->count == before)
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s: the plug-in registered no pass type", path);
    for (uint32_t i = before; i < reg->count; i++) { /* a type the runtime cannot create or record: not taken */
        const pg_pass_type *t = reg->types[i];
        if (!t->create || !t->record || !t->destroy)
            return pg_fail(err, PG_ERR_INVALID_ARG, "%s: pass type '%s' has no %s function (a plug-in's pass types "
                           "give declare, create, record and destroy)",
                           path, t->name, !t->create ? "create" : !t->record ? "record" : "destroy");
    }
    return PG_OK;
}

static pg_result load_one(pg_pass_registry *reg, const char *path, pg_plugins *out, pg_error *err)
{
    struct stat st;
    if (!path[0]) return pg_fail(err, PG_ERR_IO, "--plugin \"\": an empty path");
    if (stat(path, &st) != 0) return pg_fail(err, PG_ERR_IO, "%s: cannot load plug-in: %s", path, strerror(errno));
    if (S_ISDIR(st.st_mode)) return pg_fail(err, PG_ERR_IO, "%s: cannot load plug-in: is a directory", path);
    /* a bare name would be searched in the system's library path: make it a path */
    char full[PG_PATH_MAX + 4];
    snprintf(full, sizeof full, "%s%s", strchr(path, '/') ? "" : "./", path);
    char real0[PATH_MAX] = ""; /* a library is loaded once by its real path (named twice, or through a link) */
    if (!realpath(full, real0)) real0[0] = 0; /* unset on failure */
    else
        for (uint32_t k = 0; k < out->n; k++)
            if (!strcmp(out->paths[k], real0)) return PG_OK;
    void *h = dlopen(full, RTLD_NOW | RTLD_LOCAL);
    if (!h) {
        const char *why = dlerror();
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s: cannot load plug-in: %s", path, why ? why : "dlopen failed");
    }
    const uint32_t before = reg->count;
    pg_result r = register_types(reg, h, path, before, err);
    if (r) { /* not kept: recorded, a later load of the same path said PG_OK and loaded nothing */
        reg->count = before; /* the types a failed registration added are not taken either */
        dlclose(h);
        return r;
    }
    pg_strlcpy(out->paths[out->n], real0[0] ? real0 : full, PG_PATH_MAX);
    out->handles[out->n++] = h;
    return PG_OK;
}

pg_result pg_plugins_load(pg_pass_registry *reg, const char *const *paths, uint32_t n, pg_plugins *out,
                          pg_error *err)
{
    if (n > PG_MAX_PLUGINS)
        return pg_fail(err, PG_ERR_LIMIT, "--plugin: %u plug-ins, at most %d", n, PG_MAX_PLUGINS);
    for (uint32_t i = 0; i < n; i++) {
        pg_result r = load_one(reg, paths[i], out, err);
        if (r) return r;
    }
    return PG_OK;
}

pg_result pg_plugins_load_listed(pg_pass_registry *reg, const char *pipeline_path, pg_plugins *out, pg_error *err)
{
    pg_pipeline *p = NULL;
    pg_error ignored;
    if (pg_pipeline_load(pipeline_path, NULL, 0, &p, &ignored)) return PG_OK; /* the session says why */
    pg_result r = PG_OK;
    for (uint32_t i = 0; i < p->n_plugins && !r; i++) {
        char real[PATH_MAX];
        if (!realpath(p->plugins[i], real)) pg_strlcpy(real, p->plugins[i], sizeof real);
        bool loaded = false;
        for (uint32_t k = 0; k < out->n && !loaded; k++) loaded = !strcmp(out->paths[k], real);
        if (loaded) continue;
        if (out->n >= PG_MAX_PLUGINS) {
            r = pg_fail(err, PG_ERR_LIMIT, "%s: plugins: more than %d plug-ins in all", pipeline_path, PG_MAX_PLUGINS);
        } else if ((r = load_one(reg, p->plugins[i], out, err))) {
            pg_error_prefix(err, "%s: plugins[%u]", pipeline_path, i);
        }
    }
    pg_pipeline_free(p);
    return r;
}

void pg_plugins_close(pg_plugins *p)
{
    for (uint32_t i = p->n; i-- > 0;)
        if (p->handles[i]) dlclose(p->handles[i]);
    memset(p, 0, sizeof *p);
}
