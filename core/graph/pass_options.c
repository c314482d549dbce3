/* pass_options.c - typed readers for a pass's "options" object (see pass_api.h).
 *
 * Missing key -> the default. Wrong JSON type, non-integral (ints), out of range or not one of
 * the choices -> PG_ERR_SCHEMA "FILE: passes[i].options.KEY: expected ..., got ...".
 * (pg_decl_* and pg_registry_* live in core/graph/pass_registry.c.)
 */
#include "json_describe.h"
#include "pass_api.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

static const cJSON *opt_get(const pg_pass_desc *desc, const char *key)
{
    if (!desc || !key || !cJSON_IsObject(desc->options)) return NULL;
    return cJSON_GetObjectItemCaseSensitive(desc->options, key);
}

static void opt_describe(const cJSON *v, char *buf, size_t n) { pj_describe(v, buf, n); }

static const char *desc_file(const pg_pass_desc *d) { return d && d->file[0] ? d->file : "<pipeline>"; }
static const char *desc_path(const pg_pass_desc *d) { return d && d->json_path[0] ? d->json_path : "passes[?]"; }

pg_result pg_opt_float(const pg_pass_desc *desc, const char *key, double def, double min,
                       double max, double *out, pg_error *err)
{
    const cJSON *v = opt_get(desc, key);
    if (!v) {
        *out = def;
        return PG_OK;
    }
    if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble) || v->valuedouble < min ||
        v->valuedouble > max) {
        char got[96];
        opt_describe(v, got, sizeof got);
        return pg_fail(err, PG_ERR_SCHEMA, "%s: %s.options.%s: expected a number in [%g, %g], got %s",
                       desc_file(desc), desc_path(desc), key, min, max, got);
    }
    *out = v->valuedouble;
    return PG_OK;
}

pg_result pg_opt_int(const pg_pass_desc *desc, const char *key, int64_t def, int64_t min,
                     int64_t max, int64_t *out, pg_error *err)
{
    const cJSON *v = opt_get(desc, key);
    if (!v) {
        *out = def;
        return PG_OK;
    }
    bool ok = cJSON_IsNumber(v);
    double d = ok ? v->valuedouble : 0;
    /* [-2^63, 2^63) is exactly the range that converts to int64_t without overflow */
    ok = ok && isfinite(d) && d == floor(d) && d >= -9223372036854775808.0 &&
         d < 9223372036854775808.0;
    int64_t i = ok ? (int64_t)d : 0;
    if (!ok || i < min || i > max) {
        char got[96];
        opt_describe(v, got, sizeof got);
        return pg_fail(err, PG_ERR_SCHEMA,
                       "%s: %s.options.%s: expected an integer in [%lld, %lld], got %s",
                       desc_file(desc), desc_path(desc), key, (long long)min, (long long)max, got);
    }
    *out = i;
    return PG_OK;
}

pg_result pg_opt_bool(const pg_pass_desc *desc, const char *key, bool def, bool *out,
                      pg_error *err)
{
    const cJSON *v = opt_get(desc, key);
    if (!v) {
        *out = def;
        return PG_OK;
    }
    if (!cJSON_IsBool(v)) {
        char got[96];
        opt_describe(v, got, sizeof got);
        return pg_fail(err, PG_ERR_SCHEMA, "%s: %s.options.%s: expected true or false, got %s",
                       desc_file(desc), desc_path(desc), key, got);
    }
    *out = cJSON_IsTrue(v);
    return PG_OK;
}

static void choice_list(const char *const *choices, char *buf, size_t n)
{
    buf[0] = 0;
    for (const char *const *c = choices; c && *c; c++) {
        size_t len = strlen(buf);
        if (len + strlen(*c) + 8 >= n) {
            snprintf(buf + len, n - len, ", ...");
            return;
        }
        snprintf(buf + len, n - len, "%s\"%s\"", len ? ", " : "", *c);
    }
}

pg_result pg_opt_enum(const pg_pass_desc *desc, const char *key, const char *const *choices,
                      int def, int *out, pg_error *err)
{
    const cJSON *v = opt_get(desc, key);
    if (!v) {
        *out = def;
        return PG_OK;
    }
    if (cJSON_IsString(v) && choices) {
        for (int i = 0; choices[i]; i++) {
            if (strcmp(choices[i], v->valuestring) == 0) {
                *out = i;
                return PG_OK;
            }
        }
    }
    char got[96], list[512];
    opt_describe(v, got, sizeof got);
    choice_list(choices, list, sizeof list);
    return pg_fail(err, PG_ERR_SCHEMA, "%s: %s.options.%s: expected one of %s, got %s",
                   desc_file(desc), desc_path(desc), key, list, got);
}

pg_result pg_opt_string(const pg_pass_desc *desc, const char *key, const char *def, char *out, size_t out_size,
                        pg_error *err)
{
    const cJSON *v = opt_get(desc, key);
    if (!v) {
        snprintf(out, out_size, "%s", def ? def : "");
        return PG_OK;
    }
    if (!cJSON_IsString(v) || !v->valuestring || strlen(v->valuestring) >= out_size) {
        char got[96];
        opt_describe(v, got, sizeof got);
        return pg_fail(err, PG_ERR_SCHEMA, "%s: %s.options.%s: expected a string of at most %zu bytes, got %s",
                       desc_file(desc), desc_path(desc), key, out_size - 1, got);
    }
    snprintf(out, out_size, "%s", v->valuestring);
    return PG_OK;
}

pg_result pg_opt_check_known(const pg_pass_desc *desc, const char *const *known, pg_error *err)
{
    if (!desc || !cJSON_IsObject(desc->options)) return PG_OK;
    const cJSON *c;
    cJSON_ArrayForEach(c, desc->options) {
        bool found = false;
        for (const char *const *k = known; k && *k && !found; k++)
            found = c->string && strcmp(*k, c->string) == 0;
        if (found) continue;
        char list[512];
        choice_list(known, list, sizeof list);
        return pg_fail(err, PG_ERR_SCHEMA,
                       "%s: %s.options: unknown option \"%.64s\" for pass type '%s' (known: %s)",
                       desc_file(desc), desc_path(desc), c->string ? c->string : "",
                       desc->type[0] ? desc->type : "?",
                       list[0] ? list : "none, this pass type takes no options");
    }
    return PG_OK;
}
