/* pipeline_json.c - loads a pipeline description (pipelines/README.md documents the format).
 *
 * Phases, in order:
 *   1. parse   read the top-level file and, depth first, its includes; check JSON syntax, the
 *              keys allowed at the top level, duplicate object keys, the include graph (missing,
 *              cyclic, too deep) and every parameter declaration; collect the resource and pass
 *              objects in merge order (an include's items before the includer's own).
 *   2. params  apply the --set overrides (typed, range checked).
 *   3. items   pj_substitute "$param" strings inside every resource and pass, then validate each
 *              one, evaluate its "when" condition and record what was omitted and why.
 *   4. links   resolve reads/writes/after names and the outputs against the surviving items.
 *   5. build   copy the surviving items into the pg_pipeline; each pass's options object is
 *              detached from its file's tree and owned by the pipeline.
 * Every parsed tree is owned by the loader and freed on every path.
 *
 * The loader is split over the files pipeline_json_internal.h lists; this one holds the passes,
 * the links, the build and the entry points (pg_pipeline_load, pg_pipeline_load_string).
 */
#ifndef _XOPEN_SOURCE
#define _XOPEN_SOURCE 700 /* realpath() */
#endif
#include "pipeline_json_internal.h"
#include "pipeline_paths.h"
#include "pg_file.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static const char *const k_pass_keys[] = {"name",  "type",         "reads",   "writes",
                                          "after", "side_effects", "options", "when",
                                          "description", "queue", NULL};

/* ------------------------------------------------------------------ passes */

static pg_result name_list(loader *L, const src_file *f, const cJSON *o, const char *ip,
                           const char *key, uint32_t max, char (*out)[PG_NAME_MAX], uint32_t *n)
{
    char path[PG_JSON_PATH_MAX], got[96];
    snprintf(path, sizeof path, "%s.%s", ip, key);
    *n = 0;
    const cJSON *arr = cJSON_GetObjectItemCaseSensitive(o, key);
    if (!arr) return PG_OK;
    if (!cJSON_IsArray(arr)) {
        pj_describe(arr, got, sizeof got);
        return pj_fail_at(L, PG_ERR_SCHEMA, f, path, "expected an array of names, got %s", got);
    }
    int cnt = cJSON_GetArraySize(arr);
    if (cnt > (int)max)
        return pj_fail_at(L, PG_ERR_LIMIT, f, path, "%d entries, the limit is %u", cnt, max);
    uint32_t k = 0;
    for (const cJSON *c = arr->child; c; c = c->next, k++) {
        if (!cJSON_IsString(c) || !pg_ident_ok(c->valuestring)) {
            pj_describe(c, got, sizeof got);
            snprintf(path, sizeof path, "%s.%s[%u]", ip, key, k);
            return pj_fail_at(L, PG_ERR_SCHEMA, f, path,
                           "expected a name matching [A-Za-z0-9_]+, got %s", got);
        }
        pg_strlcpy(out[k], c->valuestring, PG_NAME_MAX);
    }
    *n = k;
    return PG_OK;
}

static pg_result parse_pass(loader *L, uint32_t idx)
{
    item_ref *it = &L->pass[idx];
    pg_pass_desc *d = &L->pdesc[idx];
    const src_file *f = it->file;
    char ip[48], path[PG_JSON_PATH_MAX], got[96];
    snprintf(ip, sizeof ip, "passes[%u]", it->index);
    memset(d, 0, sizeof *d);
    pg_strlcpy(d->file, f->path, sizeof d->file);
    pg_strlcpy(d->json_path, ip, sizeof d->json_path);
    cJSON *o = it->node;
    pg_result r = pj_item_begin(L, f, o, ip, "pass", k_pass_keys, d->name);
    if (r) return r;
    for (uint32_t j = 0; j < idx; j++)
        if (strcmp(L->pdesc[j].name, d->name) == 0)
            return pj_item_twice(L, f, ip, "pass", d->name, L->pass[j].file, L->pdesc[j].file,
                                 L->pdesc[j].json_path);
    r = pj_req_ident(L, f, o, ip, "type", d->type);
    if (r) return r;
    r = name_list(L, f, o, ip, "reads", PG_MAX_SLOTS, d->reads, &d->n_reads);
    if (r) return r;
    r = name_list(L, f, o, ip, "writes", PG_MAX_SLOTS, d->writes, &d->n_writes);
    if (r) return r;
    r = name_list(L, f, o, ip, "after", PG_MAX_AFTER, d->after, &d->n_after);
    if (r) return r;
    const cJSON *se = cJSON_GetObjectItemCaseSensitive(o, "side_effects");
    if (se) {
        if (!cJSON_IsBool(se)) {
            pj_describe(se, got, sizeof got);
            snprintf(path, sizeof path, "%s.side_effects", ip);
            return pj_fail_at(L, PG_ERR_SCHEMA, f, path, "expected true or false, got %s", got);
        }
        d->side_effects = cJSON_IsTrue(se);
    }
    const cJSON *qu = cJSON_GetObjectItemCaseSensitive(o, "queue");
    if (qu) {
        const char *qs = cJSON_IsString(qu) ? qu->valuestring : NULL;
        if (qs && !strcmp(qs, "auto")) d->queue = PG_QUEUE_PREF_AUTO;
        else if (qs && !strcmp(qs, "graphics")) d->queue = PG_QUEUE_PREF_GRAPHICS;
        else if (qs && !strcmp(qs, "compute")) d->queue = PG_QUEUE_PREF_COMPUTE;
        else {
            pj_describe(qu, got, sizeof got);
            snprintf(path, sizeof path, "%s.queue", ip);
            return pj_fail_at(L, PG_ERR_SCHEMA, f, path,
                              "expected \"auto\", \"graphics\" or \"compute\", got %s", got);
        }
    }
    cJSON *opts = cJSON_GetObjectItemCaseSensitive(o, "options");
    if (opts && !cJSON_IsObject(opts)) {
        pj_describe(opts, got, sizeof got);
        snprintf(path, sizeof path, "%s.options", ip);
        return pj_fail_at(L, PG_ERR_SCHEMA, f, path, "expected an object, got %s", got);
    }
    it->options = opts;
    d->options = opts;
    r = pj_opt_description(L, f, o, ip);
    if (r) return r;

    bool active;
    char why[sizeof L->p->omitted[0].why];
    r = pj_eval_when(L, f, o, ip, &active, why, sizeof why);
    if (r) return r;
    if (!active) {
        pg_omitted *om = &L->p->omitted[L->p->n_omitted];
        snprintf(om->what, sizeof om->what, "pass '%s'", d->name);
        pg_strlcpy(om->why, why, sizeof om->why);
        it->omitted = true;
        it->omit_index = L->p->n_omitted++;
    }
    return PG_OK;
}

static int find_res(const loader *L, const char *name)
{
    for (uint32_t i = 0; i < L->n_res; i++)
        if (strcmp(L->rdesc[i].name, name) == 0) return (int)i;
    return -1;
}

static int find_pass(const loader *L, const char *name)
{
    for (uint32_t i = 0; i < L->n_pass; i++)
        if (strcmp(L->pdesc[i].name, name) == 0) return (int)i;
    return -1;
}

static void resource_names(const loader *L, char *buf, size_t n)
{
    buf[0] = 0;
    for (uint32_t i = 0; i < L->n_res; i++)
        if (!L->res[i].omitted) pj_list_append(buf, n, L->rdesc[i].name);
    if (!buf[0]) snprintf(buf, n, "none");
}

/* Resolves a pass's reads/writes against the declared resources. */
static pg_result link_slots(loader *L, uint32_t idx, const char *key, char (*names)[PG_NAME_MAX],
                            uint32_t n)
{
    const item_ref *it = &L->pass[idx];
    for (uint32_t k = 0; k < n; k++) {
        char path[PG_JSON_PATH_MAX];
        snprintf(path, sizeof path, "passes[%u].%s[%u]", it->index, key, k);
        int j = find_res(L, names[k]);
        if (j < 0) {
            char list[600];
            resource_names(L, list, sizeof list);
            return pj_fail_at(L, PG_ERR_UNKNOWN_RESOURCE, it->file, path,
                           "unknown resource '%s' (declared: %s)", names[k], list);
        }
        if (L->res[j].omitted && !it->omitted)
            return pj_fail_at(L, PG_ERR_UNKNOWN_RESOURCE, it->file, path,
                           "resource '%s' (%s: %s) is omitted: %s", names[k], L->rdesc[j].file,
                           L->rdesc[j].json_path, L->p->omitted[L->res[j].omit_index].why);
    }
    return PG_OK;
}

static pg_result link_pass(loader *L, uint32_t idx)
{
    pg_pass_desc *d = &L->pdesc[idx];
    const item_ref *it = &L->pass[idx];
    pg_result r = link_slots(L, idx, "reads", d->reads, d->n_reads);
    if (r) return r;
    r = link_slots(L, idx, "writes", d->writes, d->n_writes);
    if (r) return r;
    uint32_t kept = 0;
    for (uint32_t k = 0; k < d->n_after; k++) {
        int j = find_pass(L, d->after[k]);
        if (j < 0) {
            char path[PG_JSON_PATH_MAX];
            snprintf(path, sizeof path, "passes[%u].after[%u]", it->index, k);
            return pj_fail_at(L, PG_ERR_SCHEMA, it->file, path, "unknown pass '%s'", d->after[k]);
        }
        if (L->pass[j].omitted) continue; /* ordering against a dropped pass is moot */
        bool dup = false;
        for (uint32_t m = 0; m < kept; m++)
            if (strcmp(d->after[m], d->after[k]) == 0) dup = true;
        if (dup) continue;
        if (kept != k) memcpy(d->after[kept], d->after[k], PG_NAME_MAX);
        kept++;
    }
    d->n_after = kept;
    return PG_OK;
}

/* ------------------------------------------------------------------ top level */

static pg_result read_output(loader *L, const char *key, bool required, char *out)
{
    const src_file *f = L->files[0];
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(f->root, key);
    out[0] = 0;
    if (!v) {
        if (!required) return PG_OK;
        return pj_fail_at(L, PG_ERR_NO_OUTPUT, f, key,
                       "missing: name the image resource to display (\"%s\": \"...\")", key);
    }
    char got[96];
    if (!cJSON_IsString(v)) {
        pj_describe(v, got, sizeof got);
        return pj_fail_at(L, PG_ERR_SCHEMA, f, key, "expected an image resource name, got %s", got);
    }
    int j = pg_ident_ok(v->valuestring) ? find_res(L, v->valuestring) : -1;
    if (j < 0) {
        char list[600];
        resource_names(L, list, sizeof list);
        return pj_fail_at(L, PG_ERR_NO_OUTPUT, f, key, "unknown resource '%.64s' (declared: %s)",
                       v->valuestring, list);
    }
    if (L->res[j].omitted)
        return pj_fail_at(L, PG_ERR_NO_OUTPUT, f, key, "resource '%s' is omitted: %s",
                       v->valuestring, L->p->omitted[L->res[j].omit_index].why);
    if (L->rdesc[j].kind != PG_RES_IMAGE)
        return pj_fail_at(L, PG_ERR_NO_OUTPUT, f, key,
                       "'%s' is a buffer (%s: %s); the output must be an image", v->valuestring,
                       L->rdesc[j].file, L->rdesc[j].json_path);
    pg_strlcpy(out, v->valuestring, PG_NAME_MAX);
    return PG_OK;
}

/* "plugins": [paths] of the top-level file, resolved and confined like includes; each must exist */
static pg_result read_plugins(loader *L, const src_file *f)
{
    const cJSON *pl = cJSON_GetObjectItemCaseSensitive(f->root, "plugins");
    if (!pl) return PG_OK;
    char got[96], where[32];
    if (!cJSON_IsArray(pl)) {
        pj_describe(pl, got, sizeof got);
        return pj_fail_at(L, PG_ERR_SCHEMA, f, "plugins", "expected an array of at most %d shared-library paths, got %s",
                          PG_MAX_PIPELINE_PLUGINS, got);
    }
    if (cJSON_GetArraySize(pl) > PG_MAX_PIPELINE_PLUGINS)
        return pj_fail_at(L, PG_ERR_LIMIT, f, "plugins", "%d plug-ins, at most %d", cJSON_GetArraySize(pl),
                          PG_MAX_PIPELINE_PLUGINS);
    uint32_t i = 0;
    for (const cJSON *c = pl->child; c; c = c->next, i++) {
        snprintf(where, sizeof where, "plugins[%u]", i);
        pg_error e;
        char *dst = L->p->plugins[L->p->n_plugins];
        struct stat st;
        if (!cJSON_IsString(c) || !c->valuestring[0]) {
            pj_describe(c, got, sizeof got);
            return pj_fail_at(L, PG_ERR_SCHEMA, f, where, "expected a file path, got %s", got);
        }
        if (pg_pipeline_resolve_file(f->path, f->path, c->valuestring, dst, PG_PATH_MAX, &e))
            return pj_fail_at(L, e.code, f, where, "plug-in %s", e.msg);
        if (stat(dst, &st) != 0 || !S_ISREG(st.st_mode))
            return pj_fail_at(L, PG_ERR_IO, f, where, "plug-in '%s' (%s): %s", c->valuestring, dst,
                              stat(dst, &st) != 0  ? strerror(errno)
                              : S_ISDIR(st.st_mode) ? "is a directory"
                                                    : "not a regular file");
        L->p->n_plugins++;
    }
    return PG_OK;
}

static pg_result read_header(loader *L)
{
    const src_file *f = L->files[0];
    pg_pipeline *p = L->p;
    char got[96];
    const cJSON *name = cJSON_GetObjectItemCaseSensitive(f->root, "name");
    if (name) {
        if (!cJSON_IsString(name) || !name->valuestring[0] ||
            strlen(name->valuestring) >= PG_NAME_MAX) {
            pj_describe(name, got, sizeof got);
            return pj_fail_at(L, PG_ERR_SCHEMA, f, "name",
                           "expected a non-empty string of at most %d characters, got %s",
                           PG_NAME_MAX - 1, got);
        }
        pg_strlcpy(p->name, name->valuestring, sizeof p->name);
    } else {
        /* default: the file name without directory and extension */
        const char *base = strrchr(f->path, '/');
        base = base ? base + 1 : f->path;
        size_t n = strcspn(base, ".");
        if (n >= sizeof p->name) n = sizeof p->name - 1;
        memcpy(p->name, base, n);
        p->name[n] = 0;
    }
    const cJSON *desc = cJSON_GetObjectItemCaseSensitive(f->root, "description");
    if (desc) {
        if (!cJSON_IsString(desc)) {
            pj_describe(desc, got, sizeof got);
            return pj_fail_at(L, PG_ERR_SCHEMA, f, "description", "expected a string, got %s", got);
        }
        pg_strlcpy(p->description, desc->valuestring, sizeof p->description);
    }
    return read_plugins(L, f);
}

static void loader_free(loader *L)
{
    for (uint32_t i = 0; i < L->n_files; i++) {
        cJSON_Delete(L->files[i]->root);
        free(L->files[i]->canon);
        free(L->files[i]);
    }
    free(L->files);
    free(L);
}

static pg_result load_all(loader *L, const char *text, size_t len, const char *path,
                          const pg_param_override *ov, uint32_t n_ov)
{
    pg_pipeline *p = L->p;
    src_file *f = pj_new_file(L, path);
    if (!f) return pg_fail(L->err, PG_ERR_OOM, "%s: out of memory", path);
    f->canon = realpath(path, NULL);
    if (!f->canon) f->canon = strdup(path);
    if (!f->canon) return pg_fail(L->err, PG_ERR_OOM, "%s: out of memory", path);
    pg_strlcpy(p->path, path, sizeof p->path);
    L->stack[0] = f;
    L->depth = 0;
    pg_result r = pj_parse_text(L, f, text, len);
    if (r) return r;
    r = pj_process_file(L, f);
    if (r) return r;
    r = read_header(L);
    if (r) return r;
    if (n_ov && !ov) return pg_fail(L->err, PG_ERR_INVALID_ARG, "%s: overrides is NULL", path);
    r = pj_apply_overrides(L, ov, n_ov);
    if (r) return r;
    for (uint32_t i = 0; i < L->n_res; i++) {
        r = pj_parse_resource(L, i);
        if (r) return r;
    }
    for (uint32_t i = 0; i < L->n_pass; i++) {
        r = parse_pass(L, i);
        if (r) return r;
    }
    for (uint32_t i = 0; i < L->n_pass; i++) {
        r = link_pass(L, i);
        if (r) return r;
    }
    r = read_output(L, "output", true, p->output);
    if (r) return r;
    r = read_output(L, "hdr_output", false, p->hdr_output);
    if (r) return r;

    /* build: surviving items in merge order; options move into the pipeline */
    for (uint32_t i = 0; i < L->n_res; i++)
        if (!L->res[i].omitted) p->resources[p->n_resources++] = L->rdesc[i];
    for (uint32_t i = 0; i < L->n_pass; i++) {
        if (L->pass[i].omitted) continue;
        cJSON *opts = L->pass[i].options
                          ? cJSON_DetachItemViaPointer(L->pass[i].node, L->pass[i].options)
                          : cJSON_CreateObject();
        if (!opts) return pg_fail(L->err, PG_ERR_OOM, "%s: out of memory", path);
        pg_pass_desc *d = &p->passes[p->n_passes++];
        *d = L->pdesc[i];
        d->options = opts;
    }
    return PG_OK;
}

static pg_result load_common(const char *text, size_t len, const char *path,
                             const pg_param_override *ov, uint32_t n_ov, pg_pipeline **out,
                             pg_error *err)
{
    loader *L = calloc(1, sizeof *L);
    pg_pipeline *p = calloc(1, sizeof *p);
    if (!L || !p) {
        free(L);
        free(p);
        return pg_fail(err, PG_ERR_OOM, "%s: out of memory", path);
    }
    pg_error local;
    L->p = p;
    L->err = err ? err : &local;
    pg_result r = load_all(L, text, len, path, ov, n_ov);
    for (uint32_t i = 0; !r && i < L->n_files && p->n_source_dirs < PG_MAX_SOURCE_DIRS; i++) {
        char dir[PG_PATH_MAX];
        pg_strlcpy(dir, L->files[i]->canon ? L->files[i]->canon : L->files[i]->path, sizeof dir);
        char *slash = strrchr(dir, '/');
        if (!slash) continue; /* a string's virtual path */
        *slash = 0;
        bool seen = false;
        for (uint32_t k = 0; k < p->n_source_dirs && !seen; k++) seen = !strcmp(p->source_dirs[k], dir);
        if (!seen) pg_strlcpy(p->source_dirs[p->n_source_dirs++], dir, PG_PATH_MAX);
    }
    loader_free(L);
    if (r) {
        pg_pipeline_free(p);
        return r;
    }
    *out = p;
    return PG_OK;
}

pg_result pg_pipeline_load_string(const char *json_text, const char *virtual_path,
                                  const pg_param_override *overrides, uint32_t n_overrides,
                                  pg_pipeline **out, pg_error *err)
{
    const char *path = virtual_path && virtual_path[0] ? virtual_path : "<string>";
    if (!out) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: out is NULL", path);
    *out = NULL;
    if (!json_text) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: json_text is NULL", path);
    if (strlen(path) >= PG_PATH_MAX)
        return pg_fail(err, PG_ERR_INVALID_ARG, "%.64s...: path longer than %d characters",
                       path, PG_PATH_MAX - 1);
    return load_common(json_text, strlen(json_text), path, overrides, n_overrides, out, err);
}

pg_result pg_pipeline_load(const char *path, const pg_param_override *overrides,
                           uint32_t n_overrides, pg_pipeline **out, pg_error *err)
{
    if (!out) return pg_fail(err, PG_ERR_INVALID_ARG, "pg_pipeline_load: out is NULL");
    *out = NULL;
    if (!path || !path[0]) return pg_fail(err, PG_ERR_INVALID_ARG, "pg_pipeline_load: no path");
    if (strlen(path) >= PG_PATH_MAX)
        return pg_fail(err, PG_ERR_INVALID_ARG, "%.64s...: path longer than %d characters",
                       path, PG_PATH_MAX - 1);
    char *text = NULL;
    size_t len = 0;
    pg_result r = pg_file_read(path, "pipeline", PG_FILE_CAP_PIPELINE, &text, &len, err);
    if (r) return r;
    r = load_common(text, len, path, overrides, n_overrides, out, err);
    free(text);
    return r;
}

void pg_pipeline_free(pg_pipeline *p)
{
    if (!p) return;
    for (uint32_t i = 0; i < p->n_passes && i < PG_MAX_PASSES; i++)
        cJSON_Delete(p->passes[i].options);
    free(p);
}

void pg_resource_extent(const pg_resource_desc *rd, uint32_t output_width, uint32_t output_height, uint64_t *w,
                        uint64_t *h)
{
    if (rd->extent_mode == PG_EXTENT_RELATIVE) {
        /* scale is a float: 1/3 is 0.33333334f, and 900 * that is 300.0000...6. Without the
         * small tolerance ceil() would give 301. */
        *w = (uint64_t)ceil(output_width * (double)rd->scale[0] - 1e-4);
        *h = (uint64_t)ceil(output_height * (double)rd->scale[1] - 1e-4);
    } else {
        *w = rd->size[0];
        *h = rd->size[1];
    }
    if (*w < 1) *w = 1;
    if (*h < 1) *h = 1;
}

const pg_resource_desc *pg_pipeline_find_resource(const pg_pipeline *p, const char *name)
{
    if (!p || !name) return NULL;
    for (uint32_t i = 0; i < p->n_resources; i++)
        if (strcmp(p->resources[i].name, name) == 0) return &p->resources[i];
    return NULL;
}
