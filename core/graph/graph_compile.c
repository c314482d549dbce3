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
#include "graph.h"
#include "alias_pack.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <vulkan/vulkan_core.h>

#define MAX_USES (2 * PG_MAX_SLOTS)
#define MAX_VISIBLE 8
#define MAX_BYTES (1ull << 40) /* 1 TiB: anything larger is a mistake (or an overflow) */
#define MAX_EXTENT 65536u

/* Access bits that write. A barrier's src_access only needs these (read bits in a source scope
 * make nothing available), so the plan keeps src_access to the writes. */
#define WRITE_ACCESS_BITS                                                                    \
    (VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |                 \
     VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT |       \
     VK_ACCESS_2_HOST_WRITE_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT |                             \
     VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT)

/* One resource as one pass touches it: all of the pass's slots bound to it, merged. */
typedef struct pass_use {
    int res;
    int slot; /* first plan slot bound to res (for messages) */
    uint64_t stages, access;
    uint32_t layout; /* images; UNDEFINED (0) for buffers */
    bool reads, writes;
    bool full_write; /* some slot fully overwrites it and no slot reads it, or a slot is
                      * marked initializes (the pass writes every element before reading) */
    bool initializes;
} pass_use;

/* Synchronization state of one resource while walking the frame. */
typedef struct res_state {
    bool seen;                    /* used earlier in this walk */
    uint32_t layout;              /* current layout (images) */
    bool w_valid;                 /* a write happened (this frame, or at the end of the last) */
    uint64_t w_stages, w_access;  /* the last write */
    uint64_t r_stages, r_access;  /* reads since the last write */
    bool transitioned;            /* a layout transition happened since the last write */
    uint32_t n_vis;               /* (stages, access) pairs the last write is visible to */
    uint64_t vis_stages[MAX_VISIBLE], vis_access[MAX_VISIBLE];
} res_state;

typedef struct compile_ctx {
    const pg_compile_desc *desc;
    const pg_pipeline *pl;
    pg_graph_plan *plan;
    pg_error *err;
    uint32_t n_uses[PG_MAX_PASSES];
    pass_use uses[PG_MAX_PASSES][MAX_USES];
    bool edge[PG_MAX_PASSES][PG_MAX_PASSES]; /* edge[a][b]: a runs before b */
    int topo[PG_MAX_PASSES];                 /* every declared pass in dependency order */
    bool needed_res[PG_MAX_RESOURCES];
    bool used_at_all[PG_MAX_RESOURCES];
    res_state st[PG_MAX_RESOURCES];
    res_state end[PG_MAX_RESOURCES]; /* state at the end of the frame (after the output barrier) */
} compile_ctx;

/* ------------------------------------------------------------------------------------------ */
/* messages                                                                                   */

static const char *pass_file(const compile_ctx *c, int i)
{
    const pg_pass_desc *p = &c->pl->passes[i];
    if (p->file[0]) return p->file;
    if (c->pl->path[0]) return c->pl->path;
    return "<pipeline>";
}

static void pass_path(const compile_ctx *c, int i, char *buf, size_t size)
{
    const pg_pass_desc *p = &c->pl->passes[i];
    if (p->json_path[0])
        snprintf(buf, size, "%s", p->json_path);
    else
        snprintf(buf, size, "passes[%d]", i);
}

/* "passes[i].reads[k]" or "passes[i].writes[k]" for plan slot s (reads first, then writes). */
static void slot_path(const compile_ctx *c, int i, int s, char *buf, size_t size)
{
    char pp[PG_JSON_PATH_MAX + 16];
    pass_path(c, i, pp, sizeof pp);
    const uint32_t nr = c->pl->passes[i].n_reads;
    if ((uint32_t)s < nr)
        snprintf(buf, size, "%s.reads[%d]", pp, s);
    else
        snprintf(buf, size, "%s.writes[%d]", pp, s - (int)nr);
}

static const char *res_file(const compile_ctx *c, int r)
{
    const pg_resource_desc *d = &c->pl->resources[r];
    if (d->file[0]) return d->file;
    if (c->pl->path[0]) return c->pl->path;
    return "<pipeline>";
}

static void res_path(const compile_ctx *c, int r, char *buf, size_t size)
{
    const pg_resource_desc *d = &c->pl->resources[r];
    if (d->json_path[0])
        snprintf(buf, size, "%s", d->json_path);
    else
        snprintf(buf, size, "resources[%d]", r);
}

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

/* snprintf that may truncate on purpose (names are bounded, messages are not worth failing) */
static void fmt_into(char *dst, size_t size, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
static void fmt_into(char *dst, size_t size, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(dst, size, fmt, ap);
    va_end(ap);
}

static void add_explain(pg_graph_plan *plan, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static void add_explain(pg_graph_plan *plan, const char *fmt, ...)
{
    if (plan->n_explain >= PG_MAX_EXPLAIN) {
        pg_strlcpy(plan->explain[PG_MAX_EXPLAIN - 1], "(more explanations left out)",
                   PG_EXPLAIN_MAX);
        return;
    }
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(plan->explain[plan->n_explain], PG_EXPLAIN_MAX, fmt, ap);
    va_end(ap);
    plan->n_explain++;
}

/* ------------------------------------------------------------------------------------------ */
/* lookups                                                                                    */

static int find_resource(const pg_pipeline *pl, const char *name)
{
    for (uint32_t i = 0; i < pl->n_resources; i++)
        if (strcmp(pl->resources[i].name, name) == 0) return (int)i;
    return -1;
}

static int find_pass(const pg_pipeline *pl, const char *name)
{
    for (uint32_t i = 0; i < pl->n_passes; i++)
        if (strcmp(pl->passes[i].name, name) == 0) return (int)i;
    return -1;
}

static pass_use *find_use(compile_ctx *c, int p, int r)
{
    for (uint32_t k = 0; k < c->n_uses[p]; k++)
        if (c->uses[p][k].res == r) return &c->uses[p][k];
    return NULL;
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
                res_path(c, (int)i, rp, sizeof rp);
                return pg_fail(c->err, PG_ERR_SCHEMA, "%s: %s.name: resource '%s' declared twice",
                               res_file(c, (int)i), rp, pl->resources[i].name);
            }
    }
    for (uint32_t i = 0; i < pl->n_passes; i++) {
        const pg_pass_desc *p = &pl->passes[i];
        char pp[PG_JSON_PATH_MAX + 16];
        pass_path(c, (int)i, pp, sizeof pp);
        for (uint32_t j = 0; j < i; j++)
            if (strcmp(p->name, pl->passes[j].name) == 0)
                return pg_fail(c->err, PG_ERR_SCHEMA, "%s: %s.name: pass '%s' declared twice",
                               pass_file(c, (int)i), pp, p->name);
        if (p->n_reads > PG_MAX_SLOTS || p->n_writes > PG_MAX_SLOTS)
            return pg_fail(c->err, PG_ERR_LIMIT, "%s: %s: at most %d reads and %d writes",
                           pass_file(c, (int)i), pp, PG_MAX_SLOTS, PG_MAX_SLOTS);
        if (p->n_after > PG_MAX_AFTER)
            return pg_fail(c->err, PG_ERR_LIMIT, "%s: %s.after: at most %d entries",
                           pass_file(c, (int)i), pp, PG_MAX_AFTER);
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
        pass_path(c, (int)i, jp, sizeof jp);
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
                           "%s: %s.type: unknown pass type '%s' (known: %s)", pass_file(c, (int)i),
                           jp, pd->type, known[0] ? known : "none");
        }
        pp->type = t;
        if (!t->declare)
            return pg_fail(c->err, PG_ERR_INVALID_ARG, "%s: %s.type: pass type '%s' has no declare()",
                           pass_file(c, (int)i), jp, t->name);
        pg_declare_in in;
        memset(&in, 0, sizeof in);
        in.desc = pd;
        in.pipeline = pl;
        in.features = c->desc->features;
        in.output_width = c->desc->output_width;
        in.output_height = c->desc->output_height;
        pg_error e;
        memset(&e, 0, sizeof e);
        memset(&pp->decl, 0, sizeof pp->decl);
        pg_result r = t->declare(&in, &pp->decl, &e);
        if (r != PG_OK) {
            if (!e.msg[0])
                snprintf(e.msg, sizeof e.msg, "%s: %s: pass type '%s' rejected its options (%s)",
                         pass_file(c, (int)i), jp, t->name, pg_result_name(r));
            return pg_fail(c->err, r, "%s", e.msg);
        }
        r = pg_decl_check_counts(pd, &pp->decl, t, c->err);
        if (r != PG_OK) return r;
        if (pp->decl.n_defines > PG_MAX_DEFINES)
            return pg_fail(c->err, PG_ERR_LIMIT,
                           "%s: %s: pass type '%s' declares more than %d shader defines (or one "
                           "longer than %d characters)",
                           pass_file(c, (int)i), jp, t->name, PG_MAX_DEFINES, PG_NAME_MAX - 1);
        if (pp->decl.n_explain > 8) pp->decl.n_explain = 8;
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
    const char *file = pass_file(c, i);
    char sp[PG_JSON_PATH_MAX + 48];
    slot_path(c, i, s, sp, sizeof sp);
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
    pass_use *u = find_use(c, i, ps->resource);
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
            pass_path(c, i, pth, sizeof pth);
            const pg_plan_slot *first = &pp->slots[u->slot];
            return pg_fail(c->err, PG_ERR_FORMAT,
                           "%s: %s: resource '%s' is used as '%s' (%s layout) and '%s' (%s "
                           "layout) in the same pass; an image has one layout during a pass",
                           pass_file(c, i), pth, rd->name, pg_access_name(first->decl.access),
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
/* 3. order                                                                                   */

static bool has_after(const pg_pass_desc *p, const char *name)
{
    for (uint32_t k = 0; k < p->n_after && k < PG_MAX_AFTER; k++)
        if (strcmp(p->after[k], name) == 0) return true;
    return false;
}

static bool dfs_cycle(const compile_ctx *c, const bool *done, int u, int *color, int *path,
                      int *len, int *cyc, int *cyc_len)
{
    const int n = (int)c->pl->n_passes;
    color[u] = 1;
    path[(*len)++] = u;
    for (int v = 0; v < n; v++) {
        if (!c->edge[u][v] || done[v]) continue;
        if (color[v] == 1) {
            int start = 0;
            while (path[start] != v) start++;
            *cyc_len = 0;
            for (int k = start; k < *len; k++) cyc[(*cyc_len)++] = path[k];
            return true;
        }
        if (color[v] == 0 && dfs_cycle(c, done, v, color, path, len, cyc, cyc_len)) return true;
    }
    color[u] = 2;
    (*len)--;
    return false;
}

static pg_result report_cycle(compile_ctx *c, const bool *done)
{
    const int n = (int)c->pl->n_passes;
    int color[PG_MAX_PASSES] = {0}, path[PG_MAX_PASSES], cyc[PG_MAX_PASSES];
    int len = 0, cyc_len = 0;
    for (int s = 0; s < n && !cyc_len; s++)
        if (!done[s] && color[s] == 0) {
            len = 0;
            dfs_cycle(c, done, s, color, path, &len, cyc, &cyc_len);
        }
    if (cyc_len == 0) /* cannot happen: Kahn's algorithm stalled, so a cycle exists */
        return pg_fail(c->err, PG_ERR_CYCLE, "%s: cycle between passes", pass_file(c, 0));
    /* start the path at its first declared pass, so the message is the same however found */
    int lo = 0;
    for (int k = 1; k < cyc_len; k++)
        if (cyc[k] < cyc[lo]) lo = k;
    char msg[PG_ERROR_MSG_MAX - 64];
    size_t m = 0;
    msg[0] = 0;
    for (int k = 0; k <= cyc_len && m < sizeof msg; k++) {
        int w = snprintf(msg + m, sizeof msg - m, "%s%s", k ? " -> " : "",
                         c->pl->passes[cyc[(lo + k) % cyc_len]].name);
        if (w < 0) break;
        m += (size_t)w;
    }
    return pg_fail(c->err, PG_ERR_CYCLE,
                   "%s: cycle: %s (each pass must run after the one before it, through the "
                   "resources it reads and writes or \"after\")",
                   pass_file(c, cyc[lo]), msg);
}

static pg_result phase_order(compile_ctx *c)
{
    const pg_pipeline *pl = c->pl;
    const int n = (int)pl->n_passes;
    /* Writers of a resource, in declaration order, form a chain: the first may simply write;
     * every later one must read it (load, RMW) or name the previous writer in "after", otherwise
     * the order of the two writes would be a guess. Pure readers run after the LAST writer: a
     * resource has one final value per frame that every pure reader sees. */
    for (uint32_t r = 0; r < pl->n_resources; r++) {
        int prev = -1;
        for (int p = 0; p < n; p++) {
            pass_use *u = find_use(c, p, (int)r);
            if (!u || !u->writes) continue;
            if (prev >= 0) {
                if (!u->reads && !has_after(&pl->passes[p], pl->passes[prev].name)) {
                    char sp[PG_JSON_PATH_MAX + 48], pp[PG_JSON_PATH_MAX + 16];
                    int s = u->slot;
                    /* name a write slot bound to r */
                    for (uint32_t k = 0; k < c->plan->passes[p].n_slots; k++)
                        if (c->plan->passes[p].slots[k].resource == (int)r &&
                            c->plan->passes[p].slots[k].is_write) {
                            s = (int)k;
                            break;
                        }
                    slot_path(c, p, s, sp, sizeof sp);
                    pass_path(c, prev, pp, sizeof pp);
                    return pg_fail(c->err, PG_ERR_WRITE_CONFLICT,
                                   "%s: %s: resource '%s' is also written by pass '%s' (%s) with "
                                   "no ordering between them: make the later pass read it (load) "
                                   "or add \"after\": [\"%s\"]",
                                   pass_file(c, p), sp, pl->resources[r].name,
                                   pl->passes[prev].name, pp, pl->passes[prev].name);
                }
                c->edge[prev][p] = true;
            }
            prev = p;
        }
        if (prev < 0) continue;
        for (int p = 0; p < n; p++) {
            pass_use *u = find_use(c, p, (int)r);
            if (u && !u->writes && p != prev) c->edge[prev][p] = true;
        }
    }
    for (int p = 0; p < n; p++) {
        const pg_pass_desc *pd = &pl->passes[p];
        for (uint32_t k = 0; k < pd->n_after; k++) {
            int q = find_pass(pl, pd->after[k]);
            if (q < 0) {
                char pp[PG_JSON_PATH_MAX + 16];
                pass_path(c, p, pp, sizeof pp);
                return pg_fail(c->err, PG_ERR_SCHEMA, "%s: %s.after[%u]: unknown pass '%s'",
                               pass_file(c, p), pp, k, pd->after[k]);
            }
            c->edge[q][p] = true; /* q == p is a one-pass cycle, reported below */
        }
    }
    /* Kahn's algorithm, always taking the ready pass declared first: deterministic, and it keeps
     * declaration order wherever dependencies allow (immediate mode runs this order too: the
     * compiler moves a pass only where a dependency requires it). O(n^2) with n <= 64. */
    int indeg[PG_MAX_PASSES] = {0};
    bool done[PG_MAX_PASSES] = {false};
    for (int a = 0; a < n; a++)
        for (int b = 0; b < n; b++)
            if (c->edge[a][b]) indeg[b]++;
    for (int k = 0; k < n; k++) {
        int pick = -1;
        for (int p = 0; p < n && pick < 0; p++)
            if (!done[p] && indeg[p] == 0) pick = p;
        if (pick < 0) return report_cycle(c, done);
        done[pick] = true;
        c->topo[k] = pick;
        for (int b = 0; b < n; b++)
            if (c->edge[pick][b]) indeg[b]--;
    }
    /* A transient has no contents at the start of a frame: its first access must write it
     * without reading it first: a full write, a write declared partial (its readers read only
     * what it wrote), or a read-modify-write slot the pass marks as initialized by itself. A
     * blend, a depth load or a storage read-write as the first use would read undefined memory.
     * Checked over all passes, culled or not, so a mistake does not hide behind a cull. */
    for (uint32_t r = 0; r < pl->n_resources; r++) {
        if (pl->resources[r].lifetime != PG_LIFETIME_TRANSIENT) continue;
        for (int k = 0; k < n; k++) {
            int p = c->topo[k];
            pass_use *u = find_use(c, p, (int)r);
            if (!u) continue;
            if (!u->writes) {
                char sp[PG_JSON_PATH_MAX + 48];
                slot_path(c, p, u->slot, sp, sizeof sp);
                return pg_fail(c->err, PG_ERR_READ_BEFORE_WRITE,
                               "%s: %s: pass '%s' reads transient resource '%s' before any pass "
                               "writes it (make a pass write it first, or declare it persistent)",
                               pass_file(c, p), sp, pl->passes[p].name, pl->resources[r].name);
            }
            if (u->reads && !u->full_write) {
                /* name the slot that reads what it writes (else the first reading slot) */
                const pg_plan_pass *pp = &c->plan->passes[p];
                int s = -1;
                for (uint32_t k = 0; k < pp->n_slots; k++) {
                    const pg_plan_slot *ps = &pp->slots[k];
                    if (ps->resource != (int)r || ps->decl.unused || !ps->sync.reads) continue;
                    if (s < 0 || (ps->is_write && !pp->slots[s].is_write)) s = (int)k;
                }
                if (s < 0) s = u->slot;
                char sp[PG_JSON_PATH_MAX + 48];
                slot_path(c, p, s, sp, sizeof sp);
                return pg_fail(c->err, PG_ERR_READ_BEFORE_WRITE,
                               "%s: %s: pass '%s' reads transient resource '%s' before it is fully "
                               "written: it is the first pass to use it and slot '%s' (%s) reads "
                               "its contents, undefined at the start of a frame (write it in full "
                               "first, e.g. clear it, declare it persistent, or, if the pass writes "
                               "every element before reading any, mark the slot with "
                               "pg_decl_mark_initializes())",
                               pass_file(c, p), sp, pl->passes[p].name, pl->resources[r].name,
                               pp->slots[s].decl.name, pg_access_name(pp->slots[s].decl.access));
            }
            break;
        }
    }
    return PG_OK;
}

/* ------------------------------------------------------------------------------------------ */
/* 4. cull                                                                                    */

static bool pass_has_side_effects(const compile_ctx *c, int p)
{
    return c->pl->passes[p].side_effects || c->plan->passes[p].decl.side_effects;
}

static pg_result phase_cull(compile_ctx *c)
{
    const pg_pipeline *pl = c->pl;
    pg_graph_plan *plan = c->plan;
    const int n = (int)pl->n_passes;
    bool needed[PG_MAX_PASSES] = {false};
    /* Outputs must be produced by something. */
    const int outs[2] = {plan->output, plan->hdr_output};
    const char *keys[2] = {"output", "hdr_output"};
    for (int k = 0; k < 2; k++) {
        if (outs[k] < 0) continue;
        bool written = false;
        int skipped = -1;
        for (int p = 0; p < n && !written; p++) {
            pass_use *u = find_use(c, p, outs[k]);
            if (u && u->writes && plan->passes[p].decl.skip) skipped = p;
            else written = u && u->writes;
        }
        if (!written && skipped >= 0)
            return pg_fail(c->err, PG_ERR_NO_OUTPUT,
                           "%s: %s: '%s' is written only by pass '%s', which is skipped for this "
                           "scene (%s)",
                           pl->path[0] ? pl->path : "<pipeline>", keys[k],
                           pl->resources[outs[k]].name, plan->passes[skipped].name,
                           plan->passes[skipped].decl.skip_reason);
        if (!written)
            return pg_fail(c->err, PG_ERR_NO_OUTPUT, "%s: %s: no pass writes '%s'",
                           pl->path[0] ? pl->path : "<pipeline>", keys[k],
                           pl->resources[outs[k]].name);
        c->needed_res[outs[k]] = true;
    }
    /* Roots: passes with side effects and (below) the writers of the outputs. A pass runs if it
     * writes a needed resource; everything a running pass touches is needed. Iterate to a fixed
     * point (at most n rounds): a chain a -> b -> out needs two rounds in the worst order. */
    /* A pass that declared itself not needed for this scene (pg_decl_skip) is never a root and
     * never needed: its writes keep the previous writer's value, which is the one readers get. */
    for (int p = 0; p < n; p++) needed[p] = pass_has_side_effects(c, p) && !plan->passes[p].decl.skip;
    bool changed = true;
    while (changed) {
        changed = false;
        for (int p = 0; p < n; p++) {
            if (plan->passes[p].decl.skip) continue;
            if (!needed[p])
                for (uint32_t k = 0; k < c->n_uses[p]; k++)
                    if (c->uses[p][k].writes && c->needed_res[c->uses[p][k].res]) {
                        needed[p] = true;
                        changed = true;
                        break;
                    }
            if (needed[p])
                for (uint32_t k = 0; k < c->n_uses[p]; k++)
                    if (!c->needed_res[c->uses[p][k].res]) {
                        c->needed_res[c->uses[p][k].res] = true;
                        changed = true;
                    }
        }
    }
    plan->n_order = 0;
    for (int k = 0; k < n; k++) {
        int p = c->topo[k];
        pg_plan_pass *pp = &plan->passes[p];
        if (needed[p]) {
            plan->order[plan->n_order++] = p;
            continue;
        }
        pp->culled = true;
        if (pp->decl.skip) {
            pg_strlcpy(pp->cull_reason, pp->decl.skip_reason, sizeof pp->cull_reason);
            continue;
        }
        char list[PG_EXPLAIN_MAX];
        size_t len = 0;
        list[0] = 0;
        for (uint32_t u = 0; u < c->n_uses[p] && len < sizeof list; u++) {
            if (!c->uses[p][u].writes) continue;
            int w = snprintf(list + len, sizeof list - len, "%s%s", len ? ", " : "",
                             pl->resources[c->uses[p][u].res].name);
            if (w < 0) break;
            len += (size_t)w;
        }
        if (!list[0])
            snprintf(pp->cull_reason, sizeof pp->cull_reason,
                     "it writes nothing and has no side effects");
        else if (plan->hdr_output >= 0 && plan->hdr_output != plan->output)
            fmt_into(pp->cull_reason, sizeof pp->cull_reason,
                     "nothing reads its writes (%s) on the way to output '%s' or hdr_output '%s'",
                     list, pl->output, pl->hdr_output);
        else
            fmt_into(pp->cull_reason, sizeof pp->cull_reason,
                     "nothing reads its writes (%s) on the way to output '%s'", list, pl->output);
    }
    for (uint32_t r = 0; r < pl->n_resources; r++) {
        pg_plan_resource *pr = &plan->resources[r];
        if (c->needed_res[r]) continue;
        pr->culled = true;
        snprintf(pr->cull_reason, sizeof pr->cull_reason, "%s",
                 c->used_at_all[r] ? "not used by any pass that runs" : "not used by any pass");
    }
    return PG_OK;
}

/* ------------------------------------------------------------------------------------------ */
/* 5. sizes and lifetimes                                                                     */

static pg_result resolve_size(compile_ctx *c, int r)
{
    const pg_resource_desc *rd = &c->pl->resources[r];
    pg_plan_resource *pr = &c->plan->resources[r];
    char rp[PG_JSON_PATH_MAX + 16];
    res_path(c, r, rp, sizeof rp);
    if (rd->kind == PG_RES_IMAGE) {
        uint64_t w, h;
        if (rd->extent_mode == PG_EXTENT_RELATIVE) {
            const double sx = rd->scale[0], sy = rd->scale[1];
            if (!isfinite(sx) || !isfinite(sy) || sx < 0 || sy < 0 || sx > 16 || sy > 16)
                return pg_fail(c->err, PG_ERR_LIMIT, "%s: %s.scale: [%g, %g] is out of range",
                               res_file(c, r), rp, sx, sy);
            /* scale is a float: 1/3 is 0.33333334f, and 900 * that is 300.0000...6. Without the
             * small tolerance ceil() would give 301. */
            w = (uint64_t)ceil(c->desc->output_width * sx - 1e-4);
            h = (uint64_t)ceil(c->desc->output_height * sy - 1e-4);
        } else {
            w = rd->size[0];
            h = rd->size[1];
        }
        if (w < 1) w = 1;
        if (h < 1) h = 1;
        if (w > MAX_EXTENT || h > MAX_EXTENT)
            return pg_fail(c->err, PG_ERR_LIMIT, "%s: %s: image '%s' would be %llux%llu, at most %u a side",
                           res_file(c, r), rp, rd->name, (unsigned long long)w,
                           (unsigned long long)h, MAX_EXTENT);
        pr->width = (uint32_t)w;
        pr->height = (uint32_t)h;
        pr->size_bytes = w * h * pg_format_get(rd->format)->bytes_per_pixel;
        return PG_OK;
    }
    /* buffers: stride * product(count terms); everything is checked against 2^40 before it can
     * overflow 64 bits. */
    uint64_t count = 1;
    for (uint32_t t = 0; t < rd->n_count_terms && t < PG_MAX_COUNT_TERMS; t++) {
        uint64_t v = 0;
        switch (rd->count[t].kind) {
        case PG_COUNT_CONST: {
            double d = rd->count[t].value;
            if (!isfinite(d) || d < 0 || d > (double)MAX_BYTES)
                return pg_fail(c->err, PG_ERR_LIMIT, "%s: %s.count[%u]: %g is out of range",
                               res_file(c, r), rp, t, d);
            v = (uint64_t)ceil(d);
            break;
        }
        case PG_COUNT_LIGHTS: v = c->desc->features.light_count; break;
        case PG_COUNT_PIXELS:
            v = (uint64_t)c->desc->output_width * c->desc->output_height;
            break;
        default:
            return pg_fail(c->err, PG_ERR_SCHEMA, "%s: %s.count[%u]: unknown term", res_file(c, r),
                           rp, t);
        }
        if (v != 0 && count > MAX_BYTES / v)
            return pg_fail(c->err, PG_ERR_LIMIT,
                           "%s: %s: buffer '%s' count overflows (more than 2^40 elements)",
                           res_file(c, r), rp, rd->name);
        count *= v;
    }
    uint64_t stride = rd->stride;
    if (stride != 0 && count > MAX_BYTES / stride)
        return pg_fail(c->err, PG_ERR_LIMIT,
                       "%s: %s: buffer '%s' needs %llu x %llu bytes, more than the 2^40 byte limit",
                       res_file(c, r), rp, rd->name, (unsigned long long)count,
                       (unsigned long long)stride);
    uint64_t bytes = stride * count;
    /* A zero-sized buffer is not legal in Vulkan (e.g. no lights in the scene): keep one element
     * (at least 16 bytes) so descriptors stay valid; passes get the real count separately. */
    if (bytes == 0) bytes = stride > 16 ? stride : 16;
    pr->size_bytes = bytes;
    return PG_OK;
}

static pg_result phase_lifetimes(compile_ctx *c)
{
    pg_graph_plan *plan = c->plan;
    const pg_pipeline *pl = c->pl;
    plan->n_resources = pl->n_resources;
    for (uint32_t r = 0; r < pl->n_resources; r++) {
        const pg_resource_desc *rd = &pl->resources[r];
        pg_plan_resource *pr = &plan->resources[r];
        pg_strlcpy(pr->name, rd->name, sizeof pr->name);
        pr->kind = rd->kind;
        pr->lifetime = rd->lifetime;
        pr->format = rd->kind == PG_RES_IMAGE ? rd->format : PG_FMT_UNDEFINED;
        pr->desc_index = (int)r;
        pr->first_pass = pr->last_pass = -1;
        pr->block = -1;
        pr->is_output = (int)r == plan->output || (int)r == plan->hdr_output;
        pr->growable = rd->kind == PG_RES_BUFFER && rd->growable;
        pg_result res = resolve_size(c, (int)r);
        if (res) return res;
    }
    for (uint32_t k = 0; k < plan->n_order; k++) {
        const int p = plan->order[k];
        const pg_plan_pass *pp = &plan->passes[p];
        for (uint32_t s = 0; s < pp->n_slots; s++) {
            if (pp->slots[s].decl.unused) continue; /* bound but not touched this time */
            pg_plan_resource *pr = &plan->resources[pp->slots[s].resource];
            if (pr->first_pass < 0) pr->first_pass = (int)k;
            pr->last_pass = (int)k;
            pr->usage |= pp->slots[s].sync.usage;
        }
    }
    for (uint32_t r = 0; r < pl->n_resources; r++) {
        pg_plan_resource *pr = &plan->resources[r];
        if (!pr->is_output) continue;
        pr->last_pass = (int)plan->n_order; /* read back / presented after the last pass */
        pr->usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    }
    return PG_OK;
}

/* ------------------------------------------------------------------------------------------ */
/* 6. alias                                                                                   */

static const pass_use *first_use(const compile_ctx *c, int r)
{
    const pg_plan_resource *pr = &c->plan->resources[r];
    if (pr->first_pass < 0) return NULL;
    const int p = c->plan->order[pr->first_pass];
    for (uint32_t k = 0; k < c->n_uses[p]; k++)
        if (c->uses[p][k].res == r) return &c->uses[p][k];
    return NULL;
}

static void phase_alias(compile_ctx *c)
{
    pg_graph_plan *plan = c->plan;
    plan->aliasing_disabled = c->desc->disable_aliasing || c->desc->immediate;
    /* transients that run, by first use (ties: declaration index) */
    int list[PG_MAX_RESOURCES];
    int n = 0;
    for (uint32_t r = 0; r < plan->n_resources; r++) {
        pg_plan_resource *pr = &plan->resources[r];
        if (pr->lifetime != PG_LIFETIME_TRANSIENT || pr->culled || pr->first_pass < 0) continue;
        if (pr->growable) { /* re-created at run time with a new size: its own memory */
            plan->transient_bytes_unaliased += pr->size_bytes;
            plan->transient_bytes_aliased += pr->size_bytes;
            continue;
        }
        if (pr->queues == 3u) { /* used on both queues: sharing its bytes would race across them */
            plan->transient_bytes_unaliased += pr->size_bytes;
            plan->transient_bytes_aliased += pr->size_bytes;
            add_explain(plan, "resource '%s' is used on the graphics and the compute queue: own memory (a "
                              "memory block is shared only by transients of one queue)", pr->name);
            continue;
        }
        /* Sharing an earlier resource's bytes means starting from whatever it left: only a
         * resource whose first access overwrites everything without reading may do that. */
        const pass_use *fu = first_use(c, (int)r);
        pr->may_inherit = fu && fu->full_write;
        int k = n++;
        while (k > 0 && plan->resources[list[k - 1]].first_pass > pr->first_pass) {
            list[k] = list[k - 1];
            k--;
        }
        list[k] = (int)r;
    }
    /* lifetime x size packing with estimated sizes and alignments (core/graph/alias_pack.c) */
    _Static_assert(PG_MAX_RESOURCES <= PG_PACK_MAX, "the packer must take every resource");
    pg_pack_item items[PG_MAX_RESOURCES];
    pg_pack_place place[PG_MAX_RESOURCES];
    pg_pack_block blocks[PG_MAX_RESOURCES];
    for (int i = 0; i < n; i++) {
        const pg_plan_resource *pr = &plan->resources[list[i]];
        items[i] = (pg_pack_item){
            .size = pr->size_bytes,
            .alignment = pr->kind == PG_RES_IMAGE ? PG_ALIAS_EST_ALIGN_IMAGE : PG_ALIAS_EST_ALIGN_BUFFER,
            .type_bits = ~0u,
            .klass = (uint32_t)pr->kind + (pr->queues == 2u ? 2u : 0u), /* one queue per block */
            .first = pr->first_pass,
            .last = pr->last_pass,
            .may_inherit = pr->may_inherit,
        };
        plan->transient_bytes_unaliased += pr->size_bytes;
    }
    const int nb = pg_alias_pack(items, (uint32_t)n, !plan->aliasing_disabled, place, blocks);
    plan->n_blocks = nb > 0 ? (uint32_t)nb : 0;
    for (uint32_t b = 0; b < plan->n_blocks; b++) {
        memset(&plan->blocks[b], 0, sizeof plan->blocks[b]);
        plan->blocks[b].kind = (pg_res_kind)(blocks[b].klass & 1u);
        plan->blocks[b].queue = blocks[b].klass & 2u ? PG_QUEUE_COMPUTE : PG_QUEUE_GRAPHICS;
        plan->blocks[b].size_bytes = blocks[b].size;
        plan->transient_bytes_aliased += blocks[b].size;
    }
    for (int i = 0; i < n && nb > 0; i++) { /* members by first use */
        pg_plan_resource *pr = &plan->resources[list[i]];
        pg_plan_block *bl = &plan->blocks[place[i].block];
        bl->members[bl->n_members++] = list[i];
        pr->block = place[i].block;
        pr->block_offset = place[i].offset;
    }
}

/* ------------------------------------------------------------------------------------------ */
/* 7. barriers                                                                                */

typedef struct access_req {
    uint64_t stages, access;
    uint32_t layout;
    bool reads, writes;
} access_req;

static access_req req_of(const pass_use *u)
{
    access_req a = {u->stages, u->access, u->layout, u->reads, u->writes};
    return a;
}

static bool visible_to(const res_state *s, const access_req *a)
{
    for (uint32_t k = 0; k < s->n_vis; k++)
        if ((a->stages & ~s->vis_stages[k]) == 0 && (a->access & ~s->vis_access[k]) == 0)
            return true;
    return false;
}

static void add_visible(res_state *s, uint64_t stages, uint64_t access)
{
    if (s->n_vis == MAX_VISIBLE) { /* forget the oldest: at worst one barrier too many */
        memmove(s->vis_stages, s->vis_stages + 1, sizeof s->vis_stages[0] * (MAX_VISIBLE - 1));
        memmove(s->vis_access, s->vis_access + 1, sizeof s->vis_access[0] * (MAX_VISIBLE - 1));
        s->n_vis--;
    }
    s->vis_stages[s->n_vis] = stages;
    s->vis_access[s->n_vis] = access;
    s->n_vis++;
}

/* State after access a (barrier: one was placed right before it; layout_change: it did a layout
 * transition).
 *  - A write becomes the last write; earlier reads are ordered before it (the barrier that
 *    allowed the write waited for them) and nothing has seen it yet: visibility is EMPTY. (Even
 *    the same stages in a later pass need a barrier: e.g. compute storage write, then a compute
 *    storage read in the next dispatch.)
 *  - A read joins the readers; if a barrier brought the last write to it, its (stages, access)
 *    pair now sees the write. A layout transition is itself a write to the image, so after one
 *    only the transition's destination scope is known to see it, and later barriers must chain
 *    through those stages (tracked by "transitioned"). */
static void apply_access(res_state *s, const access_req *a, bool barrier, bool layout_change)
{
    s->seen = true;
    if (a->writes) {
        s->w_valid = true;
        s->w_stages = a->stages;
        s->w_access = a->access & WRITE_ACCESS_BITS;
        if (!s->w_access) s->w_access = a->access;
        s->r_stages = s->r_access = 0;
        s->transitioned = false;
        s->n_vis = 0;
    } else {
        s->r_stages |= a->stages;
        s->r_access |= a->access;
        if (barrier) {
            if (layout_change) {
                s->transitioned = true;
                s->n_vis = 0;
            }
            add_visible(s, a->stages, a->access);
        }
    }
    s->layout = a->layout;
}

/* Barrier rules for an access after the first one of the frame:
 *   layout change                     -> barrier (the transition must wait for earlier users)
 *   write after a write (WAW)         -> src = last write stages/access (+ readers since)
 *   write after reads (WAR)           -> src += reader stages (no access: reads need no flush)
 *   read of a write not yet visible   -> src = last write stages/access (RAW)
 * A read that changes layout (or follows a transition) also waits for the readers so far, so
 * the transition does not pull the image from under them and the chain of barriers holds.
 * Returns true and fills b when a barrier is needed. */
static bool decide_barrier(const res_state *s, const access_req *a, bool is_image, pg_barrier *b)
{
    const bool layout_change = is_image && s->layout != a->layout;
    const bool raw = a->reads && s->w_valid && (layout_change || !visible_to(s, a));
    const bool waw = a->writes && s->w_valid;
    const bool war = a->writes && s->r_stages != 0;
    if (!layout_change && !raw && !waw && !war) return false;
    b->src_stages = s->w_valid ? s->w_stages : 0;
    if (a->writes || layout_change || s->transitioned) b->src_stages |= s->r_stages;
    b->src_access = s->w_valid ? s->w_access : 0;
    b->dst_stages = a->stages;
    b->dst_access = a->access;
    b->old_layout = is_image ? s->layout : VK_IMAGE_LAYOUT_UNDEFINED;
    b->new_layout = is_image ? a->layout : VK_IMAGE_LAYOUT_UNDEFINED;
    char why[48] = "";
    const char *parts[4] = {raw ? "RAW" : NULL, waw ? "WAW" : NULL, war ? "WAR" : NULL,
                            layout_change ? "layout" : NULL};
    for (int k = 0; k < 4; k++)
        if (parts[k]) {
            if (why[0]) strncat(why, "+", sizeof why - strlen(why) - 1);
            strncat(why, parts[k], sizeof why - strlen(why) - 1);
        }
    pg_strlcpy(b->why, why, sizeof b->why);
    return true;
}

static pg_barrier new_barrier(int r, bool is_image)
{
    pg_barrier b;
    memset(&b, 0, sizeof b);
    b.resource = r;
    b.is_image = is_image;
    b.alias_prev = -1;
    return b;
}

static access_req output_req(const compile_ctx *c)
{
    access_req a = {0};
    a.layout = c->desc->output_layout ? c->desc->output_layout
                                      : (uint32_t)VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    a.reads = true;
    if (a.layout != VK_IMAGE_LAYOUT_PRESENT_SRC_KHR) { /* presentation waits on a semaphore */
        a.stages = c->desc->output_stages ? c->desc->output_stages : VK_PIPELINE_STAGE_2_COPY_BIT;
        a.access = VK_ACCESS_2_TRANSFER_READ_BIT;
    }
    return a;
}

static void push_barrier(pg_plan_pass *pp, const pg_barrier *b)
{
    /* one use per resource per pass and at most 2 * PG_MAX_SLOTS uses... */
    if (pp->n_barriers < PG_MAX_BARRIERS_PER_PASS) pp->barriers[pp->n_barriers++] = *b;
}

/* Walks the frame. Pass 1 (emit = false) only finds each resource's end-of-frame state (after
 * the output barrier), which is the start state of persistent/imported resources in the next
 * frame. Pass 2 (emit = true) places the barriers. */
static void walk_frame(compile_ctx *c, bool emit)
{
    pg_graph_plan *plan = c->plan;
    memset(c->st, 0, sizeof c->st);
    for (uint32_t k = 0; k < plan->n_order; k++) {
        const int p = plan->order[k];
        pg_plan_pass *pp = &plan->passes[p];
        for (uint32_t i = 0; i < c->n_uses[p]; i++) {
            const pass_use *u = &c->uses[p][i];
            const int r = u->res;
            const pg_plan_resource *pr = &plan->resources[r];
            const bool img = pr->kind == PG_RES_IMAGE;
            res_state *s = &c->st[r];
            const access_req a = req_of(u);
            pg_barrier b = new_barrier(r, img);
            if (!emit && !s->seen) {
                apply_access(s, &a, true, true);
                continue;
            }
            if (s->seen) {
                bool need = decide_barrier(s, &a, img, &b);
                if (emit && need) push_barrier(pp, &b);
                apply_access(s, &a, need, need && img && b.old_layout != b.new_layout);
                continue;
            }
            /* first use in the frame (emit pass) */
            if (pr->lifetime == PG_LIFETIME_TRANSIENT) {
                /* Every earlier member of the block that ended before this use may share bytes
                 * with it at run time, unless it may not inherit (the runtime re-packs the block with the real memory
                 * requirements, only ever inside the block): wait for all their accesses (last
                 * write and the reads since) and discard the contents. alias_prev names the
                 * latest one that overlaps in the planned placement (else the latest one). */
                int prev = -1, prev_overlap = -1;
                uint64_t src_stages = 0, src_access = 0;
                if (pr->block >= 0 && pr->may_inherit) { /* else it shares no earlier byte */
                    const pg_plan_block *bl = &plan->blocks[pr->block];
                    for (uint32_t m = 0; m < bl->n_members; m++) {
                        const int q = bl->members[m];
                        const pg_plan_resource *qr = &plan->resources[q];
                        if (q == r || !(qr->last_pass < pr->first_pass)) continue;
                        src_stages |= c->st[q].w_stages | c->st[q].r_stages;
                        src_access |= c->st[q].w_access;
                        if (prev < 0 || qr->last_pass >= plan->resources[prev].last_pass) prev = q;
                        const bool overlap = qr->block_offset < pr->block_offset + pr->size_bytes &&
                                             pr->block_offset < qr->block_offset + qr->size_bytes;
                        if (overlap && (prev_overlap < 0 ||
                                        qr->last_pass >= plan->resources[prev_overlap].last_pass))
                            prev_overlap = q;
                    }
                }
                bool placed = false;
                if (prev >= 0) {
                    b.src_stages = src_stages;
                    b.src_access = src_access;
                    b.alias_prev = prev_overlap >= 0 ? prev_overlap : prev;
                    pg_strlcpy(b.why, "alias first use", sizeof b.why);
                    placed = true;
                } else if (img) {
                    /* nothing earlier in the frame: the contents are not needed */
                    pg_strlcpy(b.why, "first use", sizeof b.why);
                    placed = true;
                }
                if (placed) {
                    b.dst_stages = a.stages;
                    b.dst_access = a.access;
                    b.old_layout = VK_IMAGE_LAYOUT_UNDEFINED;
                    b.new_layout = img ? a.layout : VK_IMAGE_LAYOUT_UNDEFINED;
                    push_barrier(pp, &b);
                }
                memset(s, 0, sizeof *s);
                apply_access(s, &a, placed, img);
                continue;
            }
            /* persistent / imported: the previous frame's end state leads into this use. A
             * resource only read all frame long, in one layout, needs nothing. */
            *s = c->end[r];
            bool need = true;
            if (!s->w_valid && !a.writes && (!img || s->layout == a.layout)) need = false;
            if (need) {
                b.wrap = true;
                b.src_stages = s->w_stages | s->r_stages;
                b.src_access = s->w_valid ? s->w_access : 0;
                b.dst_stages = a.stages;
                b.dst_access = a.access;
                b.old_layout = img ? s->layout : VK_IMAGE_LAYOUT_UNDEFINED;
                b.new_layout = img ? a.layout : VK_IMAGE_LAYOUT_UNDEFINED;
                pg_strlcpy(b.why, "frame wrap", sizeof b.why);
                push_barrier(pp, &b);
                /* The wrap barrier waited for every access of the last frame: later barriers in
                 * this frame chain through it and need not name last frame's readers again. */
                s->r_stages = s->r_access = 0;
                s->n_vis = 0;
            }
            apply_access(s, &a, need, need && img && b.old_layout != b.new_layout);
        }
    }
    /* after the last pass: the outputs go to the layout the caller reads them in */
    const access_req oa = output_req(c);
    const int outs[2] = {plan->output,
                         plan->hdr_output != plan->output ? plan->hdr_output : -1};
    for (int k = 0; k < 2; k++) {
        const int r = outs[k];
        if (r < 0) continue;
        res_state *s = &c->st[r];
        pg_barrier b = new_barrier(r, true);
        bool need = decide_barrier(s, &oa, true, &b);
        if (need && emit) {
            pg_strlcpy(b.why, "output", sizeof b.why);
            plan->final_barriers[plan->n_final_barriers++] = b;
        }
        apply_access(s, &oa, need, need && b.old_layout != b.new_layout);
    }
    if (!emit) memcpy(c->end, c->st, sizeof c->end);
}

static void phase_barriers(compile_ctx *c)
{
    walk_frame(c, false);
    walk_frame(c, true);
}

/* ------------------------------------------------------------------------------------------ */

static void collect_explain(compile_ctx *c)
{
    const pg_pipeline *pl = c->pl;
    pg_graph_plan *plan = c->plan;
    if (plan->queue_note[0] && (c->desc->queues.n_queues >= 2 || c->desc->queues.why_single[0]))
        add_explain(plan, "%s", plan->queue_note);
    for (uint32_t i = 0; i < pl->n_omitted && i < PG_MAX_PASSES + PG_MAX_RESOURCES; i++)
        add_explain(plan, "omitted %s: %s", pl->omitted[i].what, pl->omitted[i].why);
    for (uint32_t p = 0; p < pl->n_passes; p++)
        if (plan->passes[p].culled)
            add_explain(plan, "culled pass '%s': %s", plan->passes[p].name,
                        plan->passes[p].cull_reason);
    for (uint32_t r = 0; r < pl->n_resources; r++)
        if (plan->resources[r].culled)
            add_explain(plan, "culled resource '%s': %s", plan->resources[r].name,
                        plan->resources[r].cull_reason);
    for (uint32_t k = 0; k < plan->n_order; k++) {
        const pg_plan_pass *pp = &plan->passes[plan->order[k]];
        for (uint32_t e = 0; e < pp->decl.n_explain && e < 8; e++)
            add_explain(plan, "%s: %s", pp->name, pp->decl.explain[e]);
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
    if (!r) r = phase_order(c);
    if (!r) r = phase_cull(c);
    if (!r) r = phase_lifetimes(c);
    if (!r) r = pg_queues_assign(plan, desc, err);
    if (!r) {
        phase_alias(c);
        phase_barriers(c);
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
