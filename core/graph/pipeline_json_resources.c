/* pipeline_json_resources.c - the pipeline loader's resource objects: name, type, lifetime,
 * image format and size (scale or extent), buffer stride, count terms and growth, "when".
 * Part of the loader (pipeline_json_internal.h).
 */
#include "pipeline_json_internal.h"
#include "compile_vars.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* ------------------------------------------------------------------ resources */

static const char *const k_res_keys[] = {"name",  "type",     "format", "scale",       "extent",
                                         "stride", "count",   "lifetime", "when",      "description",
                                         "grow", NULL};

static void format_names(char *buf, size_t n)
{
    buf[0] = 0;
    for (int f = 1; f < PG_FMT_COUNT; f++) pj_list_append(buf, n, pg_format_get((pg_format)f)->name);
}

/* An image resource's format and size ("scale" relative to the output, or "extent" in pixels). */
static pg_result parse_image_fields(loader *L, const src_file *f, const cJSON *o, const char *ip,
                                    pg_resource_desc *d)
{
    char path[PG_JSON_PATH_MAX], got[96];
    const cJSON *fmt = cJSON_GetObjectItemCaseSensitive(o, "format");
    snprintf(path, sizeof path, "%s.format", ip);
    char names[400];
    format_names(names, sizeof names);
    if (!fmt) return pj_fail_at(L, PG_ERR_SCHEMA, f, path, "missing (one of: %s)", names);
    if (!cJSON_IsString(fmt)) {
        pj_describe(fmt, got, sizeof got);
        return pj_fail_at(L, PG_ERR_SCHEMA, f, path, "expected a format name, got %s", got);
    }
    d->format = pg_format_from_name(fmt->valuestring);
    if (d->format == PG_FMT_UNDEFINED)
        return pj_fail_at(L, PG_ERR_FORMAT, f, path, "unknown format '%.64s' (valid: %s)",
                       fmt->valuestring, names);

    const cJSON *scale = cJSON_GetObjectItemCaseSensitive(o, "scale");
    const cJSON *ext = cJSON_GetObjectItemCaseSensitive(o, "extent");
    d->extent_mode = PG_EXTENT_RELATIVE;
    d->scale[0] = d->scale[1] = 1.0f;
    if (scale && ext) {
        snprintf(path, sizeof path, "%s.extent", ip);
        return pj_fail_at(L, PG_ERR_SCHEMA, f, path,
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
            pj_describe(scale, got, sizeof got);
            if (cJSON_IsArray(scale) && sx) {
                const cJSON *bad = cJSON_IsNumber(sx) && sx->valuedouble > 0 &&
                                           sx->valuedouble <= 16 ? sy : sx;
                pj_describe(bad, got, sizeof got);
            }
            return pj_fail_at(L, PG_ERR_SCHEMA, f, path,
                           "expected a number or [x, y] in (0, 16], got %s", got);
        }
    }
    if (ext) {
        snprintf(path, sizeof path, "%s.extent", ip);
        const cJSON *w = cJSON_IsArray(ext) ? ext->child : NULL;
        const cJSON *h = w ? w->next : NULL;
        double dw = 0, dh = 0;
        if (!w || !h || h->next || !pj_json_integer(w, 1, 16384, &dw) ||
            !pj_json_integer(h, 1, 16384, &dh)) {
            pj_describe(ext, got, sizeof got);
            return pj_fail_at(L, PG_ERR_SCHEMA, f, path,
                           "expected [width, height], integers in 1..16384, got %s%s", got,
                           cJSON_IsArray(ext) ? " with a bad element" : "");
        }
        d->extent_mode = PG_EXTENT_ABSOLUTE;
        d->size[0] = (uint32_t)dw;
        d->size[1] = (uint32_t)dh;
    }
    return PG_OK;
}

/* A buffer resource's stride, "grow" and element count terms. */
static pg_result parse_buffer_fields(loader *L, const src_file *f, const cJSON *o, const char *ip,
                                     pg_resource_desc *d)
{
    char path[PG_JSON_PATH_MAX], got[96];
    const cJSON *stride = cJSON_GetObjectItemCaseSensitive(o, "stride");
    snprintf(path, sizeof path, "%s.stride", ip);
    if (!stride)
        return pj_fail_at(L, PG_ERR_SCHEMA, f, path, "missing (bytes per element, 1..65536)");
    double sv = 0;
    if (!pj_json_integer(stride, 1, 65536, &sv)) {
        pj_describe(stride, got, sizeof got);
        return pj_fail_at(L, PG_ERR_SCHEMA, f, path, "expected an integer in 1..65536, got %s",
                       got);
    }
    d->stride = (uint32_t)sv;
    const cJSON *grow = cJSON_GetObjectItemCaseSensitive(o, "grow");
    if (grow) {
        snprintf(path, sizeof path, "%s.grow", ip);
        if (!cJSON_IsBool(grow)) {
            pj_describe(grow, got, sizeof got);
            return pj_fail_at(L, PG_ERR_SCHEMA, f, path, "expected true or false, got %s", got);
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
            pj_describe(count, got, sizeof got);
            return pj_fail_at(L, PG_ERR_SCHEMA, f, path,
                           "expected a non-empty array of terms like [\"lights\", 4], got %s",
                           got);
        }
        if (nt > PG_MAX_COUNT_TERMS)
            return pj_fail_at(L, PG_ERR_LIMIT, f, path, "%d terms, the limit is %d", nt,
                           PG_MAX_COUNT_TERMS);
        uint32_t k = 0;
        for (const cJSON *t = count->child; t; t = t->next, k++) {
            pg_count_term *term = &d->count[k];
            double v = 0;
            if (cJSON_IsString(t) && strcmp(t->valuestring, "pixels") == 0) {
                term->kind = PG_COUNT_PIXELS;
            } else if (cJSON_IsString(t) && pg_var_name_ok(t->valuestring)) {
                term->kind = PG_COUNT_VAR;
                pg_strlcpy(term->var, t->valuestring, sizeof term->var);
            } else if (pj_json_integer(t, 0, 4294967295.0, &v)) {
                term->kind = PG_COUNT_CONST;
                term->value = v;
            } else {
                pj_describe(t, got, sizeof got);
                snprintf(path, sizeof path, "%s.count[%u]", ip, k);
                return pj_fail_at(L, PG_ERR_SCHEMA, f, path,
                               "expected a non-negative integer, \"pixels\" or the name of a "
                               "compile variable (e.g. \"lights\"), got %s",
                               got);
            }
        }
        d->n_count_terms = k;
    }
    return PG_OK;
}

pg_result pj_parse_resource(loader *L, uint32_t idx)
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
    pg_result r = pj_item_begin(L, f, o, ip, "resource", k_res_keys, d->name);
    if (r) return r;
    for (uint32_t j = 0; j < idx; j++)
        if (strcmp(L->rdesc[j].name, d->name) == 0)
            return pj_item_twice(L, f, ip, "resource", d->name, L->res[j].file, L->rdesc[j].file,
                                 L->rdesc[j].json_path);

    const cJSON *type = cJSON_GetObjectItemCaseSensitive(o, "type");
    snprintf(path, sizeof path, "%s.type", ip);
    if (!type) return pj_fail_at(L, PG_ERR_SCHEMA, f, path, "missing (\"image\" or \"buffer\")");
    if (cJSON_IsString(type) && strcmp(type->valuestring, "image") == 0) {
        d->kind = PG_RES_IMAGE;
    } else if (cJSON_IsString(type) && strcmp(type->valuestring, "buffer") == 0) {
        d->kind = PG_RES_BUFFER;
    } else {
        pj_describe(type, got, sizeof got);
        return pj_fail_at(L, PG_ERR_SCHEMA, f, path, "expected \"image\" or \"buffer\", got %s",
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
            pj_describe(lt, got, sizeof got);
            return pj_fail_at(L, PG_ERR_SCHEMA, f, path,
                           "expected \"transient\", \"persistent\" or \"imported\", got %s", got);
        }
    }

    static const char *const image_only[] = {"format", "scale", "extent", NULL};
    static const char *const buffer_only[] = {"stride", "count", "grow", NULL};
    const char *const *wrong = d->kind == PG_RES_IMAGE ? buffer_only : image_only;
    for (; *wrong; wrong++) {
        if (!cJSON_GetObjectItemCaseSensitive(o, *wrong)) continue;
        snprintf(path, sizeof path, "%s.%s", ip, *wrong);
        return pj_fail_at(L, PG_ERR_SCHEMA, f, path, "'%s' is only for %s resources", *wrong,
                       d->kind == PG_RES_IMAGE ? "buffer" : "image");
    }

    r = d->kind == PG_RES_IMAGE ? parse_image_fields(L, f, o, ip, d)
                                : parse_buffer_fields(L, f, o, ip, d);
    if (r) return r;
    r = pj_opt_description(L, f, o, ip);
    if (r) return r;

    bool active;
    char why[sizeof L->p->omitted[0].why];
    r = pj_eval_when(L, f, o, ip, &active, why, sizeof why);
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
