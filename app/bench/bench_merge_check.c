/* bench_merge_check.c - field types of a results.json row (bench_merge_check.h). The shapes are
 * those bench_output.c writes: numbers may also be null (not measured) or "inf"/"-inf". */
#include "bench_merge_check.h"

#include <stdio.h>
#include <string.h>

typedef enum { T_NUM, T_STR, T_STATS, T_NUMOBJ, T_PASSES } ftype;

typedef struct field {
    const char *name;
    ftype type;
} field;

static const field k_fields[] = {
    {"index", T_NUM},        {"scene", T_STR},        {"pipeline", T_STR},    {"pipeline_path", T_STR},
    {"variant", T_STR},      {"sets", T_STR},         {"lights", T_NUM},      {"width", T_NUM},
    {"height", T_NUM},       {"status", T_STR},       {"message", T_STR},     {"frames", T_NUM},
    {"gpu_ms", T_STATS},     {"cpu_ms", T_STATS},     {"wait_ms", T_STATS},   {"passes", T_PASSES},
    {"memory", T_NUMOBJ},    {"overflow", T_NUMOBJ},  {"grow_events", T_NUM}, {"reference", T_STR},
    {"reference_sets", T_STR}, {"error", T_NUMOBJ},   {"nonfinite", T_NUM},   {"error_note", T_STR},
    {"accumulate", T_NUM},   {"light_evals", T_NUM},
};

static const char *const k_expected[] = {"a number", "a string", "an object of statistics",
                                         "an object of numbers", "an array of pass objects"};

static void describe(const cJSON *v, char *buf, size_t n)
{
    if (!v) {
        snprintf(buf, n, "nothing (missing)");
    } else if (cJSON_IsString(v)) {
        size_t len = strlen(v->valuestring);
        snprintf(buf, n, "string \"%.40s%s\"", v->valuestring, len > 40 ? "..." : "");
    } else if (cJSON_IsNumber(v)) {
        snprintf(buf, n, "number %g", v->valuedouble);
    } else if (cJSON_IsBool(v)) {
        snprintf(buf, n, "%s", cJSON_IsTrue(v) ? "true" : "false");
    } else if (cJSON_IsNull(v)) {
        snprintf(buf, n, "null");
    } else if (cJSON_IsArray(v)) {
        snprintf(buf, n, "an array");
    } else {
        snprintf(buf, n, "an object");
    }
}

static bool is_num(const cJSON *v)
{
    return cJSON_IsNumber(v) || cJSON_IsNull(v) ||
           (cJSON_IsString(v) && (!strcmp(v->valuestring, "inf") || !strcmp(v->valuestring, "-inf")));
}

static pg_result bad(const char *file, uint32_t row, const char *name, const char *expected,
                     const cJSON *v, pg_error *err)
{
    char got[96];
    describe(v, got, sizeof got);
    return pg_fail(err, PG_ERR_PARSE, "'%s' rows[%u].%s: expected %s, got %s", file, row, name,
                   expected, got);
}

/* every member of an object is a number (or null / "inf") */
static pg_result numbers_in(const char *file, uint32_t row, const char *prefix, const cJSON *o,
                            const char *skip, pg_error *err)
{
    const cJSON *c;
    cJSON_ArrayForEach(c, o)
    {
        if (skip && c->string && !strcmp(c->string, skip)) continue;
        if (!is_num(c)) {
            char name[160];
            snprintf(name, sizeof name, "%s.%s", prefix, c->string ? c->string : "?");
            return bad(file, row, name, "a number", c, err);
        }
    }
    return PG_OK;
}

pg_result pg_bench_row_check(const char *file, uint32_t row, const cJSON *o, pg_error *err)
{
    if (!cJSON_IsObject(o)) {
        char got[96];
        describe(o, got, sizeof got);
        return pg_fail(err, PG_ERR_PARSE, "'%s' rows[%u]: expected an object, got %s", file, row, got);
    }
    for (size_t i = 0; i < sizeof k_fields / sizeof k_fields[0]; i++) {
        const field *f = &k_fields[i];
        const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, f->name);
        if (!v) continue; /* absent: the reader's checks say what is missing */
        const char *exp = k_expected[f->type];
        pg_result r = PG_OK;
        switch (f->type) {
        case T_NUM:
            if (!is_num(v)) r = bad(file, row, f->name, exp, v, err);
            break;
        case T_STR:
            if (!cJSON_IsString(v)) r = bad(file, row, f->name, exp, v, err);
            break;
        case T_STATS:
        case T_NUMOBJ:
            if (f->type == T_NUMOBJ && cJSON_IsNull(v)) break; /* not measured */
            if (!cJSON_IsObject(v)) r = bad(file, row, f->name, exp, v, err);
            else r = numbers_in(file, row, f->name, v, NULL, err);
            break;
        case T_PASSES: {
            if (!cJSON_IsArray(v)) {
                r = bad(file, row, f->name, exp, v, err);
                break;
            }
            uint32_t k = 0;
            const cJSON *p;
            cJSON_ArrayForEach(p, v)
            {
                char name[64];
                snprintf(name, sizeof name, "passes[%u]", k++);
                if (!cJSON_IsObject(p)) r = bad(file, row, name, "an object", p, err);
                else if (!cJSON_IsString(cJSON_GetObjectItemCaseSensitive(p, "name")))
                    r = bad(file, row, strcat(name, ".name"), "a string",
                            cJSON_GetObjectItemCaseSensitive(p, "name"), err);
                else r = numbers_in(file, row, name, p, "name", err);
                if (r) break;
            }
            break;
        }
        }
        if (r) return r;
    }
    return PG_OK;
}
