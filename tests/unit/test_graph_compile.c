/* test_graph_compile.c - the graph compiler on hand-made pipelines, no GPU.
 *
 * Fake pass types are registered in a local registry; pipelines are built directly in C (no JSON
 * loader). Covers order, errors, culling, lifetimes, sizes, aliasing (with a randomized property
 * test), exact barriers and the text report. test_skip_shipped also loads the shipped pipelines
 * with the built-in pass types: their transparent pass is skipped without BLEND materials. */
#include "graph.h"
#include "pipeline.h"
#include "fake_passes.h"
#include "test_util.h"

#include <cjson/cJSON.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <vulkan/vulkan_core.h>

/* ------------------------------------------------------------------------------------------ */
/* fake pass types                                                                            */

static const pg_resource_desc *find_res(const pg_pipeline *pl, const char *name)
{
    for (uint32_t i = 0; i < pl->n_resources; i++)
        if (strcmp(pl->resources[i].name, name) == 0) return &pl->resources[i];
    return NULL;
}

#define IMG PG_RES_IMAGE
#define BUF PG_RES_BUFFER
#define FRAG PG_STAGE_FRAGMENT
#define COMP PG_STAGE_COMPUTE

static pg_result d_depth_color(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_write(d, "color", IMG, PG_ACCESS_COLOR_WRITE, 0, PG_FMTCLASS_FLOAT);
    pg_decl_write(d, "depth", IMG, PG_ACCESS_DEPTH_WRITE, 0, PG_FMTCLASS_DEPTH);
    pg_decl_define(d, "HAS_DEPTH");
    return PG_OK;
}
static pg_result d_blend(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_read(d, "src", IMG, PG_ACCESS_SAMPLED, FRAG, PG_FMTCLASS_FLOAT);
    pg_decl_write(d, "dst", IMG, PG_ACCESS_COLOR_RMW, 0, PG_FMTCLASS_FLOAT);
    return PG_OK;
}
static pg_result d_blur_cs(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_read(d, "src", IMG, PG_ACCESS_SAMPLED, COMP, PG_FMTCLASS_FLOAT);
    pg_decl_write(d, "dst", IMG, PG_ACCESS_STORAGE_WRITE, COMP, PG_FMTCLASS_ANY_COLOR);
    return PG_OK;
}
static pg_result d_buf_to_color(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_read(d, "buf", BUF, PG_ACCESS_STORAGE_READ, FRAG, 0);
    pg_decl_write(d, "color", IMG, PG_ACCESS_COLOR_WRITE, 0, PG_FMTCLASS_FLOAT);
    return PG_OK;
}
/* reads a buffer only when there are lights: the cluster-list pattern of the clustered passes */
static pg_result d_buf_maybe(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)e;
    pg_slot buf = pg_decl_read(d, "buf", BUF, PG_ACCESS_STORAGE_READ, FRAG, 0);
    pg_decl_write(d, "color", IMG, PG_ACCESS_COLOR_WRITE, 0, PG_FMTCLASS_FLOAT);
    if (pg_var(in, "lights") == 0) pg_decl_mark_unused(d, buf, "0 lights");
    return PG_OK;
}
static pg_result d_buf_blur(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_read(d, "buf", BUF, PG_ACCESS_STORAGE_READ, FRAG, 0);
    pg_decl_read(d, "src", IMG, PG_ACCESS_SAMPLED, FRAG, PG_FMTCLASS_FLOAT);
    pg_decl_write(d, "color", IMG, PG_ACCESS_COLOR_WRITE, 0, PG_FMTCLASS_FLOAT);
    return PG_OK;
}
static pg_result d_rmw(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_write(d, "depth", IMG, PG_ACCESS_DEPTH_RMW, 0, PG_FMTCLASS_DEPTH);
    return PG_OK;
}
static pg_result d_color_rmw(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_write(d, "color", IMG, PG_ACCESS_COLOR_RMW, 0, PG_FMTCLASS_FLOAT);
    return PG_OK;
}
static pg_result d_depth_read(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_read(d, "depth", IMG, PG_ACCESS_DEPTH_READ, 0, PG_FMTCLASS_DEPTH);
    pg_decl_write(d, "color", IMG, PG_ACCESS_COLOR_WRITE, 0, PG_FMTCLASS_FLOAT);
    return PG_OK;
}
static pg_result d_depth_sample(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_read(d, "depth", IMG, PG_ACCESS_DEPTH_READ, 0, PG_FMTCLASS_DEPTH);
    pg_decl_read(d, "depth_tex", IMG, PG_ACCESS_SAMPLED, FRAG, PG_FMTCLASS_DEPTH);
    pg_decl_write(d, "color", IMG, PG_ACCESS_COLOR_WRITE, 0, PG_FMTCLASS_FLOAT);
    return PG_OK;
}
static pg_result d_storage_rw(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_write(d, "img", IMG, PG_ACCESS_STORAGE_RW, COMP, PG_FMTCLASS_ANY_COLOR);
    return PG_OK;
}
/* read-modify-write slots the pass initializes itself (a clear, a first store without load) */
static pg_result d_blend_init(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_read(d, "src", IMG, PG_ACCESS_SAMPLED, FRAG, PG_FMTCLASS_FLOAT);
    pg_slot w = pg_decl_write(d, "dst", IMG, PG_ACCESS_COLOR_RMW, 0, PG_FMTCLASS_FLOAT);
    pg_decl_mark_initializes(d, w);
    return PG_OK;
}
static pg_result d_storage_rw_init(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_slot w = pg_decl_write(d, "img", IMG, PG_ACCESS_STORAGE_RW, COMP, PG_FMTCLASS_ANY_COLOR);
    pg_decl_mark_initializes(d, w);
    return PG_OK;
}
/* a buffer filled only up to a count (the cluster-list pattern) */
static pg_result d_partial_buf(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_slot w = pg_decl_write(d, "buf", BUF, PG_ACCESS_STORAGE_WRITE, COMP, 0);
    pg_decl_mark_partial(d, w);
    return PG_OK;
}
/* pass type bugs: initializes on a full write, partial on a read-modify-write */
static pg_result d_bad_init(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_slot w = pg_decl_write(d, "color", IMG, PG_ACCESS_COLOR_WRITE, 0, PG_FMTCLASS_FLOAT);
    pg_decl_mark_initializes(d, w);
    return PG_OK;
}
static pg_result d_bad_partial(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_slot w = pg_decl_write(d, "img", IMG, PG_ACCESS_STORAGE_RW, COMP, PG_FMTCLASS_ANY_COLOR);
    pg_decl_mark_partial(d, w);
    return PG_OK;
}
static pg_result d_storage_read(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_read(d, "img", IMG, PG_ACCESS_STORAGE_READ, COMP, PG_FMTCLASS_ANY_COLOR);
    pg_decl_read(d, "src", IMG, PG_ACCESS_SAMPLED, COMP, PG_FMTCLASS_FLOAT);
    pg_decl_write(d, "dst", IMG, PG_ACCESS_STORAGE_WRITE, COMP, PG_FMTCLASS_ANY_COLOR);
    return PG_OK;
}
static pg_result d_side(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_read(d, "buf", BUF, PG_ACCESS_STORAGE_READ, COMP, 0);
    d->side_effects = true;
    return PG_OK;
}
/* the transparent-pass pattern: blends onto colour over the depth of an earlier pass, reads a
 * buffer of its own; not needed (pg_decl_skip) when the scene has no BLEND material. Declares
 * side effects so the test shows that a skip wins over them. */
static pg_result d_transparent(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)e;
    pg_decl_read(d, "buf", BUF, PG_ACCESS_STORAGE_READ, FRAG, 0);
    pg_decl_read(d, "depth", IMG, PG_ACCESS_DEPTH_READ, 0, PG_FMTCLASS_DEPTH);
    pg_decl_write(d, "color", IMG, PG_ACCESS_COLOR_RMW, 0, PG_FMTCLASS_FLOAT);
    d->side_effects = true;
    if (!pg_var(in, "has_blend")) pg_decl_skip(d, "no BLEND materials: no transparent pass");
    return PG_OK;
}
/* options.inputs (default 1) sampled inputs, one colour output; explains what it did */
static pg_result d_opts(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    int n = 1;
    const cJSON *v =
        in->desc->options ? cJSON_GetObjectItemCaseSensitive(in->desc->options, "inputs") : NULL;
    if (v) {
        if (!cJSON_IsNumber(v) || v->valuedouble < 0 || v->valuedouble > 4)
            return pg_fail(e, PG_ERR_SCHEMA, "%s: %s.options.inputs: must be 0..4", in->desc->file,
                           in->desc->json_path);
        n = (int)v->valuedouble;
    }
    for (int i = 0; i < n; i++) {
        char name[16];
        snprintf(name, sizeof name, "input%d", i);
        pg_decl_read(d, name, IMG, PG_ACCESS_SAMPLED, FRAG, PG_FMTCLASS_FLOAT);
    }
    pg_decl_write(d, "color", IMG, PG_ACCESS_COLOR_WRITE, 0, PG_FMTCLASS_FLOAT);
    if (!pg_var(in, "has_alpha_mask")) pg_decl_explain(d, "no alpha-mask materials: no discard");
    pg_decl_explain(d, "%d inputs", n);
    return PG_OK;
}
static pg_result d_many_defines(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_write(d, "color", IMG, PG_ACCESS_COLOR_WRITE, 0, PG_FMTCLASS_FLOAT);
    for (int i = 0; i < PG_MAX_DEFINES + 1; i++) pg_decl_define(d, "X");
    return PG_OK;
}
static pg_result d_many_reads(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    for (int i = 0; i < PG_MAX_SLOTS + 1; i++)
        pg_decl_read(d, "r", IMG, PG_ACCESS_SAMPLED, FRAG, PG_FMTCLASS_FLOAT);
    pg_decl_write(d, "color", IMG, PG_ACCESS_COLOR_WRITE, 0, PG_FMTCLASS_FLOAT);
    return PG_OK;
}
static pg_result d_fail(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)d;
    return pg_fail(e, PG_ERR_SCHEMA, "%s: %s.options.mode: 'x' is not one of a, b", in->desc->file,
                   in->desc->json_path);
}
/* A pass type bug: a write slot with a read-only access. */
static pg_result d_bad_write(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_write(d, "color", IMG, PG_ACCESS_SAMPLED, FRAG, PG_FMTCLASS_FLOAT);
    return PG_OK;
}
/* Generic passes for the random test: slots follow the bound resources' kinds and formats; the
 * type name picks how writes are done. */
static pg_result d_rnd(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)e;
    const char *t = in->desc->type;
    const bool storage = strcmp(t, "rnd_storage") == 0, init = strcmp(t, "rnd_init") == 0;
    const bool rmw = init || strcmp(t, "rnd_rmw") == 0;
    for (uint32_t i = 0; i < in->desc->n_reads; i++) {
        const pg_resource_desc *r = find_res(in->pipeline, in->desc->reads[i]);
        if (r && r->kind == BUF)
            pg_decl_read(d, "in", BUF, PG_ACCESS_STORAGE_READ, storage ? COMP : FRAG, 0);
        else
            pg_decl_read(d, "in", IMG, PG_ACCESS_SAMPLED, storage ? COMP : FRAG, PG_FMTCLASS_ANY);
    }
    for (uint32_t i = 0; i < in->desc->n_writes; i++) {
        const pg_resource_desc *r = find_res(in->pipeline, in->desc->writes[i]);
        pg_slot w;
        if (r && r->kind == BUF) {
            w = pg_decl_write(d, "out", BUF, rmw ? PG_ACCESS_STORAGE_RW : PG_ACCESS_STORAGE_WRITE, COMP,
                          0);
        } else if (r && r->format == PG_FMT_D32F) {
            w = pg_decl_write(d, "out", IMG, rmw ? PG_ACCESS_DEPTH_RMW : PG_ACCESS_DEPTH_WRITE, 0,
                          PG_FMTCLASS_DEPTH);
        } else if (storage) {
            w = pg_decl_write(d, "out", IMG, PG_ACCESS_STORAGE_WRITE, COMP, PG_FMTCLASS_ANY_COLOR);
        } else {
            w = pg_decl_write(d, "out", IMG, rmw ? PG_ACCESS_COLOR_RMW : PG_ACCESS_COLOR_WRITE, 0,
                          PG_FMTCLASS_ANY_COLOR);
        }
        if (init) pg_decl_mark_initializes(d, w);
    }
    return PG_OK;
}

#define TYPE(n, fn, rs, ws) {.name = n, .summary = "test type", .declare = fn} /* rs, ws: the slots, for the reader */
static const pg_pass_type g_types[] = {
    TYPE("fake_color", pg_fake_color, "", "color"),
    TYPE("fake_depth_color", d_depth_color, "", "color, depth"),
    TYPE("fake_blur", pg_fake_blur, "src", "dst"),
    TYPE("fake_blend", d_blend, "src", "dst"),
    TYPE("fake_blur_cs", d_blur_cs, "src", "dst"),
    TYPE("fake_compose2", pg_fake_compose2, "a, b", "color"),
    TYPE("fake_compute_buf", pg_fake_fill_buffer, "", "buf"),
    TYPE("fake_buf_to_color", d_buf_to_color, "buf", "color"),
    TYPE("fake_buf_blur", d_buf_blur, "buf, src", "color"),
    TYPE("fake_buf_maybe", d_buf_maybe, "buf", "color"),
    TYPE("fake_rmw", d_rmw, "", "depth"),
    TYPE("fake_color_rmw", d_color_rmw, "", "color"),
    TYPE("fake_depth_read", d_depth_read, "depth", "color"),
    TYPE("fake_depth_sample", d_depth_sample, "depth, depth_tex", "color"),
    TYPE("fake_storage_rw", d_storage_rw, "", "img"),
    TYPE("fake_storage_write", pg_fake_storage_write, "", "img"),
    TYPE("fake_storage_read", d_storage_read, "img, src", "dst"),
    TYPE("fake_side", d_side, "buf", ""),
    TYPE("fake_transparent", d_transparent, "buf, depth", "color"),
    TYPE("fake_opts", d_opts, "input0..input3 (options.inputs)", "color"),
    TYPE("fake_many_defines", d_many_defines, "", "color"),
    TYPE("fake_many_reads", d_many_reads, "r x13", "color"),
    TYPE("fake_fail", d_fail, "", ""),
    TYPE("fake_bad_write", d_bad_write, "", "color"),
    TYPE("rnd_color", d_rnd, "any", "any"),
    TYPE("rnd_storage", d_rnd, "any", "any"),
    TYPE("rnd_rmw", d_rnd, "any", "any"),
    TYPE("rnd_init", d_rnd, "any", "any"),
    TYPE("fake_blend_init", d_blend_init, "src", "dst"),
    TYPE("fake_storage_rw_init", d_storage_rw_init, "", "img"),
    TYPE("fake_partial_buf", d_partial_buf, "", "buf"),
    TYPE("fake_bad_init", d_bad_init, "", "color"),
    TYPE("fake_bad_partial", d_bad_partial, "", "img"),
};
static pg_pass_registry g_reg;

/* ------------------------------------------------------------------------------------------ */
/* pipeline builders                                                                          */

static pg_pipeline *pl_new(const char *output)
{
    pg_pipeline *pl = calloc(1, sizeof *pl);
    pg_strlcpy(pl->name, "test", sizeof pl->name);
    pg_strlcpy(pl->path, "test.json", sizeof pl->path);
    pg_strlcpy(pl->output, output, sizeof pl->output);
    return pl;
}

static void pl_free(pg_pipeline *pl)
{
    for (uint32_t i = 0; i < pl->n_passes; i++) cJSON_Delete(pl->passes[i].options);
    free(pl);
}

static pg_resource_desc *res_add(pg_pipeline *pl, const char *name, pg_res_kind kind,
                                 pg_lifetime_kind life)
{
    pg_resource_desc *r = &pl->resources[pl->n_resources];
    memset(r, 0, sizeof *r);
    pg_strlcpy(r->name, name, sizeof r->name);
    r->kind = kind;
    r->lifetime = life;
    r->scale[0] = r->scale[1] = 1.0f;
    pg_strlcpy(r->file, "test.json", sizeof r->file);
    snprintf(r->json_path, sizeof r->json_path, "resources[%u]", pl->n_resources);
    pl->n_resources++;
    return r;
}

static pg_resource_desc *img(pg_pipeline *pl, const char *name, pg_format f)
{
    pg_resource_desc *r = res_add(pl, name, IMG, PG_LIFETIME_TRANSIENT);
    r->format = f;
    return r;
}

static pg_resource_desc *img_l(pg_pipeline *pl, const char *name, pg_format f,
                               pg_lifetime_kind life)
{
    pg_resource_desc *r = img(pl, name, f);
    r->lifetime = life;
    return r;
}

/* buffer of stride bytes x the given terms (kind, value pairs; n_terms of them) */
static pg_resource_desc *buf(pg_pipeline *pl, const char *name, uint32_t stride, int n_terms, ...)
{
    pg_resource_desc *r = res_add(pl, name, BUF, PG_LIFETIME_TRANSIENT);
    r->stride = stride;
    va_list ap;
    va_start(ap, n_terms);
    for (int i = 0; i < n_terms; i++) {
        r->count[i].kind = (pg_count_term_kind)va_arg(ap, int);
        r->count[i].value = va_arg(ap, double);
        if (r->count[i].kind == PG_COUNT_VAR) strcpy(r->count[i].var, "lights"); /* the one variable here */
    }
    va_end(ap);
    r->n_count_terms = (uint32_t)n_terms;
    return r;
}

static void split_into(const char *list, char out[][PG_NAME_MAX], uint32_t *n)
{
    *n = 0;
    if (!list || !list[0]) return;
    const char *p = list;
    while (*p) {
        const char *comma = strchr(p, ',');
        size_t len = comma ? (size_t)(comma - p) : strlen(p);
        while (len && *p == ' ') p++, len--;
        memcpy(out[*n], p, len);
        out[*n][len] = 0;
        (*n)++;
        p += len;
        if (*p == ',') p++;
    }
}

static pg_pass_desc *pass(pg_pipeline *pl, const char *name, const char *type, const char *reads,
                          const char *writes)
{
    pg_pass_desc *p = &pl->passes[pl->n_passes];
    memset(p, 0, sizeof *p);
    pg_strlcpy(p->name, name, sizeof p->name);
    pg_strlcpy(p->type, type, sizeof p->type);
    split_into(reads, p->reads, &p->n_reads);
    split_into(writes, p->writes, &p->n_writes);
    pg_strlcpy(p->file, "test.json", sizeof p->file);
    snprintf(p->json_path, sizeof p->json_path, "passes[%u]", pl->n_passes);
    pl->n_passes++;
    return p;
}

static void after(pg_pass_desc *p, const char *name)
{
    pg_strlcpy(p->after[p->n_after++], name, PG_NAME_MAX);
}

static pg_compile_desc desc_of(const pg_pipeline *pl)
{
    pg_compile_desc d;
    memset(&d, 0, sizeof d);
    d.pipeline = pl;
    d.registry = &g_reg;
    pg_vars_set(&d.vars, "lights", 100, NULL);
    d.output_width = 100;
    d.output_height = 50;
    return d;
}

static pg_graph_plan *compile_d(const pg_compile_desc *d, int line)
{
    pg_graph_plan *plan = NULL;
    pg_error err = {0};
    pg_result r = pg_graph_compile(d, &plan, &err);
    CHECK_MSG(r == PG_OK && plan, "line %d: %s: %s", line, pg_result_name(r), err.msg);
    return r == PG_OK ? plan : NULL;
}
static pg_graph_plan *compile_pl(const pg_pipeline *pl, int line)
{
    pg_compile_desc d = desc_of(pl);
    return compile_d(&d, line);
}
#define COMPILE(pl) compile_pl(pl, __LINE__)

/* Expects failure with code; returns the message (static buffer). */
static const char *compile_fail(const pg_pipeline *pl, pg_result want, int line)
{
    static pg_error err;
    memset(&err, 0, sizeof err);
    pg_graph_plan *plan = (pg_graph_plan *)(uintptr_t)1;
    pg_compile_desc d = desc_of(pl);
    pg_result r = pg_graph_compile(&d, &plan, &err);
    CHECK_MSG(r == want, "line %d: got %s, want %s: %s", line, pg_result_name(r),
              pg_result_name(want), err.msg);
    CHECK_MSG(plan == NULL, "line %d: plan not NULL on error", line);
    if (r == PG_OK) pg_graph_plan_free(plan);
    CHECK_MSG(err.code == want, "line %d: err.code %s", line, pg_result_name(err.code));
    return err.msg;
}
#define FAIL(pl, code) compile_fail(pl, code, __LINE__)
#define HAS(msg, frag) CHECK_MSG(strstr((msg), (frag)) != NULL, "'%s' not in '%s'", frag, msg)

/* ------------------------------------------------------------------------------------------ */
/* plan queries                                                                               */

static int pidx(const pg_graph_plan *p, const char *name)
{
    for (uint32_t i = 0; i < p->n_passes; i++)
        if (strcmp(p->passes[i].name, name) == 0) return (int)i;
    return -1;
}
static int ridx(const pg_graph_plan *p, const char *name)
{
    for (uint32_t i = 0; i < p->n_resources; i++)
        if (strcmp(p->resources[i].name, name) == 0) return (int)i;
    return -1;
}
/* position of a pass in the execution order, -1 if culled */
static int pos(const pg_graph_plan *p, const char *name)
{
    int i = pidx(p, name);
    for (uint32_t k = 0; k < p->n_order; k++)
        if (p->order[k] == i) return (int)k;
    return -1;
}
static const pg_plan_resource *res(const pg_graph_plan *p, const char *name)
{
    int i = ridx(p, name);
    return i >= 0 ? &p->resources[i] : NULL;
}
static int n_barriers_for(const pg_graph_plan *p, const char *pass_name, const char *res_name)
{
    const pg_plan_pass *pp = &p->passes[pidx(p, pass_name)];
    int n = 0, r = ridx(p, res_name);
    for (uint32_t b = 0; b < pp->n_barriers; b++) n += pp->barriers[b].resource == r;
    return n;
}
static const pg_barrier *barrier_for(const pg_graph_plan *p, const char *pass_name,
                                     const char *res_name)
{
    const pg_plan_pass *pp = &p->passes[pidx(p, pass_name)];
    int r = ridx(p, res_name);
    for (uint32_t b = 0; b < pp->n_barriers; b++)
        if (pp->barriers[b].resource == r) return &pp->barriers[b];
    return NULL;
}
static bool explain_has(const pg_graph_plan *p, const char *frag)
{
    for (uint32_t i = 0; i < p->n_explain; i++)
        if (strstr(p->explain[i], frag)) return true;
    return false;
}
static uint32_t total_barriers(const pg_graph_plan *p)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < p->n_passes; i++) n += p->passes[i].n_barriers;
    return n;
}

/* Stage / access shorthands */
#define S_COLOR VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT
#define S_FRAG VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT
#define S_COMP VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT
#define S_TESTS (VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT)
#define S_COPY VK_PIPELINE_STAGE_2_COPY_BIT
#define A_CW VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT
#define A_CR VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT
#define A_SAMPLED VK_ACCESS_2_SHADER_SAMPLED_READ_BIT
#define A_SR VK_ACCESS_2_SHADER_STORAGE_READ_BIT
#define A_SW VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT
#define A_DR VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT
#define A_DW VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT
#define A_TR VK_ACCESS_2_TRANSFER_READ_BIT
#define L_UNDEF VK_IMAGE_LAYOUT_UNDEFINED
#define L_COLOR VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL
#define L_SRO VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL
#define L_DEPTH VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL
#define L_DRO VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL
#define L_GENERAL VK_IMAGE_LAYOUT_GENERAL
#define L_TSRC VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL

static void check_barrier(const pg_barrier *b, uint64_t ss, uint64_t sa, uint64_t ds, uint64_t da,
                          uint32_t ol, uint32_t nl, const char *why, int line)
{
    CHECK_MSG(b != NULL, "line %d: no barrier", line);
    if (!b) return;
    CHECK_MSG(b->src_stages == ss, "line %d: src_stages 0x%llx want 0x%llx", line,
              (unsigned long long)b->src_stages, (unsigned long long)ss);
    CHECK_MSG(b->src_access == sa, "line %d: src_access 0x%llx want 0x%llx", line,
              (unsigned long long)b->src_access, (unsigned long long)sa);
    CHECK_MSG(b->dst_stages == ds, "line %d: dst_stages 0x%llx want 0x%llx", line,
              (unsigned long long)b->dst_stages, (unsigned long long)ds);
    CHECK_MSG(b->dst_access == da, "line %d: dst_access 0x%llx want 0x%llx", line,
              (unsigned long long)b->dst_access, (unsigned long long)da);
    CHECK_MSG(b->old_layout == ol && b->new_layout == nl, "line %d: layouts %s -> %s", line,
              pg_layout_name(b->old_layout), pg_layout_name(b->new_layout));
    CHECK_MSG(strcmp(b->why, why) == 0, "line %d: why '%s' want '%s'", line, b->why, why);
}
#define CHECK_BARRIER(b, ss, sa, ds, da, ol, nl, why)                                          \
    check_barrier(b, ss, sa, ds, da, ol, nl, why, __LINE__)

/* ------------------------------------------------------------------------------------------ */
/* registry and decl helpers                                                                  */

static void test_registry(void)
{
    pg_pass_registry reg = {0};
    pg_error err = {0};
    CHECK(pg_registry_add(&reg, &g_types[0], &err) == PG_OK);
    CHECK(pg_registry_find(&reg, "fake_color") == &g_types[0]);
    CHECK(pg_registry_find(&reg, "nope") == NULL);
    CHECK(pg_registry_add(&reg, &g_types[0], &err) == PG_ERR_INVALID_ARG);
    HAS(err.msg, "registered twice");
    { /* a type name no pipeline can write is refused where it is registered (a plug-in's type
       * 'my-pass' loaded, and every pipeline naming it failed with "expected a name") */
        static char long_name[PG_NAME_MAX + 1];
        memset(long_name, 'a', PG_NAME_MAX);
        const char *bad[] = {"my-pass", "two words", "t\xc3\xa9", long_name};
        for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
            pg_pass_type t = g_types[0];
            t.name = bad[i];
            CHECK(pg_registry_add(&reg, &t, &err) == PG_ERR_INVALID_ARG);
            HAS(err.msg, "cannot be written in a pipeline: a type name matches [A-Za-z0-9_]+, at most 63 characters");
        }
        HAS(err.msg, "'aaaaaaaa");
        pg_pass_type huge = g_types[0];
        huge.name = "huge";
        huge.instance_size = (size_t)PG_MAX_PASS_INSTANCE + 1; /* was a bare "out of memory" at create */
        CHECK(pg_registry_add(&reg, &huge, &err) == PG_ERR_LIMIT);
        HAS(err.msg, "pass type 'huge': its instance_size is 67108865 bytes, more than 67108864");
        huge.instance_size = PG_MAX_PASS_INSTANCE;
        CHECK(pg_registry_add(&reg, &huge, &err) == PG_OK);
        reg.count--;
        CHECK(reg.count == 1);
    }
    static pg_pass_type many[70];
    static char names[70][16];
    for (int i = 0; i < 70; i++) {
        snprintf(names[i], sizeof names[i], "t%d", i);
        many[i] = g_types[0];
        many[i].name = names[i];
    }
    pg_result last = PG_OK;
    for (int i = 0; i < 70 && last == PG_OK; i++) last = pg_registry_add(&reg, &many[i], &err);
    CHECK(last == PG_ERR_LIMIT);
    CHECK(reg.count == 64);

    pg_pass_decl d;
    memset(&d, 0, sizeof d);
    pg_decl_read(&d, "a", IMG, PG_ACCESS_SAMPLED, FRAG, PG_FMTCLASS_FLOAT);
    pg_decl_write(&d, "b", BUF, PG_ACCESS_STORAGE_WRITE, COMP, 0);
    pg_decl_define(&d, "FOO=1");
    pg_decl_explain(&d, "line %d", 7);
    CHECK(d.n_reads == 1 && d.n_writes == 1 && strcmp(d.reads[0].name, "a") == 0);
    CHECK(d.reads[0].access == PG_ACCESS_SAMPLED && d.reads[0].stages == FRAG);
    CHECK(d.writes[0].kind == BUF && d.writes[0].access == PG_ACCESS_STORAGE_WRITE);
    CHECK(d.n_defines == 1 && strcmp(d.defines[0], "FOO=1") == 0);
    CHECK(d.n_explain == 1 && strcmp(d.explain[0], "line 7") == 0);
    for (int i = 0; i < PG_MAX_PASS_EXPLAIN + 4; i++) pg_decl_explain(&d, "more");
    CHECK(d.n_explain == PG_MAX_PASS_EXPLAIN);
    HAS(d.explain[PG_MAX_PASS_EXPLAIN - 1], "left out");

    pg_pass_desc pd;
    memset(&pd, 0, sizeof pd);
    pg_strlcpy(pd.file, "f.json", sizeof pd.file);
    pg_strlcpy(pd.json_path, "passes[3]", sizeof pd.json_path);
    pd.n_reads = 2;
    pd.n_writes = 1;
    pg_result r = pg_decl_check_counts(&pd, &d, &g_types[2], &err);
    CHECK(r == PG_ERR_SCHEMA);
    HAS(err.msg, "f.json: passes[3].reads: pass type 'fake_blur' expects 1 read (a)");
    HAS(err.msg, "got 2");
    pd.n_reads = 1;
    CHECK(pg_decl_check_counts(&pd, &d, &g_types[2], &err) == PG_OK);
    pd.n_writes = 0;
    CHECK(pg_decl_check_counts(&pd, &d, &g_types[2], &err) == PG_ERR_SCHEMA);
    HAS(err.msg, "passes[3].writes: pass type 'fake_blur' expects 1 write (b)");
}

/* ------------------------------------------------------------------------------------------ */
/* order                                                                                      */

static void test_order(void)
{
    { /* dependency order, whatever the declaration order */
        pg_pipeline *pl = pl_new("out");
        img(pl, "t1", PG_FMT_RGBA16F);
        img(pl, "t2", PG_FMT_RGBA16F);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "C", "fake_blur", "t2", "out");
        pass(pl, "B", "fake_blur", "t1", "t2");
        pass(pl, "A", "fake_color", "", "t1");
        pg_graph_plan *p = COMPILE(pl);
        if (p) {
            CHECK(p->n_order == 3);
            CHECK(p->order[0] == 2 && p->order[1] == 1 && p->order[2] == 0);
            CHECK(p->n_passes == 3 && strcmp(p->passes[0].name, "C") == 0);
            CHECK(p->passes[0].desc_index == 0 && p->passes[0].type == &g_types[2]);
        }
        pg_graph_plan_free(p);
        pl_free(pl);
    }
    { /* independent passes keep declaration order */
        for (int flip = 0; flip < 2; flip++) {
            pg_pipeline *pl = pl_new("out");
            img(pl, "x", PG_FMT_RGBA16F);
            img(pl, "y", PG_FMT_RGBA16F);
            img(pl, "out", PG_FMT_RGBA8_UNORM);
            pass(pl, flip ? "Y" : "X", "fake_color", "", flip ? "y" : "x");
            pass(pl, flip ? "X" : "Y", "fake_color", "", flip ? "x" : "y");
            pass(pl, "Z", "fake_compose2", "x, y", "out");
            pg_graph_plan *p = COMPILE(pl);
            if (p) {
                CHECK(p->n_order == 3 && p->order[0] == 0 && p->order[1] == 1 && p->order[2] == 2);
                CHECK(pos(p, "Z") == 2);
            }
            pg_graph_plan_free(p);
            pl_free(pl);
        }
    }
    { /* "after" overrides declaration order */
        pg_pipeline *pl = pl_new("out");
        img(pl, "a", PG_FMT_RGBA16F);
        img(pl, "b", PG_FMT_RGBA16F);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pg_pass_desc *b = pass(pl, "B", "fake_color", "", "b");
        pass(pl, "A", "fake_color", "", "a");
        pass(pl, "C", "fake_compose2", "a, b", "out");
        after(b, "A");
        pg_graph_plan *p = COMPILE(pl);
        if (p) CHECK(pos(p, "A") == 0 && pos(p, "B") == 1 && pos(p, "C") == 2);
        pg_graph_plan_free(p);
        pl_free(pl);
    }
    { /* write chain through a read-modify-write; the pure reader goes after the last writer */
        pg_pipeline *pl = pl_new("out");
        img(pl, "c0", PG_FMT_RGBA16F);
        img(pl, "d", PG_FMT_D32F);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "R", "fake_depth_read", "d", "out");
        pass(pl, "D0", "fake_depth_color", "", "c0, d");
        pass(pl, "D1", "fake_rmw", "", "d");
        pg_graph_plan *p = COMPILE(pl);
        if (p) {
            CHECK(pos(p, "D0") == 0 && pos(p, "D1") == 1 && pos(p, "R") == 2);
            CHECK(strcmp(p->passes[pidx(p, "D0")].decl.defines[0], "HAS_DEPTH") == 0);
        }
        pg_graph_plan_free(p);
        pl_free(pl);
    }
    { /* two pure writers ordered by "after" */
        pg_pipeline *pl = pl_new("out");
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "W0", "fake_color", "", "out");
        after(pass(pl, "W1", "fake_color", "", "out"), "W0");
        pg_graph_plan *p = COMPILE(pl);
        if (p) CHECK(p->n_order == 2 && pos(p, "W0") == 0 && pos(p, "W1") == 1);
        pg_graph_plan_free(p);
        pl_free(pl);
    }
}

/* ------------------------------------------------------------------------------------------ */
/* errors                                                                                     */

static void test_errors(void)
{
    const char *m;
    { /* unknown pass type */
        pg_pipeline *pl = pl_new("out");
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "A", "fake_color", "", "out");
        pass(pl, "B", "nope", "", "");
        m = FAIL(pl, PG_ERR_UNKNOWN_PASS);
        HAS(m, "test.json: passes[1].type: unknown pass type 'nope' (known: fake_color, "
               "fake_depth_color, fake_blur");
        pl_free(pl);
    }
    { /* slot counts */
        pg_pipeline *pl = pl_new("out");
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "A", "fake_blur", "", "out");
        m = FAIL(pl, PG_ERR_SCHEMA);
        HAS(m, "test.json: passes[0].reads: pass type 'fake_blur' expects 1 read (src)");
        HAS(m, "got 0");
        pl_free(pl);
    }
    { /* slot counts follow the options */
        pg_pipeline *pl = pl_new("out");
        img(pl, "a", PG_FMT_RGBA16F);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "A", "fake_color", "", "a");
        pg_pass_desc *o = pass(pl, "O", "fake_opts", "a, a, a", "out");
        o->options = cJSON_CreateObject();
        cJSON_AddNumberToObject(o->options, "inputs", 2);
        m = FAIL(pl, PG_ERR_SCHEMA);
        HAS(m, "passes[1].reads: pass type 'fake_opts' expects 2 reads (input0, input1) with these "
               "options, got 3");
        /* the declare() error comes through unchanged */
        cJSON_ReplaceItemInObject(o->options, "inputs", cJSON_CreateString("many"));
        m = FAIL(pl, PG_ERR_SCHEMA);
        CHECK(strcmp(m, "test.json: passes[1].options.inputs: must be 0..4") == 0);
        pl_free(pl);
    }
    { /* declare failing */
        pg_pipeline *pl = pl_new("out");
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "A", "fake_color", "", "out");
        pass(pl, "F", "fake_fail", "", "");
        m = FAIL(pl, PG_ERR_SCHEMA);
        CHECK(strcmp(m, "test.json: passes[1].options.mode: 'x' is not one of a, b") == 0);
        pl_free(pl);
    }
    { /* kind mismatch, both ways */
        pg_pipeline *pl = pl_new("out");
        buf(pl, "lights", 16, 1, PG_COUNT_VAR, 0.0);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "A", "fake_color", "", "lights");
        m = FAIL(pl, PG_ERR_FORMAT);
        CHECK(strcmp(m, "test.json: passes[0].writes[0]: slot 'color' needs an image, 'lights' is "
                        "a buffer") == 0);
        pl->n_passes = 0;
        pass(pl, "A", "fake_compute_buf", "", "out");
        m = FAIL(pl, PG_ERR_FORMAT);
        HAS(m, "passes[0].writes[0]: slot 'buf' needs a buffer, 'out' is an image");
        pl_free(pl);
    }
    { /* format classes */
        pg_pipeline *pl = pl_new("out");
        img(pl, "c", PG_FMT_RGBA16F);
        img(pl, "hdr", PG_FMT_RGBA16F);
        img(pl, "d", PG_FMT_D32F);
        img(pl, "u", PG_FMT_R32UI);
        img(pl, "s", PG_FMT_RGBA8_SRGB);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "X", "fake_color", "", "out");
        pass(pl, "G", "fake_depth_color", "", "c, hdr");
        m = FAIL(pl, PG_ERR_FORMAT);
        CHECK(strcmp(m, "test.json: passes[1].writes[1]: slot 'depth' (depth_write) needs a depth "
                        "format, resource 'hdr' is rgba16f") == 0);
        pl->n_passes = 1;
        pass(pl, "G", "fake_color", "", "d");
        m = FAIL(pl, PG_ERR_FORMAT);
        HAS(m, "passes[1].writes[0]: slot 'color' (color_write) needs a float color format");
        HAS(m, "resource 'd' is d32f");
        pl->n_passes = 1;
        pass(pl, "G", "fake_storage_rw", "", "d"); /* storage on depth: ANY_COLOR slot */
        m = FAIL(pl, PG_ERR_FORMAT);
        HAS(m, "slot 'img' (storage_rw) needs a color format, resource 'd' is d32f");
        pl->n_passes = 1;
        pass(pl, "G", "fake_blur", "u", "c"); /* uint on a float sampled slot */
        m = FAIL(pl, PG_ERR_FORMAT);
        HAS(m, "passes[1].reads[0]: slot 'src' (sampled) needs a float color format");
        HAS(m, "resource 'u' is r32ui");
        pl->n_passes = 1;
        pass(pl, "G", "fake_storage_write", "", "s"); /* sRGB is not storage-capable */
        m = FAIL(pl, PG_ERR_FORMAT);
        HAS(m, "passes[1].writes[0]: slot 'img' (storage_write) needs a format usable as a storage "
               "image, resource 's' is rgba8_srgb");
        pl->n_passes = 1;
        pass(pl, "G", "fake_storage_write", "", "u"); /* r32ui storage is fine */
        pass(pl, "H", "fake_blur", "c", "c");         /* one image, two layouts in one pass */
        m = FAIL(pl, PG_ERR_FORMAT);
        HAS(m, "passes[2]: resource 'c' is used as 'sampled' (shader_read_only layout) and "
               "'color_write' (color_attachment layout) in the same pass");
        pl->n_passes = 1;
        pass(pl, "G", "fake_bad_write", "", "c");
        m = FAIL(pl, PG_ERR_SCHEMA);
        HAS(m, "declares write slot 'color' with read-only access 'sampled'");
        pl_free(pl);
    }
    { /* unknown resource, unknown "after", limits */
        pg_pipeline *pl = pl_new("out");
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "A", "fake_color", "", "nothing");
        m = FAIL(pl, PG_ERR_UNKNOWN_RESOURCE);
        CHECK(strcmp(m, "test.json: passes[0].writes[0]: unknown resource 'nothing'") == 0);
        pl->n_passes = 0;
        after(pass(pl, "A", "fake_color", "", "out"), "ghost");
        m = FAIL(pl, PG_ERR_SCHEMA);
        CHECK(strcmp(m, "test.json: passes[0].after[0]: unknown pass 'ghost'") == 0);
        pl->n_passes = 0;
        pass(pl, "A", "fake_many_defines", "", "out");
        m = FAIL(pl, PG_ERR_LIMIT);
        HAS(m, "shader defines");
        pl->n_passes = 0;
        pass(pl, "A", "fake_many_reads", "", "out");
        m = FAIL(pl, PG_ERR_LIMIT);
        HAS(m, "more than 12 read slots");
        pl_free(pl);
    }
    { /* outputs */
        pg_pipeline *pl = pl_new("missing");
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "A", "fake_color", "", "out");
        m = FAIL(pl, PG_ERR_NO_OUTPUT);
        HAS(m, "output: unknown resource 'missing'");
        img(pl, "unwritten", PG_FMT_RGBA8_UNORM);
        pg_strlcpy(pl->output, "unwritten", sizeof pl->output);
        m = FAIL(pl, PG_ERR_NO_OUTPUT);
        HAS(m, "output: no pass writes 'unwritten'");
        pl_free(pl);
    }
    { /* write conflict: two pure writers */
        pg_pipeline *pl = pl_new("out");
        img(pl, "x", PG_FMT_RGBA16F);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "A", "fake_color", "", "x");
        pass(pl, "B", "fake_color", "", "x");
        pass(pl, "C", "fake_blur", "x", "out");
        m = FAIL(pl, PG_ERR_WRITE_CONFLICT);
        CHECK_MSG(strcmp(m, "test.json: passes[1].writes[0]: resource 'x' is also written by pass "
                            "'A' (passes[0]) with no ordering between them: make the later pass "
                            "read it (load) or add \"after\": [\"A\"]") == 0,
                  "%s", m);
        /* an RMW pass that does not read is still a conflict the other way round */
        pl->n_passes = 0;
        img(pl, "d", PG_FMT_D32F);
        pass(pl, "M", "fake_rmw", "", "d");
        pass(pl, "W", "fake_depth_color", "", "x, d");
        pass(pl, "C", "fake_depth_read", "d", "out");
        m = FAIL(pl, PG_ERR_WRITE_CONFLICT);
        HAS(m, "passes[1].writes[1]: resource 'd' is also written by pass 'M' (passes[0])");
        pl_free(pl);
    }
    { /* cycles: through resources, through "after", and a pass after itself */
        pg_pipeline *pl = pl_new("out");
        img(pl, "a", PG_FMT_RGBA16F);
        img(pl, "b", PG_FMT_RGBA16F);
        img(pl, "c", PG_FMT_RGBA16F);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "out_pass", "fake_blur", "a", "out");
        pass(pl, "pa", "fake_blur", "c", "a");
        pass(pl, "pb", "fake_blur", "a", "b");
        pass(pl, "pc", "fake_blur", "b", "c");
        m = FAIL(pl, PG_ERR_CYCLE);
        HAS(m, "test.json: cycle: pa -> pb -> pc -> pa");
        pl->n_passes = 0;
        pg_pass_desc *x = pass(pl, "X", "fake_color", "", "a");
        pg_pass_desc *y = pass(pl, "Y", "fake_color", "", "b");
        pass(pl, "Z", "fake_compose2", "a, b", "out");
        after(x, "Y");
        after(y, "X");
        m = FAIL(pl, PG_ERR_CYCLE);
        HAS(m, "cycle: X -> Y -> X");
        x->n_after = y->n_after = 0;
        after(y, "Y");
        m = FAIL(pl, PG_ERR_CYCLE);
        HAS(m, "cycle: Y -> Y");
        pl_free(pl);
    }
    { /* read before write of a transient; persistent is fine */
        pg_pipeline *pl = pl_new("out");
        img(pl, "t", PG_FMT_RGBA16F);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "B", "fake_blur", "t", "out");
        m = FAIL(pl, PG_ERR_READ_BEFORE_WRITE);
        CHECK_MSG(strcmp(m, "test.json: passes[0].reads[0]: pass 'B' reads transient resource 't' "
                            "before any pass writes it (make a pass write it first, or declare it "
                            "persistent)") == 0,
                  "%s", m);
        pl->resources[0].lifetime = PG_LIFETIME_PERSISTENT;
        pg_graph_plan *p = COMPILE(pl);
        pg_graph_plan_free(p);
        pl->resources[0].lifetime = PG_LIFETIME_IMPORTED;
        p = COMPILE(pl);
        pg_graph_plan_free(p);
        /* also when only a culled pass reads it */
        pl->resources[0].lifetime = PG_LIFETIME_TRANSIENT;
        pl->n_passes = 0;
        img(pl, "junk", PG_FMT_RGBA16F);
        pass(pl, "A", "fake_color", "", "out");
        pass(pl, "Culled", "fake_blur", "t", "junk");
        m = FAIL(pl, PG_ERR_READ_BEFORE_WRITE);
        HAS(m, "pass 'Culled' reads transient resource 't'");
        pl_free(pl);
    }
    { /* sizes beyond limits; bad arguments */
        pg_pipeline *pl = pl_new("out");
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        buf(pl, "huge", 1u << 20, 2, PG_COUNT_CONST, 1048576.0, PG_COUNT_PIXELS, 0.0);
        pass(pl, "A", "fake_color", "", "out");
        m = FAIL(pl, PG_ERR_LIMIT);
        HAS(m, "test.json: resources[1]: buffer 'huge'");
        pl_free(pl);
        pg_graph_plan *p = (pg_graph_plan *)(uintptr_t)1;
        pg_error err = {0};
        CHECK(pg_graph_compile(NULL, &p, &err) == PG_ERR_INVALID_ARG && p == NULL);
        pl = pl_new("out");
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "A", "fake_color", "", "out");
        pg_compile_desc d = desc_of(pl);
        d.output_width = 0;
        CHECK(pg_graph_compile(&d, &p, &err) == PG_ERR_INVALID_ARG);
        pl_free(pl);
    }
}

/* ------------------------------------------------------------------------------------------ */
/* culling                                                                                    */

static void test_culling(void)
{
    { /* an unread output is culled with its resources; chains too */
        pg_pipeline *pl = pl_new("out");
        img(pl, "a", PG_FMT_RGBA16F);
        img(pl, "b", PG_FMT_RGBA16F);
        img(pl, "c", PG_FMT_RGBA16F);
        img(pl, "d", PG_FMT_D32F);
        img(pl, "unused", PG_FMT_RGBA16F);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "A", "fake_color", "", "a");
        pass(pl, "B", "fake_blur", "a", "b");
        pass(pl, "G", "fake_depth_color", "", "c, d");
        pass(pl, "Final", "fake_color", "", "out");
        pl->n_omitted = 1;
        pg_strlcpy(pl->omitted[0].what, "pass 'ssao'", sizeof pl->omitted[0].what);
        pg_strlcpy(pl->omitted[0].why, "when: $ao (ao is false)", sizeof pl->omitted[0].why);
        pg_graph_plan *p = COMPILE(pl);
        if (p) {
            CHECK(p->n_order == 1 && pos(p, "Final") == 0);
            const pg_plan_pass *a = &p->passes[pidx(p, "A")], *b = &p->passes[pidx(p, "B")];
            const pg_plan_pass *g = &p->passes[pidx(p, "G")];
            CHECK(a->culled && b->culled && g->culled && !p->passes[pidx(p, "Final")].culled);
            CHECK_MSG(strcmp(b->cull_reason,
                             "nothing reads its writes (b) on the way to output 'out'") == 0,
                      "%s", b->cull_reason);
            HAS(a->cull_reason, "nothing reads its writes (a)");
            HAS(g->cull_reason, "nothing reads its writes (c, d) on the way to output 'out'");
            CHECK(a->n_barriers == 0 && g->n_barriers == 0);
            const char *names[] = {"a", "b", "c", "d"};
            for (int i = 0; i < 4; i++) {
                const pg_plan_resource *r = res(p, names[i]);
                CHECK(r->culled && strcmp(r->cull_reason, "not used by any pass that runs") == 0);
                CHECK(r->first_pass == -1 && r->last_pass == -1 && r->block == -1);
            }
            CHECK(res(p, "unused")->culled);
            CHECK(strcmp(res(p, "unused")->cull_reason, "not used by any pass") == 0);
            CHECK(!res(p, "out")->culled);
            CHECK(explain_has(p, "omitted pass 'ssao': when: $ao (ao is false)"));
            CHECK(explain_has(p, "culled pass 'B': nothing reads its writes (b)"));
            CHECK(explain_has(p, "culled resource 'd': not used by any pass that runs"));
            CHECK(strncmp(p->explain[0], "omitted", 7) == 0);
            /* only the output is allocated */
            CHECK(p->transient_bytes_unaliased == 100 * 50 * 4);
        }
        pg_graph_plan_free(p);
        pl_free(pl);
    }
    { /* side effects keep passes (declared by the type or the pipeline) and what feeds them */
        pg_pipeline *pl = pl_new("out");
        buf(pl, "stats", 4, 1, PG_COUNT_CONST, 64.0);
        img(pl, "dbg", PG_FMT_RGBA16F);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "Count", "fake_compute_buf", "", "stats");
        pass(pl, "Report", "fake_side", "stats", "");
        pass(pl, "Debug", "fake_color", "", "dbg")->side_effects = true;
        pass(pl, "Final", "fake_color", "", "out");
        pg_graph_plan *p = COMPILE(pl);
        if (p) {
            CHECK(p->n_order == 4);
            CHECK(pos(p, "Count") == 0 && pos(p, "Report") == 1 && pos(p, "Debug") == 2);
            CHECK(!res(p, "stats")->culled && !res(p, "dbg")->culled);
            CHECK(res(p, "stats")->size_bytes == 256);
        }
        pg_graph_plan_free(p);
        pl_free(pl);
    }
    { /* hdr_output is a root too; explain lines of running passes are collected */
        pg_pipeline *pl = pl_new("out");
        img(pl, "hdr", PG_FMT_RGBA16F);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "Scene", "fake_opts", "", "hdr")->options = NULL;
        pl->passes[0].options = cJSON_CreateObject();
        cJSON_AddNumberToObject(pl->passes[0].options, "inputs", 0);
        pass(pl, "Final", "fake_color", "", "out");
        pg_graph_plan *p = COMPILE(pl);
        if (p) {
            CHECK(p->n_order == 1 && p->passes[0].culled);
            HAS(p->passes[0].cull_reason, "(hdr) on the way to output 'out'");
        }
        pg_graph_plan_free(p);
        pg_strlcpy(pl->hdr_output, "hdr", sizeof pl->hdr_output);
        p = COMPILE(pl);
        if (p) {
            CHECK(p->n_order == 2 && !p->passes[0].culled);
            CHECK(p->hdr_output == 0 && p->output == 1);
            CHECK(res(p, "hdr")->is_output && res(p, "out")->is_output);
            CHECK(explain_has(p, "Scene: no alpha-mask materials: no discard"));
            CHECK(explain_has(p, "Scene: 0 inputs"));
            CHECK(p->n_final_barriers == 2);
            CHECK(p->final_barriers[0].resource == 1 && p->final_barriers[1].resource == 0);
        }
        pg_graph_plan_free(p);
        pl_free(pl);
    }
}

/* ------------------------------------------------------------------------------------------ */
/* lifetimes and sizes                                                                        */

static void test_lifetimes(void)
{
    pg_pipeline *pl = pl_new("out");
    img(pl, "t1", PG_FMT_RGBA16F);
    img(pl, "t2", PG_FMT_RGBA16F)->scale[0] = 0.5f;
    pl->resources[1].scale[1] = 0.5f;
    img(pl, "out", PG_FMT_RGBA8_UNORM);
    pg_resource_desc *third = img(pl, "third", PG_FMT_R32F);
    third->scale[0] = 1.0f / 3.0f;
    third->scale[1] = 0.335f;
    pg_resource_desc *fixed = img(pl, "fixed", PG_FMT_RGBA32F);
    fixed->extent_mode = PG_EXTENT_ABSOLUTE;
    fixed->size[0] = 7;
    fixed->size[1] = 9;
    img(pl, "tiny", PG_FMT_RGBA8_UNORM)->scale[0] = 0.001f;
    pl->resources[5].scale[1] = 0.001f;
    buf(pl, "lights", 16, 1, PG_COUNT_VAR, 0.0);
    buf(pl, "perpix", 32, 1, PG_COUNT_PIXELS, 0.0);
    buf(pl, "grid", 4, 2, PG_COUNT_CONST, 3.0, PG_COUNT_VAR, 0.0);
    buf(pl, "nolights", 48, 1, PG_COUNT_VAR, 0.0);
    buf(pl, "nolights_small", 4, 1, PG_COUNT_VAR, 0.0);
    pass(pl, "A", "fake_color", "", "t1");
    pass(pl, "B", "fake_blur", "t1", "t2");
    pass(pl, "C", "fake_blur", "t2", "out");
    pg_graph_plan *p = COMPILE(pl);
    if (p) {
        const pg_plan_resource *t1 = res(p, "t1"), *t2 = res(p, "t2"), *out = res(p, "out");
        CHECK(t1->first_pass == 0 && t1->last_pass == 1);
        CHECK(t2->first_pass == 1 && t2->last_pass == 2);
        CHECK(out->first_pass == 2 && out->last_pass == 3 && p->n_order == 3);
        CHECK(t1->width == 100 && t1->height == 50 && t1->size_bytes == 40000);
        CHECK(t2->width == 50 && t2->height == 25 && t2->size_bytes == 10000);
        CHECK(out->size_bytes == 20000);
        CHECK(t1->usage == (VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT));
        CHECK(out->usage == (VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT));
        CHECK(out->is_output && !t1->is_output);
        /* sizes of unused resources are resolved too */
        CHECK(res(p, "third")->width == 34 && res(p, "third")->height == 17); /* 33.33, 16.75 */
        CHECK(res(p, "fixed")->width == 7 && res(p, "fixed")->height == 9);
        CHECK(res(p, "fixed")->size_bytes == 7 * 9 * 16);
        CHECK(res(p, "tiny")->width == 1 && res(p, "tiny")->height == 1);
        CHECK(res(p, "lights")->size_bytes == 1600);
        CHECK(res(p, "perpix")->size_bytes == 32 * 5000);
        CHECK(res(p, "grid")->size_bytes == 1200);
        CHECK(res(p, "third")->culled && res(p, "lights")->culled);
    }
    pg_graph_plan_free(p);
    /* float scales that are exact fractions of the output do not round up */
    pg_compile_desc d = desc_of(pl);
    d.output_width = 900;
    d.output_height = 600;
    pg_vars_set(&d.vars, "lights", 0, NULL);
    p = compile_d(&d, __LINE__);
    if (p) {
        CHECK(res(p, "third")->width == 300 && res(p, "third")->height == 201);
        CHECK(res(p, "nolights")->size_bytes == 48);      /* zero count: one stride */
        CHECK(res(p, "nolights_small")->size_bytes == 16); /* ... at least 16 bytes */
        CHECK(res(p, "grid")->size_bytes == 16);
    }
    pg_graph_plan_free(p);
    pl_free(pl);
}

/* ------------------------------------------------------------------------------------------ */
/* aliasing                                                                                   */

static bool bytes_overlap(const pg_plan_resource *a, const pg_plan_resource *b)
{
    return a->block >= 0 && a->block == b->block && a->block_offset < b->block_offset + b->size_bytes &&
           b->block_offset < a->block_offset + a->size_bytes;
}

/* Members of a block alive at the same time share no byte; a member shares bytes with an
 * earlier one only if it may inherit; offsets are aligned; blocks end at their last byte;
 * sizes add up; never more than one block per resource. */
static void check_blocks(const pg_graph_plan *p, int line)
{
    uint64_t sum_blocks = 0, sum_transients = 0;
    for (uint32_t b = 0; b < p->n_blocks; b++) {
        const pg_plan_block *bl = &p->blocks[b];
        uint64_t end = 0;
        CHECK_MSG(bl->n_members >= 1, "line %d: empty block", line);
        for (uint32_t i = 0; i < bl->n_members; i++) {
            const pg_plan_resource *ri = &p->resources[bl->members[i]];
            CHECK_MSG(ri->kind == bl->kind, "line %d: block %u mixes kinds", line, b);
            CHECK_MSG(ri->lifetime == PG_LIFETIME_TRANSIENT && !ri->culled && ri->block == (int)b,
                      "line %d: bad member %s", line, ri->name);
            const uint64_t al = ri->kind == IMG ? PG_ALIAS_EST_ALIGN_IMAGE : PG_ALIAS_EST_ALIGN_BUFFER;
            CHECK_MSG(ri->block_offset % al == 0, "line %d: %s at unaligned offset %llu", line, ri->name,
                      (unsigned long long)ri->block_offset);
            if (ri->block_offset + ri->size_bytes > end) end = ri->block_offset + ri->size_bytes;
            if (i > 0)
                CHECK_MSG(p->resources[bl->members[i - 1]].first_pass <= ri->first_pass,
                          "line %d: block %u not in first-use order", line, b);
            for (uint32_t j = 0; j < i; j++) {
                const pg_plan_resource *rj = &p->resources[bl->members[j]];
                if (!bytes_overlap(ri, rj)) continue;
                bool disjoint = rj->last_pass < ri->first_pass || ri->last_pass < rj->first_pass;
                CHECK_MSG(disjoint, "line %d: %s [%d,%d] shares bytes with %s [%d,%d] in block %u", line,
                          rj->name, rj->first_pass, rj->last_pass, ri->name, ri->first_pass,
                          ri->last_pass, b);
                const pg_plan_resource *later = ri->first_pass > rj->first_pass ? ri : rj;
                CHECK_MSG(later->may_inherit, "line %d: %s starts in %s's bytes without a full write", line,
                          later->name, later == ri ? rj->name : ri->name);
            }
        }
        CHECK_MSG(bl->size_bytes == end, "line %d: block size", line);
        sum_blocks += bl->size_bytes;
    }
    for (uint32_t r = 0; r < p->n_resources; r++) {
        const pg_plan_resource *pr = &p->resources[r];
        if (pr->lifetime == PG_LIFETIME_TRANSIENT && !pr->culled && pr->growable) {
            /* a "grow" buffer is re-created at run time: its own memory, counted in both totals */
            sum_transients += pr->size_bytes;
            sum_blocks += pr->size_bytes;
            CHECK_MSG(pr->block == -1, "line %d: grow buffer %s is in a block", line, pr->name);
        } else if (pr->lifetime == PG_LIFETIME_TRANSIENT && !pr->culled) {
            sum_transients += pr->size_bytes;
            CHECK_MSG(pr->block >= 0, "line %d: transient %s has no block", line, pr->name);
        } else {
            CHECK_MSG(pr->block == -1, "line %d: %s has a block", line, pr->name);
        }
    }
    CHECK_MSG(sum_blocks == p->transient_bytes_aliased, "line %d: aliased bytes", line);
    CHECK_MSG(sum_transients == p->transient_bytes_unaliased, "line %d: unaliased bytes", line);
    CHECK_MSG(p->transient_bytes_aliased <= p->transient_bytes_unaliased, "line %d: worse than no aliasing", line);
}

static pg_pipeline *chain_pipeline(const char *third_type)
{
    pg_pipeline *pl = pl_new("out");
    img(pl, "t1", PG_FMT_RGBA16F);
    img(pl, "t2", PG_FMT_RGBA16F);
    img(pl, "t3", PG_FMT_RGBA16F);
    img(pl, "out", PG_FMT_RGBA8_UNORM);
    pass(pl, "A", "fake_color", "", "t1");
    pass(pl, "B", "fake_blur", "t1", "t2");
    pass(pl, "C", third_type, "t2", "t3");
    pass(pl, "D", "fake_blur", "t3", "out");
    return pl;
}

/* "grow" buffers are never aliased: a buffer with a disjoint lifetime does not join them */
static void test_grow_not_aliased(void)
{
    pg_pipeline *pl = pl_new("out");
    buf(pl, "a", 4, 1, PG_COUNT_CONST, 1000.0)->growable = true;
    buf(pl, "b", 4, 1, PG_COUNT_CONST, 1000.0);
    img(pl, "c", PG_FMT_RGBA16F);
    img(pl, "d", PG_FMT_RGBA16F);
    img(pl, "out", PG_FMT_RGBA8_UNORM);
    pass(pl, "W1", "fake_compute_buf", "", "a");
    pass(pl, "R1", "fake_buf_to_color", "a", "c");
    pass(pl, "W2", "fake_compute_buf", "", "b");
    pass(pl, "R2", "fake_buf_to_color", "b", "d");
    after(&pl->passes[2], "R1");
    pass(pl, "final", "fake_compose2", "c, d", "out");
    pg_graph_plan *p = COMPILE(pl);
    if (p) {
        const pg_plan_resource *a = res(p, "a"), *b = res(p, "b");
        CHECK(a->growable && !b->growable);
        CHECK(a->block == -1);
        CHECK(b->block >= 0 && p->blocks[b->block].n_members == 1);
        check_blocks(p, __LINE__);
        pg_graph_plan_free(p);
        /* the same without "grow": b may share a's memory */
        pl->resources[0].growable = false;
        p = COMPILE(pl);
        if (p) {
            CHECK(res(p, "a")->block >= 0 && res(p, "a")->block == res(p, "b")->block);
            check_blocks(p, __LINE__);
            pg_graph_plan_free(p);
        }
    }
    pl_free(pl);
}

static void test_aliasing(void)
{
    { /* A -> t1 -> B -> t2 -> C -> t3 -> D -> out: t1 and t3 share, t2 and out share */
        pg_pipeline *pl = chain_pipeline("fake_blur");
        pg_graph_plan *p = COMPILE(pl);
        if (p) {
            check_blocks(p, __LINE__);
            const pg_plan_resource *t1 = res(p, "t1"), *t2 = res(p, "t2"), *t3 = res(p, "t3"),
                                   *out = res(p, "out");
            CHECK(t1->first_pass == 0 && t1->last_pass == 1 && t3->first_pass == 2 &&
                  t3->last_pass == 3);
            /* stacked at offsets, t2 would start at 40960 (4096 alignment estimate): 80960 B;
             * two blocks of their own take 80000 B, so the packer keeps those */
            CHECK(p->n_blocks == 2);
            CHECK(t1->block == 0 && t3->block == 0 && t2->block == 1 && out->block == 1);
            CHECK(p->blocks[0].n_members == 2 && p->blocks[0].members[0] == ridx(p, "t1") &&
                  p->blocks[0].members[1] == ridx(p, "t3"));
            CHECK(p->blocks[1].members[0] == ridx(p, "t2") && p->blocks[1].members[1] == ridx(p, "out"));
            CHECK(bytes_overlap(t1, t3) && bytes_overlap(t2, out) && !bytes_overlap(t1, t2));
            CHECK(p->blocks[0].size_bytes == 40000 && p->blocks[1].size_bytes == 40000);
            CHECK(p->blocks[0].kind == IMG);
            CHECK(p->transient_bytes_unaliased == 140000);
            CHECK(p->transient_bytes_aliased == 80000);
            CHECK(p->transient_bytes_aliased < p->transient_bytes_unaliased);
            CHECK(!p->aliasing_disabled);
            /* t3 starts after t1: waits for A's write and B's read of t1, discards contents */
            CHECK(n_barriers_for(p, "C", "t3") == 1);
            const pg_barrier *b = barrier_for(p, "C", "t3");
            CHECK_BARRIER(b, S_COLOR | S_FRAG, A_CW, S_COLOR, A_CW, L_UNDEF, L_COLOR,
                          "alias first use");
            if (b) CHECK(b->alias_prev == ridx(p, "t1") && b->is_image && !b->wrap);
            b = barrier_for(p, "D", "out");
            CHECK_BARRIER(b, S_COLOR | S_FRAG, A_CW, S_COLOR, A_CW, L_UNDEF, L_COLOR,
                          "alias first use");
            if (b) CHECK(b->alias_prev == ridx(p, "t2"));
            /* the first members start from nothing */
            b = barrier_for(p, "A", "t1");
            CHECK_BARRIER(b, 0, 0, S_COLOR, A_CW, L_UNDEF, L_COLOR, "first use");
            if (b) CHECK(b->alias_prev == -1);
        }
        pg_graph_plan_free(p);
        /* the debugging switch: every transient alone */
        pg_compile_desc d = desc_of(pl);
        d.disable_aliasing = true;
        p = compile_d(&d, __LINE__);
        if (p) {
            check_blocks(p, __LINE__);
            CHECK(p->n_blocks == 4 && p->aliasing_disabled);
            CHECK(p->transient_bytes_aliased == 140000 && p->transient_bytes_unaliased == 140000);
            for (uint32_t b = 0; b < p->n_blocks; b++) CHECK(p->blocks[b].n_members == 1);
            const pg_barrier *b = barrier_for(p, "C", "t3");
            CHECK_BARRIER(b, 0, 0, S_COLOR, A_CW, L_UNDEF, L_COLOR, "first use");
        }
        pg_graph_plan_free(p);
        pl_free(pl);
    }
    { /* a transient first used by a read-modify-write reads undefined memory: an error naming
       * the pass, the slot and the resource; the same pass marked "initializes" is a full write
       * (it may join a block like any full write) */
        pg_pipeline *pl = chain_pipeline("fake_blend");
        const char *m = FAIL(pl, PG_ERR_READ_BEFORE_WRITE);
        CHECK_MSG(strcmp(m, "test.json: passes[2].writes[0]: pass 'C' reads transient resource 't3' "
                            "before it is fully written: it is the first pass to use it and slot "
                            "'dst' (color_rmw) reads its contents, undefined at the start of a "
                            "frame (write it in full first, e.g. clear it, declare it persistent, "
                            "or, if the pass writes every element before reading any, mark the "
                            "slot with pg_decl_mark_initializes())") == 0,
                  "%s", m);
        pl_free(pl);
        pl = chain_pipeline("fake_blend_init");
        pg_graph_plan *p = COMPILE(pl);
        if (p) {
            check_blocks(p, __LINE__);
            const pg_plan_pass *c = &p->passes[pidx(p, "C")];
            CHECK(c->slots[1].decl.initializes && !c->slots[1].decl.partial);
            /* t1 and t3 share, t2 and out share: as with a full write (fake_blur above) */
            CHECK(p->n_blocks == 2 && res(p, "t3")->block == res(p, "t1")->block);
            CHECK(p->transient_bytes_unaliased == 140000 && p->transient_bytes_aliased == 80000);
            const pg_barrier *b = barrier_for(p, "C", "t3");
            CHECK(b && b->alias_prev == ridx(p, "t1") && b->old_layout == L_UNDEF &&
                  b->new_layout == L_COLOR);
        }
        pg_graph_plan_free(p);
        pl_free(pl);
        /* the same with a storage read-write, a depth load and a blend with no earlier writer */
        pl = pl_new("out");
        img(pl, "t1", PG_FMT_RGBA16F);
        img(pl, "t2", PG_FMT_RGBA16F);
        img(pl, "x", PG_FMT_RGBA16F);
        img(pl, "out", PG_FMT_RGBA16F);
        pass(pl, "A", "fake_color", "", "t1");
        pass(pl, "B", "fake_blur", "t1", "x");
        pass(pl, "S", "fake_storage_rw", "", "t2");
        pass(pl, "C", "fake_compose2", "x, t2", "out");
        m = FAIL(pl, PG_ERR_READ_BEFORE_WRITE);
        HAS(m, "test.json: passes[2].writes[0]: pass 'S' reads transient resource 't2' before it is "
               "fully written: it is the first pass to use it and slot 'img' (storage_rw) reads");
        pg_strlcpy(pl->passes[2].type, "fake_storage_rw_init", sizeof pl->passes[2].type);
        p = COMPILE(pl);
        if (p) {
            check_blocks(p, __LINE__);
            /* t2 [2,3] follows t1 [0,1] in its block: its first access writes every texel */
            CHECK(res(p, "t2")->block == res(p, "t1")->block);
            CHECK_BARRIER(barrier_for(p, "S", "t2"), S_COLOR | S_FRAG, A_CW, S_COMP, A_SR | A_SW,
                          L_UNDEF, L_GENERAL, "alias first use");
            CHECK(barrier_for(p, "S", "t2") && barrier_for(p, "S", "t2")->alias_prev == ridx(p, "t1"));
        }
        pg_graph_plan_free(p);
        /* persistent: the read-modify-write loads last frame's value, which is fine */
        pl->resources[1].lifetime = PG_LIFETIME_PERSISTENT;
        pg_strlcpy(pl->passes[2].type, "fake_storage_rw", sizeof pl->passes[2].type);
        p = COMPILE(pl);
        pg_graph_plan_free(p);
        pl_free(pl);
        pl = pl_new("out");
        img(pl, "d", PG_FMT_D32F);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "Z", "fake_rmw", "", "d");
        pass(pl, "R", "fake_depth_read", "d", "out");
        m = FAIL(pl, PG_ERR_READ_BEFORE_WRITE);
        HAS(m, "pass 'Z' reads transient resource 'd' before it is fully written");
        HAS(m, "slot 'depth' (depth_rmw)");
        pl_free(pl);
        pl = pl_new("out");
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "Blend", "fake_color_rmw", "", "out");
        m = FAIL(pl, PG_ERR_READ_BEFORE_WRITE);
        HAS(m, "pass 'Blend' reads transient resource 'out' before it is fully written");
        pl_free(pl);
    }
    { /* a partial write is not a full write: accepted as a first use, never joins a block after
       * another resource; "initializes" and "partial" on the wrong access are pass-type bugs */
        pg_pipeline *pl = pl_new("out");
        buf(pl, "b1", 8, 1, PG_COUNT_PIXELS, 0.0);
        buf(pl, "b2", 8, 1, PG_COUNT_PIXELS, 0.0);
        img(pl, "c", PG_FMT_RGBA16F);
        img(pl, "d", PG_FMT_RGBA16F);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "W1", "fake_compute_buf", "", "b1");
        pass(pl, "R1", "fake_buf_to_color", "b1", "c");
        pass(pl, "W2", "fake_partial_buf", "", "b2");
        pass(pl, "R2", "fake_buf_to_color", "b2", "d");
        after(&pl->passes[2], "R1");
        pass(pl, "final", "fake_compose2", "c, d", "out");
        pg_graph_plan *p = COMPILE(pl);
        if (p) {
            check_blocks(p, __LINE__);
            CHECK(p->passes[pidx(p, "W2")].slots[0].decl.partial);
            CHECK(!p->passes[pidx(p, "W2")].slots[0].sync.full_write);
            CHECK(res(p, "b2")->block != res(p, "b1")->block);
        }
        pg_graph_plan_free(p);
        pg_strlcpy(pl->passes[2].type, "fake_compute_buf", sizeof pl->passes[2].type);
        p = COMPILE(pl); /* a full write shares b1's memory */
        if (p) CHECK(res(p, "b2")->block == res(p, "b1")->block);
        pg_graph_plan_free(p);
        pl_free(pl);
        pl = pl_new("out");
        img(pl, "out", PG_FMT_RGBA16F);
        pass(pl, "A", "fake_bad_init", "", "out");
        const char *m = FAIL(pl, PG_ERR_SCHEMA);
        CHECK_MSG(strcmp(m, "test.json: passes[0].writes[0]: pass type 'fake_bad_init' marks slot "
                            "'color' (color_write) as initialized by the pass, which only a write "
                            "slot whose access reads can be (a bug in the pass type)") == 0,
                  "%s", m);
        pg_strlcpy(pl->passes[0].type, "fake_bad_partial", sizeof pl->passes[0].type);
        m = FAIL(pl, PG_ERR_SCHEMA);
        CHECK_MSG(strcmp(m, "test.json: passes[0].writes[0]: pass type 'fake_bad_partial' marks "
                            "slot 'img' (storage_rw) as a partial write, which only a write slot "
                            "with a full-write access can be (a bug in the pass type)") == 0,
                  "%s", m);
        pl_free(pl);
    }
    { /* images never share with buffers; buffers share with buffers; persistent never */
        pg_pipeline *pl = pl_new("out");
        buf(pl, "b1", 8, 1, PG_COUNT_PIXELS, 0.0); /* 40000 bytes, like t1 */
        img(pl, "t1", PG_FMT_RGBA16F);
        buf(pl, "b2", 8, 1, PG_COUNT_PIXELS, 0.0);
        img(pl, "t2", PG_FMT_RGBA16F);
        img_l(pl, "hist", PG_FMT_RGBA16F, PG_LIFETIME_PERSISTENT);
        img(pl, "out", PG_FMT_RGBA16F);
        pass(pl, "A", "fake_compute_buf", "", "b1");
        pass(pl, "B", "fake_buf_to_color", "b1", "t1");
        pass(pl, "C", "fake_compute_buf", "", "b2");
        pass(pl, "D", "fake_buf_blur", "b2, t1", "t2");
        pass(pl, "E", "fake_blur", "t2", "hist");
        pass(pl, "F", "fake_blur", "hist", "out");
        pg_graph_plan *p = COMPILE(pl);
        if (p) {
            check_blocks(p, __LINE__);
            const pg_plan_resource *b1 = res(p, "b1"), *b2 = res(p, "b2"), *t1 = res(p, "t1"),
                                   *t2 = res(p, "t2");
            CHECK(b1->first_pass == 0 && b1->last_pass == 1 && b2->first_pass == 2);
            CHECK(t2->first_pass == 3 && t2->last_pass == 4);
            CHECK(b1->block == b2->block && p->blocks[b1->block].kind == BUF);
            CHECK(t2->block != b1->block && t1->block != b1->block);
            CHECK(res(p, "hist")->block == -1);
            CHECK(res(p, "out")->block == t1->block); /* t1 [1,3] < out [5,6] */
            CHECK(p->n_blocks == 3); /* one of buffers, two of images (no padding between them) */
            CHECK(bytes_overlap(b1, b2) && bytes_overlap(res(p, "out"), t1) && !bytes_overlap(t1, t2));
            CHECK(p->transient_bytes_unaliased == 5 * 40000);
            CHECK(p->transient_bytes_aliased == 3 * 40000);
            /* buffer alias barrier: after b1's compute write and fragment read */
            const pg_barrier *b = barrier_for(p, "C", "b2");
            CHECK_BARRIER(b, S_COMP | S_FRAG, A_SW, S_COMP, A_SW, L_UNDEF, L_UNDEF,
                          "alias first use");
            if (b) CHECK(!b->is_image && b->alias_prev == ridx(p, "b1"));
            CHECK(barrier_for(p, "A", "b1") == NULL); /* a fresh buffer needs nothing */
        }
        pg_graph_plan_free(p);
        pl_free(pl);
    }
}

/* ------------------------------------------------------------------------------------------ */
/* randomized property test                                                                   */

static uint32_t g_rng = 0x2545F491u;
static uint32_t rnd(uint32_t n)
{
    g_rng ^= g_rng << 13;
    g_rng ^= g_rng >> 17;
    g_rng ^= g_rng << 5;
    return n ? g_rng % n : 0;
}

static pg_pipeline *random_pipeline(void)
{
    for (;;) {
        pg_pipeline *pl = pl_new("");
        const uint32_t n_res = 3 + rnd(12);
        const pg_format fmts[] = {PG_FMT_RGBA8_UNORM, PG_FMT_RGBA16F, PG_FMT_R32F, PG_FMT_RGBA32F,
                                  PG_FMT_D32F};
        for (uint32_t i = 0; i < n_res; i++) {
            char name[16];
            snprintf(name, sizeof name, "r%u", i);
            if (rnd(5) == 0) {
                buf(pl, name, 4u << rnd(4), 1, rnd(2) ? PG_COUNT_PIXELS : PG_COUNT_CONST, 1000.0);
            } else {
                pg_resource_desc *r = img(pl, name, fmts[rnd(8) == 0 ? 4 : rnd(4)]);
                const float scales[] = {1.0f, 0.5f, 0.25f};
                r->scale[0] = r->scale[1] = scales[rnd(3)];
            }
            if (rnd(8) == 0) pl->resources[i].lifetime = PG_LIFETIME_PERSISTENT;
        }
        int writers[PG_MAX_RESOURCES];
        bool has_reader[PG_MAX_RESOURCES] = {false};
        for (uint32_t i = 0; i < n_res; i++) writers[i] = -1;
        const uint32_t n_pass = 2 + rnd(14);
        for (uint32_t pi = 0; pi < n_pass; pi++) {
            const char *types[] = {"rnd_color", "rnd_storage", "rnd_rmw"};
            const uint32_t mode = rnd(3);
            char wl[PG_MAX_SLOTS][PG_NAME_MAX], rl[PG_MAX_SLOTS][PG_NAME_MAX];
            uint32_t nw = 0, nr = 0;
            char after_name[PG_MAX_SLOTS][PG_NAME_MAX];
            uint32_t n_after = 0;
            bool used[PG_MAX_RESOURCES] = {false};
            const uint32_t want_w = 1 + rnd(2);
            float att_scale = 0; /* the attachments of a colour pass share one size (the compiler checks) */
            for (uint32_t tries = 0; tries < 8 && nw < want_w; tries++) {
                uint32_t r = rnd(n_res);
                const pg_resource_desc *rd = &pl->resources[r];
                if (used[r]) continue;
                if (mode == 1 && rd->kind == IMG && rd->format == PG_FMT_D32F) continue;
                if (mode != 1 && rd->kind == IMG) {
                    if (att_scale && rd->scale[0] != att_scale) continue;
                    att_scale = rd->scale[0];
                }
                /* pure readers run after the LAST writer: no writer may follow a reader, or the
                 * edges would point backwards (and could close a cycle) */
                if (has_reader[r]) continue;
                if (writers[r] >= 0) {
                    /* a later writer must read it (rmw) or come "after" the last writer */
                    if (mode != 2) {
                        pg_strlcpy(after_name[n_after++], pl->passes[writers[r]].name, PG_NAME_MAX);
                    }
                }
                used[r] = true;
                pg_strlcpy(wl[nw++], rd->name, PG_NAME_MAX);
            }
            if (!nw) continue;
            const uint32_t want_r = rnd(4);
            for (uint32_t tries = 0; tries < 8 && nr < want_r; tries++) {
                uint32_t r = rnd(n_res);
                if (used[r]) continue;
                if (writers[r] < 0 && pl->resources[r].lifetime == PG_LIFETIME_TRANSIENT) continue;
                used[r] = true;
                pg_strlcpy(rl[nr++], pl->resources[r].name, PG_NAME_MAX);
            }
            /* a read-modify-write first use of a transient is an error unless the pass
             * initializes it: such passes are declared "rnd_init" */
            const char *type = types[mode];
            for (uint32_t k = 0; k < nw && mode == 2; k++) {
                const pg_resource_desc *rd = find_res(pl, wl[k]);
                if (writers[rd - pl->resources] < 0 && rd->lifetime == PG_LIFETIME_TRANSIENT)
                    type = "rnd_init";
            }
            char name[16];
            snprintf(name, sizeof name, "p%u", pl->n_passes);
            pg_pass_desc *p = pass(pl, name, type, "", "");
            for (uint32_t k = 0; k < nw; k++) pg_strlcpy(p->writes[p->n_writes++], wl[k], PG_NAME_MAX);
            for (uint32_t k = 0; k < nr; k++) pg_strlcpy(p->reads[p->n_reads++], rl[k], PG_NAME_MAX);
            for (uint32_t k = 0; k < n_after; k++) after(p, after_name[k]);
            if (pl->n_passes > 1 && rnd(8) == 0 && p->n_after < PG_MAX_AFTER)
                after(p, pl->passes[rnd(pl->n_passes - 1)].name);
            if (rnd(10) == 0) p->side_effects = true;
            for (uint32_t k = 0; k < nw; k++)
                writers[find_res(pl, wl[k]) - pl->resources] = (int)pl->n_passes - 1;
            for (uint32_t k = 0; k < nr; k++) has_reader[find_res(pl, rl[k]) - pl->resources] = true;
        }
        /* output: an image written by the last pass that writes one */
        for (int pi = (int)pl->n_passes - 1; pi >= 0 && !pl->output[0]; pi--)
            for (uint32_t k = 0; k < pl->passes[pi].n_writes; k++) {
                const pg_resource_desc *rd = find_res(pl, pl->passes[pi].writes[k]);
                if (rd->kind == IMG) {
                    pg_strlcpy(pl->output, rd->name, sizeof pl->output);
                    break;
                }
            }
        if (pl->output[0]) return pl;
        pl_free(pl);
    }
}

/* Checks the barrier list against an independent walk: the first use of every transient image
 * starts from UNDEFINED (after its block's previous occupant, if any); every access after a write
 * or in a new layout has exactly one barrier whose layouts match. */
static void check_random_plan(const pg_graph_plan *p, int iter)
{
    check_blocks(p, iter);
    uint32_t prev_layout[PG_MAX_RESOURCES] = {0};
    bool prev_write[PG_MAX_RESOURCES] = {false}, seen[PG_MAX_RESOURCES] = {false};
    for (uint32_t k = 0; k < p->n_order; k++) {
        const pg_plan_pass *pp = &p->passes[p->order[k]];
        for (uint32_t b = 0; b < pp->n_barriers; b++)
            for (uint32_t c = 0; c < b; c++)
                CHECK_MSG(pp->barriers[b].resource != pp->barriers[c].resource,
                          "iter %d: two barriers for one resource in %s", iter, pp->name);
        bool done[PG_MAX_RESOURCES] = {false};
        for (uint32_t s = 0; s < pp->n_slots; s++) {
            const int r = pp->slots[s].resource;
            if (done[r]) continue;
            done[r] = true;
            const pg_plan_resource *pr = &p->resources[r];
            bool writes = false;
            for (uint32_t t = 0; t < pp->n_slots; t++)
                if (pp->slots[t].resource == r) writes |= pp->slots[t].sync.writes;
            const uint32_t layout = pp->slots[s].sync.layout;
            const pg_barrier *bar = NULL;
            for (uint32_t b = 0; b < pp->n_barriers; b++)
                if (pp->barriers[b].resource == r) bar = &pp->barriers[b];
            if (!seen[r] && pr->lifetime == PG_LIFETIME_TRANSIENT) {
                CHECK_MSG(pr->first_pass == (int)k, "iter %d: first_pass of %s", iter, pr->name);
                const pg_plan_block *bl = &p->blocks[pr->block];
                /* earlier members of the block that ended before: the alias barrier waits for
                 * them (a resource that may not inherit shares none of their bytes) */
                int idx = 0, overlapped = 0;
                for (uint32_t m = 0; m < bl->n_members && pr->may_inherit; m++) {
                    const pg_plan_resource *q = &p->resources[bl->members[m]];
                    if (bl->members[m] == r || !(q->last_pass < pr->first_pass)) continue;
                    idx = 1;
                    overlapped |= bytes_overlap(q, pr);
                }
                if (pr->kind == IMG || idx) {
                    CHECK_MSG(bar && bar->old_layout == L_UNDEF && bar->new_layout == layout,
                              "iter %d: first use of %s in %s has no UNDEFINED barrier", iter,
                              pr->name, pp->name);
                    if (bar && idx) {
                        const pg_plan_resource *q = bar->alias_prev >= 0 ? &p->resources[bar->alias_prev] : NULL;
                        CHECK_MSG(q && q->block == pr->block && q->last_pass < pr->first_pass &&
                                      (!overlapped || bytes_overlap(q, pr)),
                                  "iter %d: alias_prev", iter);
                        /* it waits for the last accesses of every earlier member of the block */
                        CHECK_MSG(bar->src_stages != 0, "iter %d: alias barrier waits for nothing", iter);
                        for (uint32_t m = 0; m < bl->n_members; m++) {
                            const pg_plan_resource *e = &p->resources[bl->members[m]];
                            if (bl->members[m] == r || !(e->last_pass < pr->first_pass)) continue;
                            const pg_plan_pass *lp = &p->passes[p->order[e->last_pass]];
                            uint64_t st = 0;
                            for (uint32_t t = 0; t < lp->n_slots; t++)
                                if (lp->slots[t].resource == bl->members[m] && !lp->slots[t].decl.unused)
                                    st |= lp->slots[t].sync.stages;
                            CHECK_MSG((st & ~bar->src_stages) == 0,
                                      "iter %d: %s's alias barrier does not wait for %s's last use in %s", iter,
                                      pr->name, e->name, lp->name);
                        }
                    }
                } else {
                    CHECK_MSG(!bar, "iter %d: fresh buffer %s has a barrier", iter, pr->name);
                }
                if (idx) {
                    /* joined a block: its first access fully overwrites it */
                    bool full = false, reads = false, init = false;
                    for (uint32_t t = 0; t < pp->n_slots; t++)
                        if (pp->slots[t].resource == r) {
                            full |= pp->slots[t].sync.full_write;
                            reads |= pp->slots[t].sync.reads;
                            init |= pp->slots[t].decl.initializes;
                        }
                    CHECK_MSG((full && !reads) || init,
                              "iter %d: %s joined a block without a full write", iter, pr->name);
                }
            } else if (seen[r]) {
                const bool need = prev_write[r] || (pr->kind == IMG && prev_layout[r] != layout);
                if (need)
                    CHECK_MSG(bar && bar->old_layout == (pr->kind == IMG ? prev_layout[r] : 0) &&
                                  bar->new_layout == (pr->kind == IMG ? layout : 0),
                              "iter %d: %s in %s needs a barrier", iter, pr->name, pp->name);
                if (!need && !writes && bar)
                    CHECK_MSG(strstr(bar->why, "RAW") != NULL, "iter %d: unexpected barrier %s",
                              iter, bar->why);
            }
            seen[r] = true;
            prev_write[r] = writes;
            prev_layout[r] = pr->kind == IMG ? layout : 0;
        }
    }
    /* the output goes to TRANSFER_SRC */
    CHECK_MSG(p->n_final_barriers == 1 && p->final_barriers[0].resource == p->output &&
                  p->final_barriers[0].new_layout == L_TSRC &&
                  p->final_barriers[0].old_layout == prev_layout[p->output],
              "iter %d: final barrier", iter);
}

static void test_random(void)
{
    int compiled = 0, aliased_some = 0;
    for (int iter = 0; iter < 200; iter++) {
        pg_pipeline *pl = random_pipeline();
        pg_graph_plan *p = NULL;
        pg_error err = {0};
        pg_compile_desc d = desc_of(pl);
        d.output_width = 64;
        d.output_height = 48;
        pg_result r = pg_graph_compile(&d, &p, &err);
        CHECK_MSG(r == PG_OK, "iter %d: %s: %s", iter, pg_result_name(r), err.msg);
        if (r == PG_OK) {
            compiled++;
            check_random_plan(p, iter);
            if (p->transient_bytes_aliased < p->transient_bytes_unaliased) aliased_some++;
            /* deterministic */
            pg_graph_plan *q = NULL;
            CHECK(pg_graph_compile(&d, &q, &err) == PG_OK);
            if (q) CHECK_MSG(memcmp(p, q, sizeof *p) == 0, "iter %d: not deterministic", iter);
            pg_graph_plan_free(q);
            if (iter == 7) {
                FILE *f = tmpfile();
                pg_graph_plan_print(p, pl, f);
                fclose(f);
            }
            pg_graph_plan_free(p);
            d.disable_aliasing = true;
            p = NULL;
            r = pg_graph_compile(&d, &p, &err);
            CHECK(r == PG_OK);
            if (p) {
                check_random_plan(p, iter);
                CHECK(p->transient_bytes_aliased == p->transient_bytes_unaliased);
                for (uint32_t b = 0; b < p->n_blocks; b++) CHECK(p->blocks[b].n_members == 1);
            }
            pg_graph_plan_free(p);
        }
        pl_free(pl);
    }
    CHECK(compiled == 200);
    CHECK_MSG(aliased_some > 20, "only %d random graphs aliased anything", aliased_some);
    printf("random: %d graphs compiled, %d with aliasing savings\n", compiled, aliased_some);
}

/* ------------------------------------------------------------------------------------------ */
/* barriers                                                                                   */

static void test_barriers(void)
{
    { /* colour write then sampled read */
        pg_pipeline *pl = pl_new("out");
        img(pl, "t", PG_FMT_RGBA16F);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "A", "fake_color", "", "t");
        pass(pl, "B", "fake_blur", "t", "out");
        pg_graph_plan *p = COMPILE(pl);
        if (p) {
            CHECK(p->passes[0].n_barriers == 1);
            CHECK_BARRIER(barrier_for(p, "A", "t"), 0, 0, S_COLOR, A_CW, L_UNDEF, L_COLOR,
                          "first use");
            CHECK(p->passes[1].n_barriers == 2 && n_barriers_for(p, "B", "t") == 1);
            CHECK_BARRIER(barrier_for(p, "B", "t"), S_COLOR, A_CW, S_FRAG, A_SAMPLED, L_COLOR, L_SRO,
                          "RAW+layout");
            CHECK_BARRIER(barrier_for(p, "B", "out"), 0, 0, S_COLOR, A_CW, L_UNDEF, L_COLOR,
                          "first use");
            CHECK(p->n_final_barriers == 1);
            CHECK_BARRIER(&p->final_barriers[0], S_COLOR, A_CW, S_COPY, A_TR, L_COLOR, L_TSRC,
                          "output");
            CHECK(p->final_barriers[0].resource == ridx(p, "out"));
            CHECK(total_barriers(p) == 3);
            CHECK(p->passes[1].slots[0].sync.layout == L_SRO && !p->passes[1].slots[0].is_write);
            CHECK(p->passes[1].slots[1].is_write && p->passes[1].slots[1].resource == 1);
        }
        pg_graph_plan_free(p);
        /* presenting: the output ends in PRESENT_SRC with no destination stage */
        pg_compile_desc d = desc_of(pl);
        d.output_layout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
        p = compile_d(&d, __LINE__);
        if (p)
            CHECK_BARRIER(&p->final_barriers[0], S_COLOR, A_CW, 0, 0, L_COLOR,
                          VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, "output");
        pg_graph_plan_free(p);
        pl_free(pl);
    }
    { /* compute storage buffer write then fragment storage read */
        pg_pipeline *pl = pl_new("out");
        buf(pl, "b", 16, 1, PG_COUNT_VAR, 0.0);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "A", "fake_compute_buf", "", "b");
        pass(pl, "B", "fake_buf_to_color", "b", "out");
        pg_graph_plan *p = COMPILE(pl);
        if (p) {
            CHECK(p->passes[0].n_barriers == 0);
            const pg_barrier *b = barrier_for(p, "B", "b");
            CHECK_BARRIER(b, S_COMP, A_SW, S_FRAG, A_SR, L_UNDEF, L_UNDEF, "RAW");
            if (b) CHECK(!b->is_image && b->alias_prev == -1 && !b->wrap);
            CHECK(res(p, "b")->usage == VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        }
        pg_graph_plan_free(p);
        pl_free(pl);
    }
    { /* WAW (two ordered pure writers), RAW+WAW (read-modify-write) */
        pg_pipeline *pl = pl_new("out");
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "W0", "fake_color", "", "out");
        after(pass(pl, "W1", "fake_color", "", "out"), "W0");
        pass(pl, "W2", "fake_color_rmw", "", "out");
        pg_graph_plan *p = COMPILE(pl);
        if (p) {
            CHECK_BARRIER(barrier_for(p, "W1", "out"), S_COLOR, A_CW, S_COLOR, A_CW, L_COLOR,
                          L_COLOR, "WAW");
            CHECK_BARRIER(barrier_for(p, "W2", "out"), S_COLOR, A_CW, S_COLOR, A_CW | A_CR, L_COLOR,
                          L_COLOR, "RAW+WAW");
            CHECK(total_barriers(p) == 3);
        }
        pg_graph_plan_free(p);
        pl_free(pl);
    }
    { /* storage image write then read-modify-write in compute: GENERAL stays */
        pg_pipeline *pl = pl_new("out");
        img(pl, "s", PG_FMT_RGBA16F);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "A", "fake_storage_write", "", "s");
        pass(pl, "B", "fake_storage_rw", "", "s");
        pass(pl, "C", "fake_blur", "s", "out");
        pg_graph_plan *p = COMPILE(pl);
        if (p) {
            CHECK_BARRIER(barrier_for(p, "A", "s"), 0, 0, S_COMP, A_SW, L_UNDEF, L_GENERAL,
                          "first use");
            CHECK_BARRIER(barrier_for(p, "B", "s"), S_COMP, A_SW, S_COMP, A_SR | A_SW, L_GENERAL,
                          L_GENERAL, "RAW+WAW");
            CHECK_BARRIER(barrier_for(p, "C", "s"), S_COMP, A_SW, S_FRAG, A_SAMPLED, L_GENERAL,
                          L_SRO, "RAW+layout");
            CHECK(res(p, "s")->usage == (VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT));
        }
        pg_graph_plan_free(p);
        pl_free(pl);
    }
    { /* depth write then depth test read-only */
        pg_pipeline *pl = pl_new("out");
        img(pl, "c", PG_FMT_RGBA16F);
        img(pl, "d", PG_FMT_D32F);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "G", "fake_depth_color", "", "c, d");
        pass(pl, "L", "fake_depth_read", "d", "out");
        pg_graph_plan *p = COMPILE(pl);
        if (p) {
            CHECK_BARRIER(barrier_for(p, "G", "d"), 0, 0, S_TESTS, A_DR | A_DW, L_UNDEF, L_DEPTH,
                          "first use");
            CHECK_BARRIER(barrier_for(p, "L", "d"), S_TESTS, A_DW, S_TESTS, A_DR, L_DEPTH, L_DRO,
                          "RAW+layout");
            CHECK(!res(p, "c")->culled); /* written by a pass that runs */
        }
        pg_graph_plan_free(p);
        pl_free(pl);
    }
    { /* depth both tested read-only and sampled in one pass: one barrier, DEPTH_READ_ONLY */
        pg_pipeline *pl = pl_new("out");
        img(pl, "c", PG_FMT_RGBA16F);
        img(pl, "d", PG_FMT_D32F);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "G", "fake_depth_color", "", "c, d");
        pass(pl, "L", "fake_depth_sample", "d, d", "out");
        pg_graph_plan *p = COMPILE(pl);
        if (p) {
            CHECK(n_barriers_for(p, "L", "d") == 1);
            CHECK_BARRIER(barrier_for(p, "L", "d"), S_TESTS, A_DW, S_TESTS | S_FRAG, A_DR | A_SAMPLED,
                          L_DEPTH, L_DRO, "RAW+layout");
            const pg_plan_pass *l = &p->passes[pidx(p, "L")];
            CHECK(l->slots[0].sync.layout == L_DRO && l->slots[1].sync.layout == L_DRO);
            CHECK(res(p, "d")->usage ==
                  (VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT));
        }
        pg_graph_plan_free(p);
        pl_free(pl);
    }
    { /* read after read in the same stages: nothing; in new stages: RAW chained through the
       * first reader (which did the layout transition) */
        pg_pipeline *pl = pl_new("out");
        img(pl, "t", PG_FMT_RGBA16F);
        img(pl, "u", PG_FMT_RGBA16F);
        img(pl, "v", PG_FMT_RGBA16F);
        img(pl, "w", PG_FMT_RGBA16F);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "A", "fake_color", "", "t");
        pass(pl, "B", "fake_blur", "t", "u");
        pass(pl, "C", "fake_compose2", "t, u", "v");
        pass(pl, "D", "fake_blur_cs", "t", "w");
        pass(pl, "E", "fake_compose2", "v, w", "out");
        pg_graph_plan *p = COMPILE(pl);
        if (p) {
            CHECK(n_barriers_for(p, "C", "t") == 0);
            CHECK(n_barriers_for(p, "C", "u") == 1);
            CHECK_BARRIER(barrier_for(p, "D", "t"), S_COLOR | S_FRAG, A_CW, S_COMP, A_SAMPLED,
                          L_SRO, L_SRO, "RAW");
            CHECK_BARRIER(barrier_for(p, "E", "w"), S_COMP, A_SW, S_FRAG, A_SAMPLED, L_GENERAL,
                          L_SRO, "RAW+layout");
        }
        pg_graph_plan_free(p);
        pl_free(pl);
    }
    { /* persistent history: last frame's sampled read is followed by this frame's write (WAR
       * across the frame: the wrap barrier waits for the reader and the previous write) */
        pg_pipeline *pl = pl_new("out");
        img_l(pl, "hist", PG_FMT_RGBA16F, PG_LIFETIME_PERSISTENT);
        img_l(pl, "lut", PG_FMT_RGBA16F, PG_LIFETIME_PERSISTENT);
        img(pl, "tmp", PG_FMT_RGBA16F);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "Acc", "fake_color_rmw", "", "hist");
        pass(pl, "Use", "fake_compose2", "hist, lut", "tmp");
        pass(pl, "Final", "fake_blur", "tmp", "out");
        pg_graph_plan *p = COMPILE(pl);
        if (p) {
            const pg_barrier *b = barrier_for(p, "Acc", "hist");
            CHECK_BARRIER(b, S_COLOR | S_FRAG, A_CW, S_COLOR, A_CW | A_CR, L_SRO, L_COLOR,
                          "frame wrap");
            if (b) CHECK(b->wrap && b->alias_prev == -1);
            CHECK_BARRIER(barrier_for(p, "Use", "hist"), S_COLOR, A_CW, S_FRAG, A_SAMPLED, L_COLOR,
                          L_SRO, "RAW+layout");
            /* only ever sampled, one layout: nothing to wait for from frame to frame, only the
             * first frame's transition out of UNDEFINED (the runtime records it while the image
             * holds nothing) */
            CHECK(n_barriers_for(p, "Use", "lut") == 1);
            const pg_barrier *l = barrier_for(p, "Use", "lut");
            CHECK_BARRIER(l, 0, 0, S_FRAG, A_SAMPLED, VK_IMAGE_LAYOUT_UNDEFINED, L_SRO, "first frame");
            if (l) CHECK(l->wrap && l->first_frame && l->alias_prev == -1);
            if (b) CHECK(!b->first_frame);
            CHECK(res(p, "hist")->block == -1 && res(p, "lut")->block == -1);
            CHECK(res(p, "hist")->first_pass == 0 && res(p, "hist")->last_pass == 1);
            CHECK(p->transient_bytes_unaliased == 40000 + 20000);
        }
        pg_graph_plan_free(p);
        pl_free(pl);
    }
    { /* persistent read in two layouts, never written: the layout change waits for the reader
       * before it (no access to flush), and the wrap goes back from the last layout */
        pg_pipeline *pl = pl_new("out");
        img_l(pl, "lut", PG_FMT_RGBA16F, PG_LIFETIME_PERSISTENT);
        img(pl, "a", PG_FMT_RGBA16F);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "S", "fake_blur", "lut", "a");
        pass(pl, "C", "fake_storage_read", "lut, a", "out");
        pg_graph_plan *p = COMPILE(pl);
        if (p) {
            const pg_barrier *b = barrier_for(p, "S", "lut");
            CHECK_BARRIER(b, S_FRAG | S_COMP, 0, S_FRAG, A_SAMPLED, L_GENERAL, L_SRO, "frame wrap");
            if (b) CHECK(b->wrap);
            CHECK_BARRIER(barrier_for(p, "C", "lut"), S_FRAG, 0, S_COMP, A_SR, L_SRO, L_GENERAL,
                          "layout");
        }
        pg_graph_plan_free(p);
        pl_free(pl);
    }
    { /* an imported swapchain image presented each frame */
        pg_pipeline *pl = pl_new("swap");
        img(pl, "t", PG_FMT_RGBA16F);
        img_l(pl, "swap", PG_FMT_RGBA8_UNORM, PG_LIFETIME_IMPORTED);
        pass(pl, "A", "fake_color", "", "t");
        pass(pl, "B", "fake_blur", "t", "swap");
        pg_compile_desc d = desc_of(pl);
        d.output_layout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
        pg_graph_plan *p = compile_d(&d, __LINE__);
        if (p) {
            const pg_barrier *b = barrier_for(p, "B", "swap");
            CHECK_BARRIER(b, S_COLOR, A_CW, S_COLOR, A_CW, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, L_COLOR,
                          "frame wrap");
            if (b) CHECK(b->wrap);
            CHECK_BARRIER(&p->final_barriers[0], S_COLOR, A_CW, 0, 0, L_COLOR,
                          VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, "output");
            CHECK(res(p, "swap")->block == -1);
        }
        pg_graph_plan_free(p);
        pl_free(pl);
    }
}

/* ------------------------------------------------------------------------------------------ */
/* report                                                                                     */

static void test_report(void)
{
    pg_pipeline *pl = chain_pipeline("fake_blur");
    img(pl, "junk", PG_FMT_RGBA16F);
    pass(pl, "Junk", "fake_color", "", "junk");
    pg_graph_plan *p = COMPILE(pl);
    if (p) {
        FILE *f = tmpfile();
        CHECK(f != NULL);
        if (f) {
            pg_graph_plan_print(p, pl, f);
            long len = ftell(f);
            CHECK(len > 0);
            rewind(f);
            char *text = calloc(1, (size_t)len + 1);
            CHECK(fread(text, 1, (size_t)len, f) == (size_t)len);
            fclose(f);
            HAS(text, "saving 42.9%");
            HAS(text, "alias first use after 't1'");
            HAS(text, "fragment_shader|color_output/color_write -> color_output/color_write");
            HAS(text, "undefined -> color_attachment");
            HAS(text, "Junk: nothing reads its writes (junk)");
            HAS(text, "junk: not used by any pass that runs");
            HAS(text, "(output)");
            HAS(text, "140000 B");
            if (getenv("PG_TEST_VERBOSE")) fputs(text, stdout);
            free(text);
        }
    }
    char buf[256];
    pg_stage_names(0, buf, sizeof buf);
    CHECK(strcmp(buf, "none") == 0);
    pg_stage_names(S_TESTS | S_COPY, buf, sizeof buf);
    CHECK(strcmp(buf, "early_tests|late_tests|copy") == 0);
    pg_access_mask_names(A_SAMPLED | A_CW, buf, sizeof buf);
    CHECK(strcmp(buf, "color_write|sampled_read") == 0);
    pg_access_mask_names(1ull << 60, buf, sizeof buf);
    CHECK(strcmp(buf, "0x1000000000000000") == 0);
    pg_stage_names(S_TESTS, buf, 8); /* truncates safely */
    CHECK(strlen(buf) == 7);
    CHECK(strcmp(pg_layout_name(L_DRO), "depth_read_only") == 0);
    CHECK(strcmp(pg_layout_name(12345), "?") == 0);
    CHECK(strcmp(pg_lifetime_name(PG_LIFETIME_IMPORTED), "imported") == 0);
    pg_graph_plan_free(p);
    pl_free(pl);
}

/* A slot declared unused (0 lights) creates no dependency, barrier or lifetime: its producer and
 * the resource are culled; with lights everything runs. */
static void test_unused_slots(void)
{
    for (int lights = 0; lights < 2; lights++) {
        pg_pipeline *pl = pl_new("out");
        buf(pl, "buf", 32, 0);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "Make", "fake_compute_buf", "", "buf");
        pass(pl, "Use", "fake_buf_maybe", "buf", "out");
        pg_compile_desc d = desc_of(pl);
        pg_vars_set(&d.vars, "lights", lights, NULL);
        pg_graph_plan *p = compile_d(&d, __LINE__);
        if (p) {
            const pg_plan_pass *make = &p->passes[pidx(p, "Make")], *use = &p->passes[pidx(p, "Use")];
            if (lights == 0) {
                CHECK(make->culled && !use->culled && p->n_order == 1);
                CHECK(p->resources[0].culled);
                for (uint32_t b = 0; b < use->n_barriers; b++) CHECK(use->barriers[b].resource != 0);
                bool explained = false;
                for (uint32_t i = 0; i < p->n_explain; i++)
                    if (strstr(p->explain[i], "slot 'buf' unused: 0 lights")) explained = true;
                CHECK(explained);
            } else {
                CHECK(!make->culled && !use->culled && p->n_order == 2);
                CHECK(use->n_barriers >= 1 && use->barriers[0].resource == 0);
            }
            pg_graph_plan_free(p);
        }
        pl_free(pl);
    }
}

/* pg_decl_skip: the pass is culled with its own reason (even with side effects), what only it
 * reads is culled too, and its RMW target passes through from the previous writer. */
static void test_skip(void)
{
    for (int blend = 0; blend < 2; blend++) {
        pg_pipeline *pl = pl_new("out");
        buf(pl, "tbuf", 32, 0);
        img(pl, "color", PG_FMT_RGBA16F);
        img(pl, "depth", PG_FMT_D32F);
        img(pl, "out", PG_FMT_RGBA8_UNORM);
        pass(pl, "Make", "fake_compute_buf", "", "tbuf");
        pass(pl, "Opaque", "fake_depth_color", "", "color, depth");
        pass(pl, "Trans", "fake_transparent", "tbuf, depth", "color");
        pass(pl, "Final", "fake_blur", "color", "out");
        pg_compile_desc d = desc_of(pl);
        pg_vars_set(&d.vars, "has_blend", blend == 1, NULL);
        pg_graph_plan *p = compile_d(&d, __LINE__);
        if (p) {
            const pg_plan_pass *t = &p->passes[pidx(p, "Trans")];
            if (!blend) {
                CHECK(t->culled && p->n_order == 2 && pos(p, "Opaque") == 0 && pos(p, "Final") == 1);
                CHECK_MSG(strcmp(t->cull_reason, "no BLEND materials: no transparent pass") == 0, "%s",
                          t->cull_reason);
                CHECK(explain_has(p, "culled pass 'Trans': no BLEND materials: no transparent pass"));
                CHECK(p->passes[pidx(p, "Make")].culled && res(p, "tbuf")->culled);
                CHECK(!res(p, "depth")->culled && !res(p, "color")->culled);
                /* Final reads what Opaque wrote: one barrier from the colour attachment write */
                const pg_barrier *b = barrier_for(p, "Final", "color");
                CHECK(b && b->src_stages == VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT &&
                      b->old_layout == VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL &&
                      b->new_layout == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
                CHECK(res(p, "color")->usage == (VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT));
                CHECK(res(p, "depth")->last_pass == 0);
            } else {
                CHECK(!t->culled && p->n_order == 4 && pos(p, "Trans") == 2 && pos(p, "Final") == 3);
                CHECK(!res(p, "tbuf")->culled && res(p, "depth")->last_pass == 2);
                const pg_barrier *b = barrier_for(p, "Trans", "depth");
                CHECK(b && b->new_layout == VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL);
                CHECK(n_barriers_for(p, "Trans", "color") == 1);
            }
            pg_graph_plan_free(p);
        }
        pl_free(pl);
    }
    /* a skipped pass cannot be the only producer of an output */
    pg_pipeline *pl = pl_new("color");
    buf(pl, "tbuf", 32, 0);
    img_l(pl, "color", PG_FMT_RGBA16F, PG_LIFETIME_PERSISTENT);
    img_l(pl, "depth", PG_FMT_D32F, PG_LIFETIME_PERSISTENT);
    pass(pl, "Make", "fake_compute_buf", "", "tbuf");
    pass(pl, "Trans", "fake_transparent", "tbuf, depth", "color");
    const char *m = FAIL(pl, PG_ERR_NO_OUTPUT);
    HAS(m, "'color' is written only by pass 'Trans', which is skipped for this scene (no BLEND materials");
    pl_free(pl);
}

/* ------------------------------------------------------------------------------------------ */
/* typed, versioned handles; immediate mode                                                   */

static void test_handles(void)
{
    pg_pipeline *pl = chain_pipeline("fake_blur");
    pg_graph_plan *a = COMPILE(pl);
    pg_graph_plan *a2 = COMPILE(pl); /* the same plan again: the same generation */
    pg_compile_desc d = desc_of(pl);
    d.output_width = 50; /* another size: another plan */
    pg_graph_plan *b = compile_d(&d, __LINE__);
    if (a && a2 && b) {
        CHECK(a->generation != 0 && a->generation == a2->generation && a->generation != b->generation);
        pg_error err = {0};
        pg_res_handle h;
        pg_pass_handle ph;
        const pg_plan_resource *r = NULL;
        const pg_plan_pass *pp = NULL;
        CHECK(pg_plan_find_resource(a, "t3", &h, &err) == PG_OK && h.index == (uint32_t)ridx(a, "t3") &&
              h.generation == a->generation);
        CHECK(pg_plan_resource_get(a, h, &r, &err) == PG_OK && r == &a->resources[ridx(a, "t3")]);
        CHECK(pg_plan_resource_get(a2, h, &r, &err) == PG_OK && r == &a2->resources[ridx(a2, "t3")]);
        /* a handle from another plan is caught */
        CHECK(pg_plan_resource_get(b, h, &r, &err) == PG_ERR_INVALID_ARG && r == NULL);
        char want[256];
        snprintf(want, sizeof want,
                 "stale resource handle #%u: it is from another compiled plan (generation %016llx, this plan's is "
                 "%016llx); look the name up again in this plan",
                 h.index, (unsigned long long)a->generation, (unsigned long long)b->generation);
        CHECK_MSG(strcmp(err.msg, want) == 0, "%s", err.msg);
        CHECK(pg_plan_find_pass(a, "C", &ph, &err) == PG_OK && ph.index == (uint32_t)pidx(a, "C"));
        CHECK(pg_plan_pass_get(a, ph, &pp, &err) == PG_OK && pp == &a->passes[pidx(a, "C")]);
        CHECK(pg_plan_pass_get(b, ph, &pp, &err) == PG_ERR_INVALID_ARG && pp == NULL);
        HAS(err.msg, "stale pass handle #2: it is from another compiled plan");
        /* unknown names, the zero handle, out of range */
        CHECK(pg_plan_find_resource(a, "nope", &h, &err) == PG_ERR_UNKNOWN_RESOURCE && h.generation == 0);
        CHECK_MSG(strcmp(err.msg, "the compiled graph has no resource 'nope'") == 0, "%s", err.msg);
        CHECK(pg_plan_find_pass(a, "nope", &ph, &err) == PG_ERR_UNKNOWN_PASS);
        CHECK(pg_plan_resource_get(a, h, &r, &err) == PG_ERR_INVALID_ARG);
        HAS(err.msg, "not a handle (generation 0)");
        h.generation = a->generation;
        h.index = a->n_resources;
        CHECK(pg_plan_resource_get(a, h, &r, &err) == PG_ERR_INVALID_ARG);
        HAS(err.msg, "out of range");
    }
    pg_graph_plan_free(a);
    pg_graph_plan_free(a2);
    pg_graph_plan_free(b);
    pl_free(pl);
}

static void test_immediate(void)
{
    pg_pipeline *pl = chain_pipeline("fake_blur");
    pg_graph_plan *p = COMPILE(pl);
    pg_compile_desc d = desc_of(pl);
    d.immediate = true;
    pg_graph_plan *q = compile_d(&d, __LINE__);
    if (p && q) {
        CHECK(!p->immediate && !p->aliasing_disabled && p->transient_bytes_aliased < p->transient_bytes_unaliased);
        CHECK(q->immediate && q->aliasing_disabled && q->transient_bytes_aliased == q->transient_bytes_unaliased);
        CHECK(q->n_order == p->n_order && !memcmp(q->order, p->order, sizeof p->order));
        const uint64_t all = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, A_MW = VK_ACCESS_2_MEMORY_WRITE_BIT,
                       rw = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
        uint32_t nb = 0;
        for (uint32_t k = 0; k < q->n_order; k++) {
            const pg_plan_pass *pp = &q->passes[q->order[k]];
            for (uint32_t b = 0; b < pp->n_barriers; b++, nb++) {
                const pg_barrier *x = &pp->barriers[b];
                CHECK(x->src_stages == all && x->src_access == A_MW && x->dst_stages == all && x->dst_access == rw);
            }
        }
        for (uint32_t b = 0; b < q->n_final_barriers; b++)
            CHECK(q->final_barriers[b].dst_stages == all && q->final_barriers[b].new_layout == L_TSRC);
        /* layouts still right: t1 colour attachment in A, sampled in B */
        const pg_barrier *b = barrier_for(q, "B", "t1");
        CHECK(b && b->old_layout == L_COLOR && b->new_layout == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        b = barrier_for(q, "A", "t1");
        CHECK(b && b->old_layout == L_UNDEF && b->new_layout == L_COLOR);
        CHECK(nb >= 7);
        CHECK(p->generation != q->generation);
        /* the report says so */
        FILE *f = tmpfile();
        if (f) {
            pg_graph_plan_print(q, pl, f);
            rewind(f);
            char text[8192];
            size_t n = fread(text, 1, sizeof text - 1, f);
            text[n] = 0;
            fclose(f);
            HAS(text, "mode: immediate (declaration order, no aliasing, before every pass a full barrier "
                      "all_commands/memory_write -> all_commands/memory_read|memory_write)");
        }
    }
    pg_graph_plan_free(p);
    pg_graph_plan_free(q);
    pl_free(pl);
}

/* A pass type that lists run-time options must mark where its params hold them
 * (pg_decl_runtime_param): else the runtime could not tell a new value from a new pipeline. */
static pg_result rt_update(void *self, const void *params, pg_error *err)
{
    (void)self, (void)params, (void)err;
    return PG_OK;
}
static pg_result d_rt_marked(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    pg_result r = pg_fake_color(in, d, e);
    float *gain = pg_decl_params(d, sizeof *gain);
    *gain = 2.0f;
    pg_decl_runtime_param(d, gain, sizeof *gain);
    return r;
}
static void test_runtime_params(void)
{
    static const char *const rt_opts[] = {"gain", NULL};
    static const pg_pass_type unmarked = {.name = "fake_rt_unmarked", .summary = "test", .declare = pg_fake_color,
                                          .runtime_options = rt_opts, .update = rt_update};
    static const pg_pass_type marked = {.name = "fake_rt_marked", .summary = "test", .declare = d_rt_marked,
                                        .params_size = sizeof(float), .runtime_options = rt_opts,
                                        .update = rt_update};
    pg_pass_registry reg = g_reg;
    pg_error err = {0};
    CHECK(pg_registry_add(&reg, &unmarked, &err) == PG_OK && pg_registry_add(&reg, &marked, &err) == PG_OK);
    for (int m = 0; m < 2; m++) {
        pg_pipeline *pl = pl_new("color");
        img(pl, "color", PG_FMT_RGBA8_UNORM);
        pass(pl, "A", m ? "fake_rt_marked" : "fake_rt_unmarked", "", "color");
        pg_compile_desc d = desc_of(pl);
        d.registry = &reg;
        pg_graph_plan *p = NULL;
        memset(&err, 0, sizeof err);
        pg_result r = pg_graph_compile(&d, &p, &err);
        if (m) {
            CHECK_MSG(r == PG_OK, "marked: %s", err.msg);
            CHECK(p && p->passes[0].decl.n_runtime_params == 1 && p->passes[0].decl.runtime_params[0].offset == 0 &&
                  p->passes[0].decl.runtime_params[0].size == sizeof(float));
        } else {
            CHECK_MSG(r == PG_ERR_INVALID_ARG &&
                          strstr(err.msg, "lists run-time options but marks no run-time field of its params"),
                      "unmarked: %s %s", pg_result_name(r), err.msg);
        }
        pg_graph_plan_free(p);
        pl_free(pl);
    }
}

int main(void)
{
    for (size_t i = 0; i < sizeof g_types / sizeof g_types[0]; i++) {
        pg_error err = {0};
        CHECK_MSG(pg_registry_add(&g_reg, &g_types[i], &err) == PG_OK, "%s", err.msg);
    }
    test_registry();
    test_runtime_params();
    test_order();
    test_errors();
    test_culling();
    test_lifetimes();
    test_aliasing();
    test_grow_not_aliased();
    test_barriers();
    test_random();
    test_report();
    test_unused_slots();
    test_skip();
    test_handles();
    test_immediate();
    return pg_test_finish("test_graph_compile");
}
