/* graph_dump_json.c - the JSON view of a compiled graph (docs/dump-format.md). */
#include "graph_dump_internal.h"

#include <cjson/cJSON.h>
#include <inttypes.h>
#include <math.h>
#include <string.h>

/* ------------------------------------------------------------------------------------------ */
/* JSON                                                                                       */

/* Adds an exact unsigned integer (cJSON's numbers are doubles: raw text keeps 64 bits). */
static bool add_u64(cJSON *o, const char *key, uint64_t v)
{
    char t[32];
    snprintf(t, sizeof t, "%" PRIu64, v);
    return cJSON_AddRawToObject(o, key, t) != NULL;
}

/* A number that reads back as the same double: an integer without an exponent, any other with
 * 17 significant digits (cJSON's 15 digits turned 1.7976931348623157e308 into infinity on reading). */
static cJSON *exact_number(double v, bool integer)
{
    char t[40];
    if (integer && fabs(v) <= 9007199254740992.0) snprintf(t, sizeof t, "%lld", (long long)v);
    else snprintf(t, sizeof t, "%.17g", v);
    return cJSON_CreateRaw(t);
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
    bool ok = cJSON_AddStringToObject(o, "resource", pg_dmp_res_name(plan, b->resource)) &&
              cJSON_AddStringToObject(o, "why", b->why) &&
              add_stage_names(o, "src_stages", b->src_stages) &&
              add_access_names(o, "src_access", b->src_access) &&
              add_stage_names(o, "dst_stages", b->dst_stages) &&
              add_access_names(o, "dst_access", b->dst_access) &&
              add_str_or_null(o, "old_layout", b->is_image ? pg_layout_name(b->old_layout) : NULL) &&
              add_str_or_null(o, "new_layout", b->is_image ? pg_layout_name(b->new_layout) : NULL) &&
              add_str_or_null(o, "after_alias_of",
                              b->alias_prev >= 0 && pg_dmp_res_ok(plan, b->alias_prev)
                                  ? plan->resources[b->alias_prev].name
                                  : NULL) &&
              cJSON_AddBoolToObject(o, "wrap", b->wrap) && cJSON_AddBoolToObject(o, "first_frame", b->first_frame);
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
    const bool image = pg_dmp_res_ok(plan, sl->resource) && plan->resources[sl->resource].kind == PG_RES_IMAGE;
    bool ok = cJSON_AddStringToObject(o, "resource", pg_dmp_res_name(plan, sl->resource)) &&
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
            cJSON *item = names_only ? cJSON_CreateString(pg_dmp_res_name(plan, sl->resource)) : json_slot(plan, sl);
            if (!item) return false;
            cJSON_AddItemToArray(a, item);
        }
    }
    return true;
}

/* n strings of a fixed-size char array (stride bytes apart) as the array o[key] */
static bool add_strings(cJSON *o, const char *key, const char *first, size_t stride, uint32_t n)
{
    cJSON *a = cJSON_AddArrayToObject(o, key);
    if (!a) return false;
    for (uint32_t i = 0; i < n; i++) {
        cJSON *s = cJSON_CreateString(first + i * stride);
        if (!s) return false;
        cJSON_AddItemToArray(a, s);
    }
    return true;
}
#define ADD_STRING_LIST(o, key, list, n) add_strings((o), (key), (list)[0], sizeof (list)[0], (n))

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
        case PG_PARAM_FLOAT: v = exact_number(p->number, p->type == PG_PARAM_INT); break;
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
        if (!cJSON_AddStringToObject(x, "resource", pg_dmp_res_name(plan, t->resource)) ||
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

/* "output" (the output image, or nulls), then the "aliasing" and "immediate" flags. */
static bool json_output(cJSON *root, const pg_graph_plan *plan)
{
    cJSON *out = cJSON_AddObjectToObject(root, "output");
    if (!out) return false;
    const bool has_out = pg_dmp_res_ok(plan, plan->output);
    const bool has_hdr = pg_dmp_res_ok(plan, plan->hdr_output);
    if (!add_str_or_null(out, "resource", has_out ? plan->resources[plan->output].name : NULL) ||
        !add_str_or_null(out, "hdr_resource", has_hdr ? plan->resources[plan->hdr_output].name : NULL) ||
        !add_int_or_null(out, "width", has_out, has_out ? (int)plan->resources[plan->output].width : 0) ||
        !add_int_or_null(out, "height", has_out, has_out ? (int)plan->resources[plan->output].height : 0))
        return false;
    if (!cJSON_AddBoolToObject(root, "aliasing", !plan->aliasing_disabled)) return false;
    return cJSON_AddBoolToObject(root, "immediate", plan->immediate) != NULL;
}

/* "order": the executed passes' names in execution order. */
static bool json_order(cJSON *root, const pg_graph_plan *plan)
{
    cJSON *order = cJSON_AddArrayToObject(root, "order");
    if (!order) return false;
    for (uint32_t k = 0; k < plan->n_order; k++) {
        cJSON *s = cJSON_CreateString(plan->passes[plan->order[k]].name);
        if (!s) return false;
        cJSON_AddItemToArray(order, s);
    }
    return true;
}

/* One executed pass: position, name, type, barriers before it, slots, defines, left-out lines. */
static bool json_executed_pass(cJSON *passes, const pg_graph_plan *plan, const pg_pipeline *pl, uint32_t k)
{
    const pg_plan_pass *pp = &plan->passes[plan->order[k]];
    cJSON *o = cJSON_CreateObject();
    if (!o) return false;
    cJSON_AddItemToArray(passes, o);
    const uint32_t n_def = pp->decl.n_defines < PG_MAX_DEFINES ? pp->decl.n_defines : PG_MAX_DEFINES;
    const uint32_t n_exp = pp->decl.n_explain < PG_MAX_PASS_EXPLAIN ? pp->decl.n_explain : PG_MAX_PASS_EXPLAIN;
    return cJSON_AddNumberToObject(o, "position", k) && cJSON_AddStringToObject(o, "name", pp->name) &&
           cJSON_AddStringToObject(o, "type", pg_dmp_type_name(pp)) &&
           cJSON_AddNumberToObject(o, "declared_index", pp->desc_index) &&
           cJSON_AddBoolToObject(o, "side_effects", pp->decl.side_effects ||
                                                        (pl && pp->desc_index >= 0 &&
                                                         (uint32_t)pp->desc_index < pl->n_passes &&
                                                         pl->passes[pp->desc_index].side_effects)) &&
           add_barriers(o, "barriers", plan, pp->barriers,
                        pp->n_barriers < PG_MAX_BARRIERS_PER_PASS ? pp->n_barriers : PG_MAX_BARRIERS_PER_PASS) &&
           add_slots(o, plan, pp, false) && ADD_STRING_LIST(o, "defines", pp->decl.defines, n_def) &&
           ADD_STRING_LIST(o, "left_out", pp->decl.explain, n_exp);
}

/* "passes" (the executed ones, in execution order), then "final_barriers". */
static bool json_passes(cJSON *root, const pg_graph_plan *plan, const pg_pipeline *pl)
{
    cJSON *passes = cJSON_AddArrayToObject(root, "passes");
    if (!passes) return false;
    for (uint32_t k = 0; k < plan->n_order; k++)
        if (!json_executed_pass(passes, plan, pl, k)) return false;
    return add_barriers(root, "final_barriers", plan, plan->final_barriers,
                        plan->n_final_barriers < PG_MAX_RESOURCES ? plan->n_final_barriers : PG_MAX_RESOURCES);
}

/* "culled_passes", in declaration order, each with its reason and the names of its slots. */
static bool json_culled_passes(cJSON *root, const pg_graph_plan *plan)
{
    cJSON *culled = cJSON_AddArrayToObject(root, "culled_passes");
    if (!culled) return false;
    for (uint32_t i = 0; i < plan->n_passes; i++) {
        const pg_plan_pass *pp = &plan->passes[i];
        if (!pp->culled) continue;
        cJSON *o = cJSON_CreateObject();
        if (!o) return false;
        cJSON_AddItemToArray(culled, o);
        if (!cJSON_AddStringToObject(o, "name", pp->name) || !cJSON_AddStringToObject(o, "type", pg_dmp_type_name(pp)) ||
            !cJSON_AddNumberToObject(o, "declared_index", pp->desc_index) ||
            !cJSON_AddStringToObject(o, "reason", pp->cull_reason) || !add_slots(o, plan, pp, true))
            return false;
    }
    return true;
}

/* "omitted" (what the pipeline's "when" left out, and why), then the plan's "explain" lines. */
static bool json_omitted(cJSON *root, const pg_graph_plan *plan, const pg_pipeline *pl)
{
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
    return ADD_STRING_LIST(root, "explain", plan->explain, plan->n_explain < PG_MAX_EXPLAIN ? plan->n_explain : PG_MAX_EXPLAIN);
}

/* One resource: kind, lifetime, format and size, culling, live range, memory block and offset. */
static bool json_resource(cJSON *res, const pg_graph_plan *plan, const pg_plan_resource *pr)
{
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
        !add_str_or_null(o, "first_pass", live ? pg_dmp_pass_at(plan, pr->first_pass) : NULL) ||
        !add_str_or_null(o, "last_pass", live ? pg_dmp_pass_at(plan, pr->last_pass) : NULL) ||
        !add_int_or_null(o, "first_position", live, pr->first_pass) ||
        !add_int_or_null(o, "last_position", live, pr->last_pass) ||
        !add_int_or_null(o, "block", pr->block >= 0, pr->block))
        return false;
    return pr->block >= 0 ? add_u64(o, "offset", pr->block_offset) : cJSON_AddNullToObject(o, "offset") != NULL;
}

/* "resources", in declaration order. */
static bool json_resources(cJSON *root, const pg_graph_plan *plan)
{
    cJSON *res = cJSON_AddArrayToObject(root, "resources");
    if (!res) return false;
    for (uint32_t r = 0; r < plan->n_resources; r++)
        if (!json_resource(res, plan, &plan->resources[r])) return false;
    return true;
}

/* One memory block: index, kind, size and its members with their offsets and live ranges. */
static bool json_block(cJSON *blocks, const pg_graph_plan *plan, uint32_t b)
{
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
        const pg_plan_resource *pr = pg_dmp_res_ok(plan, r) ? &plan->resources[r] : NULL;
        cJSON *mo = cJSON_CreateObject();
        if (!mo) return false;
        cJSON_AddItemToArray(members, mo);
        if (!cJSON_AddStringToObject(mo, "resource", pg_dmp_res_name(plan, r)) ||
            !add_u64(mo, "offset", pr ? pr->block_offset : 0) || !add_u64(mo, "size_bytes", pr ? pr->size_bytes : 0) ||
            !cJSON_AddNumberToObject(mo, "first_position", pr ? pr->first_pass : -1) ||
            !cJSON_AddNumberToObject(mo, "last_position", pr ? pr->last_pass : -1))
            return false;
    }
    return true;
}

/* "blocks": the memory blocks. */
static bool json_blocks(cJSON *root, const pg_graph_plan *plan)
{
    cJSON *blocks = cJSON_AddArrayToObject(root, "blocks");
    if (!blocks) return false;
    for (uint32_t b = 0; b < plan->n_blocks; b++)
        if (!json_block(blocks, plan, b)) return false;
    return true;
}

/* "totals": counts, transient memory before and after aliasing, the saving. */
static bool json_totals(cJSON *root, const pg_graph_plan *plan, const pg_pipeline *pl)
{
    uint32_t res_culled = 0;
    for (uint32_t r = 0; r < plan->n_resources; r++) res_culled += plan->resources[r].culled;
    cJSON *t = cJSON_AddObjectToObject(root, "totals");
    return t && cJSON_AddNumberToObject(t, "passes_declared", plan->n_passes) &&
           cJSON_AddNumberToObject(t, "passes_run", plan->n_order) &&
           cJSON_AddNumberToObject(t, "passes_culled", pg_graph_plan_count_culled(plan)) &&
           cJSON_AddNumberToObject(t, "resources_declared", plan->n_resources) &&
           cJSON_AddNumberToObject(t, "resources_culled", res_culled) &&
           cJSON_AddNumberToObject(t, "omitted", pl ? pl->n_omitted : 0) &&
           cJSON_AddNumberToObject(t, "barriers", pg_graph_plan_count_barriers(plan)) &&
           cJSON_AddNumberToObject(t, "final_barriers", plan->n_final_barriers) &&
           cJSON_AddNumberToObject(t, "blocks", plan->n_blocks) &&
           add_u64(t, "transient_bytes_unaliased", plan->transient_bytes_unaliased) &&
           add_u64(t, "transient_bytes_aliased", plan->transient_bytes_aliased) &&
           cJSON_AddNumberToObject(t, "saving_percent", (double)(int64_t)(pg_graph_plan_saving_percent(plan) * 10.0 + 0.5) / 10.0);
}

/* The dump's keys in docs/dump-format.md order; the first that fails stops it. */
static bool json_body(cJSON *root, const pg_graph_plan *plan, const pg_pipeline *pl)
{
    return cJSON_AddNumberToObject(root, "format_version", PG_DUMP_FORMAT_VERSION) && json_pipeline(root, pl) &&
           json_output(root, plan) && json_order(root, plan) && json_passes(root, plan, pl) &&
           json_culled_passes(root, plan) && json_omitted(root, plan, pl) && json_resources(root, plan) &&
           json_blocks(root, plan) && json_totals(root, plan, pl) &&
           /* queues, after the existing keys (two-queue plans only; a one-queue plan has no such key) */
           (!plan->async || json_queues(root, plan));
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
