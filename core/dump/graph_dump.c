/* graph_dump.c - text, JSON, Graphviz DOT and memory-timeline SVG views of a compiled graph
 * (see graph_dump.h; the formats are documented in docs/dump-format.md).
 *
 * Everything here reads the plan only. pg_dump_run_graphviz() at the end is the one function
 * with a side effect: it runs `dot` through posix_spawnp (no shell). */
#include "graph_dump.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <inttypes.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

/* ------------------------------------------------------------------------------------------ */
/* shared helpers                                                                             */

/* "12.5 MiB" style, as graph_report.c prints it */
static void fmt_bytes(uint64_t b, char *buf, size_t size)
{
    if (b >= (1ull << 30))
        snprintf(buf, size, "%.2f GiB", (double)b / (double)(1ull << 30));
    else if (b >= (1ull << 20))
        snprintf(buf, size, "%.2f MiB", (double)b / (double)(1ull << 20));
    else if (b >= 1024)
        snprintf(buf, size, "%.1f KiB", (double)b / 1024.0);
    else
        snprintf(buf, size, "%" PRIu64 " B", b);
}

static bool res_ok(const pg_graph_plan *plan, int r)
{
    return r >= 0 && (uint32_t)r < plan->n_resources;
}

static const char *res_name(const pg_graph_plan *plan, int r)
{
    return res_ok(plan, r) ? plan->resources[r].name : "?";
}

static const char *type_name(const pg_plan_pass *pp)
{
    return pp->type && pp->type->name ? pp->type->name : "?";
}

/* name of the executed pass at position pos; "(end)" past the last pass */
static const char *pass_at(const pg_graph_plan *plan, int pos)
{
    if (pos < 0) return NULL;
    if ((uint32_t)pos >= plan->n_order) return "(end)";
    return plan->passes[plan->order[pos]].name;
}

/* position of pass index p in the execution order, -1 when culled */
static int position_of(const pg_graph_plan *plan, uint32_t p)
{
    for (uint32_t k = 0; k < plan->n_order; k++)
        if (plan->order[k] == (int)p) return (int)k;
    return -1;
}

static uint32_t count_barriers(const pg_graph_plan *plan)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < plan->n_passes; i++) n += plan->passes[i].n_barriers;
    return n;
}

static uint32_t count_culled_passes(const pg_graph_plan *plan)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < plan->n_passes; i++) n += plan->passes[i].culled;
    return n;
}

static double saving_percent(const pg_graph_plan *plan)
{
    if (!plan->transient_bytes_unaliased || plan->transient_bytes_aliased > plan->transient_bytes_unaliased)
        return 0.0;
    return 100.0 * (double)(plan->transient_bytes_unaliased - plan->transient_bytes_aliased) /
           (double)plan->transient_bytes_unaliased;
}

/* Colours of memory blocks, shared by the DOT graph and the timeline (ColorBrewer Set3: light
 * enough for black text). stroke is a darker shade of the same hue. */
static const char *const k_block_fill[] = {"#8dd3c7", "#ffffb3", "#bebada", "#fb8072",
                                           "#80b1d3", "#fdb462", "#b3de69", "#fccde5",
                                           "#bc80bd", "#ccebc5", "#ffed6f", "#d9d9d9"};
static const char *const k_block_stroke[] = {"#3c8c80", "#a6a64d", "#6f6a99", "#b04032",
                                             "#3a6f94", "#b06e1c", "#6a9a22", "#b06e99",
                                             "#7a3f7b", "#6e9a6a", "#a89a1a", "#808080"};
#define N_BLOCK_COLOURS (sizeof k_block_fill / sizeof k_block_fill[0])

/* ------------------------------------------------------------------------------------------ */
/* short names for edge labels                                                                */

/* Access mask -> "color", "sampled", "depth", "storage" ... (read/write suffixes dropped: the
 * hazard name says which side writes), joined with '+'; "-" for none. */
static void short_access(uint64_t access, char *buf, size_t size)
{
    char names[256];
    pg_access_mask_names(access, names, sizeof names);
    buf[0] = 0;
    if (!strcmp(names, "none")) {
        pg_strlcpy(buf, "-", size);
        return;
    }
    size_t len = 0;
    char *save = NULL;
    for (char *t = strtok_r(names, "|", &save); t; t = strtok_r(NULL, "|", &save)) {
        char word[64];
        pg_strlcpy(word, t, sizeof word);
        size_t wl = strlen(word);
        if (wl > 6 && !strcmp(word + wl - 6, "_write")) word[wl - 6] = 0;
        else if (wl > 5 && !strcmp(word + wl - 5, "_read")) word[wl - 5] = 0;
        /* skip duplicates ("depth_read|depth_write" -> "depth") */
        bool dup = false;
        char *s = buf;
        while (*s) {
            size_t n = strcspn(s, "+");
            if (n == strlen(word) && !strncmp(s, word, n)) dup = true;
            s += n;
            if (*s) s++;
        }
        if (dup) continue;
        int w = snprintf(buf + len, size > len ? size - len : 0, "%s%s", len ? "+" : "", word);
        if (w < 0) break;
        len += (size_t)w;
        if (len >= size) break;
    }
}

static const char *short_layout(uint32_t layout)
{
    const char *n = pg_layout_name(layout);
    if (!strcmp(n, "undefined")) return "undef";
    if (!strcmp(n, "color_attachment")) return "color_att";
    if (!strcmp(n, "depth_stencil_attachment")) return "ds_att";
    if (!strcmp(n, "depth_stencil_read_only")) return "ds_ro";
    if (!strcmp(n, "depth_attachment")) return "depth_att";
    if (!strcmp(n, "depth_read_only")) return "depth_ro";
    if (!strcmp(n, "shader_read_only")) return "shader_ro";
    if (!strcmp(n, "transfer_src")) return "xfer_src";
    if (!strcmp(n, "transfer_dst")) return "xfer_dst";
    return n;
}

void pg_dump_barrier_label(const pg_graph_plan *plan, const pg_barrier *b, char *buf, size_t size)
{
    if (!buf || !size) return;
    char sa[128], da[128], why[96];
    short_access(b->src_access, sa, sizeof sa);
    short_access(b->dst_access, da, sizeof da);
    pg_strlcpy(why, b->why, sizeof why);
    if (b->alias_prev >= 0 && plan && res_ok(plan, b->alias_prev)) {
        /* "alias first use" -> "alias after depth" */
        snprintf(why, sizeof why, "alias after %s", plan->resources[b->alias_prev].name);
    }
    int w = b->src_access ? snprintf(buf, size, "%s%s %s\xe2\x86\x92%s", why, b->wrap ? " (prev frame)" : "", sa, da)
                          : snprintf(buf, size, "%s%s: %s", why, b->wrap ? " (prev frame)" : "", da);
    if (w < 0 || (size_t)w >= size) return;
    if (b->is_image && b->old_layout != b->new_layout)
        snprintf(buf + w, size - (size_t)w, "\n%s\xe2\x86\x92%s", short_layout(b->old_layout),
                 short_layout(b->new_layout));
}

/* ------------------------------------------------------------------------------------------ */
/* text                                                                                       */

void pg_dump_text(const pg_graph_plan *plan, const pg_pipeline *pipeline, FILE *f)
{
    if (!f) return;
    if (!plan) {
        fprintf(f, "(no plan)\n");
        return;
    }
    if (pipeline) {
        if (pipeline->description[0]) fprintf(f, "description: %s\n", pipeline->description);
        fprintf(f, "parameters:%s", pipeline->n_params ? "" : " none");
        for (uint32_t i = 0; i < pipeline->n_params && i < PG_MAX_PARAMS; i++) {
            char v[PG_NAME_MAX + 32];
            pg_param_format(&pipeline->params[i], v, sizeof v);
            fprintf(f, " %s=%s%s", pipeline->params[i].name, v,
                    pipeline->params[i].overridden ? " (--set)" : "");
        }
        fprintf(f, "\n");
    }
    pg_graph_plan_print(plan, pipeline, f);
}

/* ------------------------------------------------------------------------------------------ */
/* JSON                                                                                       */

/* Adds an exact unsigned integer (cJSON's numbers are doubles: raw text keeps 64 bits). */
static bool add_u64(cJSON *o, const char *key, uint64_t v)
{
    char t[32];
    snprintf(t, sizeof t, "%" PRIu64, v);
    return cJSON_AddRawToObject(o, key, t) != NULL;
}

static bool add_str_or_null(cJSON *o, const char *key, const char *s)
{
    return (s ? cJSON_AddStringToObject(o, key, s) : cJSON_AddNullToObject(o, key)) != NULL;
}

static bool add_int_or_null(cJSON *o, const char *key, bool present, int v)
{
    return (present ? cJSON_AddNumberToObject(o, key, v) : cJSON_AddNullToObject(o, key)) != NULL;
}

/* "a|b|c" -> ["a", "b", "c"] */
static cJSON *names_array(const char *joined)
{
    cJSON *a = cJSON_CreateArray();
    if (!a) return NULL;
    char tmp[512];
    pg_strlcpy(tmp, joined, sizeof tmp);
    if (!strcmp(tmp, "none")) return a;
    char *save = NULL;
    for (char *t = strtok_r(tmp, "|", &save); t; t = strtok_r(NULL, "|", &save)) {
        cJSON *s = cJSON_CreateString(t);
        if (!s) {
            cJSON_Delete(a);
            return NULL;
        }
        cJSON_AddItemToArray(a, s);
    }
    return a;
}

static bool add_stage_names(cJSON *o, const char *key, uint64_t stages)
{
    char buf[512];
    pg_stage_names(stages, buf, sizeof buf);
    cJSON *a = names_array(buf);
    return a && cJSON_AddItemToObject(o, key, a);
}

static bool add_access_names(cJSON *o, const char *key, uint64_t access)
{
    char buf[512];
    pg_access_mask_names(access, buf, sizeof buf);
    cJSON *a = names_array(buf);
    return a && cJSON_AddItemToObject(o, key, a);
}

static cJSON *json_barrier(const pg_graph_plan *plan, const pg_barrier *b)
{
    cJSON *o = cJSON_CreateObject();
    if (!o) return NULL;
    bool ok = cJSON_AddStringToObject(o, "resource", res_name(plan, b->resource)) &&
              cJSON_AddStringToObject(o, "why", b->why) &&
              add_stage_names(o, "src_stages", b->src_stages) &&
              add_access_names(o, "src_access", b->src_access) &&
              add_stage_names(o, "dst_stages", b->dst_stages) &&
              add_access_names(o, "dst_access", b->dst_access) &&
              add_str_or_null(o, "old_layout", b->is_image ? pg_layout_name(b->old_layout) : NULL) &&
              add_str_or_null(o, "new_layout", b->is_image ? pg_layout_name(b->new_layout) : NULL) &&
              add_str_or_null(o, "after_alias_of",
                              b->alias_prev >= 0 && res_ok(plan, b->alias_prev)
                                  ? plan->resources[b->alias_prev].name
                                  : NULL) &&
              cJSON_AddBoolToObject(o, "wrap", b->wrap);
    if (!ok) {
        cJSON_Delete(o);
        return NULL;
    }
    return o;
}

static bool add_barriers(cJSON *o, const char *key, const pg_graph_plan *plan, const pg_barrier *bs,
                         uint32_t n)
{
    cJSON *a = cJSON_AddArrayToObject(o, key);
    if (!a) return false;
    for (uint32_t i = 0; i < n; i++) {
        cJSON *b = json_barrier(plan, &bs[i]);
        if (!b) return false;
        cJSON_AddItemToArray(a, b);
    }
    return true;
}

static cJSON *json_slot(const pg_graph_plan *plan, const pg_plan_slot *sl)
{
    cJSON *o = cJSON_CreateObject();
    if (!o) return NULL;
    const bool image = res_ok(plan, sl->resource) && plan->resources[sl->resource].kind == PG_RES_IMAGE;
    bool ok = cJSON_AddStringToObject(o, "resource", res_name(plan, sl->resource)) &&
              cJSON_AddStringToObject(o, "slot", sl->decl.name) &&
              cJSON_AddStringToObject(o, "access", pg_access_name(sl->decl.access)) &&
              cJSON_AddBoolToObject(o, "unused", sl->decl.unused) &&
              cJSON_AddBoolToObject(o, "initializes", sl->decl.initializes) &&
              cJSON_AddBoolToObject(o, "partial", sl->decl.partial) &&
              add_stage_names(o, "stages", sl->decl.unused ? 0 : sl->sync.stages) &&
              add_str_or_null(o, "layout", image && !sl->decl.unused ? pg_layout_name(sl->sync.layout) : NULL);
    if (!ok) {
        cJSON_Delete(o);
        return NULL;
    }
    return o;
}

/* reads and writes of a pass: full slot objects (executed passes) or names (culled ones) */
static bool add_slots(cJSON *o, const pg_graph_plan *plan, const pg_plan_pass *pp, bool names_only)
{
    for (int w = 0; w < 2; w++) {
        cJSON *a = cJSON_AddArrayToObject(o, w ? "writes" : "reads");
        if (!a) return false;
        for (uint32_t s = 0; s < pp->n_slots && s < 2 * PG_MAX_SLOTS; s++) {
            const pg_plan_slot *sl = &pp->slots[s];
            if (sl->is_write != (w == 1)) continue;
            cJSON *item = names_only ? cJSON_CreateString(res_name(plan, sl->resource)) : json_slot(plan, sl);
            if (!item) return false;
            cJSON_AddItemToArray(a, item);
        }
    }
    return true;
}

static bool add_string_list(cJSON *o, const char *key, const char (*list)[PG_NAME_MAX], uint32_t n)
{
    cJSON *a = cJSON_AddArrayToObject(o, key);
    if (!a) return false;
    for (uint32_t i = 0; i < n; i++) {
        cJSON *s = cJSON_CreateString(list[i]);
        if (!s) return false;
        cJSON_AddItemToArray(a, s);
    }
    return true;
}

static bool add_explain_list(cJSON *o, const char *key, const char (*list)[PG_EXPLAIN_MAX], uint32_t n)
{
    cJSON *a = cJSON_AddArrayToObject(o, key);
    if (!a) return false;
    for (uint32_t i = 0; i < n; i++) {
        cJSON *s = cJSON_CreateString(list[i]);
        if (!s) return false;
        cJSON_AddItemToArray(a, s);
    }
    return true;
}

static bool json_pipeline(cJSON *root, const pg_pipeline *pl)
{
    cJSON *o = cJSON_AddObjectToObject(root, "pipeline");
    if (!o) return false;
    if (!pl) {
        return cJSON_AddNullToObject(o, "name") && cJSON_AddNullToObject(o, "path") &&
               cJSON_AddNullToObject(o, "description") && cJSON_AddObjectToObject(o, "parameters") &&
               cJSON_AddArrayToObject(o, "overridden");
    }
    if (!cJSON_AddStringToObject(o, "name", pl->name) || !cJSON_AddStringToObject(o, "path", pl->path) ||
        !cJSON_AddStringToObject(o, "description", pl->description))
        return false;
    cJSON *params = cJSON_AddObjectToObject(o, "parameters");
    cJSON *over = cJSON_CreateArray();
    if (!params || !over) {
        cJSON_Delete(over);
        return false;
    }
    cJSON_AddItemToObject(o, "overridden", over);
    for (uint32_t i = 0; i < pl->n_params && i < PG_MAX_PARAMS; i++) {
        const pg_param *p = &pl->params[i];
        cJSON *v = NULL;
        switch (p->type) {
        case PG_PARAM_INT:
        case PG_PARAM_FLOAT: v = cJSON_CreateNumber(p->number); break;
        case PG_PARAM_BOOL: v = cJSON_CreateBool(p->boolean); break;
        case PG_PARAM_ENUM: v = cJSON_CreateString(p->enum_value); break;
        }
        if (!v) return false;
        cJSON_AddItemToObject(params, p->name, v);
        if (p->overridden) {
            cJSON *n = cJSON_CreateString(p->name);
            if (!n) return false;
            cJSON_AddItemToArray(over, n);
        }
    }
    return true;
}

/* "queues": every executed pass's queue and batch, the batches with their waits, and the
 * ownership transfers (docs/dump-format.md). */
static bool json_queues(cJSON *root, const pg_graph_plan *plan)
{
    cJSON *q = cJSON_AddObjectToObject(root, "queues");
    if (!q || !cJSON_AddBoolToObject(q, "ownership_transfers", plan->qfot)) return false;
    cJSON *pa = cJSON_AddArrayToObject(q, "passes");
    if (!pa) return false;
    for (uint32_t k = 0; k < plan->n_order; k++) {
        const pg_plan_pass *pp = &plan->passes[plan->order[k]];
        cJSON *o = cJSON_CreateObject();
        if (!o) return false;
        cJSON_AddItemToArray(pa, o);
        if (!cJSON_AddStringToObject(o, "name", pp->name) || !cJSON_AddStringToObject(o, "queue", pg_queue_name(pp->queue)) ||
            !cJSON_AddNumberToObject(o, "batch", pp->batch) || !cJSON_AddStringToObject(o, "why", pp->queue_reason))
            return false;
    }
    cJSON *ba = cJSON_AddArrayToObject(q, "batches");
    if (!ba) return false;
    for (uint32_t b = 0; b < plan->n_batches; b++) {
        const pg_plan_batch *bt = &plan->batches[b];
        cJSON *o = cJSON_CreateObject(), *names = cJSON_CreateArray();
        if (!o || !names) {
            cJSON_Delete(o);
            cJSON_Delete(names);
            return false;
        }
        cJSON_AddItemToArray(ba, o);
        cJSON_AddItemToObject(o, "passes", names);
        for (uint32_t k = bt->first; k < bt->first + bt->count; k++)
            cJSON_AddItemToArray(names, cJSON_CreateString(plan->passes[plan->order[k]].name));
        if (!cJSON_AddStringToObject(o, "queue", pg_queue_name(bt->queue)) || !cJSON_AddBoolToObject(o, "last", bt->last) ||
            !add_int_or_null(o, "waits_previous_frame", bt->prev_frame_wait >= 0, bt->prev_frame_wait))
            return false;
        cJSON *wa = cJSON_AddArrayToObject(o, "waits");
        if (!wa) return false;
        for (uint32_t w = 0; w < bt->n_waits; w++) {
            cJSON *x = cJSON_CreateObject();
            if (!x) return false;
            cJSON_AddItemToArray(wa, x);
            if (!cJSON_AddNumberToObject(x, "batch", bt->waits[w].batch) || !add_stage_names(x, "stages", bt->waits[w].stages) ||
                !cJSON_AddStringToObject(x, "why", bt->waits[w].why))
                return false;
        }
    }
    cJSON *ta = cJSON_AddArrayToObject(q, "ownership");
    if (!ta) return false;
    for (uint32_t i = 0; i < plan->n_qfots; i++) {
        const pg_qfot *t = &plan->qfots[i];
        cJSON *x = cJSON_CreateObject();
        if (!x) return false;
        cJSON_AddItemToArray(ta, x);
        if (!cJSON_AddStringToObject(x, "resource", res_name(plan, t->resource)) ||
            !cJSON_AddStringToObject(x, "from", pg_queue_name(t->src_queue)) ||
            !cJSON_AddStringToObject(x, "to", pg_queue_name(t->dst_queue)) ||
            !cJSON_AddNumberToObject(x, "release_batch", t->release_batch) ||
            !cJSON_AddNumberToObject(x, "acquire_batch", t->acquire_batch) ||
            !add_stage_names(x, "release_stages", t->src_stages) || !add_access_names(x, "release_access", t->src_access) ||
            !add_stage_names(x, "acquire_stages", t->dst_stages) || !add_access_names(x, "acquire_access", t->dst_access) ||
            !add_str_or_null(x, "old_layout", t->is_image ? pg_layout_name(t->old_layout) : NULL) ||
            !add_str_or_null(x, "new_layout", t->is_image ? pg_layout_name(t->new_layout) : NULL))
            return false;
    }
    return true;
}

static bool json_body(cJSON *root, const pg_graph_plan *plan, const pg_pipeline *pl)
{
    if (!cJSON_AddNumberToObject(root, "format_version", PG_DUMP_FORMAT_VERSION)) return false;
    if (!json_pipeline(root, pl)) return false;

    /* output */
    cJSON *out = cJSON_AddObjectToObject(root, "output");
    if (!out) return false;
    const bool has_out = res_ok(plan, plan->output);
    const bool has_hdr = res_ok(plan, plan->hdr_output);
    if (!add_str_or_null(out, "resource", has_out ? plan->resources[plan->output].name : NULL) ||
        !add_str_or_null(out, "hdr_resource", has_hdr ? plan->resources[plan->hdr_output].name : NULL) ||
        !add_int_or_null(out, "width", has_out, has_out ? (int)plan->resources[plan->output].width : 0) ||
        !add_int_or_null(out, "height", has_out, has_out ? (int)plan->resources[plan->output].height : 0))
        return false;
    if (!cJSON_AddBoolToObject(root, "aliasing", !plan->aliasing_disabled)) return false;
    if (!cJSON_AddBoolToObject(root, "immediate", plan->immediate)) return false;

    /* order */
    cJSON *order = cJSON_AddArrayToObject(root, "order");
    if (!order) return false;
    for (uint32_t k = 0; k < plan->n_order; k++) {
        cJSON *s = cJSON_CreateString(plan->passes[plan->order[k]].name);
        if (!s) return false;
        cJSON_AddItemToArray(order, s);
    }

    /* executed passes */
    cJSON *passes = cJSON_AddArrayToObject(root, "passes");
    if (!passes) return false;
    for (uint32_t k = 0; k < plan->n_order; k++) {
        const pg_plan_pass *pp = &plan->passes[plan->order[k]];
        cJSON *o = cJSON_CreateObject();
        if (!o) return false;
        cJSON_AddItemToArray(passes, o);
        const uint32_t n_def = pp->decl.n_defines < PG_MAX_DEFINES ? pp->decl.n_defines : PG_MAX_DEFINES;
        const uint32_t n_exp = pp->decl.n_explain < PG_MAX_PASS_EXPLAIN ? pp->decl.n_explain : PG_MAX_PASS_EXPLAIN;
        if (!cJSON_AddNumberToObject(o, "position", k) || !cJSON_AddStringToObject(o, "name", pp->name) ||
            !cJSON_AddStringToObject(o, "type", type_name(pp)) ||
            !cJSON_AddNumberToObject(o, "declared_index", pp->desc_index) ||
            !cJSON_AddBoolToObject(o, "side_effects", pp->decl.side_effects ||
                                                          (pl && pp->desc_index >= 0 &&
                                                           (uint32_t)pp->desc_index < pl->n_passes &&
                                                           pl->passes[pp->desc_index].side_effects)) ||
            !add_barriers(o, "barriers", plan, pp->barriers,
                          pp->n_barriers < PG_MAX_BARRIERS_PER_PASS ? pp->n_barriers : PG_MAX_BARRIERS_PER_PASS) ||
            !add_slots(o, plan, pp, false) || !add_string_list(o, "defines", pp->decl.defines, n_def) ||
            !add_explain_list(o, "left_out", pp->decl.explain, n_exp))
            return false;
    }
    if (!add_barriers(root, "final_barriers", plan, plan->final_barriers,
                      plan->n_final_barriers < PG_MAX_RESOURCES ? plan->n_final_barriers : PG_MAX_RESOURCES))
        return false;

    /* culled passes (declaration order) */
    cJSON *culled = cJSON_AddArrayToObject(root, "culled_passes");
    if (!culled) return false;
    for (uint32_t i = 0; i < plan->n_passes; i++) {
        const pg_plan_pass *pp = &plan->passes[i];
        if (!pp->culled) continue;
        cJSON *o = cJSON_CreateObject();
        if (!o) return false;
        cJSON_AddItemToArray(culled, o);
        if (!cJSON_AddStringToObject(o, "name", pp->name) || !cJSON_AddStringToObject(o, "type", type_name(pp)) ||
            !cJSON_AddNumberToObject(o, "declared_index", pp->desc_index) ||
            !cJSON_AddStringToObject(o, "reason", pp->cull_reason) || !add_slots(o, plan, pp, true))
            return false;
    }

    /* omitted by "when" */
    cJSON *omitted = cJSON_AddArrayToObject(root, "omitted");
    if (!omitted) return false;
    for (uint32_t i = 0; pl && i < pl->n_omitted && i < PG_MAX_PASSES + PG_MAX_RESOURCES; i++) {
        cJSON *o = cJSON_CreateObject();
        if (!o) return false;
        cJSON_AddItemToArray(omitted, o);
        if (!cJSON_AddStringToObject(o, "what", pl->omitted[i].what) ||
            !cJSON_AddStringToObject(o, "why", pl->omitted[i].why))
            return false;
    }
    if (!add_explain_list(root, "explain", plan->explain, plan->n_explain < PG_MAX_EXPLAIN ? plan->n_explain : PG_MAX_EXPLAIN))
        return false;

    /* resources (declaration order) */
    cJSON *res = cJSON_AddArrayToObject(root, "resources");
    if (!res) return false;
    for (uint32_t r = 0; r < plan->n_resources; r++) {
        const pg_plan_resource *pr = &plan->resources[r];
        const bool image = pr->kind == PG_RES_IMAGE;
        const bool live = !pr->culled && pr->first_pass >= 0;
        cJSON *o = cJSON_CreateObject();
        if (!o) return false;
        cJSON_AddItemToArray(res, o);
        if (!cJSON_AddStringToObject(o, "name", pr->name) ||
            !cJSON_AddStringToObject(o, "kind", pg_res_kind_name(pr->kind)) ||
            !cJSON_AddStringToObject(o, "lifetime", pg_lifetime_name(pr->lifetime)) ||
            !add_str_or_null(o, "format", image ? pg_format_get(pr->format)->name : NULL) ||
            !add_int_or_null(o, "width", image, (int)pr->width) ||
            !add_int_or_null(o, "height", image, (int)pr->height) || !add_u64(o, "size_bytes", pr->size_bytes) ||
            !cJSON_AddBoolToObject(o, "output", pr->is_output) || !cJSON_AddBoolToObject(o, "grow", pr->growable) ||
            !cJSON_AddBoolToObject(o, "culled", pr->culled) ||
            !add_str_or_null(o, "cull_reason", pr->culled ? pr->cull_reason : NULL) ||
            !add_str_or_null(o, "first_pass", live ? pass_at(plan, pr->first_pass) : NULL) ||
            !add_str_or_null(o, "last_pass", live ? pass_at(plan, pr->last_pass) : NULL) ||
            !add_int_or_null(o, "first_position", live, pr->first_pass) ||
            !add_int_or_null(o, "last_position", live, pr->last_pass) ||
            !add_int_or_null(o, "block", pr->block >= 0, pr->block))
            return false;
        if (pr->block >= 0 ? !add_u64(o, "offset", pr->block_offset) : !cJSON_AddNullToObject(o, "offset"))
            return false;
    }

    /* memory blocks */
    cJSON *blocks = cJSON_AddArrayToObject(root, "blocks");
    if (!blocks) return false;
    for (uint32_t b = 0; b < plan->n_blocks; b++) {
        const pg_plan_block *bl = &plan->blocks[b];
        cJSON *o = cJSON_CreateObject();
        if (!o) return false;
        cJSON_AddItemToArray(blocks, o);
        cJSON *members;
        if (!cJSON_AddNumberToObject(o, "index", b) || !cJSON_AddStringToObject(o, "kind", pg_res_kind_name(bl->kind)) ||
            !add_u64(o, "size_bytes", bl->size_bytes) || !(members = cJSON_AddArrayToObject(o, "members")))
            return false;
        for (uint32_t m = 0; m < bl->n_members && m < PG_MAX_RESOURCES; m++) {
            const int r = bl->members[m];
            const pg_plan_resource *pr = res_ok(plan, r) ? &plan->resources[r] : NULL;
            cJSON *mo = cJSON_CreateObject();
            if (!mo) return false;
            cJSON_AddItemToArray(members, mo);
            if (!cJSON_AddStringToObject(mo, "resource", res_name(plan, r)) ||
                !add_u64(mo, "offset", pr ? pr->block_offset : 0) || !add_u64(mo, "size_bytes", pr ? pr->size_bytes : 0) ||
                !cJSON_AddNumberToObject(mo, "first_position", pr ? pr->first_pass : -1) ||
                !cJSON_AddNumberToObject(mo, "last_position", pr ? pr->last_pass : -1))
                return false;
        }
    }

    /* totals */
    uint32_t res_culled = 0;
    for (uint32_t r = 0; r < plan->n_resources; r++) res_culled += plan->resources[r].culled;
    cJSON *t = cJSON_AddObjectToObject(root, "totals");
    const bool ok = t && cJSON_AddNumberToObject(t, "passes_declared", plan->n_passes) &&
           cJSON_AddNumberToObject(t, "passes_run", plan->n_order) &&
           cJSON_AddNumberToObject(t, "passes_culled", count_culled_passes(plan)) &&
           cJSON_AddNumberToObject(t, "resources_declared", plan->n_resources) &&
           cJSON_AddNumberToObject(t, "resources_culled", res_culled) &&
           cJSON_AddNumberToObject(t, "omitted", pl ? pl->n_omitted : 0) &&
           cJSON_AddNumberToObject(t, "barriers", count_barriers(plan)) &&
           cJSON_AddNumberToObject(t, "final_barriers", plan->n_final_barriers) &&
           cJSON_AddNumberToObject(t, "blocks", plan->n_blocks) &&
           add_u64(t, "transient_bytes_unaliased", plan->transient_bytes_unaliased) &&
           add_u64(t, "transient_bytes_aliased", plan->transient_bytes_aliased) &&
           cJSON_AddNumberToObject(t, "saving_percent", (double)(int64_t)(saving_percent(plan) * 10.0 + 0.5) / 10.0);
    /* queues, after the existing keys (two-queue plans only; a one-queue plan has no such key) */
    return ok && (!plan->async || json_queues(root, plan));
}

char *pg_dump_json(const pg_graph_plan *plan, const pg_pipeline *pipeline)
{
    if (!plan) return NULL;
    cJSON *root = cJSON_CreateObject();
    if (!root) return NULL;
    char *printed = json_body(root, plan, pipeline) ? cJSON_Print(root) : NULL;
    cJSON_Delete(root);
    /* a copy from malloc, so callers free() it whatever hooks cJSON was given */
    char *text = printed ? strdup(printed) : NULL;
    cJSON_free(printed);
    return text;
}

/* ------------------------------------------------------------------------------------------ */
/* Graphviz DOT                                                                               */

/* Writes s escaped for a Graphviz HTML-like label ('\n' -> <br/>). */
static void html_esc(FILE *f, const char *s)
{
    for (; s && *s; s++) {
        switch (*s) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        case '\n': fputs("<br/>", f); break;
        default: fputc(*s, f);
        }
    }
}

/* Writes s escaped for a double-quoted DOT string ('\n' -> "\n", a centred line break). */
static void dot_esc(FILE *f, const char *s)
{
    for (; s && *s; s++) {
        if (*s == '"' || *s == '\\') fputc('\\', f);
        if (*s == '\n') fputs("\\n", f);
        else fputc(*s, f);
    }
}

/* Writes text word-wrapped at about width characters (HTML-escaped; lines joined with <br/>). */
static void html_wrapped(FILE *f, const char *text, size_t width)
{
    size_t col = 0;
    const char *p = text;
    while (p && *p) {
        size_t n = strcspn(p, " ");
        if (col && col + 1 + n > width) {
            fputs("<br/>", f);
            col = 0;
        } else if (col) {
            fputc(' ', f);
            col++;
        }
        char word[PG_EXPLAIN_MAX];
        size_t k = n < sizeof word - 1 ? n : sizeof word - 1;
        memcpy(word, p, k);
        word[k] = 0;
        html_esc(f, word);
        col += n;
        p += n;
        while (*p == ' ') p++;
    }
}

static void dot_pass_node(FILE *f, const pg_graph_plan *plan, uint32_t i)
{
    const pg_plan_pass *pp = &plan->passes[i];
    fprintf(f, "  p%u [", i);
    if (pp->culled)
        fputs("shape=box, style=\"rounded,dashed\", color=\"#9a9a9a\", fontcolor=\"#8a8a8a\", ", f);
    else
        fputs("shape=box, style=\"rounded,filled\", fillcolor=\"#dde8f8\", color=\"#3a66a8\", ", f);
    fputs("label=<<b>", f);
    html_esc(f, pp->name);
    fputs("</b><br/><font point-size=\"9\">", f);
    html_esc(f, type_name(pp));
    const int pos = position_of(plan, i);
    if (pos >= 0) fprintf(f, " \xc2\xb7 #%d", pos);
    fputs("</font>", f);
    if (pp->culled) {
        fputs("<br/><font point-size=\"8\"><i>culled: ", f);
        html_wrapped(f, pp->cull_reason, 40);
        fputs("</i></font>", f);
    } else {
        if (pp->decl.n_defines) {
            char defs[PG_MAX_DEFINES * (PG_NAME_MAX + 1)] = "";
            size_t len = 0;
            for (uint32_t d = 0; d < pp->decl.n_defines && d < PG_MAX_DEFINES; d++) {
                int w = snprintf(defs + len, sizeof defs - len, "%s%s", d ? " " : "", pp->decl.defines[d]);
                if (w < 0 || (size_t)w >= sizeof defs - len) break;
                len += (size_t)w;
            }
            fputs("<br/><font point-size=\"8\" color=\"#4a4a4a\">", f);
            html_wrapped(f, defs, 34);
            fputs("</font>", f);
        }
        for (uint32_t e = 0; e < pp->decl.n_explain && e < 8; e++) {
            fputs("<br/><font point-size=\"8\" color=\"#7a7a7a\"><i>", f);
            html_wrapped(f, pp->decl.explain[e], 40);
            fputs("</i></font>", f);
        }
    }
    fputs(">];\n", f);
}

static void dot_resource_node(FILE *f, const pg_graph_plan *plan, uint32_t r)
{
    const pg_plan_resource *pr = &plan->resources[r];
    char bytes[32];
    fmt_bytes(pr->size_bytes, bytes, sizeof bytes);
    fprintf(f, "  r%u [shape=note, ", r);
    if (pr->culled) {
        fputs("style=dashed, color=\"#9a9a9a\", fontcolor=\"#8a8a8a\", ", f);
    } else if (pr->block >= 0) {
        fprintf(f, "style=filled, fillcolor=\"%s\", color=\"%s\", ", k_block_fill[(uint32_t)pr->block % N_BLOCK_COLOURS],
                k_block_stroke[(uint32_t)pr->block % N_BLOCK_COLOURS]);
    } else {
        fputs("style=filled, fillcolor=\"#f4f4f4\", color=\"#505050\", ", f);
    }
    if (pr->is_output && !pr->culled) fputs("penwidth=2.2, ", f);
    fputs("label=<<b>", f);
    html_esc(f, pr->name);
    fputs("</b><br/><font point-size=\"9\">", f);
    if (pr->kind == PG_RES_IMAGE) {
        html_esc(f, pg_format_get(pr->format)->name);
        fprintf(f, " %u\xc3\x97%u \xc2\xb7 %s", pr->width, pr->height, bytes);
    } else {
        fprintf(f, "buffer \xc2\xb7 %s", bytes);
    }
    fputs("</font>", f);
    if (pr->culled) {
        fputs("<br/><font point-size=\"8\"><i>culled: ", f);
        html_wrapped(f, pr->cull_reason, 36);
        fputs("</i></font>", f);
    } else {
        fputs("<br/><font point-size=\"9\">", f);
        if (pr->block >= 0)
            fprintf(f, "block #%d @ %" PRIu64, pr->block, pr->block_offset);
        else
            fputs(pg_lifetime_name(pr->lifetime), f);
        if ((int)r == plan->output) fputs(" \xc2\xb7 <b>output</b>", f);
        else if ((int)r == plan->hdr_output) fputs(" \xc2\xb7 <b>hdr output</b>", f);
        fputs("</font>", f);
    }
    fputs(">];\n", f);
}

/* Label of the barriers placed at pass pp for resource r (several joined by '\n'). */
static size_t barrier_labels_for(const pg_graph_plan *plan, const pg_plan_pass *pp, int r, char *buf, size_t size)
{
    size_t len = 0, n = 0;
    buf[0] = 0;
    for (uint32_t b = 0; b < pp->n_barriers && b < PG_MAX_BARRIERS_PER_PASS; b++) {
        if (pp->barriers[b].resource != r) continue;
        char one[256];
        pg_dump_barrier_label(plan, &pp->barriers[b], one, sizeof one);
        int w = snprintf(buf + len, size - len, "%s%s", len ? "\n" : "", one);
        if (w < 0 || (size_t)w >= size - len) break;
        len += (size_t)w;
        n++;
    }
    return n;
}

static void dot_edges_of_pass(FILE *f, const pg_graph_plan *plan, uint32_t i)
{
    const pg_plan_pass *pp = &plan->passes[i];
    for (uint32_t s = 0; s < pp->n_slots && s < 2 * PG_MAX_SLOTS; s++) {
        const pg_plan_slot *sl = &pp->slots[s];
        if (!res_ok(plan, sl->resource)) continue;
        /* one edge per (resource, direction): skip a slot when an earlier one had the same */
        bool seen = false, all_unused = sl->decl.unused;
        for (uint32_t t = 0; t < s; t++)
            if (pp->slots[t].resource == sl->resource && pp->slots[t].is_write == sl->is_write) seen = true;
        if (seen) continue;
        char access[160] = "";
        size_t alen = 0;
        for (uint32_t t = s; t < pp->n_slots && t < 2 * PG_MAX_SLOTS; t++) {
            const pg_plan_slot *o = &pp->slots[t];
            if (o->resource != sl->resource || o->is_write != sl->is_write) continue;
            all_unused &= o->decl.unused;
            int w = snprintf(access + alen, sizeof access - alen, "%s%s %s", alen ? ", " : "", o->decl.name,
                             o->decl.unused ? "unused" : pg_access_name(o->decl.access));
            if (w > 0 && (size_t)w < sizeof access - alen) alen += (size_t)w;
        }
        /* the barriers for this resource go on the read edge when the pass reads it */
        bool reads_it = false;
        for (uint32_t t = 0; t < pp->n_slots && t < 2 * PG_MAX_SLOTS; t++)
            if (pp->slots[t].resource == sl->resource && !pp->slots[t].is_write && !pp->slots[t].decl.unused)
                reads_it = true;
        char label[1024] = "";
        size_t n_b = 0;
        if (!pp->culled && (sl->is_write ? !reads_it : true) && !all_unused)
            n_b = barrier_labels_for(plan, pp, sl->resource, label, sizeof label);
        if (sl->is_write)
            fprintf(f, "  p%u -> r%d [", i, sl->resource);
        else
            fprintf(f, "  r%d -> p%u [", sl->resource, i);
        if (all_unused)
            fputs("style=dotted, color=\"#a0a0a0\", fontcolor=\"#8a8a8a\", label=\"unused\", ", f);
        else if (pp->culled || plan->resources[sl->resource].culled)
            fputs("style=dashed, color=\"#a0a0a0\", ", f);
        else if (n_b) {
            fputs("color=\"#c0392b\", fontcolor=\"#a02818\", label=\"", f);
            dot_esc(f, label);
            fputs("\", ", f);
        }
        if (sl->is_write) fputs("penwidth=1.4, ", f);
        fputs("tooltip=\"", f);
        dot_esc(f, access);
        fputs("\"];\n", f);
    }
}

void pg_dump_dot(const pg_graph_plan *plan, const pg_pipeline *pipeline, FILE *f)
{
    if (!f) return;
    if (!plan) {
        fputs("digraph passgraph { label=\"(no plan)\"; }\n", f);
        return;
    }
    const char *font = "Helvetica,Arial,sans-serif";
    fputs("digraph passgraph {\n", f);
    fprintf(f, "  graph [rankdir=TB, fontname=\"%s\", fontsize=12, labelloc=t, labeljust=l, nodesep=0.22, "
               "ranksep=0.45, pad=0.25,\n         label=<<b>",
            font);
    html_esc(f, pipeline ? pipeline->name : "graph");
    fputs("</b>", f);
    if (pipeline && pipeline->path[0]) {
        fputs(" \xc2\xb7 ", f);
        html_esc(f, pipeline->path);
    }
    if (res_ok(plan, plan->output))
        fprintf(f, " \xc2\xb7 %u\xc3\x97%u", plan->resources[plan->output].width,
                plan->resources[plan->output].height);
    char un[32], al[32];
    fmt_bytes(plan->transient_bytes_unaliased, un, sizeof un);
    fmt_bytes(plan->transient_bytes_aliased, al, sizeof al);
    fprintf(f, "<br/><font point-size=\"10\">%u passes run, %u culled \xc2\xb7 %u barriers (+%u after the last pass) "
               "\xc2\xb7 transient memory %s \xe2\x86\x92 %s %s (saving %.1f%%)</font>",
            plan->n_order, count_culled_passes(plan), count_barriers(plan), plan->n_final_barriers, un, al,
            plan->aliasing_disabled ? "(aliasing disabled)" : "with aliasing", saving_percent(plan));
    fputs("<br/><font point-size=\"9\" color=\"#555555\">rounded box = pass (type \xc2\xb7 #execution position) "
          "\xc2\xb7 note = resource, colour = memory block \xc2\xb7 arrows: resource \xe2\x86\x92 pass = read, "
          "pass \xe2\x86\x92 resource = write<br/>red edge = barrier before the pass: hazard, access "
          "src\xe2\x86\x92" "dst, layout old\xe2\x86\x92new \xc2\xb7 plain edge = no barrier needed \xc2\xb7 "
          "dashed grey = culled or left out</font>>];\n",
          f);
    fprintf(f, "  node [fontname=\"%s\", fontsize=11, penwidth=1.2, margin=\"0.12,0.05\"];\n", font);
    fprintf(f, "  edge [fontname=\"%s\", fontsize=9, color=\"#606060\", arrowsize=0.7];\n\n", font);

    fputs("  // passes (p<index in the pipeline>)\n", f);
    for (uint32_t i = 0; i < plan->n_passes; i++) dot_pass_node(f, plan, i);
    fputs("\n  // resources (r<index in the pipeline>)\n", f);
    for (uint32_t r = 0; r < plan->n_resources; r++) {
        /* a culled resource no pass touches at all would float alone: still draw it */
        dot_resource_node(f, plan, r);
    }
    fputs("\n  // reads (resource -> pass) and writes (pass -> resource); labels = barriers before the pass\n", f);
    for (uint32_t i = 0; i < plan->n_passes; i++) dot_edges_of_pass(f, plan, i);

    if (plan->n_final_barriers) {
        fputs("\n  // after the last pass: outputs are read back\n", f);
        fputs("  readback [shape=cds, style=filled, fillcolor=\"#eeeeee\", color=\"#707070\", "
              "label=<<b>read back</b><br/><font point-size=\"9\">after the last pass</font>>];\n",
              f);
        for (uint32_t b = 0; b < plan->n_final_barriers && b < PG_MAX_RESOURCES; b++) {
            const pg_barrier *bar = &plan->final_barriers[b];
            if (!res_ok(plan, bar->resource)) continue;
            char label[256];
            pg_dump_barrier_label(plan, bar, label, sizeof label);
            fprintf(f, "  r%d -> readback [color=\"#c0392b\", fontcolor=\"#a02818\", style=dashed, label=\"",
                    bar->resource);
            dot_esc(f, label);
            fputs("\"];\n", f);
        }
    }

    if (pipeline && pipeline->n_omitted) {
        fputs("\n  // items dropped by a false 'when' condition (not in the plan)\n", f);
        fputs("  omitted [shape=note, style=dashed, color=\"#9a9a9a\", fontcolor=\"#7a7a7a\", "
              "label=<<table border=\"0\" cellspacing=\"0\" cellpadding=\"1\">"
              "<tr><td align=\"left\" colspan=\"2\"><b>left out by 'when'</b></td></tr>",
              f);
        for (uint32_t i = 0; i < pipeline->n_omitted && i < PG_MAX_PASSES + PG_MAX_RESOURCES; i++) {
            fputs("<tr><td align=\"left\">", f);
            html_esc(f, pipeline->omitted[i].what);
            fputs("</td><td align=\"left\"><font point-size=\"9\">", f);
            html_esc(f, pipeline->omitted[i].why);
            fputs("</font></td></tr>", f);
        }
        fputs("</table>>];\n", f);
        fputs("  { rank=sink; omitted; }\n", f);
    }
    fputs("}\n", f);
}

/* ------------------------------------------------------------------------------------------ */
/* memory timeline SVG                                                                        */

static void xml_esc(FILE *f, const char *s)
{
    for (; s && *s; s++) {
        switch (*s) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        case '\'': fputs("&apos;", f); break;
        default: fputc(*s, f);
        }
    }
}

/* Rough width of text in a sans-serif font of size px (Helvetica's average advance is ~0.55 em;
 * a little more so labels never overflow). Counts UTF-8 code points. */
static double text_w(const char *s, double px)
{
    size_t n = 0;
    for (; s && *s; s++)
        if (((unsigned char)*s & 0xc0) != 0x80) n++;
    return (double)n * px * 0.6;
}

/* Writes s XML-escaped, cut with an ellipsis to fit width pixels at font size px. */
static void xml_fit(FILE *f, const char *s, double width, double px)
{
    if (text_w(s, px) <= width) {
        xml_esc(f, s);
        return;
    }
    char cut[PG_NAME_MAX];
    size_t keep = width > px ? (size_t)(width / (px * 0.6)) : 1;
    if (keep > 1) keep--;
    if (keep >= sizeof cut) keep = sizeof cut - 1;
    pg_strlcpy(cut, s, keep + 1);
    /* do not split a UTF-8 sequence */
    size_t n = strlen(cut);
    while (n && ((unsigned char)cut[n - 1] & 0xc0) == 0x80) n--;
    if (n && ((unsigned char)cut[n - 1] & 0xc0) == 0xc0) n--;
    cut[n] = 0;
    xml_esc(f, cut);
    fputs("\xe2\x80\xa6", f);
}

void pg_dump_timeline_svg(const pg_graph_plan *plan, const pg_pipeline *pipeline, FILE *f)
{
    if (!f) return;
    const char *font = "Helvetica, Arial, sans-serif";
    if (!plan) {
        fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"200\" height=\"40\"><text x=\"10\" "
                   "y=\"24\" font-family=\"%s\">(no plan)</text></svg>\n",
                font);
        return;
    }
    /* geometry */
    const double left = 200, right_margin = 24, end_w = 78, row_h = 38, bar_h = 26;
    double col_w = 100;
    for (uint32_t k = 0; k < plan->n_order; k++) {
        const double w = text_w(plan->passes[plan->order[k]].name, 12) + 20;
        if (w > col_w) col_w = w;
    }
    if (col_w > 200) col_w = 200;
    const uint32_t n_cols = plan->n_order + 1; /* + "read back" */
    const double grid_w = col_w * plan->n_order + end_w;
    const double top = 104; /* first row */
    /* a block gets one lane per resource alive at the same time (members sorted by offset, each in
     * the first lane free at its first pass), so bars never overlap */
    static int lane_of[PG_MAX_RESOURCES];
    double row_y[PG_MAX_RESOURCES + 1];
    uint32_t n_lanes_total = 0, lanes_in[PG_MAX_RESOURCES];
    for (uint32_t b = 0; b < plan->n_blocks && b < PG_MAX_RESOURCES; b++) {
        const pg_plan_block *bl = &plan->blocks[b];
        int order_m[PG_MAX_RESOURCES], lane_end[PG_MAX_RESOURCES];
        uint32_t n = 0, lanes = 0;
        for (uint32_t m = 0; m < bl->n_members && m < PG_MAX_RESOURCES; m++) {
            const int r = bl->members[m];
            if (!res_ok(plan, r)) continue;
            uint32_t k = n++;
            while (k > 0 && plan->resources[order_m[k - 1]].block_offset > plan->resources[r].block_offset) {
                order_m[k] = order_m[k - 1];
                k--;
            }
            order_m[k] = r;
        }
        for (uint32_t i = 0; i < n; i++) {
            const pg_plan_resource *pr = &plan->resources[order_m[i]];
            uint32_t l = 0;
            while (l < lanes && lane_end[l] >= pr->first_pass) l++;
            if (l == lanes) lanes++;
            lane_end[l] = pr->last_pass;
            lane_of[order_m[i]] = (int)l;
        }
        lanes_in[b] = lanes ? lanes : 1;
        row_y[b] = top + row_h * n_lanes_total;
        n_lanes_total += lanes_in[b];
    }
    const uint32_t n_rows = n_lanes_total ? n_lanes_total : 1;
    const double live_h = 84;
    const double rows_bottom = top + row_h * n_rows;
    const double legend_y = rows_bottom + live_h + 38;
    static const char *const legend[3] = {
        "Columns: the executed passes in order; \xe2\x80\x9cread back\xe2\x80\x9d: after the last pass (outputs "
        "live until then).",
        "Rows: memory blocks (one lane per resource alive at once); a bar is one transient resource from its "
        "first to its last pass, at the offset it names. Bars of one block share its memory.",
        "Colour = memory block (the same colours as the resources in the graph of passgraph dump --format dot). "
        "Persistent and imported resources are not shown.",
    };
    double width = left + grid_w + right_margin;
    for (int i = 0; i < 3; i++)
        if (text_w(legend[i], 11) + 40 > width) width = text_w(legend[i], 11) + 40;
    const double height = legend_y + 3 * 17 + 14;
#define COL_X(k) (left + ((uint32_t)(k) < plan->n_order ? col_w * (double)(k) : col_w * (double)plan->n_order))
#define COL_W(k) ((uint32_t)(k) < plan->n_order ? col_w : end_w)

    fprintf(f,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\" "
            "font-family=\"%s\" font-size=\"12\">\n",
            width, height, width, height, font);
    fputs("  <title>memory timeline", f);
    if (pipeline) {
        fputs(": ", f);
        xml_esc(f, pipeline->name);
    }
    fputs("</title>\n", f);
    fputs("  <defs><pattern id=\"hatch\" width=\"6\" height=\"6\" patternUnits=\"userSpaceOnUse\" "
          "patternTransform=\"rotate(45)\"><rect width=\"6\" height=\"6\" fill=\"#f2f2f2\"/>"
          "<line x1=\"0\" y1=\"0\" x2=\"0\" y2=\"6\" stroke=\"#dddddd\" stroke-width=\"2\"/></pattern></defs>\n",
          f);
    fprintf(f, "  <rect x=\"0\" y=\"0\" width=\"%.0f\" height=\"%.0f\" fill=\"#ffffff\"/>\n", width, height);

    /* title */
    fputs("  <text x=\"16\" y=\"26\" font-size=\"16\" font-weight=\"bold\">Memory timeline", f);
    if (pipeline) {
        fputs(" \xe2\x80\x94 ", f);
        xml_esc(f, pipeline->name);
    }
    if (res_ok(plan, plan->output))
        fprintf(f, " \xc2\xb7 %u\xc3\x97%u", plan->resources[plan->output].width, plan->resources[plan->output].height);
    fputs("</text>\n", f);
    char un[32], al[32];
    fmt_bytes(plan->transient_bytes_unaliased, un, sizeof un);
    fmt_bytes(plan->transient_bytes_aliased, al, sizeof al);
    uint32_t n_transient = 0;
    for (uint32_t b = 0; b < plan->n_blocks; b++) n_transient += plan->blocks[b].n_members;
    fprintf(f,
            "  <text x=\"16\" y=\"46\" fill=\"#333333\">%u transient resources in %u memory blocks: %s unaliased "
            "\xe2\x86\x92 %s %s (saving %.1f%%)</text>\n",
            n_transient, plan->n_blocks, un, al, plan->aliasing_disabled ? "(aliasing disabled)" : "aliased",
            saving_percent(plan));

    /* column headers and grid */
    for (uint32_t k = 0; k < n_cols; k++) {
        const double x = COL_X(k), w = COL_W(k);
        if (k < plan->n_order) {
            if (k % 2 == 1)
                fprintf(f, "  <rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"#f7f9fc\"/>\n", x, top,
                        w, row_h * n_rows);
            const bool on_c = plan->async && plan->passes[plan->order[k]].queue == PG_QUEUE_COMPUTE;
            fprintf(f, "  <text x=\"%.1f\" y=\"72\" text-anchor=\"middle\" font-size=\"10\" fill=\"#777777\">#%u%s</text>\n",
                    x + w / 2, k, !plan->async ? "" : on_c ? " compute" : " graphics"); /* its queue, when two */
            fprintf(f, "  <text x=\"%.1f\" y=\"90\" text-anchor=\"middle\" font-weight=\"bold\">", x + w / 2);
            xml_fit(f, plan->passes[plan->order[k]].name, w - 8, 12);
            fputs("</text>\n", f);
        } else {
            fprintf(f, "  <rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"url(#hatch)\"/>\n", x, top,
                    w, row_h * n_rows);
            fprintf(f, "  <text x=\"%.1f\" y=\"72\" text-anchor=\"middle\" font-size=\"10\" fill=\"#777777\">after</text>\n",
                    x + w / 2);
            fprintf(f, "  <text x=\"%.1f\" y=\"90\" text-anchor=\"middle\" font-style=\"italic\">read back</text>\n",
                    x + w / 2);
        }
    }
    for (uint32_t k = 0; k <= n_cols; k++) {
        const double x = k < n_cols ? COL_X(k) : COL_X(plan->n_order) + end_w;
        fprintf(f, "  <line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#d0d0d0\"/>\n", x, top - 8, x,
                rows_bottom + live_h + 8);
    }

    /* one row per memory block, one bar per member */
    if (!plan->n_blocks)
        fprintf(f, "  <text x=\"%.1f\" y=\"%.1f\" fill=\"#777777\">no transient resources</text>\n", left + 10,
                top + row_h / 2 + 4);
    for (uint32_t b = 0; b < plan->n_blocks; b++) {
        const pg_plan_block *bl = &plan->blocks[b];
        const double y = row_y[b], block_h = row_h * lanes_in[b];
        const char *fill = k_block_fill[b % N_BLOCK_COLOURS], *stroke = k_block_stroke[b % N_BLOCK_COLOURS];
        char bytes[32];
        fmt_bytes(bl->size_bytes, bytes, sizeof bytes);
        fprintf(f, "  <line x1=\"16\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#e4e4e4\"/>\n", y + block_h,
                left + grid_w, y + block_h);
        fprintf(f, "  <rect x=\"16\" y=\"%.1f\" width=\"10\" height=\"%.1f\" rx=\"2\" fill=\"%s\" stroke=\"%s\"/>\n",
                y + 8, block_h - 16, fill, stroke);
        fprintf(f, "  <text x=\"34\" y=\"%.1f\"><tspan font-weight=\"bold\">block #%u</tspan> %s</text>\n", y + 17, b,
                bytes);
        fprintf(f, "  <text x=\"34\" y=\"%.1f\" font-size=\"10\" fill=\"#666666\">%s%s</text>\n", y + 31,
                pg_res_kind_name(bl->kind),
                bl->n_members > 1 ? (bl->n_members == 2 ? " \xc2\xb7 shared by 2 resources" : " \xc2\xb7 shared")
                                  : "");
        for (uint32_t m = 0; m < bl->n_members && m < PG_MAX_RESOURCES; m++) {
            const int r = bl->members[m];
            if (!res_ok(plan, r)) continue;
            const pg_plan_resource *pr = &plan->resources[r];
            int first = pr->first_pass < 0 ? 0 : pr->first_pass;
            int last = pr->last_pass < first ? first : pr->last_pass;
            if ((uint32_t)last > plan->n_order) last = (int)plan->n_order;
            const double x0 = COL_X(first) + 3, x1 = COL_X(last) + COL_W(last) - 3;
            const double by = y + row_h * lane_of[r] + (row_h - bar_h) / 2;
            char rb[32], ro[32], detail[96];
            fmt_bytes(pr->size_bytes, rb, sizeof rb);
            fmt_bytes(pr->block_offset, ro, sizeof ro);
            if (pr->kind == PG_RES_IMAGE)
                snprintf(detail, sizeof detail, "%s \xc2\xb7 %s @ %s", pg_format_get(pr->format)->name, rb, ro);
            else
                snprintf(detail, sizeof detail, "%s @ %s", rb, ro);
            fprintf(f,
                    "  <g><title>%s", "");
            xml_esc(f, pr->name);
            fprintf(f, ": %s%s, %s .. %s, block #%u @ %" PRIu64 "</title>\n", detail,
                    pr->is_output ? " (output)" : "", pass_at(plan, pr->first_pass) ? pass_at(plan, pr->first_pass) : "-",
                    pass_at(plan, pr->last_pass) ? pass_at(plan, pr->last_pass) : "-", b, pr->block_offset);
            fprintf(f,
                    "    <rect class=\"bar\" data-resource=\"");
            xml_esc(f, pr->name);
            fprintf(f, "\" data-block=\"%u\" x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" rx=\"5\" "
                       "fill=\"%s\" stroke=\"%s\" stroke-width=\"1.2\"/>\n",
                    b, x0, by, x1 - x0, bar_h, fill, stroke);
            /* label: "name  format · size" when it fits, else the name, else a cut name */
            const double avail = x1 - x0 - 12;
            const double name_w = text_w(pr->name, 12), det_w = text_w(detail, 10) + 8;
            fprintf(f, "    <text x=\"%.1f\" y=\"%.1f\">", x0 + 6, by + bar_h / 2 + 4);
            if (name_w <= avail) {
                fputs("<tspan font-weight=\"bold\">", f);
                xml_esc(f, pr->name);
                fputs("</tspan>", f);
                if (name_w + det_w <= avail) {
                    fputs("<tspan font-size=\"10\" fill=\"#333333\" dx=\"8\">", f);
                    xml_esc(f, detail);
                    fputs("</tspan>", f);
                }
            } else {
                fputs("<tspan font-weight=\"bold\">", f);
                xml_fit(f, pr->name, avail, 12);
                fputs("</tspan>", f);
            }
            fputs("</text></g>\n", f);
        }
    }

    /* live transient bytes per column */
    uint64_t live[PG_MAX_PASSES + 1] = {0}, max_live = 0;
    for (uint32_t k = 0; k < n_cols && k <= PG_MAX_PASSES; k++) {
        for (uint32_t r = 0; r < plan->n_resources; r++) {
            const pg_plan_resource *pr = &plan->resources[r];
            if (pr->block < 0 || pr->culled || pr->first_pass < 0) continue;
            if ((int)k >= pr->first_pass && (int)k <= pr->last_pass) live[k] += pr->size_bytes;
        }
        if (live[k] > max_live) max_live = live[k];
    }
    /* the memory the blocks take (all allocated for the whole frame) is the reference line */
    const uint64_t allocated = plan->transient_bytes_aliased;
    if (allocated > max_live) max_live = allocated;
    const double live_top = rows_bottom + 8, live_bar_max = live_h - 30;
    fprintf(f, "  <text x=\"16\" y=\"%.1f\" font-weight=\"bold\">live bytes</text>\n", live_top + 18);
    fprintf(f, "  <text x=\"16\" y=\"%.1f\" font-size=\"10\" fill=\"#666666\">sum of the live resources</text>\n",
            live_top + 32);
    for (uint32_t k = 0; k < n_cols && k <= PG_MAX_PASSES; k++) {
        const double w = COL_W(k) * 0.5, x = COL_X(k) + (COL_W(k) - w) / 2;
        double h = max_live ? live_bar_max * (double)live[k] / (double)max_live : 0;
        if (live[k] && h < 1.5) h = 1.5;
        const double base = live_top + live_h - 16;
        char lb[32];
        fmt_bytes(live[k], lb, sizeof lb);
        fprintf(f, "  <rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"#9fb6d6\"/>\n", x, base - h, w,
                h);
        fprintf(f, "  <text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\" font-size=\"10\" fill=\"#333333\">%s</text>\n",
                COL_X(k) + COL_W(k) / 2, base + 12, lb);
    }

    if (allocated && plan->n_blocks) {
        const double base = live_top + live_h - 16;
        const double ya = base - live_bar_max * (double)allocated / (double)max_live;
        fprintf(f,
                "  <line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#b04032\" stroke-width=\"1\" "
                "stroke-dasharray=\"5,3\"/>\n",
                left, ya, left + grid_w, ya);
        fprintf(f,
                "  <text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\" font-size=\"10\" fill=\"#b04032\">allocated "
                "%s</text>\n",
                left + grid_w - 4, ya - 3, al);
    }

    /* legend */
    for (int i = 0; i < 3; i++) {
        fprintf(f, "  <text x=\"16\" y=\"%.1f\" font-size=\"11\" fill=\"#444444\">", legend_y + 17 * i);
        xml_esc(f, legend[i]);
        fputs("</text>\n", f);
    }
    fputs("</svg>\n", f);
#undef COL_X
#undef COL_W
}

/* ------------------------------------------------------------------------------------------ */
/* running Graphviz                                                                           */

const char *pg_dump_graphviz_format_for(const char *path)
{
    if (!path) return NULL;
    const char *dot = strrchr(path, '.');
    const char *slash = strrchr(path, '/');
    if (!dot || (slash && dot < slash)) return NULL;
    static const char *const fmts[] = {"svg", "png", "pdf", NULL};
    for (int i = 0; fmts[i]; i++) {
        const char *a = dot + 1, *b = fmts[i];
        while (*a && *b && (*a | 0x20) == *b) a++, b++;
        if (!*a && !*b) return fmts[i];
    }
    return NULL;
}

/* Finds an executable named name on PATH; returns false when there is none. */
static bool find_on_path(const char *name, char *out, size_t size)
{
    const char *path = getenv("PATH");
    if (!path || !*path) path = "/usr/local/bin:/usr/bin:/bin";
    while (*path) {
        size_t n = strcspn(path, ":");
        char cand[PG_PATH_MAX];
        if (n == 0) {
            snprintf(cand, sizeof cand, "./%s", name);
        } else if (n + 1 + strlen(name) < sizeof cand) {
            memcpy(cand, path, n);
            snprintf(cand + n, sizeof cand - n, "/%s", name);
        } else {
            cand[0] = 0;
        }
        struct stat st;
        if (cand[0] && stat(cand, &st) == 0 && S_ISREG(st.st_mode) && access(cand, X_OK) == 0) {
            pg_strlcpy(out, cand, size);
            return true;
        }
        path += n;
        if (*path == ':') path++;
    }
    return false;
}

pg_result pg_dump_run_graphviz(const char *dot_text, const char *format, const char *out_path, pg_error *err)
{
    if (!dot_text || !format || !*format || !out_path || !*out_path)
        return pg_fail(err, PG_ERR_INVALID_ARG, "graphviz: missing DOT text, format or output path");
    for (const char *c = format; *c; c++)
        if (!((*c >= 'a' && *c <= 'z') || (*c >= '0' && *c <= '9')))
            return pg_fail(err, PG_ERR_INVALID_ARG, "graphviz: bad output format '%s'", format);
    char exe[PG_PATH_MAX];
    if (!find_on_path("dot", exe, sizeof exe))
        return pg_fail(err, PG_ERR_IO,
                       "Graphviz's 'dot' was not found on PATH; install the package 'graphviz' "
                       "(Debian/Ubuntu: apt-get install graphviz) to render %s, or write the DOT text "
                       "itself (--out FILE.dot)",
                       out_path);
    char targ[32], oarg[PG_PATH_MAX + 3];
    snprintf(targ, sizeof targ, "-T%s", format);
    if (snprintf(oarg, sizeof oarg, "-o%s", out_path) >= (int)sizeof oarg)
        return pg_fail(err, PG_ERR_INVALID_ARG, "graphviz: output path too long: %s", out_path);
    char *const argv[] = {"dot", targ, oarg, NULL};

    int fds[2];
    if (pipe(fds) != 0) return pg_fail(err, PG_ERR_IO, "graphviz: pipe: %s", strerror(errno));
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, fds[0], STDIN_FILENO);
    posix_spawn_file_actions_addclose(&fa, fds[0]);
    posix_spawn_file_actions_addclose(&fa, fds[1]);
    pid_t pid;
    int rc = posix_spawn(&pid, exe, &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    close(fds[0]);
    if (rc != 0) {
        close(fds[1]);
        return pg_fail(err, PG_ERR_IO, "graphviz: cannot run %s: %s%s", exe, strerror(rc),
                       rc == ENOENT ? " (install the package 'graphviz')" : "");
    }
    /* dot may exit early (bad input): write with SIGPIPE ignored so that shows as EPIPE */
    struct sigaction ign, old;
    memset(&ign, 0, sizeof ign);
    ign.sa_handler = SIG_IGN;
    sigemptyset(&ign.sa_mask);
    sigaction(SIGPIPE, &ign, &old);
    const char *p = dot_text;
    size_t left = strlen(dot_text);
    int write_errno = 0;
    while (left) {
        ssize_t w = write(fds[1], p, left);
        if (w < 0) {
            if (errno == EINTR) continue;
            write_errno = errno;
            break;
        }
        p += w;
        left -= (size_t)w;
    }
    close(fds[1]);
    sigaction(SIGPIPE, &old, NULL);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) return pg_fail(err, PG_ERR_IO, "graphviz: waitpid: %s", strerror(errno));
    }
    if (WIFSIGNALED(status))
        return pg_fail(err, PG_ERR_IO, "graphviz: dot -T%s killed by signal %d while writing %s", format,
                       WTERMSIG(status), out_path);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        return pg_fail(err, PG_ERR_IO, "graphviz: dot -T%s failed with exit status %d writing %s (its message is above)",
                       format, WIFEXITED(status) ? WEXITSTATUS(status) : -1, out_path);
    if (write_errno)
        return pg_fail(err, PG_ERR_IO, "graphviz: writing to dot: %s", strerror(write_errno));
    return PG_OK;
}
