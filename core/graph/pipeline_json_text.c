/* pipeline_json_text.c - the pipeline loader's JSON text: syntax errors as "FILE:LINE:COL: ...",
 * unknown and duplicate object keys, and the helpers every message uses ("got ...", name lists,
 * JSON paths). Part of the loader (pipeline_json_internal.h).
 */
#include "pipeline_json_internal.h"
#include "pg_file.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------ small helpers */

pg_result pj_fail_at(loader *L, pg_result code, const src_file *f, const char *path,
                  const char *fmt, ...)
{
    char cause[PG_ERROR_MSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(cause, sizeof cause, fmt, ap);
    va_end(ap);
    return pg_fail(L->err, code, "%s: %s: %s", f ? f->path : "<pipeline>", path, cause);
}

/* "%.17g" trimmed to the shortest text that reads back as the same double. */
void pj_fmt_double(double v, char *buf, size_t n)
{
    for (int prec = 15; prec <= 17; prec++) {
        snprintf(buf, n, "%.*g", prec, v);
        if (strtod(buf, NULL) == v) return;
    }
}

/* Describes a JSON value for "got ..." in messages. */
void pj_describe(const cJSON *v, char *buf, size_t n)
{
    if (!v) {
        snprintf(buf, n, "nothing");
    } else if (cJSON_IsNumber(v)) {
        pj_fmt_double(v->valuedouble, buf, n);
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
void pj_list_append(char *buf, size_t n, const char *item)
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

static bool in_list(const char *s, const char *const *list)
{
    for (; *list; list++)
        if (strcmp(s, *list) == 0) return true;
    return false;
}

/* Integral, finite, within [lo, hi]. */
bool pj_json_integer(const cJSON *v, double lo, double hi, double *out)
{
    if (!cJSON_IsNumber(v)) return false;
    double d = v->valuedouble;
    if (!isfinite(d) || d != floor(d) || d < lo || d > hi) return false;
    *out = d;
    return true;
}

/* JSON path scratch buffer: push appends, pop restores. */
size_t pj_jp_push(loader *L, const char *fmt, ...)
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
void pj_jp_pop(loader *L, size_t mark) { L->jp[mark] = 0; }

/* ------------------------------------------------------------------ keys and JSON text */

pg_result pj_check_keys(loader *L, const src_file *f, const cJSON *obj, const char *path,
                     const char *what, const char *const *allowed)
{
    const cJSON *c;
    cJSON_ArrayForEach(c, obj) {
        if (in_list(c->string, allowed)) continue;
        char list[400] = "";
        for (const char *const *a = allowed; *a; a++) pj_list_append(list, sizeof list, *a);
        return pj_fail_at(L, PG_ERR_SCHEMA, f, path, "unknown key '%.64s' in %s (allowed: %s)",
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
                return pj_fail_at(L, PG_ERR_SCHEMA, f, L->jp[0] ? L->jp : "(top level)",
                               "key '%s' appears more than once", key);
            }
        }
        free(keys);
    }
    uint32_t i = 0;
    for (const cJSON *c = node->child; c; c = c->next, i++) {
        if (!cJSON_IsObject(c) && !cJSON_IsArray(c)) continue;
        size_t mark = cJSON_IsObject(node) ? pj_jp_push(L, "%s%s", L->jp[0] ? "." : "", c->string)
                                           : pj_jp_push(L, "[%u]", i);
        pg_result r = check_dup_keys(L, f, c);
        pj_jp_pop(L, mark);
        if (r) return r;
    }
    return PG_OK;
}

/* Parses text as f's JSON tree; syntax errors are "FILE:LINE:COL: ...". */
pg_result pj_parse_text(loader *L, src_file *f, const char *text, size_t len)
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
        /* line and column only: the file may not be JSON at all, and its text is never echoed */
        if (!extra[0]) extra = pg_json_depth_note(text, bad < text + len ? (size_t)(bad - text) + 1 : len, CJSON_NESTING_LIMIT);
        return pg_fail(L->err, PG_ERR_PARSE, "%s:%u:%u: JSON syntax error%s", f->path, line, col,
                       extra);
    }
    f->root = root;
    if (!cJSON_IsObject(root)) {
        char got[96];
        pj_describe(root, got, sizeof got);
        return pj_fail_at(L, PG_ERR_SCHEMA, f, "(top level)", "expected a JSON object, got %s", got);
    }
    L->jp[0] = 0;
    return check_dup_keys(L, f, root);
}
