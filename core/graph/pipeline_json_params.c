/* pipeline_json_params.c - the pipeline loader's parameters: declarations (typed, ranged, enum
 * values), an identical redeclaration in an include, --set overrides, "$param" substitution
 * inside resources and passes, and "when" conditions. Part of the loader
 * (pipeline_json_internal.h).
 */
#include "pipeline_json_internal.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_SAFE_INT 9007199254740991.0 /* 2^53 - 1: the JSON text of a larger integer may round to it (2^53 + 1
                                         * reads as 2^53), so 2^53 and past are refused */

/* ------------------------------------------------------------------ parameters */

/* A whole-string parameter reference: "$" followed by an identifier. */
static bool is_param_ref(const char *s) { return s && s[0] == '$' && pg_ident_ok(s + 1); }

static void param_names(const pg_pipeline *p, char *buf, size_t n)
{
    buf[0] = 0;
    for (uint32_t i = 0; i < p->n_params; i++) pj_list_append(buf, n, p->params[i].name);
    if (!buf[0]) snprintf(buf, n, "none");
}

void pg_param_format(const pg_param *param, char *buf, size_t buf_size)
{
    if (!buf || !buf_size) return;
    if (!param) {
        buf[0] = 0;
        return;
    }
    switch (param->type) {
    case PG_PARAM_INT: snprintf(buf, buf_size, "%lld", (long long)param->number); break;
    case PG_PARAM_FLOAT: pj_fmt_double(param->number, buf, buf_size); break;
    case PG_PARAM_BOOL: snprintf(buf, buf_size, "%s", param->boolean ? "true" : "false"); break;
    case PG_PARAM_ENUM: snprintf(buf, buf_size, "%s", param->enum_value); break;
    default: buf[0] = 0; break;
    }
}

const pg_param *pg_pipeline_find_param(const pg_pipeline *p, const char *name)
{
    if (!p || !name) return NULL;
    for (uint32_t i = 0; i < p->n_params; i++)
        if (strcmp(p->params[i].name, name) == 0) return &p->params[i];
    return NULL;
}

static const char *param_type_name(pg_param_type t)
{
    switch (t) {
    case PG_PARAM_INT: return "int";
    case PG_PARAM_FLOAT: return "float";
    case PG_PARAM_BOOL: return "bool";
    case PG_PARAM_ENUM: return "enum";
    }
    return "?";
}

static void enum_values_list(const pg_param *prm, char *buf, size_t n)
{
    buf[0] = 0;
    for (uint32_t i = 0; i < prm->n_values; i++) pj_list_append(buf, n, prm->values[i]);
}

static bool text_is_integer(const char *s)
{
    if (*s == '+' || *s == '-') s++;
    if (!*s) return false;
    for (; *s; s++)
        if (*s < '0' || *s > '9') return false;
    return true;
}

static bool text_is_number(const char *s)
{
    bool digit = false;
    if (*s == '+' || *s == '-') s++;
    for (; *s >= '0' && *s <= '9'; s++) digit = true;
    if (*s == '.')
        for (s++; *s >= '0' && *s <= '9'; s++) digit = true;
    if (!digit) return false;
    if (*s == 'e' || *s == 'E') {
        s++;
        if (*s == '+' || *s == '-') s++;
        if (*s < '0' || *s > '9') return false;
        while (*s >= '0' && *s <= '9') s++;
    }
    return *s == 0;
}

/* whether an int parameter with values lists x */
static bool int_listed(const pg_param *prm, double x)
{
    char text[48];
    snprintf(text, sizeof text, "%lld", (long long)x);
    for (uint32_t i = 0; i < prm->n_values; i++)
        if (strcmp(prm->values[i], text) == 0) return true;
    return false;
}

/* Parses text as a value of prm's type into val (a copy of prm). On failure writes why. */
static bool parse_typed(const pg_param *prm, const char *text, bool check_range, pg_param *val,
                        char *why, size_t whyn)
{
    *val = *prm;
    char buf[256];
    switch (prm->type) {
    case PG_PARAM_INT: {
        if (!text_is_integer(text)) {
            snprintf(why, whyn, "'%s' is not an integer", text);
            return false;
        }
        errno = 0;
        long long v = strtoll(text, NULL, 10);
        if (errno == ERANGE || v >= (1LL << 53) || v <= -(1LL << 53)) { /* as the JSON text: 2^53 + 1 is no double */
            snprintf(why, whyn, "%s is too large", text);
            return false;
        }
        val->number = (double)v;
        if (prm->n_values && !int_listed(prm, val->number)) {
            enum_values_list(prm, buf, sizeof buf);
            snprintf(why, whyn, "%s is not one of: %s", text, buf);
            return false;
        }
        break;
    }
    case PG_PARAM_FLOAT: {
        if (!text_is_number(text)) {
            snprintf(why, whyn, "'%s' is not a number", text);
            return false;
        }
        double v = strtod(text, NULL);
        if (!isfinite(v)) {
            snprintf(why, whyn, "%s is not a finite number", text);
            return false;
        }
        val->number = v;
        break;
    }
    case PG_PARAM_BOOL:
        if (strcmp(text, "true") == 0 || strcmp(text, "1") == 0) {
            val->boolean = true;
        } else if (strcmp(text, "false") == 0 || strcmp(text, "0") == 0) {
            val->boolean = false;
        } else {
            snprintf(why, whyn, "'%s' is not a bool (true, false, 1 or 0)", text);
            return false;
        }
        return true;
    case PG_PARAM_ENUM:
        for (uint32_t i = 0; i < prm->n_values; i++) {
            if (strcmp(prm->values[i], text) == 0) {
                pg_strlcpy(val->enum_value, text, sizeof val->enum_value);
                return true;
            }
        }
        enum_values_list(prm, buf, sizeof buf);
        snprintf(why, whyn, "'%s' is not one of: %s", text, buf);
        return false;
    }
    if (check_range && (val->number < prm->min || val->number > prm->max)) {
        char lo[40], hi[40];
        pj_fmt_double(prm->min, lo, sizeof lo);
        pj_fmt_double(prm->max, hi, sizeof hi);
        snprintf(why, whyn, "%s is out of range [%s, %s]", text, lo, hi);
        return false;
    }
    return true;
}

static bool param_equal(const pg_param *a, const pg_param *b)
{
    switch (a->type) {
    case PG_PARAM_INT:
    case PG_PARAM_FLOAT: return a->number == b->number;
    case PG_PARAM_BOOL: return a->boolean == b->boolean;
    case PG_PARAM_ENUM: return strcmp(a->enum_value, b->enum_value) == 0;
    }
    return false;
}

static const char *const k_param_keys[] = {"type", "default", "min", "max", "values",
                                           "description", NULL};

/* "PATH.FIELD" in the caller's fpath buffer (PATH: "parameters.NAME") */
#define FPATH(field) (snprintf(fpath, sizeof fpath, "%s.%s", path, field), fpath)
#define FPATH_MAX (PG_JSON_PATH_MAX + 96)

/* "type": int, float, bool or enum */
static pg_result decl_type(loader *L, const src_file *f, const cJSON *decl, const char *path, pg_param *out)
{
    char fpath[FPATH_MAX], got[96];
    const cJSON *type = cJSON_GetObjectItemCaseSensitive(decl, "type");
    if (!type)
        return pj_fail_at(L, PG_ERR_PARAM, f, FPATH("type"), "missing (int, float, bool or enum)");
    if (!cJSON_IsString(type)) {
        pj_describe(type, got, sizeof got);
        return pj_fail_at(L, PG_ERR_PARAM, f, FPATH("type"),
                       "expected \"int\", \"float\", \"bool\" or \"enum\", got %s", got);
    }
    const char *ts = type->valuestring;
    if (strcmp(ts, "int") == 0) out->type = PG_PARAM_INT;
    else if (strcmp(ts, "float") == 0) out->type = PG_PARAM_FLOAT;
    else if (strcmp(ts, "bool") == 0) out->type = PG_PARAM_BOOL;
    else if (strcmp(ts, "enum") == 0) out->type = PG_PARAM_ENUM;
    else
        return pj_fail_at(L, PG_ERR_PARAM, f, FPATH("type"),
                       "unknown parameter type '%.64s' (int, float, bool or enum)", ts);
    return PG_OK;
}

/* "min" and "max" (int and float only; -inf and +inf when absent), min <= max */
static pg_result decl_bounds(loader *L, const src_file *f, const cJSON *decl, const char *path, pg_param *out)
{
    char fpath[FPATH_MAX], got[96];
    bool numeric = out->type == PG_PARAM_INT || out->type == PG_PARAM_FLOAT;
    out->min = -INFINITY;
    out->max = INFINITY;
    static const char *const bound_keys[2] = {"min", "max"};
    for (int b = 0; b < 2; b++) {
        const cJSON *v = cJSON_GetObjectItemCaseSensitive(decl, bound_keys[b]);
        if (!v) continue;
        if (!numeric)
            return pj_fail_at(L, PG_ERR_PARAM, f, FPATH(bound_keys[b]),
                           "only int and float parameters have min/max");
        double d = 0;
        bool ok = out->type == PG_PARAM_INT ? pj_json_integer(v, -MAX_SAFE_INT, MAX_SAFE_INT, &d)
                                            : (cJSON_IsNumber(v) && isfinite(v->valuedouble));
        if (out->type == PG_PARAM_FLOAT && ok) d = v->valuedouble;
        if (!ok) {
            pj_describe(v, got, sizeof got);
            return pj_fail_at(L, PG_ERR_PARAM, f, FPATH(bound_keys[b]), "expected %s, got %s",
                           out->type == PG_PARAM_INT ? "an integer" : "a finite number", got);
        }
        if (b == 0) out->min = d;
        else out->max = d;
    }
    if (out->min > out->max) {
        char lo[40], hi[40];
        pj_fmt_double(out->min, lo, sizeof lo);
        pj_fmt_double(out->max, hi, sizeof hi);
        return pj_fail_at(L, PG_ERR_PARAM, f, FPATH("max"), "%s is less than min %s", hi, lo);
    }
    return PG_OK;
}

/* "values" of an int (optional): the only integers it takes, distinct, within min..max, kept as
 * their decimal text */
static pg_result decl_int_values(loader *L, const src_file *f, const cJSON *values, const char *path, pg_param *out)
{
    char fpath[FPATH_MAX], got[96];
    if (!cJSON_IsArray(values) || !values->child)
        return pj_fail_at(L, PG_ERR_PARAM, f, FPATH("values"), "an int's values must be a non-empty array of integers");
    int nv = cJSON_GetArraySize(values);
    if (nv > PG_MAX_ENUM_VALUES)
        return pj_fail_at(L, PG_ERR_LIMIT, f, FPATH("values"), "%d values, the limit is %d", nv, PG_MAX_ENUM_VALUES);
    const cJSON *v;
    uint32_t i = 0;
    cJSON_ArrayForEach(v, values) {
        double d = 0;
        snprintf(fpath, sizeof fpath, "%s.values[%u]", path, i);
        if (!pj_json_integer(v, -MAX_SAFE_INT, MAX_SAFE_INT, &d) || d < out->min || d > out->max) {
            char lo[40], hi[40];
            pj_describe(v, got, sizeof got);
            pj_fmt_double(out->min, lo, sizeof lo);
            pj_fmt_double(out->max, hi, sizeof hi);
            return pj_fail_at(L, PG_ERR_PARAM, f, fpath, "expected an integer in [%s, %s], got %s", lo, hi, got);
        }
        snprintf(out->values[i], PG_NAME_MAX, "%lld", (long long)d);
        for (uint32_t j = 0; j < i; j++)
            if (strcmp(out->values[j], out->values[i]) == 0)
                return pj_fail_at(L, PG_ERR_PARAM, f, fpath, "%s is listed twice", out->values[i]);
        i++;
    }
    out->n_values = i;
    return PG_OK;
}

/* "values": an enum's names (required there: distinct, non-empty, without spaces) or the integers an
 * int takes (optional) */
static pg_result decl_values(loader *L, const src_file *f, const cJSON *decl, const char *path, pg_param *out)
{
    char fpath[FPATH_MAX], got[96];
    const cJSON *values = cJSON_GetObjectItemCaseSensitive(decl, "values");
    out->n_values = 0;
    if (values && out->type == PG_PARAM_INT) return decl_int_values(L, f, values, path, out);
    if (values && out->type != PG_PARAM_ENUM)
        return pj_fail_at(L, PG_ERR_PARAM, f, FPATH("values"), "only enum and int parameters have values");
    if (out->type != PG_PARAM_ENUM) return PG_OK;
    if (!cJSON_IsArray(values) || !values->child)
        return pj_fail_at(L, PG_ERR_PARAM, f, FPATH("values"),
                       "an enum needs a non-empty array of strings");
    int nv = cJSON_GetArraySize(values);
    if (nv > PG_MAX_ENUM_VALUES)
        return pj_fail_at(L, PG_ERR_LIMIT, f, FPATH("values"), "%d values, the limit is %d", nv,
                       PG_MAX_ENUM_VALUES);
    const cJSON *v;
    uint32_t i = 0;
    cJSON_ArrayForEach(v, values) {
        bool ok = cJSON_IsString(v) && v->valuestring[0] &&
                  strlen(v->valuestring) < PG_NAME_MAX;
        for (const char *c = ok ? v->valuestring : ""; *c; c++)
            if ((unsigned char)*c <= ' ' || *c == 0x7f) ok = false;
        if (!ok) {
            pj_describe(v, got, sizeof got);
            snprintf(fpath, sizeof fpath, "%s.values[%u]", path, i);
            return pj_fail_at(L, PG_ERR_PARAM, f, fpath,
                           "expected a non-empty string without spaces "
                           "(at most %d characters), got %s",
                           PG_NAME_MAX - 1, got);
        }
        for (uint32_t j = 0; j < i; j++)
            if (strcmp(out->values[j], v->valuestring) == 0) {
                snprintf(fpath, sizeof fpath, "%s.values[%u]", path, i);
                return pj_fail_at(L, PG_ERR_PARAM, f, fpath, "'%s' is listed twice",
                               v->valuestring);
            }
        pg_strlcpy(out->values[i++], v->valuestring, PG_NAME_MAX);
    }
    out->n_values = i;
    return PG_OK;
}

/* "description": a string, when given */
static pg_result decl_description(loader *L, const src_file *f, const cJSON *decl, const char *path,
                                  pg_param *out)
{
    char fpath[FPATH_MAX], got[96];
    const cJSON *desc = cJSON_GetObjectItemCaseSensitive(decl, "description");
    if (!desc) return PG_OK;
    if (!cJSON_IsString(desc)) {
        pj_describe(desc, got, sizeof got);
        return pj_fail_at(L, PG_ERR_PARAM, f, FPATH("description"), "expected a string, got %s",
                       got);
    }
    pg_strlcpy(out->description, desc->valuestring, sizeof out->description);
    return PG_OK;
}

/* "default" (required): a value of the type, one of the values of an enum, within min..max */
static pg_result decl_default(loader *L, const src_file *f, const cJSON *decl, const char *path, pg_param *out)
{
    char fpath[FPATH_MAX], got[96];
    const cJSON *def = cJSON_GetObjectItemCaseSensitive(decl, "default");
    if (!def)
        return pj_fail_at(L, PG_ERR_PARAM, f, FPATH("default"), "missing (every parameter needs one)");
    pj_describe(def, got, sizeof got);
    switch (out->type) {
    case PG_PARAM_INT:
        if (!pj_json_integer(def, -MAX_SAFE_INT, MAX_SAFE_INT, &out->number))
            return pj_fail_at(L, PG_ERR_PARAM, f, FPATH("default"),
                              "expected an integer of magnitude below 2^53, got %s", got);
        break;
    case PG_PARAM_FLOAT:
        if (!cJSON_IsNumber(def) || !isfinite(def->valuedouble))
            return pj_fail_at(L, PG_ERR_PARAM, f, FPATH("default"), "expected a finite number, got %s",
                           got);
        out->number = def->valuedouble;
        break;
    case PG_PARAM_BOOL:
        if (!cJSON_IsBool(def))
            return pj_fail_at(L, PG_ERR_PARAM, f, FPATH("default"), "expected true or false, got %s",
                           got);
        out->boolean = cJSON_IsTrue(def);
        break;
    case PG_PARAM_ENUM: {
        bool found = false;
        if (cJSON_IsString(def))
            for (uint32_t i = 0; i < out->n_values; i++)
                if (strcmp(out->values[i], def->valuestring) == 0) found = true;
        if (!found) {
            char vals[512];
            enum_values_list(out, vals, sizeof vals);
            return pj_fail_at(L, PG_ERR_PARAM, f, FPATH("default"), "%s is not one of the values (%s)",
                           got, vals);
        }
        pg_strlcpy(out->enum_value, def->valuestring, sizeof out->enum_value);
        break;
    }
    }
    bool numeric = out->type == PG_PARAM_INT || out->type == PG_PARAM_FLOAT;
    if (numeric && (out->number < out->min || out->number > out->max)) {
        char lo[40], hi[40];
        pj_fmt_double(out->min, lo, sizeof lo);
        pj_fmt_double(out->max, hi, sizeof hi);
        return pj_fail_at(L, PG_ERR_PARAM, f, FPATH("default"), "%s is out of range [%s, %s]", got, lo,
                       hi);
    }
    if (out->type == PG_PARAM_INT && out->n_values && !int_listed(out, out->number)) {
        char vals[512];
        enum_values_list(out, vals, sizeof vals);
        return pj_fail_at(L, PG_ERR_PARAM, f, FPATH("default"), "%s is not one of the values (%s)", got, vals);
    }
    return PG_OK;
}
#undef FPATH
#undef FPATH_MAX

/* Parses one declaration "parameters.NAME" into out: the name, then each field in turn (type
 * first: the others depend on it). */
static pg_result parse_param_decl(loader *L, const src_file *f, const cJSON *decl, pg_param *out)
{
    const char *name = decl->string ? decl->string : "";
    char path[PG_JSON_PATH_MAX + 32];
    char got[96];
    memset(out, 0, sizeof *out);
    snprintf(path, sizeof path, "parameters.%s", name);
    if (!pg_ident_ok(name))
        return pj_fail_at(L, PG_ERR_PARAM, f, path,
                       "parameter names must match [A-Za-z0-9_]+ (at most %d characters)",
                       PG_NAME_MAX - 1);
    pg_strlcpy(out->name, name, sizeof out->name);
    if (!cJSON_IsObject(decl)) {
        pj_describe(decl, got, sizeof got);
        return pj_fail_at(L, PG_ERR_PARAM, f, path,
                       "expected a declaration object like {\"type\": \"int\", \"default\": 1}, "
                       "got %s", got);
    }
    pg_result r;
    if ((r = pj_check_keys(L, f, decl, path, "parameter declaration", k_param_keys)) ||
        (r = decl_type(L, f, decl, path, out)) || (r = decl_bounds(L, f, decl, path, out)) ||
        (r = decl_values(L, f, decl, path, out)) || (r = decl_description(L, f, decl, path, out)) ||
        (r = decl_default(L, f, decl, path, out)))
        return r;
    return PG_OK;
}

/* Adds a parameter declaration, accepting an identical redeclaration. */
pg_result pj_add_param(loader *L, const src_file *f, const cJSON *decl)
{
    pg_param prm;
    pg_result r = parse_param_decl(L, f, decl, &prm);
    if (r) return r;
    pg_pipeline *p = L->p;
    for (uint32_t i = 0; i < p->n_params; i++) {
        if (strcmp(p->params[i].name, prm.name) != 0) continue;
        if (cJSON_Compare(L->param_decl[i], decl, 1)) return PG_OK;
        char path[PG_JSON_PATH_MAX + 16];
        snprintf(path, sizeof path, "parameters.%s", prm.name);
        return pj_fail_at(L, PG_ERR_PARAM, f, path,
                       "parameter '%s' is already declared differently at %s: parameters.%s",
                       prm.name, L->param_file[i]->path, prm.name);
    }
    if (p->n_params >= PG_MAX_PARAMS) {
        char path[PG_JSON_PATH_MAX + 16];
        snprintf(path, sizeof path, "parameters.%s", prm.name);
        return pj_fail_at(L, PG_ERR_LIMIT, f, path,
                       "more than %d parameters (the pipeline and its includes)", PG_MAX_PARAMS);
    }
    L->param_file[p->n_params] = f;
    L->param_decl[p->n_params] = decl;
    p->params[p->n_params++] = prm;
    return PG_OK;
}

/* ------------------------------------------------------------------ overrides, substitution */

pg_result pj_apply_overrides(loader *L, const pg_param_override *ov, uint32_t n)
{
    pg_pipeline *p = L->p;
    const src_file *top = L->files[0];
    for (uint32_t i = 0; i < n; i++) {
        const char *key = ov[i].key ? ov[i].key : "";
        const char *value = ov[i].value ? ov[i].value : "";
        char set[160];
        snprintf(set, sizeof set, "--set %.64s=%.64s", key, value);
        pg_param *prm = (pg_param *)pg_pipeline_find_param(p, key);
        if (!prm) {
            char names[640];
            param_names(p, names, sizeof names);
            return pj_fail_at(L, PG_ERR_PARAM, top, set, "unknown parameter '%.64s' (declared: %s)",
                           key, names);
        }
        pg_param val;
        char why[600];
        if (!parse_typed(prm, value, true, &val, why, sizeof why))
            return pj_fail_at(L, PG_ERR_PARAM, top, set, "%s parameter '%s': %s",
                           param_type_name(prm->type), prm->name, why);
        *prm = val;
        prm->overridden = true;
    }
    return PG_OK;
}

static cJSON *param_node(const pg_param *prm)
{
    switch (prm->type) {
    case PG_PARAM_INT:
    case PG_PARAM_FLOAT: return cJSON_CreateNumber(prm->number);
    case PG_PARAM_BOOL: return cJSON_CreateBool(prm->boolean);
    case PG_PARAM_ENUM: return cJSON_CreateString(prm->enum_value);
    }
    return NULL;
}

/* Replaces every "$name" string below node (the item's own "when" is skipped at the top). */
pg_result pj_substitute(loader *L, const src_file *f, cJSON *node, bool top)
{
    uint32_t i = 0;
    cJSON *next;
    for (cJSON *c = node->child; c; c = next, i++) {
        next = c->next;
        bool obj = cJSON_IsObject(node);
        if (top && obj && c->string && strcmp(c->string, "when") == 0) continue;
        size_t mark = obj ? pj_jp_push(L, ".%s", c->string) : pj_jp_push(L, "[%u]", i);
        pg_result r = PG_OK;
        if (cJSON_IsString(c) && is_param_ref(c->valuestring)) {
            const pg_param *prm = pg_pipeline_find_param(L->p, c->valuestring + 1);
            if (!prm) {
                char names[640];
                param_names(L->p, names, sizeof names);
                r = pj_fail_at(L, PG_ERR_PARAM, f, L->jp,
                            "unknown parameter '%s' (declared: %s)", c->valuestring, names);
            } else {
                cJSON *rep = param_node(prm);
                if (!rep) {
                    r = pg_fail(L->err, PG_ERR_OOM, "%s: out of memory", f->path);
                } else {
                    rep->string = c->string;
                    c->string = NULL;
                    cJSON_ReplaceItemViaPointer(node, c, rep);
                }
            }
        } else if (cJSON_IsArray(c) || cJSON_IsObject(c)) {
            r = pj_substitute(L, f, c, false);
        }
        pj_jp_pop(L, mark);
        if (r) return r;
    }
    return PG_OK;
}

/* Evaluates item's optional "when"; *active is false when the item is to be dropped. */
pg_result pj_eval_when(loader *L, const src_file *f, const cJSON *item, const char *ipath,
                    bool *active, char *why, size_t whyn)
{
    *active = true;
    const cJSON *w = cJSON_GetObjectItemCaseSensitive(item, "when");
    if (!w) return PG_OK;
    char path[PG_JSON_PATH_MAX];
    snprintf(path, sizeof path, "%s.when", ipath);
    const char *expect = "expected \"$param == value\" or \"$param != value\"";
    if (!cJSON_IsString(w)) {
        char got[96];
        pj_describe(w, got, sizeof got);
        return pj_fail_at(L, PG_ERR_SCHEMA, f, path, "%s, got %s", expect, got);
    }
    const char *s = w->valuestring;
    while (*s == ' ' || *s == '\t') s++;
    const char *cond = s;
    char name[PG_NAME_MAX] = "", value[PG_NAME_MAX] = "";
    bool ok = *s == '$';
    size_t n = 0;
    if (ok) {
        for (s++; (*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') ||
                  (*s >= '0' && *s <= '9') || *s == '_';
             s++)
            if (n + 1 < sizeof name) name[n++] = *s;
            else ok = false;
        name[n] = 0;
        ok = ok && n > 0;
    }
    while (*s == ' ' || *s == '\t') s++;
    bool eq = s[0] == '=' && s[1] == '=';
    ok = ok && (eq || (s[0] == '!' && s[1] == '='));
    if (ok) {
        s += 2;
        while (*s == ' ' || *s == '\t') s++;
        n = 0;
        for (; *s && *s != ' ' && *s != '\t'; s++)
            if (n + 1 < sizeof value) value[n++] = *s;
            else ok = false;
        value[n] = 0;
        while (*s == ' ' || *s == '\t') s++;
        ok = ok && n > 0 && *s == 0;
    }
    if (!ok)
        return pj_fail_at(L, PG_ERR_SCHEMA, f, path, "malformed condition \"%.80s\" (%s)",
                       w->valuestring, expect);
    const pg_param *prm = pg_pipeline_find_param(L->p, name);
    if (!prm) {
        char names[640];
        param_names(L->p, names, sizeof names);
        return pj_fail_at(L, PG_ERR_PARAM, f, path, "unknown parameter '$%s' (declared: %s)", name,
                       names);
    }
    pg_param val;
    char bad[600];
    if (!parse_typed(prm, value, false, &val, bad, sizeof bad))
        return pj_fail_at(L, PG_ERR_SCHEMA, f, path, "cannot compare %s parameter '%s': %s",
                       param_type_name(prm->type), prm->name, bad);
    bool same = param_equal(prm, &val);
    *active = eq ? same : !same;
    char cur[64];
    pg_param_format(prm, cur, sizeof cur);
    size_t clen = strlen(cond);
    while (clen && (cond[clen - 1] == ' ' || cond[clen - 1] == '\t')) clen--;
    snprintf(why, whyn, "when: %.*s (%s is '%s')", (int)(clen > 100 ? 100 : clen), cond,
             prm->name, cur);
    return PG_OK;
}
