/* pipeline_json_include.c - the pipeline loader's source files: the top-level file and, depth
 * first, its includes (missing, unreadable, cyclic, too deep, too many), the keys allowed in each,
 * and the parameter declarations and resource / pass objects each contributes, in merge order.
 * Part of the loader (pipeline_json_internal.h).
 */
#ifndef _XOPEN_SOURCE
#define _XOPEN_SOURCE 700 /* realpath() */
#endif
#include "pipeline_json_internal.h"
#include "pg_file.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define PG_MAX_INCLUDE_FILES 256 /* files loaded in all (guards against include fan-out) */

/* ------------------------------------------------------------------ files */

src_file *pj_new_file(loader *L, const char *path)
{
    if (L->n_files == L->cap_files) {
        uint32_t cap = L->cap_files ? L->cap_files * 2 : 8;
        src_file **nf = realloc(L->files, cap * sizeof *nf);
        if (!nf) return NULL;
        L->files = nf;
        L->cap_files = cap;
    }
    src_file *f = calloc(1, sizeof *f);
    if (!f) return NULL;
    pg_strlcpy(f->path, path, sizeof f->path);
    L->files[L->n_files++] = f;
    return f;
}

static const char *const k_top_keys[] = {"name",   "description", "include",    "parameters", "resources",
                                         "passes", "output",      "hdr_output", "plugins",    NULL};
static const char *const k_frag_keys[] = {"description", "include", "parameters", "resources",
                                          "passes", NULL};

static void include_chain(loader *L, const char *last, char *buf, size_t n)
{
    buf[0] = 0;
    for (uint32_t i = 0; i <= L->depth; i++) {
        size_t len = strlen(buf);
        snprintf(buf + len, n - len, "%s%s", i ? " -> " : "", L->stack[i]->path);
    }
    size_t len = strlen(buf);
    snprintf(buf + len, n - len, " -> %s", last);
}

static pg_result load_include(loader *L, const src_file *from, uint32_t idx, const char *rel)
{
    char ipath[32];
    snprintf(ipath, sizeof ipath, "include[%u]", idx);
    char path[PG_PATH_MAX];
    if (rel[0] == '/') {
        if (!pg_strlcpy(path, rel, sizeof path))
            return pj_fail_at(L, PG_ERR_INCLUDE, from, ipath, "path too long");
    } else {
        const char *slash = strrchr(from->path, '/');
        int dirlen = slash ? (int)(slash - from->path) + (slash == from->path) : 0;
        int n = dirlen ? snprintf(path, sizeof path, "%.*s%s%s", dirlen, from->path,
                                  from->path[dirlen - 1] == '/' ? "" : "/", rel)
                       : snprintf(path, sizeof path, "%s", rel);
        if (n < 0 || (size_t)n >= sizeof path)
            return pj_fail_at(L, PG_ERR_INCLUDE, from, ipath, "path too long");
    }
    if (L->depth + 1 > PG_MAX_INCLUDE_DEPTH) {
        char chain[700];
        include_chain(L, path, chain, sizeof chain);
        return pj_fail_at(L, PG_ERR_INCLUDE, from, ipath, "includes nested deeper than %d levels: %s",
                       PG_MAX_INCLUDE_DEPTH, chain);
    }
    if (L->n_files >= PG_MAX_INCLUDE_FILES)
        return pj_fail_at(L, PG_ERR_INCLUDE, from, ipath, "more than %d files included in all",
                       PG_MAX_INCLUDE_FILES);
    /* inside the allowed folders (decided on the name, before the file is touched) */
    pg_result r = pj_include_allowed(L, from, ipath, rel, path);
    if (r) return r;
    struct stat st;
    if (stat(path, &st) != 0)
        return pj_fail_at(L, PG_ERR_INCLUDE, from, ipath, "cannot open '%s': %s", path,
                       strerror(errno));
    if (!S_ISREG(st.st_mode))
        return pj_fail_at(L, PG_ERR_INCLUDE, from, ipath, "'%s' is %s, not a regular file", path,
                          pg_file_kind_name((unsigned)st.st_mode));
    char *canon = realpath(path, NULL);
    if (!canon) canon = strdup(path);
    if (!canon) return pg_fail(L->err, PG_ERR_OOM, "%s: out of memory", from->path);
    for (uint32_t i = 0; i <= L->depth; i++) {
        if (strcmp(L->stack[i]->canon, canon) == 0) {
            free(canon);
            char chain[700];
            include_chain(L, path, chain, sizeof chain);
            return pj_fail_at(L, PG_ERR_INCLUDE, from, ipath, "include cycle: %s", chain);
        }
    }
    src_file *f = pj_new_file(L, path);
    if (!f) {
        free(canon);
        return pg_fail(L->err, PG_ERR_OOM, "%s: out of memory", from->path);
    }
    f->canon = canon;
    char *text = NULL;
    size_t len = 0;
    r = pg_file_read(path, "pipeline", PG_FILE_CAP_PIPELINE, &text, &len, L->err);
    if (r) {
        char cause[PG_ERROR_MSG_MAX];
        pg_strlcpy(cause, L->err ? L->err->msg : "", sizeof cause);
        return pj_fail_at(L, r == PG_ERR_OOM || r == PG_ERR_LIMIT ? r : PG_ERR_INCLUDE, from, ipath,
                       "cannot read '%s': %s", path, cause);
    }
    r = pj_parse_text(L, f, text, len);
    free(text);
    if (r) return r;
    L->stack[++L->depth] = f;
    r = pj_process_file(L, f);
    L->depth--;
    return r;
}

static pg_result collect_items(loader *L, const src_file *f, const char *key, item_ref *items,
                               uint32_t *n, uint32_t max)
{
    const cJSON *arr = cJSON_GetObjectItemCaseSensitive(f->root, key);
    if (!arr) return PG_OK;
    if (!cJSON_IsArray(arr)) {
        char got[96];
        pj_describe(arr, got, sizeof got);
        return pj_fail_at(L, PG_ERR_SCHEMA, f, key, "expected an array, got %s", got);
    }
    uint32_t i = 0;
    for (cJSON *c = arr->child; c; c = c->next, i++) {
        if (*n >= max) {
            char path[64];
            snprintf(path, sizeof path, "%s[%u]", key, i);
            return pj_fail_at(L, PG_ERR_LIMIT, f, path,
                           "more than %u %s (the pipeline and its includes)", max, key);
        }
        item_ref *it = &items[(*n)++];
        memset(it, 0, sizeof *it);
        it->node = c;
        it->file = f;
        it->index = i;
    }
    return PG_OK;
}

pg_result pj_process_file(loader *L, const src_file *f)
{
    bool top = L->depth == 0;
    pg_result r = pj_check_keys(L, f, f->root, "(top level)",
                             top ? "a pipeline file" : "an included fragment",
                             top ? k_top_keys : k_frag_keys);
    if (r) return r;

    const cJSON *inc = cJSON_GetObjectItemCaseSensitive(f->root, "include");
    if (inc) {
        if (!cJSON_IsArray(inc)) {
            char got[96];
            pj_describe(inc, got, sizeof got);
            return pj_fail_at(L, PG_ERR_SCHEMA, f, "include",
                           "expected an array of relative paths, got %s", got);
        }
        uint32_t i = 0;
        for (const cJSON *c = inc->child; c; c = c->next, i++) {
            if (!cJSON_IsString(c) || !c->valuestring[0]) {
                char got[96], path[32];
                pj_describe(c, got, sizeof got);
                snprintf(path, sizeof path, "include[%u]", i);
                return pj_fail_at(L, PG_ERR_SCHEMA, f, path, "expected a file path, got %s", got);
            }
            r = load_include(L, f, i, c->valuestring);
            if (r) return r;
        }
    }

    const cJSON *params = cJSON_GetObjectItemCaseSensitive(f->root, "parameters");
    if (params) {
        if (!cJSON_IsObject(params)) {
            char got[96];
            pj_describe(params, got, sizeof got);
            return pj_fail_at(L, PG_ERR_SCHEMA, f, "parameters",
                           "expected an object of declarations, got %s", got);
        }
        for (const cJSON *c = params->child; c; c = c->next) {
            r = pj_add_param(L, f, c);
            if (r) return r;
        }
    }
    r = collect_items(L, f, "resources", L->res, &L->n_res, PG_MAX_RESOURCES);
    if (r) return r;
    return collect_items(L, f, "passes", L->pass, &L->n_pass, PG_MAX_PASSES);
}
