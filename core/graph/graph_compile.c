/* graph_compile.c - pg_graph_compile(): pipeline description + pass registry -> pg_graph_plan.
 *
 * Pure: no Vulkan calls, only Vulkan enum values. The phases (see graph.h) run in order and each
 * one states what it guarantees to the next:
 *
 *   1. declare    every pass has a known type and a declaration whose slot counts match its
 *                 bindings.
 *   2. validate   every slot names an existing resource of the right kind, whose format suits
 *                 the access; each pass's slots for one resource are merged into one "use"
 *                 (one layout per image per pass).
 *   3. order      writers of a resource are explicitly ordered; every pass is placed after the
 *                 passes it depends on; ties keep declaration order; no transient is read before
 *                 it is fully written (its first use writes without reading, or is a slot the
 *                 pass initializes itself).
 *   4. cull       the passes that run are exactly those that feed an output or have side effects
 *                 and did not skip themselves (pg_decl_skip); everything left out carries a
 *                 reason.
 *   5. lifetimes  sizes are resolved; every used resource has [first, last] positions in
 *                 plan->order (outputs to n_order) and its usage flags.
 *   6. alias      transients are placed at offsets in one block per kind (core/graph/alias_pack.c,
 *                 estimated sizes and alignments): resources alive at the same time share no
 *                 byte; only a full overwrite may start in bytes an earlier resource used. The
 *                 first use of a block member waits for every member that ended before it.
 *   7. barriers   every hazard between two accesses of a resource (and across frames, across
 *                 aliases, and to the readback) has exactly one barrier, placed before the pass.
 *
 * Ownership: the plan is one calloc'd block that pg_graph_plan_free() frees. The working state
 * lives in a second heap block freed before returning, so an error leaks nothing.
 */
#include "graph_compile_internal.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <vulkan/vulkan_core.h>

/* ------------------------------------------------------------------------------------------ */
/* messages                                                                                   */

static const char *format_class_phrase(uint32_t mask)
{
    switch (mask & PG_FMTCLASS_ANY) {
    case PG_FMTCLASS_DEPTH: return "a depth format";
    case PG_FMTCLASS_FLOAT: return "a float color format (unorm/snorm/float/srgb)";
    case PG_FMTCLASS_UINT: return "an integer color format";
    case PG_FMTCLASS_ANY_COLOR: return "a color format";
    case PG_FMTCLASS_FLOAT | PG_FMTCLASS_DEPTH: return "a float color or depth format";
    case PG_FMTCLASS_UINT | PG_FMTCLASS_DEPTH: return "an integer color or depth format";
    case PG_FMTCLASS_ANY: return "any format";
    default: return "no format at all";
    }
}

/* ------------------------------------------------------------------------------------------ */
/* lookups                                                                                    */

static int find_resource(const pg_pipeline *pl, const char *name)
{
    for (uint32_t i = 0; i < pl->n_resources; i++)
        if (strcmp(pl->resources[i].name, name) == 0) return (int)i;
    return -1;
}

/* ------------------------------------------------------------------------------------------ */
/* 0. inputs                                                                                  */

static pg_result check_inputs(compile_ctx *c)
{
    const pg_pipeline *pl = c->pl;
    const char *file = pl->path[0] ? pl->path : "<pipeline>";
    if (pl->n_passes > PG_MAX_PASSES)
        return pg_fail(c->err, PG_ERR_LIMIT, "%s: %u passes, at most %d", file, pl->n_passes,
                       PG_MAX_PASSES);
    if (pl->n_resources > PG_MAX_RESOURCES)
        return pg_fail(c->err, PG_ERR_LIMIT, "%s: %u resources, at most %d", file,
                       pl->n_resources, PG_MAX_RESOURCES);
    if (c->desc->output_width == 0 || c->desc->output_height == 0)
        return pg_fail(c->err, PG_ERR_INVALID_ARG, "%s: output size %ux%u: both must be > 0",
                       file, c->desc->output_width, c->desc->output_height);
    if (c->desc->output_width > MAX_EXTENT || c->desc->output_height > MAX_EXTENT)
        return pg_fail(c->err, PG_ERR_LIMIT, "%s: output size %ux%u: at most %u a side", file,
                       c->desc->output_width, c->desc->output_height, MAX_EXTENT);
    for (uint32_t i = 0; i < pl->n_resources; i++) {
        for (uint32_t j = 0; j < i; j++)
            if (strcmp(pl->resources[i].name, pl->resources[j].name) == 0) {
                char rp[PG_JSON_PATH_MAX + 16];
                pg_gc_res_path(c, (int)i, rp, sizeof rp);
                return pg_fail(c->err, PG_ERR_SCHEMA, "%s: %s.name: resource '%s' declared twice",
                               pg_gc_res_file(c, (int)i), rp, pl->resources[i].name);
            }
    }
    for (uint32_t i = 0; i < pl->n_passes; i++) {
        const pg_pass_desc *p = &pl->passes[i];
        char pp[PG_JSON_PATH_MAX + 16];
        pg_gc_pass_path(c, (int)i, pp, sizeof pp);
        for (uint32_t j = 0; j < i; j++)
            if (strcmp(p->name, pl->passes[j].name) == 0)
                return pg_fail(c->err, PG_ERR_SCHEMA, "%s: %s.name: pass '%s' declared twice",
                               pg_gc_pass_file(c, (int)i), pp, p->name);
        if (p->n_reads > PG_MAX_SLOTS || p->n_writes > PG_MAX_SLOTS)
            return pg_fail(c->err, PG_ERR_LIMIT, "%s: %s: at most %d reads and %d writes",
                           pg_gc_pass_file(c, (int)i), pp, PG_MAX_SLOTS, PG_MAX_SLOTS);
        if (p->n_after > PG_MAX_AFTER)
            return pg_fail(c->err, PG_ERR_LIMIT, "%s: %s.after: at most %d entries",
                           pg_gc_pass_file(c, (int)i), pp, PG_MAX_AFTER);
    }
    /* outputs */
    c->plan->output = find_resource(pl, pl->output);
    if (!pl->output[0] || c->plan->output < 0)
        return pg_fail(c->err, PG_ERR_NO_OUTPUT, "%s: output: %s%s%s", file,
                       pl->output[0] ? "unknown resource '" : "no output resource given",
                       pl->output[0] ? pl->output : "", pl->output[0] ? "'" : "");
    c->plan->hdr_output = -1;
    if (pl->hdr_output[0]) {
        c->plan->hdr_output = find_resource(pl, pl->hdr_output);
        if (c->plan->hdr_output < 0)
            return pg_fail(c->err, PG_ERR_NO_OUTPUT, "%s: hdr_output: unknown resource '%s'",
                           file, pl->hdr_output);
    }
    const int outs[2] = {c->plan->output, c->plan->hdr_output};
    const char *keys[2] = {"output", "hdr_output"};
    for (int k = 0; k < 2; k++)
        if (outs[k] >= 0 && pl->resources[outs[k]].kind != PG_RES_IMAGE)
            return pg_fail(c->err, PG_ERR_NO_OUTPUT, "%s: %s: '%s' is a buffer; it must be an image",
                           file, keys[k], pl->resources[outs[k]].name);
    if (c->plan->hdr_output >= 0) { /* read back as floats by the tools (nonfinite, EXR, error metrics) */
        const pg_format f = pl->resources[c->plan->hdr_output].format;
        if (f != PG_FMT_RGBA16F && f != PG_FMT_RGBA32F)
            return pg_fail(c->err, PG_ERR_FORMAT, "%s: hdr_output: '%s' is %s; the HDR output must be rgba16f or rgba32f",
                           file, pl->hdr_output, pg_format_get(f)->name);
    }
    return PG_OK;
}

/* ------------------------------------------------------------------------------------------ */
/* 1. declare                                                                                 */

static pg_result phase_declare(compile_ctx *c)
{
    const pg_pipeline *pl = c->pl;
    const pg_pass_registry *reg = c->desc->registry;
    for (uint32_t i = 0; i < pl->n_passes; i++) {
        const pg_pass_desc *pd = &pl->passes[i];
        pg_plan_pass *pp = &c->plan->passes[i];
        char jp[PG_JSON_PATH_MAX + 16];
        pg_gc_pass_path(c, (int)i, jp, sizeof jp);
        pg_strlcpy(pp->name, pd->name, sizeof pp->name);
        pp->desc_index = (int)i;
        const pg_pass_type *t = pg_registry_find(reg, pd->type);
        if (!t) {
            char known[PG_ERROR_MSG_MAX / 2];
            size_t len = 0;
            known[0] = 0;
            for (uint32_t k = 0; k < reg->count && k < 64 && len < sizeof known; k++) {
                if (!reg->types[k] || !reg->types[k]->name) continue;
                int w = snprintf(known + len, sizeof known - len, "%s%s", len ? ", " : "",
                                 reg->types[k]->name);
                if (w < 0) break;
                len += (size_t)w;
            }
            return pg_fail(c->err, PG_ERR_UNKNOWN_PASS,
                           "%s: %s.type: unknown pass type '%s' (known: %s)", pg_gc_pass_file(c, (int)i),
                           jp, pd->type, known[0] ? known : "none");
        }
        pp->type = t;
        if (!t->declare)
            return pg_fail(c->err, PG_ERR_INVALID_ARG, "%s: %s.type: pass type '%s' has no declare()",
                           pg_gc_pass_file(c, (int)i), jp, t->name);
        pg_declare_in in;
        memset(&in, 0, sizeof in);
        in.desc = pd;
        in.pipeline = pl;
        in.vars = &c->desc->vars;
        in.output_width = c->desc->output_width;
        in.output_height = c->desc->output_height;
        pg_error e;
        memset(&e, 0, sizeof e);
        memset(&pp->decl, 0, sizeof pp->decl);
        pg_result r = t->declare(&in, &pp->decl, &e);
        if (r != PG_OK) {
            if (!e.msg[0])
                snprintf(e.msg, sizeof e.msg, "%s: %s: pass type '%s' rejected its options (%s)",
                         pg_gc_pass_file(c, (int)i), jp, t->name, pg_result_name(r));
            return pg_fail(c->err, r, "%s", e.msg);
        }
        r = pg_decl_check_counts(pd, &pp->decl, t, c->err);
        if (r != PG_OK) return r;
        if (pp->decl.n_defines > PG_MAX_DEFINES)
            return pg_fail(c->err, PG_ERR_LIMIT,
                           "%s: %s: pass type '%s' declares more than %d shader defines (or one "
                           "longer than %d characters)",
                           pg_gc_pass_file(c, (int)i), jp, t->name, PG_MAX_DEFINES, PG_NAME_MAX - 1);
        /* a skipped pass gets no instance, so no update() */
        const bool lists_runtime = t->runtime_options && t->runtime_options[0] && !pp->decl.skip;
        if (pp->decl.n_runtime_params > PG_MAX_RUNTIME_PARAMS || (lists_runtime && !pp->decl.n_runtime_params))
            return pg_fail(c->err, PG_ERR_INVALID_ARG,
                           "%s: %s: pass type '%s' %s (a bug in the pass type: pg_decl_runtime_param)",
                           pg_gc_pass_file(c, (int)i), jp, t->name,
                           lists_runtime && !pp->decl.n_runtime_params
                               ? "lists run-time options but marks no run-time field of its params"
                               : "marks more run-time fields than PG_MAX_RUNTIME_PARAMS");
    }
    return PG_OK;
}

/* ------------------------------------------------------------------------------------------ */
/* 2. validate                                                                                */

static bool access_fits_kind(pg_access a, pg_res_kind kind)
{
    switch (a) {
    case PG_ACCESS_COLOR_WRITE:
    case PG_ACCESS_COLOR_RMW:
    case PG_ACCESS_DEPTH_WRITE:
    case PG_ACCESS_DEPTH_RMW:
    case PG_ACCESS_DEPTH_READ:
    case PG_ACCESS_SAMPLED: return kind == PG_RES_IMAGE;
    case PG_ACCESS_UNIFORM:
    case PG_ACCESS_VERTEX_INPUT:
    case PG_ACCESS_INDIRECT: return kind == PG_RES_BUFFER;
    case PG_ACCESS_STORAGE_READ:
    case PG_ACCESS_STORAGE_WRITE:
    case PG_ACCESS_STORAGE_RW:
    case PG_ACCESS_TRANSFER_SRC:
    case PG_ACCESS_TRANSFER_DST: return true;
    default: return false;
    }
}

/* The format classes an access can work with at all, whatever the slot declares. */
static uint32_t access_format_classes(pg_access a)
{
    switch (a) {
    case PG_ACCESS_COLOR_WRITE:
    case PG_ACCESS_COLOR_RMW: return PG_FMTCLASS_ANY_COLOR;
    case PG_ACCESS_DEPTH_WRITE:
    case PG_ACCESS_DEPTH_RMW:
    case PG_ACCESS_DEPTH_READ: return PG_FMTCLASS_DEPTH;
    default: return PG_FMTCLASS_ANY;
    }
}

static bool is_storage(pg_access a)
{
    return a == PG_ACCESS_STORAGE_READ || a == PG_ACCESS_STORAGE_WRITE || a == PG_ACCESS_STORAGE_RW;
}

static pg_result validate_slot(compile_ctx *c, int i, int s, const char *res_name,
                               const pg_slot_decl *sd, bool is_write)
{
    const pg_pipeline *pl = c->pl;
    pg_plan_pass *pp = &c->plan->passes[i];
    const char *file = pg_gc_pass_file(c, i);
    char sp[PG_JSON_PATH_MAX + 48];
    pg_gc_slot_path(c, i, s, sp, sizeof sp);
    int r = find_resource(pl, res_name);
    if (r < 0)
        return pg_fail(c->err, PG_ERR_UNKNOWN_RESOURCE, "%s: %s: unknown resource '%s'", file, sp,
                       res_name);
    const pg_resource_desc *rd = &pl->resources[r];
    if ((unsigned)sd->access >= PG_ACCESS_COUNT || !access_fits_kind(sd->access, sd->kind))
        return pg_fail(c->err, PG_ERR_SCHEMA,
                       "%s: %s: pass type '%s' declares slot '%s' as a%s %s with access '%s' "
                       "(a bug in the pass type)",
                       file, sp, pp->type->name, sd->name, sd->kind == PG_RES_IMAGE ? "n" : "",
                       pg_res_kind_name(sd->kind), pg_access_name(sd->access));
    if (sd->kind != rd->kind)
        return pg_fail(c->err, PG_ERR_FORMAT, "%s: %s: slot '%s' needs a%s %s, '%s' is a%s %s",
                       file, sp, sd->name, sd->kind == PG_RES_IMAGE ? "n" : "",
                       pg_res_kind_name(sd->kind), rd->name, rd->kind == PG_RES_IMAGE ? "n" : "",
                       pg_res_kind_name(rd->kind));
    pg_sync_info sync = pg_access_sync(sd->access, sd->stages, rd->kind, rd->format);
    if (is_write && !sync.writes)
        return pg_fail(c->err, PG_ERR_SCHEMA,
                       "%s: %s: pass type '%s' declares write slot '%s' with read-only access "
                       "'%s' (a bug in the pass type)",
                       file, sp, pp->type->name, sd->name, pg_access_name(sd->access));
    if (!is_write && !sync.reads)
        return pg_fail(c->err, PG_ERR_SCHEMA,
                       "%s: %s: pass type '%s' declares read slot '%s' with write-only access "
                       "'%s' (a bug in the pass type)",
                       file, sp, pp->type->name, sd->name, pg_access_name(sd->access));
    if (rd->kind == PG_RES_IMAGE) {
        const pg_format_info *fi = pg_format_get(rd->format);
        if (rd->format == PG_FMT_UNDEFINED || fi->fmt_class == PG_FMTCLASS_NONE)
            return pg_fail(c->err, PG_ERR_FORMAT, "%s: %s: resource '%s' has no format", file, sp,
                           rd->name);
        uint32_t declared = sd->formats ? (sd->formats & PG_FMTCLASS_ANY) : PG_FMTCLASS_ANY;
        uint32_t allowed = declared & access_format_classes(sd->access);
        if (!allowed)
            return pg_fail(c->err, PG_ERR_SCHEMA,
                           "%s: %s: pass type '%s' slot '%s' (%s) accepts %s, which that access "
                           "cannot use (a bug in the pass type)",
                           file, sp, pp->type->name, sd->name, pg_access_name(sd->access),
                           format_class_phrase(declared));
        if (!((uint32_t)fi->fmt_class & allowed))
            return pg_fail(c->err, PG_ERR_FORMAT,
                           "%s: %s: slot '%s' (%s) needs %s, resource '%s' is %s", file, sp,
                           sd->name, pg_access_name(sd->access), format_class_phrase(allowed),
                           rd->name, fi->name);
        if (is_storage(sd->access) && !fi->storage_ok)
            return pg_fail(c->err, PG_ERR_FORMAT,
                           "%s: %s: slot '%s' (%s) needs a format usable as a storage image, "
                           "resource '%s' is %s (not storage-capable)",
                           file, sp, sd->name, pg_access_name(sd->access), rd->name, fi->name);
    }
    if (sd->initializes && (!is_write || !sync.reads))
        return pg_fail(c->err, PG_ERR_SCHEMA,
                       "%s: %s: pass type '%s' marks slot '%s' (%s) as initialized by the pass, "
                       "which only a write slot whose access reads can be (a bug in the pass type)",
                       file, sp, pp->type->name, sd->name, pg_access_name(sd->access));
    if (sd->partial && (!is_write || !sync.full_write))
        return pg_fail(c->err, PG_ERR_SCHEMA,
                       "%s: %s: pass type '%s' marks slot '%s' (%s) as a partial write, which only "
                       "a write slot with a full-write access can be (a bug in the pass type)",
                       file, sp, pp->type->name, sd->name, pg_access_name(sd->access));
    if (sd->partial) sync.full_write = false;
    pg_plan_slot *ps = &pp->slots[s];
    ps->resource = r;
    ps->is_write = is_write;
    ps->decl = *sd;
    ps->sync = sync;
    return PG_OK;
}

/* Merges slot s of pass i into the pass's use of its resource. An image has one layout during a
 * pass: slots that disagree are an error, except depth that is both depth-tested read-only and
 * sampled, which DEPTH_READ_ONLY_OPTIMAL allows (the slots' sync.layout is updated to it). */
static pg_result merge_slot(compile_ctx *c, int i, int s)
{
    pg_plan_pass *pp = &c->plan->passes[i];
    const pg_plan_slot *ps = &pp->slots[s];
    const pg_resource_desc *rd = &c->pl->resources[ps->resource];
    pass_use *u = pg_gc_find_use(c, i, ps->resource);
    if (!u) {
        u = &c->uses[i][c->n_uses[i]++];
        memset(u, 0, sizeof *u);
        u->res = ps->resource;
        u->slot = s;
        u->layout = ps->sync.layout;
    } else if (rd->kind == PG_RES_IMAGE && u->layout != ps->sync.layout) {
        const uint32_t a = u->layout, b = ps->sync.layout;
        const bool depth_ro = (a == VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL ||
                               a == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL) &&
                              (b == VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL ||
                               b == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL) &&
                              pg_format_get(rd->format)->fmt_class == PG_FMTCLASS_DEPTH;
        if (!depth_ro) {
            char pth[PG_JSON_PATH_MAX + 16];
            pg_gc_pass_path(c, i, pth, sizeof pth);
            const pg_plan_slot *first = &pp->slots[u->slot];
            return pg_fail(c->err, PG_ERR_FORMAT,
                           "%s: %s: resource '%s' is used as '%s' (%s layout) and '%s' (%s "
                           "layout) in the same pass; an image has one layout during a pass",
                           pg_gc_pass_file(c, i), pth, rd->name, pg_access_name(first->decl.access),
                           pg_layout_name(a), pg_access_name(ps->decl.access), pg_layout_name(b));
        }
        u->layout = VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL;
    }
    u->stages |= ps->sync.stages;
    u->access |= ps->sync.access;
    u->reads |= ps->sync.reads;
    u->writes |= ps->sync.writes;
    u->full_write |= ps->sync.full_write;
    u->initializes |= ps->decl.initializes;
    return PG_OK;
}

/* A pass renders into its attachments over one area: colour and depth attachments of different
 * sizes at this output size would leave part of one outside the render area (a Vulkan error, and a
 * crash in drivers). Refused naming both resources and their sizes. */
static pg_result check_attachment_extents(compile_ctx *c, int i)
{
    const pg_plan_pass *pp = &c->plan->passes[i];
    int first = -1;
    uint64_t fw = 0, fh = 0;
    for (uint32_t s = 0; s < pp->n_slots; s++) {
        const pg_plan_slot *ps = &pp->slots[s];
        if (ps->decl.unused || ps->decl.access > PG_ACCESS_DEPTH_READ) continue; /* not an attachment */
        uint64_t w, h;
        pg_resource_extent(&c->pl->resources[ps->resource], c->desc->output_width, c->desc->output_height, &w, &h);
        if (first < 0) {
            first = (int)s;
            fw = w;
            fh = h;
            continue;
        }
        if (w == fw && h == fh) continue;
        char pth[PG_JSON_PATH_MAX + 16];
        pg_gc_pass_path(c, i, pth, sizeof pth);
        return pg_fail(c->err, PG_ERR_FORMAT,
                       "%s: %s: attachments '%s' (%llux%llu, %s) and '%s' (%llux%llu, %s) differ in size at "
                       "output %ux%u; a pass renders all its attachments over one area",
                       pg_gc_pass_file(c, i), pth, c->pl->resources[pp->slots[first].resource].name,
                       (unsigned long long)fw, (unsigned long long)fh, pg_access_name(pp->slots[first].decl.access),
                       c->pl->resources[ps->resource].name, (unsigned long long)w, (unsigned long long)h,
                       pg_access_name(ps->decl.access), c->desc->output_width, c->desc->output_height);
    }
    return PG_OK;
}

static pg_result phase_validate(compile_ctx *c)
{
    for (uint32_t i = 0; i < c->pl->n_passes; i++) {
        const pg_pass_desc *pd = &c->pl->passes[i];
        pg_plan_pass *pp = &c->plan->passes[i];
        pg_result r;
        for (uint32_t k = 0; k < pd->n_reads; k++)
            if ((r = validate_slot(c, (int)i, (int)k, pd->reads[k], &pp->decl.reads[k], false)))
                return r;
        for (uint32_t k = 0; k < pd->n_writes; k++)
            if ((r = validate_slot(c, (int)i, (int)(pd->n_reads + k), pd->writes[k],
                                   &pp->decl.writes[k], true)))
                return r;
        pp->n_slots = pd->n_reads + pd->n_writes;
        if ((r = check_attachment_extents(c, (int)i))) return r;
        c->n_uses[i] = 0;
        for (uint32_t s = 0; s < pp->n_slots; s++)
            if (!pp->slots[s].decl.unused && (r = merge_slot(c, (int)i, (int)s))) return r;
        for (uint32_t k = 0; k < c->n_uses[i]; k++) {
            pass_use *u = &c->uses[i][k];
            /* loads what it writes: not a full overwrite, unless the pass initializes it */
            u->full_write = u->initializes || (u->full_write && !u->reads);
            for (uint32_t s = 0; s < pp->n_slots; s++) /* the merged depth read-only layout */
                if (pp->slots[s].resource == u->res) pp->slots[s].sync.layout = u->layout;
            c->used_at_all[u->res] = true;
        }
    }
    return PG_OK;
}

/* ------------------------------------------------------------------------------------------ */

static void collect_explain(compile_ctx *c)
{
    const pg_pipeline *pl = c->pl;
    pg_graph_plan *plan = c->plan;
    if (plan->queue_note[0] && (c->desc->queues.n_queues >= 2 || c->desc->queues.why_single[0]))
        pg_gc_add_explain(plan, "%s", plan->queue_note);
    for (uint32_t i = 0; i < pl->n_omitted && i < PG_MAX_PASSES + PG_MAX_RESOURCES; i++)
        pg_gc_add_explain(plan, "omitted %s: %s", pl->omitted[i].what, pl->omitted[i].why);
    for (uint32_t p = 0; p < pl->n_passes; p++)
        if (plan->passes[p].culled)
            pg_gc_add_explain(plan, "culled pass '%s': %s", plan->passes[p].name,
                        plan->passes[p].cull_reason);
    for (uint32_t r = 0; r < pl->n_resources; r++)
        if (plan->resources[r].culled)
            pg_gc_add_explain(plan, "culled resource '%s': %s", plan->resources[r].name,
                        plan->resources[r].cull_reason);
    for (uint32_t k = 0; k < plan->n_order; k++) {
        const pg_plan_pass *pp = &plan->passes[plan->order[k]];
        for (uint32_t e = 0; e < pp->decl.n_explain && e < PG_MAX_PASS_EXPLAIN; e++)
            pg_gc_add_explain(plan, "%s: %s", pp->name, pp->decl.explain[e]);
    }
}

/* Immediate mode: the inferred barriers keep their resources and layouts, with full masks; the
 * executor adds a global memory barrier before every pass (pass-internal resources too). */
static void full_masks(pg_barrier *b)
{
    b->src_stages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    b->src_access = VK_ACCESS_2_MEMORY_WRITE_BIT;
    b->dst_stages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    b->dst_access = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
}

uint64_t pg_plan_generation(const pg_graph_plan *plan); /* graph_handle.c */
pg_result pg_queues_assign(pg_graph_plan *plan, const pg_compile_desc *desc, pg_error *err); /* graph_queues.c */
void pg_queues_schedule(pg_graph_plan *plan, const pg_compile_desc *desc);

static void make_immediate(pg_graph_plan *plan)
{
    plan->immediate = true;
    for (uint32_t k = 0; k < plan->n_order; k++) {
        pg_plan_pass *pp = &plan->passes[plan->order[k]];
        for (uint32_t b = 0; b < pp->n_barriers; b++) full_masks(&pp->barriers[b]);
    }
    for (uint32_t b = 0; b < plan->n_final_barriers; b++) full_masks(&plan->final_barriers[b]);
}

pg_result pg_graph_compile(const pg_compile_desc *desc, pg_graph_plan **out, pg_error *err)
{
    if (out) *out = NULL;
    if (!desc || !out || !desc->pipeline || !desc->registry)
        return pg_fail(err, PG_ERR_INVALID_ARG,
                       "pg_graph_compile: desc, desc->pipeline, desc->registry and out are required");
    pg_graph_plan *plan = calloc(1, sizeof *plan);
    compile_ctx *c = calloc(1, sizeof *c);
    if (!plan || !c) {
        free(plan);
        free(c);
        return pg_fail(err, PG_ERR_OOM, "pg_graph_compile: out of memory");
    }
    c->desc = desc;
    c->pl = desc->pipeline;
    c->plan = plan;
    c->err = err;
    plan->n_passes = c->pl->n_passes;
    pg_result r = check_inputs(c);
    if (!r) r = phase_declare(c);
    if (!r) r = phase_validate(c);
    if (!r) r = pg_gc_phase_order(c);
    if (!r) r = pg_gc_phase_cull(c);
    if (!r) r = pg_gc_phase_lifetimes(c);
    if (!r) r = pg_queues_assign(plan, desc, err);
    if (!r) {
        pg_gc_phase_alias(c);
        pg_gc_phase_barriers(c);
        pg_queues_schedule(plan, desc);
        if (desc->immediate) make_immediate(plan);
        collect_explain(c);
        plan->generation = pg_plan_generation(plan); /* last: it hashes the rest */
    }
    free(c);
    if (r) {
        free(plan);
        return r;
    }
    *out = plan;
    return PG_OK;
}

void pg_graph_plan_free(pg_graph_plan *plan)
{
    free(plan);
}
