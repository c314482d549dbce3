/* graph_lifetimes.c - compile phases 5 (sizes and lifetimes) and 6 (alias); see graph_compile.c. */
#include "graph_compile_internal.h"
#include "alias_pack.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <vulkan/vulkan_core.h>

/* ------------------------------------------------------------------------------------------ */
/* 5. sizes and lifetimes                                                                     */

static pg_result resolve_size(compile_ctx *c, int r)
{
    const pg_resource_desc *rd = &c->pl->resources[r];
    pg_plan_resource *pr = &c->plan->resources[r];
    char rp[PG_JSON_PATH_MAX + 16];
    pg_gc_res_path(c, r, rp, sizeof rp);
    if (rd->kind == PG_RES_IMAGE) {
        uint64_t w, h;
        if (rd->extent_mode == PG_EXTENT_RELATIVE) {
            const double sx = rd->scale[0], sy = rd->scale[1];
            if (!isfinite(sx) || !isfinite(sy) || sx < 0 || sy < 0 || sx > 16 || sy > 16)
                return pg_fail(c->err, PG_ERR_LIMIT, "%s: %s.scale: [%g, %g] is out of range",
                               pg_gc_res_file(c, r), rp, sx, sy);
        }
        pg_resource_extent(rd, c->desc->output_width, c->desc->output_height, &w, &h);
        if (w > MAX_EXTENT || h > MAX_EXTENT)
            return pg_fail(c->err, PG_ERR_LIMIT, "%s: %s: image '%s' would be %llux%llu, at most %u a side",
                           pg_gc_res_file(c, r), rp, rd->name, (unsigned long long)w,
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
                               pg_gc_res_file(c, r), rp, t, d);
            v = (uint64_t)ceil(d);
            break;
        }
        case PG_COUNT_VAR: {
            const pg_compile_var *var = pg_vars_find(&c->desc->vars, rd->count[t].var);
            if (!var) {
                char known[PG_MAX_COMPILE_VARS * (PG_VAR_NAME_MAX + 2) + 8] = "none";
                size_t len = 0;
                for (uint32_t i = 0; i < c->desc->vars.n && i < PG_MAX_COMPILE_VARS; i++)
                    len += (size_t)snprintf(known + len, sizeof known - len, "%s%s", i ? ", " : "",
                                            c->desc->vars.v[i].name);
                return pg_fail(c->err, PG_ERR_SCHEMA,
                               "%s: %s.count[%u]: \"%s\" is no compile variable (this compile has: %s)",
                               pg_gc_res_file(c, r), rp, t, rd->count[t].var, known);
            }
            if (var->value < 0 || (uint64_t)var->value > MAX_BYTES)
                return pg_fail(c->err, PG_ERR_LIMIT, "%s: %s.count[%u]: \"%s\" = %lld is out of range",
                               pg_gc_res_file(c, r), rp, t, rd->count[t].var, (long long)var->value);
            v = (uint64_t)var->value;
            break;
        }
        case PG_COUNT_PIXELS:
            v = (uint64_t)c->desc->output_width * c->desc->output_height;
            break;
        default:
            return pg_fail(c->err, PG_ERR_SCHEMA, "%s: %s.count[%u]: unknown term", pg_gc_res_file(c, r),
                           rp, t);
        }
        if (v != 0 && count > MAX_BYTES / v)
            return pg_fail(c->err, PG_ERR_LIMIT,
                           "%s: %s: buffer '%s' count overflows (more than 2^40 elements)",
                           pg_gc_res_file(c, r), rp, rd->name);
        count *= v;
    }
    uint64_t stride = rd->stride;
    if (stride != 0 && count > MAX_BYTES / stride)
        return pg_fail(c->err, PG_ERR_LIMIT,
                       "%s: %s: buffer '%s' needs %llu x %llu bytes, more than the 2^40 byte limit",
                       pg_gc_res_file(c, r), rp, rd->name, (unsigned long long)count,
                       (unsigned long long)stride);
    uint64_t bytes = stride * count;
    /* A zero-sized buffer is not legal in Vulkan (e.g. no lights in the scene): keep one element
     * (at least 16 bytes) so descriptors stay valid; passes get the real count separately. */
    if (bytes == 0) bytes = stride > 16 ? stride : 16;
    pr->size_bytes = bytes;
    return PG_OK;
}

pg_result pg_gc_phase_lifetimes(compile_ctx *c)
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

void pg_gc_phase_alias(compile_ctx *c)
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
            pg_gc_add_explain(plan, "resource '%s' is used on the graphics and the compute queue: own memory (a "
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
