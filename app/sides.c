/* sides.c - the --set / --pipeline-set / --reference-set rule of compare and bench (sides.h). */
#include "sides.h"

#include <stdio.h>
#include <string.h>

bool pg_ov_list_put(pg_ov_list *l, const char *key, const char *value, const char *from)
{
    for (uint32_t k = 0; k < l->n; k++)
        if (!strcmp(l->ov[k].key, key)) {
            l->ov[k].value = value;
            l->from[k] = from;
            return true;
        }
    if (l->n >= PG_SIDES_MAX_OV) return false;
    l->ov[l->n] = (pg_param_override){key, value};
    l->from[l->n] = from;
    l->n++;
    return true;
}

const char *pg_ov_list_get(const pg_ov_list *l, const char *key)
{
    for (uint32_t k = 0; k < l->n; k++)
        if (!strcmp(l->ov[k].key, key)) return l->ov[k].value;
    return NULL;
}

void pg_ov_list_format(const pg_ov_list *l, char *buf, size_t size)
{
    if (!size) return;
    buf[0] = 0;
    size_t len = 0;
    for (uint32_t k = 0; k < l->n && len < size; k++) {
        int w = snprintf(buf + len, size - len, "%s%s=%s", k ? ";" : "", l->ov[k].key, l->ov[k].value);
        if (w < 0) break;
        len += (size_t)w;
    }
}

pg_result pg_sides_parse(pg_side_sets *s, int argc, char **argv, int *i, bool *used, pg_error *err)
{
    const char *a = argv[*i];
    pg_ov_list *l = !strcmp(a, "--pipeline-set") ? &s->pipeline : !strcmp(a, "--reference-set") ? &s->reference : NULL;
    *used = l != NULL;
    if (!l) return PG_OK;
    if (*i + 1 >= argc) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: missing value", a);
    char *v = argv[++*i];
    char *eq = strchr(v, '=');
    if (!eq || eq == v) return pg_fail(err, PG_ERR_INVALID_ARG, "%s %s: expected KEY=VALUE", a, v);
    uint32_t mine = 0; /* the debug view shares the pipeline list: count this option's own entries */
    for (uint32_t k = 0; k < l->n; k++) mine += !strcmp(l->from[k], a);
    if (mine >= PG_CLI_MAX_SETS) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: at most %d", a, PG_CLI_MAX_SETS);
    *eq = 0;
    if (!pg_ov_list_put(l, v, eq + 1, !strcmp(a, "--pipeline-set") ? "--pipeline-set" : "--reference-set"))
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s: too many overrides", a);
    return PG_OK;
}

bool pg_sides_from_common(pg_side_sets *s, const pg_cli_common *c)
{
    for (uint32_t k = 0; k < c->n_sets; k++) {
        const pg_param_override *o = &c->sets[k];
        /* the one 'view' entry --view / --debug-view made (cli.c set_debug_view: same pointer) */
        bool debug_view = c->debug_view && o->value == c->debug_view && !strcmp(o->key, "view");
        /* --view NAME of no OCIO view is the debug view too: messages name the option given */
        const bool by_view = c->debug_view_option && !strcmp(c->debug_view_option, "--view");
        bool ok = debug_view ? pg_ov_list_put(&s->pipeline, o->key, o->value, by_view ? "--view" : "--debug-view")
                             : pg_ov_list_put(&s->set, o->key, o->value, "--set");
        if (!ok) return false;
    }
    return true;
}

static bool declares(const pg_pipeline *p, const char *key)
{
    return p && pg_pipeline_find_param(p, key);
}

void pg_sides_pipeline(const pg_side_sets *s, const pg_pipeline *decl, const pg_param_override *swept,
                       uint32_t n_swept, pg_ov_list *out)
{
    memset(out, 0, sizeof *out);
    for (uint32_t k = 0; k < s->set.n; k++)
        if (!decl || declares(decl, s->set.ov[k].key))
            pg_ov_list_put(out, s->set.ov[k].key, s->set.ov[k].value, s->set.from[k]);
    for (uint32_t k = 0; k < n_swept; k++)
        if (!decl || declares(decl, swept[k].key)) pg_ov_list_put(out, swept[k].key, swept[k].value, "--sweep");
    for (uint32_t k = 0; k < s->pipeline.n; k++)
        if (!decl || declares(decl, s->pipeline.ov[k].key))
            pg_ov_list_put(out, s->pipeline.ov[k].key, s->pipeline.ov[k].value, s->pipeline.from[k]);
}

void pg_sides_reference(const pg_side_sets *s, const pg_pipeline *ref, const pg_param_override *swept,
                        uint32_t n_swept, pg_ov_list *out)
{
    memset(out, 0, sizeof *out);
    for (uint32_t k = 0; k < s->set.n; k++)
        if (declares(ref, s->set.ov[k].key)) pg_ov_list_put(out, s->set.ov[k].key, s->set.ov[k].value, s->set.from[k]);
    for (uint32_t k = 0; k < n_swept; k++)
        if (declares(ref, swept[k].key)) pg_ov_list_put(out, swept[k].key, swept[k].value, "--sweep");
    for (uint32_t k = 0; k < s->reference.n; k++)
        pg_ov_list_put(out, s->reference.ov[k].key, s->reference.ov[k].value, s->reference.from[k]);
}

static void param_names(const pg_pipeline *p, char *buf, size_t size)
{
    size_t len = 0;
    buf[0] = 0;
    for (uint32_t k = 0; k < p->n_params && len < size; k++) {
        int w = snprintf(buf + len, size - len, "%s%s", k ? ", " : "", p->params[k].name);
        if (w < 0) break;
        len += (size_t)w;
    }
    if (!p->n_params) snprintf(buf, size, "none");
}

pg_result pg_sides_check_keys(const pg_ov_list *l, const pg_pipeline *p, const char *side, pg_error *err)
{
    for (uint32_t k = 0; k < l->n; k++) {
        if (pg_pipeline_find_param(p, l->ov[k].key)) continue;
        char names[600];
        param_names(p, names, sizeof names);
        const char *o = l->from[k];
        if (!strcmp(o, "--debug-view") || !strcmp(o, "--view"))
            return pg_fail(err, PG_ERR_INVALID_ARG, "%s %s: the %s %s (%s) declares no parameter 'view' (declared: %s)%s",
                           o, l->ov[k].value, side, p->name, p->path, names,
                           !strcmp(o, "--view") ? "; nor is it a view of the OCIO config" : "");
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s %s=%s: the %s %s (%s) declares no parameter '%s' (declared: %s)", o,
                       l->ov[k].key, l->ov[k].value, side, p->name, p->path, l->ov[k].key, names);
    }
    return PG_OK;
}

pg_result pg_sides_check_values(const char *path, const pg_ov_list *l, const char *side, pg_error *err)
{
    pg_pipeline *p = NULL;
    pg_result r = pg_pipeline_load(path, l->ov, l->n, &p, err);
    pg_pipeline_free(p);
    if (r != PG_ERR_PARAM) return r;
    for (uint32_t k = 0; k < l->n; k++) { /* which value: each one alone */
        pg_error one = {0};
        p = NULL;
        pg_result r1 = pg_pipeline_load(path, &l->ov[k], 1, &p, &one);
        pg_pipeline_free(p);
        if (r1 != PG_ERR_PARAM) continue;
        /* the loader says "FILE: --set KEY=VALUE: cause" whatever option gave the value */
        char label[160];
        snprintf(label, sizeof label, "--set %.64s=%.64s: ", l->ov[k].key, l->ov[k].value);
        const char *cause = strstr(one.msg, label);
        cause = cause ? cause + strlen(label) : one.msg;
        if (!strcmp(l->from[k], "--debug-view") || !strcmp(l->from[k], "--view"))
            return pg_fail(err, PG_ERR_INVALID_ARG, "%s %s: %s %s: %s%s", l->from[k], l->ov[k].value, side, path, cause,
                           !strcmp(l->from[k], "--view") ? " (debug views); nor is it a view of the OCIO config" : "");
        /* --set / --sweep values reach the reference because it declares the key: say how to keep them off */
        bool shared = !strcmp(side, "reference") && (!strcmp(l->from[k], "--set") || !strcmp(l->from[k], "--sweep"));
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s %s=%s: %s %s: %s%s%s%s", l->from[k], l->ov[k].key, l->ov[k].value,
                       side, path, cause,
                       shared ? " (the reference takes the values of keys it declares; --reference-set " : "",
                       shared ? l->ov[k].key : "", shared ? "=VALUE gives it its own)" : "");
    }
    return r;
}

pg_result pg_sides_check_common(const pg_cli_common *opt, pg_error *err)
{
    char path[PG_PATH_MAX];
    if (opt->pipeline) pg_strlcpy(path, opt->pipeline, sizeof path);
    else pg_data_path(path, sizeof path, "pipelines/naive.json"); /* pg_app_open's default */
    pg_pipeline *p = NULL;
    pg_error e = {0};
    if (pg_pipeline_load(path, NULL, 0, &p, &e)) return PG_OK; /* reported where it is opened */
    pg_side_sets s;
    pg_ov_list l;
    memset(&s, 0, sizeof s);
    pg_result r = PG_OK;
    if (!pg_sides_from_common(&s, opt)) {
        r = pg_fail(err, PG_ERR_INVALID_ARG, "too many --set values");
    } else {
        pg_sides_pipeline(&s, NULL, NULL, 0, &l);
        r = pg_sides_check_keys(&l, p, "pipeline", err);
        if (!r) r = pg_sides_check_values(path, &l, "pipeline", err);
    }
    pg_pipeline_free(p);
    return r;
}
