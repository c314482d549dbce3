/* pipeline_json_common.c - what the loader's item parsers share (pipeline_json.c's passes,
 * pipeline_json_resources.c's resources): the preamble of an item object, the duplicate-name
 * message, the name/type identifier fields and the description. A leaf: it calls none of the
 * item parsers. Part of the loader (pipeline_json_internal.h).
 */
#include "pipeline_json_internal.h"

#include <stdio.h>
#include <string.h>

/* Reads a required identifier field (name / type). */
pg_result pj_req_ident(loader *L, const src_file *f, const cJSON *obj, const char *ipath,
                    const char *key, char *out)
{
    char path[PG_JSON_PATH_MAX];
    snprintf(path, sizeof path, "%s.%s", ipath, key);
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!v) return pj_fail_at(L, PG_ERR_SCHEMA, f, path, "missing (required)");
    if (!cJSON_IsString(v) || !pg_ident_ok(v->valuestring)) {
        char got[96];
        pj_describe(v, got, sizeof got);
        return pj_fail_at(L, PG_ERR_SCHEMA, f, path,
                       "expected a name matching [A-Za-z0-9_]+ (at most %d characters), got %s",
                       PG_NAME_MAX - 1, got);
    }
    pg_strlcpy(out, v->valuestring, PG_NAME_MAX);
    return PG_OK;
}

pg_result pj_opt_description(loader *L, const src_file *f, const cJSON *obj,
                          const char *ipath)
{
    const cJSON *d = cJSON_GetObjectItemCaseSensitive(obj, "description");
    if (!d || cJSON_IsString(d)) return PG_OK;
    char got[96], path[PG_JSON_PATH_MAX];
    pj_describe(d, got, sizeof got);
    snprintf(path, sizeof path, "%s.description", ipath);
    return pj_fail_at(L, PG_ERR_SCHEMA, f, path, "expected a string, got %s", got);
}

/* The start of every item (what = "pass" or "resource"): an object, its "$param" strings
 * substituted, only the keys allowed, and a valid "name" (copied to name). */
pg_result pj_item_begin(loader *L, const src_file *f, cJSON *o, const char *ip, const char *what,
                        const char *const *keys, char *name)
{
    char got[96], a_what[32];
    if (!cJSON_IsObject(o)) {
        pj_describe(o, got, sizeof got);
        return pj_fail_at(L, PG_ERR_SCHEMA, f, ip, "expected a %s object, got %s", what, got);
    }
    snprintf(L->jp, sizeof L->jp, "%s", ip);
    pg_result r = pj_substitute(L, f, o, true);
    if (r) return r;
    snprintf(a_what, sizeof a_what, "a %s", what);
    r = pj_check_keys(L, f, o, ip, a_what, keys);
    if (r) return r;
    return pj_req_ident(L, f, o, ip, "name", name);
}

/* The error for an item whose name an earlier one (in prev_file, at prev_path:prev_json_path)
 * already has. */
pg_result pj_item_twice(loader *L, const src_file *f, const char *ip, const char *what,
                        const char *name, const src_file *prev_file, const char *prev_path,
                        const char *prev_json_path)
{
    char path[PG_JSON_PATH_MAX];
    snprintf(path, sizeof path, "%s.name", ip);
    const char *twice = prev_file == f || strcmp(prev_file->canon, f->canon) != 0
                            ? ""
                            : " (the same file is included more than once)";
    return pj_fail_at(L, PG_ERR_SCHEMA, f, path, "%s '%s' is declared twice: first at %s: %s%s",
                      what, name, prev_path, prev_json_path, twice);
}
