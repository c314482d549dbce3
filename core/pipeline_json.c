/* pipeline_json.c - loads a pipeline description (pipelines/README.md documents the format).
 *
 * Phases, in order:
 *   1. parse   read the top-level file and, depth first, its includes; check JSON syntax, the
 *              keys allowed at the top level, duplicate object keys, the include graph (missing,
 *              cyclic, too deep) and every parameter declaration; collect the resource and pass
 *              objects in merge order (an include's items before the includer's own).
 *   2. params  apply the --set overrides (typed, range checked).
 *   3. items   substitute "$param" strings inside every resource and pass, then validate each
 *              one, evaluate its "when" condition and record what was omitted and why.
 *   4. links   resolve reads/writes/after names and the outputs against the surviving items.
 *   5. build   copy the surviving items into the pg_pipeline; each pass's options object is
 *              detached from its file's tree and owned by the pipeline.
 * Every parsed tree is owned by the loader and freed on every path.
 */
#ifndef _XOPEN_SOURCE
#define _XOPEN_SOURCE 700 /* realpath() */
#endif
#include "pipeline.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define PG_MAX_INCLUDE_DEPTH 16  /* include nesting below the top-level file */
#define PG_MAX_INCLUDE_FILES 256 /* files loaded in all (guards against include fan-out) */
#define JP_MAX 512               /* JSON paths inside error messages */
#define MAX_SAFE_INT 9007199254740992.0 /* 2^53: every integer up to it is exact in a double */

typedef struct src_file {
    char path[PG_PATH_MAX]; /* as written in messages */
    char *canon;            /* realpath (or the path itself): identity for cycle detection */
    cJSON *root;
} src_file;

typedef struct item_ref {
    cJSON *node;          /* the resource / pass object inside its file's tree */
    const src_file *file;
    uint32_t index;       /* position in its own file's array */
    bool omitted;
    uint32_t omit_index;  /* into pipeline->omitted when omitted */
    cJSON *options;       /* passes: the "options" object in the tree, or NULL */
} item_ref;

typedef struct loader {
    pg_pipeline *p;
    pg_error *err;
    src_file **files;
    uint32_t n_files, cap_files;
    const src_file *stack[PG_MAX_INCLUDE_DEPTH + 1]; /* the include chain being loaded */
    uint32_t depth;
    const src_file *param_file[PG_MAX_PARAMS];
    const cJSON *param_decl[PG_MAX_PARAMS];
    uint32_t n_res, n_pass;
    item_ref res[PG_MAX_RESOURCES];
    item_ref pass[PG_MAX_PASSES];
    pg_resource_desc rdesc[PG_MAX_RESOURCES];
    pg_pass_desc pdesc[PG_MAX_PASSES];
    char jp[JP_MAX]; /* scratch JSON path for the recursive walks */
} loader;

/* ------------------------------------------------------------------ small helpers */

static pg_result fail_at(loader *L, pg_result code, const src_file *f, const char *path,
                         const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;
static pg_result fail_at(loader *L, pg_result code, const src_file *f, const char *path,
                         const char *fmt, ...)
{
    char cause[PG_ERROR_MSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(cause, sizeof cause, fmt, ap);
    va_end(ap);
    return pg_fail(L->err, code, "%s: %s: %s", f ? f->path : "<pipeline>", path, cause);
}

static bool valid_ident(const char *s)
{
    if (!s || !*s) return false;
    size_t n = 0;
    for (; s[n]; n++) {
        char c = s[n];
        bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                  c == '_';
        if (!ok) return false;
    }
    return n < PG_NAME_MAX;
}

/* A whole-string parameter reference: "$" followed by an identifier. */
static bool is_param_ref(const char *s) { return s && s[0] == '$' && valid_ident(s + 1); }

/* "%.17g" trimmed to the shortest text that reads back as the same double. */
static void fmt_double(double v, char *buf, size_t n)
{
    for (int prec = 15; prec <= 17; prec++) {
        snprintf(buf, n, "%.*g", prec, v);
        if (strtod(buf, NULL) == v) return;
    }
}

/* Describes a JSON value for "got ..." in messages. */
static void describe(const cJSON *v, char *buf, size_t n)
{
    if (!v) {
        snprintf(buf, n, "nothing");
    } else if (cJSON_IsNumber(v)) {
        fmt_double(v->valuedouble, buf, n);
    } else if (cJSON_IsString(v)) {
        const char *s = v->valuestring ? v->valuestring : "";
        if (strlen(s) > 40)
            snprintf(buf, n, "\"%.40s...\"", s);
        else
            snprintf(buf, n, "\"%s\"", s);
    } else if (cJSON_IsTrue(v)) {
        snprintf(buf, n, "true");
    } else if (cJSON_IsFalse(v)) {
        snprintf(buf, n, "false");
    } else if (cJSON_IsNull(v)) {
        snprintf(buf, n, "null");
    } else if (cJSON_IsArray(v)) {
        snprintf(buf, n, "an array");
    } else if (cJSON_IsObject(v)) {
        snprintf(buf, n, "an object");
    } else {
        snprintf(buf, n, "an invalid value");
    }
}

/* Appends "a, b, c" to buf (truncating with "..."). */
static void list_append(char *buf, size_t n, const char *item)
{
    size_t len = strlen(buf);
    if (len + 4 >= n) return;
    if (strstr(buf, "...") && len >= 3 && strcmp(buf + len - 3, "...") == 0) return;
    const char *sep = len ? ", " : "";
    if (len + strlen(sep) + strlen(item) + 4 >= n) {
        snprintf(buf + len, n - len, "%s...", sep);
        return;
    }
    snprintf(buf + len, n - len, "%s%s", sep, item);
}

static void param_names(const pg_pipeline *p, char *buf, size_t n)
{
    buf[0] = 0;
    for (uint32_t i = 0; i < p->n_params; i++) list_append(buf, n, p->params[i].name);
    if (!buf[0]) snprintf(buf, n, "none");
}

static void format_names(char *buf, size_t n)
{
    buf[0] = 0;
    for (int f = 1; f < PG_FMT_COUNT; f++) list_append(buf, n, pg_format_get((pg_format)f)->name);
}

static bool in_list(const char *s, const char *const *list)
{
    for (; *list; list++)
        if (strcmp(s, *list) == 0) return true;
    return false;
}

/* Integral, finite, within [lo, hi]. */
static bool json_integer(const cJSON *v, double lo, double hi, double *out)
{
    if (!cJSON_IsNumber(v)) return false;
    double d = v->valuedouble;
    if (!isfinite(d) || d != floor(d) || d < lo || d > hi) return false;
    *out = d;
    return true;
}

/* JSON path scratch buffer: push appends, pop restores. */
static size_t jp_push(loader *L, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static size_t jp_push(loader *L, const char *fmt, ...)
{
    size_t mark = strlen(L->jp);
    if (mark + 1 < sizeof L->jp) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(L->jp + mark, sizeof L->jp - mark, fmt, ap);
        va_end(ap);
    }
    return mark;
}
static void jp_pop(loader *L, size_t mark) { L->jp[mark] = 0; }

/* ------------------------------------------------------------------ parameters */

void pg_param_format(const pg_param *param, char *buf, size_t buf_size)
{
    if (!buf || !buf_size) return;
    if (!param) {
        buf[0] = 0;
        return;
    }
    switch (param->type) {
    case PG_PARAM_INT: snprintf(buf, buf_size, "%lld", (long long)param->number); break;
    case PG_PARAM_FLOAT: fmt_double(param->number, buf, buf_size); break;
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

const pg_resource_desc *pg_pipeline_find_resource(const pg_pipeline *p, const char *name)
{
    if (!p || !name) return NULL;
    for (uint32_t i = 0; i < p->n_resources; i++)
        if (strcmp(p->resources[i].name, name) == 0) return &p->resources[i];
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
    for (uint32_t i = 0; i < prm->n_values; i++) list_append(buf, n, prm->values[i]);
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
        if (errno == ERANGE || fabs((double)v) > MAX_SAFE_INT) {
            snprintf(why, whyn, "%s is too large", text);
            return false;
        }
        val->number = (double)v;
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
        fmt_double(prm->min, lo, sizeof lo);
        fmt_double(prm->max, hi, sizeof hi);
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

static pg_result check_keys(loader *L, const src_file *f, const cJSON *obj, const char *path,
                            const char *what, const char *const *allowed);

/* Parses one declaration "parameters.NAME" into out. */
static pg_result parse_param_decl(loader *L, const src_file *f, const cJSON *decl, pg_param *out)
{
    const char *name = decl->string ? decl->string : "";
    char path[PG_JSON_PATH_MAX + 32], fpath[PG_JSON_PATH_MAX + 96];
    char got[96];
#define FPATH(field) (snprintf(fpath, sizeof fpath, "%s.%s", path, field), fpath)
    memset(out, 0, sizeof *out);
    snprintf(path, sizeof path, "parameters.%s", name);
    if (!valid_ident(name))
        return fail_at(L, PG_ERR_PARAM, f, path,
                       "parameter names must match [A-Za-z0-9_]+ (at most %d characters)",
                       PG_NAME_MAX - 1);
    pg_strlcpy(out->name, name, sizeof out->name);
    if (!cJSON_IsObject(decl)) {
        describe(decl, got, sizeof got);
        return fail_at(L, PG_ERR_PARAM, f, path,
                       "expected a declaration object like {\"type\": \"int\", \"default\": 1}, "
                       "got %s", got);
    }
    pg_result r = check_keys(L, f, decl, path, "parameter declaration", k_param_keys);
    if (r) return r;

    const cJSON *type = cJSON_GetObjectItemCaseSensitive(decl, "type");
    if (!type)
        return fail_at(L, PG_ERR_PARAM, f, FPATH("type"), "missing (int, float, bool or enum)");
    if (!cJSON_IsString(type)) {
        describe(type, got, sizeof got);
        return fail_at(L, PG_ERR_PARAM, f, FPATH("type"),
                       "expected \"int\", \"float\", \"bool\" or \"enum\", got %s", got);
    }
    const char *ts = type->valuestring;
    if (strcmp(ts, "int") == 0) out->type = PG_PARAM_INT;
    else if (strcmp(ts, "float") == 0) out->type = PG_PARAM_FLOAT;
    else if (strcmp(ts, "bool") == 0) out->type = PG_PARAM_BOOL;
    else if (strcmp(ts, "enum") == 0) out->type = PG_PARAM_ENUM;
    else
        return fail_at(L, PG_ERR_PARAM, f, FPATH("type"),
                       "unknown parameter type '%.64s' (int, float, bool or enum)", ts);
    bool numeric = out->type == PG_PARAM_INT || out->type == PG_PARAM_FLOAT;

    out->min = -INFINITY;
    out->max = INFINITY;
    static const char *const bound_keys[2] = {"min", "max"};
    for (int b = 0; b < 2; b++) {
        const cJSON *v = cJSON_GetObjectItemCaseSensitive(decl, bound_keys[b]);
        if (!v) continue;
        if (!numeric)
            return fail_at(L, PG_ERR_PARAM, f, FPATH(bound_keys[b]),
                           "only int and float parameters have min/max");
        double d = 0;
        bool ok = out->type == PG_PARAM_INT ? json_integer(v, -MAX_SAFE_INT, MAX_SAFE_INT, &d)
                                            : (cJSON_IsNumber(v) && isfinite(v->valuedouble));
        if (out->type == PG_PARAM_FLOAT && ok) d = v->valuedouble;
        if (!ok) {
            describe(v, got, sizeof got);
            return fail_at(L, PG_ERR_PARAM, f, FPATH(bound_keys[b]), "expected %s, got %s",
                           out->type == PG_PARAM_INT ? "an integer" : "a finite number", got);
        }
        if (b == 0) out->min = d;
        else out->max = d;
    }
    if (out->min > out->max) {
        char lo[40], hi[40];
        fmt_double(out->min, lo, sizeof lo);
        fmt_double(out->max, hi, sizeof hi);
        return fail_at(L, PG_ERR_PARAM, f, FPATH("max"), "%s is less than min %s", hi, lo);
    }

    const cJSON *values = cJSON_GetObjectItemCaseSensitive(decl, "values");
    if (values && out->type != PG_PARAM_ENUM)
        return fail_at(L, PG_ERR_PARAM, f, FPATH("values"), "only enum parameters have values");
    if (out->type == PG_PARAM_ENUM) {
        if (!cJSON_IsArray(values) || !values->child)
            return fail_at(L, PG_ERR_PARAM, f, FPATH("values"),
                           "an enum needs a non-empty array of strings");
        int nv = cJSON_GetArraySize(values);
        if (nv > PG_MAX_ENUM_VALUES)
            return fail_at(L, PG_ERR_LIMIT, f, FPATH("values"), "%d values, the limit is %d", nv,
                           PG_MAX_ENUM_VALUES);
        const cJSON *v;
        uint32_t i = 0;
        cJSON_ArrayForEach(v, values) {
            bool ok = cJSON_IsString(v) && v->valuestring[0] &&
                      strlen(v->valuestring) < PG_NAME_MAX;
            for (const char *c = ok ? v->valuestring : ""; *c; c++)
                if ((unsigned char)*c <= ' ' || *c == 0x7f) ok = false;
            if (!ok) {
                describe(v, got, sizeof got);
                snprintf(fpath, sizeof fpath, "%s.values[%u]", path, i);
                return fail_at(L, PG_ERR_PARAM, f, fpath,
                               "expected a non-empty string without spaces "
                               "(at most %d characters), got %s",
                               PG_NAME_MAX - 1, got);
            }
            for (uint32_t j = 0; j < i; j++)
                if (strcmp(out->values[j], v->valuestring) == 0) {
                    snprintf(fpath, sizeof fpath, "%s.values[%u]", path, i);
                    return fail_at(L, PG_ERR_PARAM, f, fpath, "'%s' is listed twice",
                                   v->valuestring);
                }
            pg_strlcpy(out->values[i++], v->valuestring, PG_NAME_MAX);
        }
        out->n_values = i;
    }

    const cJSON *desc = cJSON_GetObjectItemCaseSensitive(decl, "description");
    if (desc) {
        if (!cJSON_IsString(desc)) {
            describe(desc, got, sizeof got);
            return fail_at(L, PG_ERR_PARAM, f, FPATH("description"), "expected a string, got %s",
                           got);
        }
        pg_strlcpy(out->description, desc->valuestring, sizeof out->description);
    }

    const cJSON *def = cJSON_GetObjectItemCaseSensitive(decl, "default");
    if (!def)
        return fail_at(L, PG_ERR_PARAM, f, FPATH("default"), "missing (every parameter needs one)");
    describe(def, got, sizeof got);
    switch (out->type) {
    case PG_PARAM_INT:
        if (!json_integer(def, -MAX_SAFE_INT, MAX_SAFE_INT, &out->number))
            return fail_at(L, PG_ERR_PARAM, f, FPATH("default"), "expected an integer, got %s",
                           got);
        break;
    case PG_PARAM_FLOAT:
        if (!cJSON_IsNumber(def) || !isfinite(def->valuedouble))
            return fail_at(L, PG_ERR_PARAM, f, FPATH("default"), "expected a finite number, got %s",
                           got);
        out->number = def->valuedouble;
        break;
    case PG_PARAM_BOOL:
        if (!cJSON_IsBool(def))
            return fail_at(L, PG_ERR_PARAM, f, FPATH("default"), "expected true or false, got %s",
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
            return fail_at(L, PG_ERR_PARAM, f, FPATH("default"), "%s is not one of the values (%s)",
                           got, vals);
        }
        pg_strlcpy(out->enum_value, def->valuestring, sizeof out->enum_value);
        break;
    }
    }
    if (numeric && (out->number < out->min || out->number > out->max)) {
        char lo[40], hi[40];
        fmt_double(out->min, lo, sizeof lo);
        fmt_double(out->max, hi, sizeof hi);
        return fail_at(L, PG_ERR_PARAM, f, FPATH("default"), "%s is out of range [%s, %s]", got, lo,
                       hi);
    }
    return PG_OK;
#undef FPATH
}

/* ------------------------------------------------------------------ files */

static pg_result check_keys(loader *L, const src_file *f, const cJSON *obj, const char *path,
                            const char *what, const char *const *allowed)
{
    const cJSON *c;
    cJSON_ArrayForEach(c, obj) {
        if (in_list(c->string, allowed)) continue;
        char list[400] = "";
        for (const char *const *a = allowed; *a; a++) list_append(list, sizeof list, *a);
        return fail_at(L, PG_ERR_SCHEMA, f, path, "unknown key '%.64s' in %s (allowed: %s)",
                       c->string, what, list);
    }
    return PG_OK;
}

static int cmp_key(const void *a, const void *b)
{
    const cJSON *x = *(const cJSON *const *)a, *y = *(const cJSON *const *)b;
    return strcmp(x->string, y->string);
}

/* Rejects objects that repeat a key anywhere in the tree (cJSON keeps both silently). */
static pg_result check_dup_keys(loader *L, const src_file *f, const cJSON *node)
{
    if (cJSON_IsObject(node) && node->child && node->child->next) {
        size_t n = 0;
        for (const cJSON *c = node->child; c; c = c->next) n++;
        const cJSON **keys = malloc(n * sizeof *keys);
        if (!keys) return pg_fail(L->err, PG_ERR_OOM, "%s: out of memory", f->path);
        n = 0;
        for (const cJSON *c = node->child; c; c = c->next) keys[n++] = c;
        qsort(keys, n, sizeof *keys, cmp_key);
        for (size_t i = 1; i < n; i++) {
            if (strcmp(keys[i - 1]->string, keys[i]->string) == 0) {
                char key[80];
                pg_strlcpy(key, keys[i]->string, sizeof key);
                free(keys);
                return fail_at(L, PG_ERR_SCHEMA, f, L->jp[0] ? L->jp : "(top level)",
                               "key '%s' appears more than once", key);
            }
        }
        free(keys);
    }
    uint32_t i = 0;
    for (const cJSON *c = node->child; c; c = c->next, i++) {
        if (!cJSON_IsObject(c) && !cJSON_IsArray(c)) continue;
        size_t mark = cJSON_IsObject(node) ? jp_push(L, "%s%s", L->jp[0] ? "." : "", c->string)
                                           : jp_push(L, "[%u]", i);
        pg_result r = check_dup_keys(L, f, c);
        jp_pop(L, mark);
        if (r) return r;
    }
    return PG_OK;
}

static src_file *new_file(loader *L, const char *path)
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

/* Parses text as f's JSON tree; syntax errors are "FILE:LINE:COL: ...". */
static pg_result parse_text(loader *L, src_file *f, const char *text, size_t len)
{
    const char *end = NULL;
    cJSON *root = len ? cJSON_ParseWithLengthOpts(text, len, &end, 0) : NULL;
    const char *bad = NULL;
    const char *extra = "";
    if (!root) {
        bad = end ? end : cJSON_GetErrorPtr();
        if (!bad || bad < text || bad > text + len) bad = text + len;
        size_t ws = 0;
        while (ws < len && (text[ws] == ' ' || text[ws] == '\t' || text[ws] == '\n' ||
                            text[ws] == '\r'))
            ws++;
        if (ws == len) {
            extra = " (empty document)";
        } else {
            /* cJSON reports the byte after the culprit: step back over whitespace to it */
            while (bad > text && (bad == text + len || *bad == ' ' || *bad == '\t' ||
                                  *bad == '\n' || *bad == '\r'))
                bad--;
            if (bad + 1 >= text + len) extra = " (unexpected end of input)";
        }
    } else {
        const char *e = end ? end : text + len;
        while (e < text + len && (*e == ' ' || *e == '\t' || *e == '\n' || *e == '\r')) e++;
        if (e < text + len) {
            cJSON_Delete(root);
            root = NULL;
            bad = e;
            extra = " (text after the JSON value)";
        }
    }
    if (!root) {
        unsigned line = 1, col = 1;
        for (const char *c = text; c < bad; c++) {
            if (*c == '\n') {
                line++;
                col = 1;
            } else {
                col++;
            }
        }
        char near[32];
        size_t k = 0;
        for (const char *c = bad; c < text + len && k < 24 && *c != '\n'; c++)
            near[k++] = (*c >= 0x20 && *c < 0x7f && *c != '\'') ? *c : '?';
        near[k] = 0;
        return pg_fail(L->err, PG_ERR_PARSE, "%s:%u:%u: JSON syntax error near '%s'%s", f->path,
                       line, col, near, extra);
    }
    f->root = root;
    if (!cJSON_IsObject(root)) {
        char got[96];
        describe(root, got, sizeof got);
        return fail_at(L, PG_ERR_SCHEMA, f, "(top level)", "expected a JSON object, got %s", got);
    }
    L->jp[0] = 0;
    return check_dup_keys(L, f, root);
}

static const char *const k_top_keys[] = {"name",   "description", "include", "parameters",
                                         "resources", "passes",   "output",  "hdr_output", NULL};
static const char *const k_frag_keys[] = {"description", "include", "parameters", "resources",
                                          "passes", NULL};

static pg_result process_file(loader *L, const src_file *f);

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
            return fail_at(L, PG_ERR_INCLUDE, from, ipath, "path too long");
    } else {
        const char *slash = strrchr(from->path, '/');
        int dirlen = slash ? (int)(slash - from->path) + (slash == from->path) : 0;
        int n = dirlen ? snprintf(path, sizeof path, "%.*s%s%s", dirlen, from->path,
                                  from->path[dirlen - 1] == '/' ? "" : "/", rel)
                       : snprintf(path, sizeof path, "%s", rel);
        if (n < 0 || (size_t)n >= sizeof path)
            return fail_at(L, PG_ERR_INCLUDE, from, ipath, "path too long");
    }
    if (L->depth + 1 > PG_MAX_INCLUDE_DEPTH) {
        char chain[700];
        include_chain(L, path, chain, sizeof chain);
        return fail_at(L, PG_ERR_INCLUDE, from, ipath, "includes nested deeper than %d levels: %s",
                       PG_MAX_INCLUDE_DEPTH, chain);
    }
    if (L->n_files >= PG_MAX_INCLUDE_FILES)
        return fail_at(L, PG_ERR_INCLUDE, from, ipath, "more than %d files included in all",
                       PG_MAX_INCLUDE_FILES);
    struct stat st;
    if (stat(path, &st) != 0)
        return fail_at(L, PG_ERR_INCLUDE, from, ipath, "cannot open '%s': %s", path,
                       strerror(errno));
    if (!S_ISREG(st.st_mode))
        return fail_at(L, PG_ERR_INCLUDE, from, ipath, "'%s' is not a regular file", path);
    char *canon = realpath(path, NULL);
    if (!canon) canon = strdup(path);
    if (!canon) return pg_fail(L->err, PG_ERR_OOM, "%s: out of memory", from->path);
    for (uint32_t i = 0; i <= L->depth; i++) {
        if (strcmp(L->stack[i]->canon, canon) == 0) {
            free(canon);
            char chain[700];
            include_chain(L, path, chain, sizeof chain);
            return fail_at(L, PG_ERR_INCLUDE, from, ipath, "include cycle: %s", chain);
        }
    }
    src_file *f = new_file(L, path);
    if (!f) {
        free(canon);
        return pg_fail(L->err, PG_ERR_OOM, "%s: out of memory", from->path);
    }
    f->canon = canon;
    char *text = NULL;
    size_t len = 0;
    pg_result r = pg_read_file_as(path, "a pipeline .json file", &text, &len, L->err);
    if (r) {
        char cause[PG_ERROR_MSG_MAX];
        pg_strlcpy(cause, L->err ? L->err->msg : "", sizeof cause);
        return fail_at(L, r == PG_ERR_OOM ? r : PG_ERR_INCLUDE, from, ipath,
                       "cannot read '%s': %s", path, cause);
    }
    r = parse_text(L, f, text, len);
    free(text);
    if (r) return r;
    L->stack[++L->depth] = f;
    r = process_file(L, f);
    L->depth--;
    return r;
}

/* Adds a parameter declaration, accepting an identical redeclaration. */
static pg_result add_param(loader *L, const src_file *f, const cJSON *decl)
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
        return fail_at(L, PG_ERR_PARAM, f, path,
                       "parameter '%s' is already declared differently at %s: parameters.%s",
                       prm.name, L->param_file[i]->path, prm.name);
    }
    if (p->n_params >= PG_MAX_PARAMS) {
        char path[PG_JSON_PATH_MAX + 16];
        snprintf(path, sizeof path, "parameters.%s", prm.name);
        return fail_at(L, PG_ERR_LIMIT, f, path,
                       "more than %d parameters (the pipeline and its includes)", PG_MAX_PARAMS);
    }
    L->param_file[p->n_params] = f;
    L->param_decl[p->n_params] = decl;
    p->params[p->n_params++] = prm;
    return PG_OK;
}

static pg_result collect_items(loader *L, const src_file *f, const char *key, item_ref *items,
                               uint32_t *n, uint32_t max)
{
    const cJSON *arr = cJSON_GetObjectItemCaseSensitive(f->root, key);
    if (!arr) return PG_OK;
    if (!cJSON_IsArray(arr)) {
        char got[96];
        describe(arr, got, sizeof got);
        return fail_at(L, PG_ERR_SCHEMA, f, key, "expected an array, got %s", got);
    }
    uint32_t i = 0;
    for (cJSON *c = arr->child; c; c = c->next, i++) {
        if (*n >= max) {
            char path[64];
            snprintf(path, sizeof path, "%s[%u]", key, i);
            return fail_at(L, PG_ERR_LIMIT, f, path,
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

static pg_result process_file(loader *L, const src_file *f)
{
    bool top = L->depth == 0;
    pg_result r = check_keys(L, f, f->root, "(top level)",
                             top ? "a pipeline file" : "an included fragment",
                             top ? k_top_keys : k_frag_keys);
    if (r) return r;

    const cJSON *inc = cJSON_GetObjectItemCaseSensitive(f->root, "include");
    if (inc) {
        if (!cJSON_IsArray(inc)) {
            char got[96];
            describe(inc, got, sizeof got);
            return fail_at(L, PG_ERR_SCHEMA, f, "include",
                           "expected an array of relative paths, got %s", got);
        }
        uint32_t i = 0;
        for (const cJSON *c = inc->child; c; c = c->next, i++) {
            if (!cJSON_IsString(c) || !c->valuestring[0]) {
                char got[96], path[32];
                describe(c, got, sizeof got);
                snprintf(path, sizeof path, "include[%u]", i);
                return fail_at(L, PG_ERR_SCHEMA, f, path, "expected a file path, got %s", got);
            }
            r = load_include(L, f, i, c->valuestring);
            if (r) return r;
        }
    }

    const cJSON *params = cJSON_GetObjectItemCaseSensitive(f->root, "parameters");
    if (params) {
        if (!cJSON_IsObject(params)) {
            char got[96];
            describe(params, got, sizeof got);
            return fail_at(L, PG_ERR_SCHEMA, f, "parameters",
                           "expected an object of declarations, got %s", got);
        }
        for (const cJSON *c = params->child; c; c = c->next) {
            r = add_param(L, f, c);
            if (r) return r;
        }
    }
    r = collect_items(L, f, "resources", L->res, &L->n_res, PG_MAX_RESOURCES);
    if (r) return r;
    return collect_items(L, f, "passes", L->pass, &L->n_pass, PG_MAX_PASSES);
}

/* ------------------------------------------------------------------ overrides, substitution */

static pg_result apply_overrides(loader *L, const pg_param_override *ov, uint32_t n)
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
            return fail_at(L, PG_ERR_PARAM, top, set, "unknown parameter '%.64s' (declared: %s)",
                           key, names);
        }
        pg_param val;
        char why[600];
        if (!parse_typed(prm, value, true, &val, why, sizeof why))
            return fail_at(L, PG_ERR_PARAM, top, set, "%s parameter '%s': %s",
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
static pg_result substitute(loader *L, const src_file *f, cJSON *node, bool top)
{
    uint32_t i = 0;
    cJSON *next;
    for (cJSON *c = node->child; c; c = next, i++) {
        next = c->next;
        bool obj = cJSON_IsObject(node);
        if (top && obj && c->string && strcmp(c->string, "when") == 0) continue;
        size_t mark = obj ? jp_push(L, ".%s", c->string) : jp_push(L, "[%u]", i);
        pg_result r = PG_OK;
        if (cJSON_IsString(c) && is_param_ref(c->valuestring)) {
            const pg_param *prm = pg_pipeline_find_param(L->p, c->valuestring + 1);
            if (!prm) {
                char names[640];
                param_names(L->p, names, sizeof names);
                r = fail_at(L, PG_ERR_PARAM, f, L->jp,
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
            r = substitute(L, f, c, false);
        }
        jp_pop(L, mark);
        if (r) return r;
    }
    return PG_OK;
}

/* Evaluates item's optional "when"; *active is false when the item is to be dropped. */
static pg_result eval_when(loader *L, const src_file *f, const cJSON *item, const char *ipath,
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
        describe(w, got, sizeof got);
        return fail_at(L, PG_ERR_SCHEMA, f, path, "%s, got %s", expect, got);
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
        return fail_at(L, PG_ERR_SCHEMA, f, path, "malformed condition \"%.80s\" (%s)",
                       w->valuestring, expect);
    const pg_param *prm = pg_pipeline_find_param(L->p, name);
    if (!prm) {
        char names[640];
        param_names(L->p, names, sizeof names);
        return fail_at(L, PG_ERR_PARAM, f, path, "unknown parameter '$%s' (declared: %s)", name,
                       names);
    }
    pg_param val;
    char bad[600];
    if (!parse_typed(prm, value, false, &val, bad, sizeof bad))
        return fail_at(L, PG_ERR_SCHEMA, f, path, "cannot compare %s parameter '%s': %s",
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

/* ------------------------------------------------------------------ resources */

static const char *const k_res_keys[] = {"name",  "type",     "format", "scale",       "extent",
                                         "stride", "count",   "lifetime", "when",      "description",
                                         "grow", NULL};
static const char *const k_pass_keys[] = {"name",  "type",         "reads",   "writes",
                                          "after", "side_effects", "options", "when",
                                          "description", "queue", NULL};

/* Reads a required identifier field (name / type). */
static pg_result req_ident(loader *L, const src_file *f, const cJSON *obj, const char *ipath,
                           const char *key, char *out)
{
    char path[PG_JSON_PATH_MAX];
    snprintf(path, sizeof path, "%s.%s", ipath, key);
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!v) return fail_at(L, PG_ERR_SCHEMA, f, path, "missing (required)");
    if (!cJSON_IsString(v) || !valid_ident(v->valuestring)) {
        char got[96];
        describe(v, got, sizeof got);
        return fail_at(L, PG_ERR_SCHEMA, f, path,
                       "expected a name matching [A-Za-z0-9_]+ (at most %d characters), got %s",
                       PG_NAME_MAX - 1, got);
    }
    pg_strlcpy(out, v->valuestring, PG_NAME_MAX);
    return PG_OK;
}

static pg_result opt_description(loader *L, const src_file *f, const cJSON *obj,
                                 const char *ipath)
{
    const cJSON *d = cJSON_GetObjectItemCaseSensitive(obj, "description");
    if (!d || cJSON_IsString(d)) return PG_OK;
    char got[96], path[PG_JSON_PATH_MAX];
    describe(d, got, sizeof got);
    snprintf(path, sizeof path, "%s.description", ipath);
    return fail_at(L, PG_ERR_SCHEMA, f, path, "expected a string, got %s", got);
}

static pg_result parse_resource(loader *L, uint32_t idx)
{
    item_ref *it = &L->res[idx];
    pg_resource_desc *d = &L->rdesc[idx];
    const src_file *f = it->file;
    char ip[48], path[PG_JSON_PATH_MAX], got[96];
    snprintf(ip, sizeof ip, "resources[%u]", it->index);
    memset(d, 0, sizeof *d);
    pg_strlcpy(d->file, f->path, sizeof d->file);
    pg_strlcpy(d->json_path, ip, sizeof d->json_path);
    cJSON *o = it->node;
    if (!cJSON_IsObject(o)) {
        describe(o, got, sizeof got);
        return fail_at(L, PG_ERR_SCHEMA, f, ip, "expected a resource object, got %s", got);
    }
    snprintf(L->jp, sizeof L->jp, "%s", ip);
    pg_result r = substitute(L, f, o, true);
    if (r) return r;
    r = check_keys(L, f, o, ip, "a resource", k_res_keys);
    if (r) return r;
    r = req_ident(L, f, o, ip, "name", d->name);
    if (r) return r;
    for (uint32_t j = 0; j < idx; j++) {
        if (strcmp(L->rdesc[j].name, d->name) != 0) continue;
        snprintf(path, sizeof path, "%s.name", ip);
        const char *twice =
            L->res[j].file == f || strcmp(L->res[j].file->canon, f->canon) != 0
                ? ""
                : " (the same file is included more than once)";
        return fail_at(L, PG_ERR_SCHEMA, f, path,
                       "resource '%s' is declared twice: first at %s: %s%s", d->name,
                       L->rdesc[j].file, L->rdesc[j].json_path, twice);
    }

    const cJSON *type = cJSON_GetObjectItemCaseSensitive(o, "type");
    snprintf(path, sizeof path, "%s.type", ip);
    if (!type) return fail_at(L, PG_ERR_SCHEMA, f, path, "missing (\"image\" or \"buffer\")");
    if (cJSON_IsString(type) && strcmp(type->valuestring, "image") == 0) {
        d->kind = PG_RES_IMAGE;
    } else if (cJSON_IsString(type) && strcmp(type->valuestring, "buffer") == 0) {
        d->kind = PG_RES_BUFFER;
    } else {
        describe(type, got, sizeof got);
        return fail_at(L, PG_ERR_SCHEMA, f, path, "expected \"image\" or \"buffer\", got %s",
                       got);
    }

    const cJSON *lt = cJSON_GetObjectItemCaseSensitive(o, "lifetime");
    d->lifetime = PG_LIFETIME_TRANSIENT;
    if (lt) {
        snprintf(path, sizeof path, "%s.lifetime", ip);
        const char *s = cJSON_IsString(lt) ? lt->valuestring : "";
        if (strcmp(s, "transient") == 0) d->lifetime = PG_LIFETIME_TRANSIENT;
        else if (strcmp(s, "persistent") == 0) d->lifetime = PG_LIFETIME_PERSISTENT;
        else if (strcmp(s, "imported") == 0) d->lifetime = PG_LIFETIME_IMPORTED;
        else {
            describe(lt, got, sizeof got);
            return fail_at(L, PG_ERR_SCHEMA, f, path,
                           "expected \"transient\", \"persistent\" or \"imported\", got %s", got);
        }
    }

    static const char *const image_only[] = {"format", "scale", "extent", NULL};
    static const char *const buffer_only[] = {"stride", "count", "grow", NULL};
    const char *const *wrong = d->kind == PG_RES_IMAGE ? buffer_only : image_only;
    for (; *wrong; wrong++) {
        if (!cJSON_GetObjectItemCaseSensitive(o, *wrong)) continue;
        snprintf(path, sizeof path, "%s.%s", ip, *wrong);
        return fail_at(L, PG_ERR_SCHEMA, f, path, "'%s' is only for %s resources", *wrong,
                       d->kind == PG_RES_IMAGE ? "buffer" : "image");
    }

    if (d->kind == PG_RES_IMAGE) {
        const cJSON *fmt = cJSON_GetObjectItemCaseSensitive(o, "format");
        snprintf(path, sizeof path, "%s.format", ip);
        char names[400];
        format_names(names, sizeof names);
        if (!fmt) return fail_at(L, PG_ERR_SCHEMA, f, path, "missing (one of: %s)", names);
        if (!cJSON_IsString(fmt)) {
            describe(fmt, got, sizeof got);
            return fail_at(L, PG_ERR_SCHEMA, f, path, "expected a format name, got %s", got);
        }
        d->format = pg_format_from_name(fmt->valuestring);
        if (d->format == PG_FMT_UNDEFINED)
            return fail_at(L, PG_ERR_FORMAT, f, path, "unknown format '%.64s' (valid: %s)",
                           fmt->valuestring, names);

        const cJSON *scale = cJSON_GetObjectItemCaseSensitive(o, "scale");
        const cJSON *ext = cJSON_GetObjectItemCaseSensitive(o, "extent");
        d->extent_mode = PG_EXTENT_RELATIVE;
        d->scale[0] = d->scale[1] = 1.0f;
        if (scale && ext) {
            snprintf(path, sizeof path, "%s.extent", ip);
            return fail_at(L, PG_ERR_SCHEMA, f, path,
                           "give either \"scale\" (relative to the output) or \"extent\" "
                           "(pixels), not both");
        }
        if (scale) {
            snprintf(path, sizeof path, "%s.scale", ip);
            const cJSON *sx = scale, *sy = scale;
            if (cJSON_IsArray(scale)) {
                sx = scale->child;
                sy = sx ? sx->next : NULL;
                if (!sx || !sy || sy->next) sx = sy = NULL;
            }
            bool ok = true;
            for (int k = 0; k < 2; k++) {
                const cJSON *v = k ? sy : sx;
                if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble) || v->valuedouble <= 0 ||
                    v->valuedouble > 16) {
                    ok = false;
                    break;
                }
                d->scale[k] = (float)v->valuedouble;
            }
            if (!ok) {
                describe(scale, got, sizeof got);
                if (cJSON_IsArray(scale) && sx) {
                    const cJSON *bad = cJSON_IsNumber(sx) && sx->valuedouble > 0 &&
                                               sx->valuedouble <= 16 ? sy : sx;
                    describe(bad, got, sizeof got);
                }
                return fail_at(L, PG_ERR_SCHEMA, f, path,
                               "expected a number or [x, y] in (0, 16], got %s", got);
            }
        }
        if (ext) {
            snprintf(path, sizeof path, "%s.extent", ip);
            const cJSON *w = cJSON_IsArray(ext) ? ext->child : NULL;
            const cJSON *h = w ? w->next : NULL;
            double dw = 0, dh = 0;
            if (!w || !h || h->next || !json_integer(w, 1, 16384, &dw) ||
                !json_integer(h, 1, 16384, &dh)) {
                describe(ext, got, sizeof got);
                return fail_at(L, PG_ERR_SCHEMA, f, path,
                               "expected [width, height], integers in 1..16384, got %s%s", got,
                               cJSON_IsArray(ext) ? " with a bad element" : "");
            }
            d->extent_mode = PG_EXTENT_ABSOLUTE;
            d->size[0] = (uint32_t)dw;
            d->size[1] = (uint32_t)dh;
        }
    } else {
        const cJSON *stride = cJSON_GetObjectItemCaseSensitive(o, "stride");
        snprintf(path, sizeof path, "%s.stride", ip);
        if (!stride)
            return fail_at(L, PG_ERR_SCHEMA, f, path, "missing (bytes per element, 1..65536)");
        double sv = 0;
        if (!json_integer(stride, 1, 65536, &sv)) {
            describe(stride, got, sizeof got);
            return fail_at(L, PG_ERR_SCHEMA, f, path, "expected an integer in 1..65536, got %s",
                           got);
        }
        d->stride = (uint32_t)sv;
        const cJSON *grow = cJSON_GetObjectItemCaseSensitive(o, "grow");
        if (grow) {
            snprintf(path, sizeof path, "%s.grow", ip);
            if (!cJSON_IsBool(grow)) {
                describe(grow, got, sizeof got);
                return fail_at(L, PG_ERR_SCHEMA, f, path, "expected true or false, got %s", got);
            }
            d->growable = cJSON_IsTrue(grow);
        }
        const cJSON *count = cJSON_GetObjectItemCaseSensitive(o, "count");
        snprintf(path, sizeof path, "%s.count", ip);
        if (!count) {
            d->n_count_terms = 1;
            d->count[0].kind = PG_COUNT_CONST;
            d->count[0].value = 1;
        } else {
            int nt = cJSON_IsArray(count) ? cJSON_GetArraySize(count) : 0;
            if (!cJSON_IsArray(count) || nt == 0) {
                describe(count, got, sizeof got);
                return fail_at(L, PG_ERR_SCHEMA, f, path,
                               "expected a non-empty array of terms like [\"lights\", 4], got %s",
                               got);
            }
            if (nt > PG_MAX_COUNT_TERMS)
                return fail_at(L, PG_ERR_LIMIT, f, path, "%d terms, the limit is %d", nt,
                               PG_MAX_COUNT_TERMS);
            uint32_t k = 0;
            for (const cJSON *t = count->child; t; t = t->next, k++) {
                pg_count_term *term = &d->count[k];
                double v = 0;
                if (cJSON_IsString(t) && strcmp(t->valuestring, "lights") == 0) {
                    term->kind = PG_COUNT_LIGHTS;
                } else if (cJSON_IsString(t) && strcmp(t->valuestring, "pixels") == 0) {
                    term->kind = PG_COUNT_PIXELS;
                } else if (json_integer(t, 0, 4294967295.0, &v)) {
                    term->kind = PG_COUNT_CONST;
                    term->value = v;
                } else {
                    describe(t, got, sizeof got);
                    snprintf(path, sizeof path, "%s.count[%u]", ip, k);
                    return fail_at(L, PG_ERR_SCHEMA, f, path,
                                   "expected a non-negative integer, \"lights\" or "
                                   "\"pixels\", got %s",
                                   got);
                }
            }
            d->n_count_terms = k;
        }
    }
    r = opt_description(L, f, o, ip);
    if (r) return r;

    bool active;
    char why[sizeof L->p->omitted[0].why];
    r = eval_when(L, f, o, ip, &active, why, sizeof why);
    if (r) return r;
    if (!active) {
        pg_omitted *om = &L->p->omitted[L->p->n_omitted];
        snprintf(om->what, sizeof om->what, "resource '%s'", d->name);
        pg_strlcpy(om->why, why, sizeof om->why);
        it->omitted = true;
        it->omit_index = L->p->n_omitted++;
    }
    return PG_OK;
}

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
        describe(arr, got, sizeof got);
        return fail_at(L, PG_ERR_SCHEMA, f, path, "expected an array of names, got %s", got);
    }
    int cnt = cJSON_GetArraySize(arr);
    if (cnt > (int)max)
        return fail_at(L, PG_ERR_LIMIT, f, path, "%d entries, the limit is %u", cnt, max);
    uint32_t k = 0;
    for (const cJSON *c = arr->child; c; c = c->next, k++) {
        if (!cJSON_IsString(c) || !valid_ident(c->valuestring)) {
            describe(c, got, sizeof got);
            snprintf(path, sizeof path, "%s.%s[%u]", ip, key, k);
            return fail_at(L, PG_ERR_SCHEMA, f, path,
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
    if (!cJSON_IsObject(o)) {
        describe(o, got, sizeof got);
        return fail_at(L, PG_ERR_SCHEMA, f, ip, "expected a pass object, got %s", got);
    }
    snprintf(L->jp, sizeof L->jp, "%s", ip);
    pg_result r = substitute(L, f, o, true);
    if (r) return r;
    r = check_keys(L, f, o, ip, "a pass", k_pass_keys);
    if (r) return r;
    r = req_ident(L, f, o, ip, "name", d->name);
    if (r) return r;
    for (uint32_t j = 0; j < idx; j++) {
        if (strcmp(L->pdesc[j].name, d->name) != 0) continue;
        snprintf(path, sizeof path, "%s.name", ip);
        const char *twice =
            L->pass[j].file == f || strcmp(L->pass[j].file->canon, f->canon) != 0
                ? ""
                : " (the same file is included more than once)";
        return fail_at(L, PG_ERR_SCHEMA, f, path, "pass '%s' is declared twice: first at %s: %s%s",
                       d->name, L->pdesc[j].file, L->pdesc[j].json_path, twice);
    }
    r = req_ident(L, f, o, ip, "type", d->type);
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
            describe(se, got, sizeof got);
            snprintf(path, sizeof path, "%s.side_effects", ip);
            return fail_at(L, PG_ERR_SCHEMA, f, path, "expected true or false, got %s", got);
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
            describe(qu, got, sizeof got);
            snprintf(path, sizeof path, "%s.queue", ip);
            return fail_at(L, PG_ERR_SCHEMA, f, path,
                           "expected \"auto\", \"graphics\" or \"compute\", got %s", got);
        }
    }
    cJSON *opts = cJSON_GetObjectItemCaseSensitive(o, "options");
    if (opts && !cJSON_IsObject(opts)) {
        describe(opts, got, sizeof got);
        snprintf(path, sizeof path, "%s.options", ip);
        return fail_at(L, PG_ERR_SCHEMA, f, path, "expected an object, got %s", got);
    }
    it->options = opts;
    d->options = opts;
    r = opt_description(L, f, o, ip);
    if (r) return r;

    bool active;
    char why[sizeof L->p->omitted[0].why];
    r = eval_when(L, f, o, ip, &active, why, sizeof why);
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
        if (!L->res[i].omitted) list_append(buf, n, L->rdesc[i].name);
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
            return fail_at(L, PG_ERR_UNKNOWN_RESOURCE, it->file, path,
                           "unknown resource '%s' (declared: %s)", names[k], list);
        }
        if (L->res[j].omitted && !it->omitted)
            return fail_at(L, PG_ERR_UNKNOWN_RESOURCE, it->file, path,
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
            return fail_at(L, PG_ERR_SCHEMA, it->file, path, "unknown pass '%s'", d->after[k]);
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
        return fail_at(L, PG_ERR_NO_OUTPUT, f, key,
                       "missing: name the image resource to display (\"%s\": \"...\")", key);
    }
    char got[96];
    if (!cJSON_IsString(v)) {
        describe(v, got, sizeof got);
        return fail_at(L, PG_ERR_SCHEMA, f, key, "expected an image resource name, got %s", got);
    }
    int j = valid_ident(v->valuestring) ? find_res(L, v->valuestring) : -1;
    if (j < 0) {
        char list[600];
        resource_names(L, list, sizeof list);
        return fail_at(L, PG_ERR_NO_OUTPUT, f, key, "unknown resource '%.64s' (declared: %s)",
                       v->valuestring, list);
    }
    if (L->res[j].omitted)
        return fail_at(L, PG_ERR_NO_OUTPUT, f, key, "resource '%s' is omitted: %s",
                       v->valuestring, L->p->omitted[L->res[j].omit_index].why);
    if (L->rdesc[j].kind != PG_RES_IMAGE)
        return fail_at(L, PG_ERR_NO_OUTPUT, f, key,
                       "'%s' is a buffer (%s: %s); the output must be an image", v->valuestring,
                       L->rdesc[j].file, L->rdesc[j].json_path);
    pg_strlcpy(out, v->valuestring, PG_NAME_MAX);
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
            describe(name, got, sizeof got);
            return fail_at(L, PG_ERR_SCHEMA, f, "name",
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
            describe(desc, got, sizeof got);
            return fail_at(L, PG_ERR_SCHEMA, f, "description", "expected a string, got %s", got);
        }
        pg_strlcpy(p->description, desc->valuestring, sizeof p->description);
    }
    return PG_OK;
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
    src_file *f = new_file(L, path);
    if (!f) return pg_fail(L->err, PG_ERR_OOM, "%s: out of memory", path);
    f->canon = realpath(path, NULL);
    if (!f->canon) f->canon = strdup(path);
    if (!f->canon) return pg_fail(L->err, PG_ERR_OOM, "%s: out of memory", path);
    pg_strlcpy(p->path, path, sizeof p->path);
    L->stack[0] = f;
    L->depth = 0;
    pg_result r = parse_text(L, f, text, len);
    if (r) return r;
    r = process_file(L, f);
    if (r) return r;
    r = read_header(L);
    if (r) return r;
    if (n_ov && !ov) return pg_fail(L->err, PG_ERR_INVALID_ARG, "%s: overrides is NULL", path);
    r = apply_overrides(L, ov, n_ov);
    if (r) return r;
    for (uint32_t i = 0; i < L->n_res; i++) {
        r = parse_resource(L, i);
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
    struct stat st;
    if (stat(path, &st) != 0)
        return pg_fail(err, PG_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    if (!S_ISREG(st.st_mode))
        return pg_fail(err, PG_ERR_IO, "%s: %s (expected a pipeline .json file)", path,
                       S_ISDIR(st.st_mode) ? "is a directory" : "is not a regular file");
    char *text = NULL;
    size_t len = 0;
    pg_result r = pg_read_file(path, &text, &len, err);
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
