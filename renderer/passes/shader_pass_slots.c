/* shader_pass_slots.c - the second half of the `shader` pass type's declare (shader_pass_declare.h):
 * push-constant values from options.params (checked member by member against the SPIR-V), colour
 * targets and depth against the fragment outputs, the slots in the order of the pass's reads and
 * writes, the compute dispatch, the explanation line. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <cjson/cJSON.h>
#include <vulkan/vulkan.h>

#include "shader_pass_declare.h"

static const char *const k_blends[] = {"none", "add", "over", NULL};
static const char *const k_filters[] = {"linear", "nearest", NULL};
static const char *const k_address[] = {"clamp", "repeat", "mirror", NULL};
static const char *const k_depth_tests[] = {"less", "equal", NULL};

static const char *scalar_name(pg_spv_scalar s)
{
    return s == PG_SPV_FLOAT ? "float" : s == PG_SPV_INT ? "int" : s == PG_SPV_UINT ? "uint" : "bool";
}

/* One number of a push member into its bytes (float, int, uint, bool as uint). A GLSL bool member
 * of a push block compiles to a uint: it takes true/false too. */
static bool put_number(const cJSON *v, pg_spv_scalar s, unsigned char *dst)
{
    if (s == PG_SPV_BOOL || (s == PG_SPV_UINT && cJSON_IsBool(v))) {
        if (!cJSON_IsBool(v)) return false;
        uint32_t b = cJSON_IsTrue(v);
        memcpy(dst, &b, 4);
        return true;
    }
    if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble)) return false;
    double d = v->valuedouble;
    if (s == PG_SPV_FLOAT) {
        if (fabs(d) > 3.4e38) return false;
        float f = (float)d;
        memcpy(dst, &f, 4);
    } else if (s == PG_SPV_INT) {
        if (d != floor(d) || d < -2147483648.0 || d > 2147483647.0) return false;
        int32_t i = (int32_t)d;
        memcpy(dst, &i, 4);
    } else {
        if (d != floor(d) || d < 0 || d > 4294967295.0) return false;
        uint32_t u = (uint32_t)d;
        memcpy(dst, &u, 4);
    }
    return true;
}

static pg_result read_member(sp_ctx *c, const cJSON *ps, const pg_spv_member *m)
{
    char sub[PG_NAME_MAX + 16];
    snprintf(sub, sizeof sub, "params.%s", m->name);
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(ps, m->name);
    if (m->scalar == PG_SPV_OTHER || m->array_size != 1 || m->components > 4)
        return pg_sp_fail(c, PG_ERR_SHADER, sub,
                       "shader '%s' push-constant member '%s' is not a scalar or a vector: a params value is a "
                       "number or 2-4 numbers",
                       c->rel, m->name);
    if (m->bits != 32) /* a double, float16_t, int64_t...: 4-byte values would land in it wrongly */
        return pg_sp_fail(c, PG_ERR_SHADER, sub,
                          "shader '%s' push-constant member '%s' is a %u-bit %s: params values are 32-bit (float, int, "
                          "uint, bool and their vectors)",
                          c->rel, m->name, m->bits, scalar_name(m->scalar));
    if (!v)
        return pg_sp_fail(c, PG_ERR_SCHEMA, sub, "shader '%s' push-constant member '%s' (%s x %u) has no value", c->rel,
                       m->name, scalar_name(m->scalar), m->components);
    if (m->offset + 4 * m->components > SP_PUSH_MAX)
        return pg_sp_fail(c, PG_ERR_LIMIT, sub, "push-constant member '%s' ends past %d bytes", m->name, SP_PUSH_MAX);
    bool ok = true;
    if (m->components == 1) {
        ok = put_number(v, m->scalar, c->p->push + m->offset);
    } else {
        ok = cJSON_IsArray(v) && cJSON_GetArraySize(v) == (int)m->components;
        for (uint32_t k = 0; ok && k < m->components; k++)
            ok = put_number(cJSON_GetArrayItem(v, (int)k), m->scalar, c->p->push + m->offset + 4 * k);
    }
    if (!ok)
        return pg_sp_fail(c, PG_ERR_SCHEMA, sub, "expected %s%u %s value%s for shader '%s' member '%s'",
                       m->components > 1 ? "an array of " : "", m->components, scalar_name(m->scalar),
                       m->components > 1 ? "s" : "", c->rel, m->name);
    return PG_OK;
}

pg_result pg_sp_read_params(sp_ctx *c)
{
    const cJSON *ps = cJSON_GetObjectItemCaseSensitive(c->in->desc->options, "params");
    if (ps && !cJSON_IsObject(ps)) return pg_sp_fail(c, PG_ERR_SCHEMA, "params", "expected an object {\"member\": value}");
    pg_decl_runtime_param(c->out, c->p->push, sizeof c->p->push); /* (all zero without a push block) */
    if (c->p->form == SP_DRAW) {
        if (ps && ps->child)
            return pg_sp_fail(c, PG_ERR_SCHEMA, "params",
                           "the draw form's push constants are the scene's per-draw block: give values as defines");
        return PG_OK;
    }
    const pg_spv_reflection *r = &c->refl;
    if (!r->has_push) {
        if (ps && ps->child)
            return pg_sp_fail(c, PG_ERR_SHADER, "params", "shader '%s' has no push_constant block for '%s'", c->rel,
                           ps->child->string);
        return PG_OK;
    }
    if (r->push_size > SP_PUSH_MAX)
        return pg_sp_fail(c, PG_ERR_LIMIT, "params", "shader '%s' push_constant block is %u bytes (at most %d)", c->rel,
                       r->push_size, SP_PUSH_MAX);
    c->p->push_size = r->push_size;
    for (uint32_t i = 0; i < r->n_push; i++) {
        pg_result e = read_member(c, ps, &r->push[i]);
        if (e) return e;
    }
    const cJSON *it;
    cJSON_ArrayForEach(it, ps)
    {
        bool found = false;
        for (uint32_t i = 0; i < r->n_push && !found; i++) found = !strcmp(r->push[i].name, it->string);
        if (!found) {
            char sub[PG_NAME_MAX + 16];
            snprintf(sub, sizeof sub, "params.%s", it->string);
            return pg_sp_fail(c, PG_ERR_SHADER, sub, "shader '%s' push_constant block %s has no member '%s'", c->rel,
                           r->push_name, it->string);
        }
    }
    return PG_OK;
}

/* The fragment outputs: locations 0..n-1, one per target, of the target's class. */
static pg_result check_outputs(sp_ctx *c, const cJSON *targets)
{
    const pg_spv_reflection *r = &c->refl;
    uint32_t seen = 0;
    for (uint32_t i = 0; i < r->n_outputs; i++) {
        uint32_t loc = r->outputs[i].location;
        if (loc >= c->p->n_targets)
            return pg_sp_fail(c, PG_ERR_SHADER, "targets",
                           "shader '%s' output '%s' is at location %u but targets lists %u image(s)", c->rel,
                           r->outputs[i].name, loc, c->p->n_targets);
        seen |= 1u << loc;
        const char *tname = cJSON_GetArrayItem(targets, (int)loc)->valuestring;
        const pg_resource_desc *rd = pg_pipeline_find_resource(c->in->pipeline, tname);
        const bool uint_target = rd && pg_format_get(rd->format)->fmt_class == PG_FMTCLASS_UINT;
        const bool uint_out = r->outputs[i].scalar == PG_SPV_UINT || r->outputs[i].scalar == PG_SPV_INT;
        if (rd && uint_target != uint_out)
            return pg_sp_fail(c, PG_ERR_FORMAT, "targets", "shader '%s' output '%s' (location %u) is %s but target '%s' is %s",
                           c->rel, r->outputs[i].name, loc, scalar_name(r->outputs[i].scalar), tname,
                           pg_format_get(rd->format)->name);
    }
    for (uint32_t t = 0; t < c->p->n_targets; t++)
        if (!(seen & (1u << t)))
            return pg_sp_fail(c, PG_ERR_SHADER, "targets", "shader '%s' writes no output at location %u (target '%s')",
                           c->rel, t, cJSON_GetArrayItem(targets, (int)t)->valuestring);
    return PG_OK;
}

static pg_result read_depth(sp_ctx *c, int blend)
{
    const cJSON *o = c->in->desc->options;
    const cJSON *dv = cJSON_GetObjectItemCaseSensitive(o, "depth");
    int test = 0;
    pg_result r = pg_opt_enum(c->in->desc, "depth_test", k_depth_tests, 0, &test, c->err);
    bool clear = true;
    if (!r) r = pg_opt_bool(c->in->desc, "depth_clear", true, &clear, c->err);
    if (r) return r;
    if (!cJSON_IsString(dv))
        return pg_sp_fail(c, PG_ERR_SCHEMA, "depth", "the draw form needs a depth image (\"depth\": RESOURCE)");
    const pg_pass_desc *d = c->in->desc;
    int w = pg_sp_find_in(d->writes, d->n_writes, dv->valuestring);
    int rd = w < 0 ? pg_sp_find_in(d->reads, d->n_reads, dv->valuestring) : -1;
    if (w < 0 && rd < 0)
        return pg_sp_fail(c, PG_ERR_SCHEMA, "depth", "'%s' is in neither the pass's reads (test only) nor its writes",
                       dv->valuestring);
    int *use = w >= 0 ? &c->write_use[w] : &c->read_use[rd];
    if (*use != SP_USE_NONE) return pg_sp_fail(c, PG_ERR_SCHEMA, "depth", "'%s' is bound twice", dv->valuestring);
    *use = SP_USE_DEPTH;
    c->p->depth_compare = test == 1 ? VK_COMPARE_OP_EQUAL : VK_COMPARE_OP_LESS;
    c->p->depth_clear = w >= 0 && clear && test == 0;
    if (w < 0 && test == 0 && blend != SP_BLEND_OVER)
        return pg_sp_fail(c, PG_ERR_SCHEMA, "depth",
                       "'%s' is read only (in reads): test it \"equal\" or blend \"over\" (both leave depth unwritten)",
                       dv->valuestring);
    if (w >= 0 && (test == 1 || blend == SP_BLEND_OVER))
        return pg_sp_fail(c, PG_ERR_SCHEMA, "depth",
                       "'%s' is in the writes but an \"equal\" test or \"over\" blending writes no depth: put it "
                       "in the reads",
                       dv->valuestring);
    return PG_OK;
}

pg_result pg_sp_read_attachments(sp_ctx *c)
{
    const cJSON *o = c->in->desc->options;
    const cJSON *targets = cJSON_GetObjectItemCaseSensitive(o, "targets");
    int blend = 0, filter = 0, address = 0;
    pg_result r = pg_opt_enum(c->in->desc, "blend", k_blends, 0, &blend, c->err);
    if (!r) r = pg_opt_enum(c->in->desc, "filter", k_filters, 0, &filter, c->err);
    if (!r) r = pg_opt_enum(c->in->desc, "address", k_address, 0, &address, c->err);
    if (r) return r;
    c->p->filter = (uint8_t)(filter == 0 ? VK_FILTER_LINEAR : VK_FILTER_NEAREST);
    c->p->address = (uint8_t)(address == 0   ? VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE
                              : address == 1 ? VK_SAMPLER_ADDRESS_MODE_REPEAT
                                             : VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT);
    if (c->p->form == SP_COMPUTE) {
        static const char *const gfx_only[] = {"targets", "blend", "depth", "depth_test", "depth_clear"};
        for (size_t i = 0; i < sizeof gfx_only / sizeof gfx_only[0]; i++)
            if (cJSON_GetObjectItemCaseSensitive(o, gfx_only[i]))
                return pg_sp_fail(c, PG_ERR_SCHEMA, gfx_only[i], "a compute shader has no attachments");
        return PG_OK;
    }
    if (!cJSON_IsArray(targets) || cJSON_GetArraySize(targets) > SP_MAX_TARGETS)
        return pg_sp_fail(c, PG_ERR_SCHEMA, "targets", "expected an array of 0..%d written images (locations 0, 1, ...)",
                       SP_MAX_TARGETS);
    const pg_pass_desc *d = c->in->desc;
    c->p->n_targets = (uint8_t)cJSON_GetArraySize(targets);
    if (c->p->n_targets == 0 && c->p->form != SP_DRAW) /* its viewport is its targets' size: 0 x 0 (nothing drawn) */
        return pg_sp_fail(c, PG_ERR_SCHEMA, "targets",
                          "a fullscreen shader needs at least one target (its size is the viewport); to write storage "
                          "images only, use a compute shader");
    for (int t = 0; t < c->p->n_targets; t++) {
        const cJSON *v = cJSON_GetArrayItem(targets, t);
        int w = cJSON_IsString(v) ? pg_sp_find_in(d->writes, d->n_writes, v->valuestring) : -1;
        if (w < 0 || c->write_use[w] != SP_USE_NONE)
            return pg_sp_fail(c, PG_ERR_SCHEMA, "targets", "targets[%d] must name an image of the pass's writes, once", t);
        c->write_use[w] = SP_USE_TARGET;
        c->target_of_write[w] = t;
    }
    if ((r = check_outputs(c, targets))) return r;
    if (c->p->form == SP_DRAW && blend == SP_BLEND_ADD)
        return pg_sp_fail(c, PG_ERR_SCHEMA, "blend", "the draw form blends \"none\" or \"over\"");
    c->p->blend = (uint8_t)blend;
    c->p->clear_targets = blend == SP_BLEND_NONE;
    if (c->p->form == SP_DRAW) return read_depth(c, blend);
    static const char *const depth_only[] = {"depth", "depth_test", "depth_clear"};
    for (size_t i = 0; i < sizeof depth_only / sizeof depth_only[0]; i++)
        if (cJSON_GetObjectItemCaseSensitive(o, depth_only[i]))
            return pg_sp_fail(c, PG_ERR_SCHEMA, depth_only[i],
                              "a fullscreen shader has no depth attachment (sample it instead)");
    return PG_OK;
}

/* The name a slot gets in dumps and messages: the shader's binding name. */
static const char *binding_name(const sp_ctx *c, int k)
{
    return c->refl.bindings[c->binding_refl[k]].name;
}

static pg_result declare_reads(sp_ctx *c, uint32_t stages)
{
    const pg_pass_desc *d = c->in->desc;
    for (uint32_t i = 0; i < d->n_reads; i++) {
        const int use = c->read_use[i];
        const pg_resource_desc *rd = pg_pipeline_find_resource(c->in->pipeline, d->reads[i]);
        if (use > 0) {
            const pg_access a = c->binding_access[use - 1];
            c->p->bindings[use - 1].slot =
                pg_decl_read(c->out, binding_name(c, use - 1), rd ? rd->kind : PG_RES_IMAGE, a, stages,
                             a == PG_ACCESS_SAMPLED ? PG_FMTCLASS_ANY : PG_FMTCLASS_ANY_COLOR);
        } else if (use == SP_USE_DEPTH) {
            c->p->depth = pg_decl_read(c->out, "depth", PG_RES_IMAGE, PG_ACCESS_DEPTH_READ, 0, PG_FMTCLASS_DEPTH);
        } else if ((c->p->form == SP_DRAW || c->p->vis_surface) && i + 1 == d->n_reads &&
                   !strcmp(d->reads[i], "geometry")) {
            break; /* the scene's posed vertices: pg_geometry_slot_declare, after every other read */
        } else {
            char sub[32];
            snprintf(sub, sizeof sub, "reads[%u]", i);
            return pg_sp_fail(c, PG_ERR_SCHEMA, "bindings",
                           "resource '%s' (reads[%u]) is used by no binding%s", d->reads[i], i,
                           c->p->form == SP_DRAW ? " or depth (and only a last read 'geometry' is the scene's)" : "");
        }
    }
    if (c->p->form == SP_DRAW) pg_geometry_slot_declare(c->in, c->out, &c->p->draw, false);
    if (c->p->vis_surface) pg_geometry_slot_declare(c->in, c->out, &c->p->draw, true);
    return PG_OK;
}

pg_result pg_sp_declare_slots(sp_ctx *c)
{
    const uint32_t stages = c->p->form == SP_COMPUTE ? PG_STAGE_COMPUTE : PG_STAGE_FRAGMENT;
    pg_result r = declare_reads(c, stages);
    if (r) return r;
    const pg_pass_desc *d = c->in->desc;
    for (uint32_t i = 0; i < d->n_writes; i++) {
        const int use = c->write_use[i];
        const pg_resource_desc *rd = pg_pipeline_find_resource(c->in->pipeline, d->writes[i]);
        if (use > 0) {
            c->p->bindings[use - 1].slot = pg_decl_write(c->out, binding_name(c, use - 1), rd ? rd->kind : PG_RES_IMAGE,
                                                         c->binding_access[use - 1], stages, PG_FMTCLASS_ANY_COLOR);
        } else if (use == SP_USE_TARGET) {
            char name[24];
            snprintf(name, sizeof name, "target%d", c->target_of_write[i]);
            c->p->targets[c->target_of_write[i]] =
                pg_decl_write(c->out, name, PG_RES_IMAGE, c->p->clear_targets ? PG_ACCESS_COLOR_WRITE : PG_ACCESS_COLOR_RMW,
                              PG_STAGE_FRAGMENT, PG_FMTCLASS_ANY_COLOR);
        } else if (use == SP_USE_DEPTH) {
            c->p->depth = pg_decl_write(c->out, "depth", PG_RES_IMAGE,
                                        c->p->depth_clear ? PG_ACCESS_DEPTH_WRITE : PG_ACCESS_DEPTH_RMW, 0,
                                        PG_FMTCLASS_DEPTH);
        } else {
            return pg_sp_fail(c, PG_ERR_SCHEMA, "bindings", "resource '%s' (writes[%u]) is used by no binding%s",
                           d->writes[i], i, c->p->form == SP_COMPUTE ? "" : ", target or depth");
        }
    }
    return PG_OK;
}

/* The slot a resource of the pass is bound to (PG_SLOT_NONE: not bound). */
static pg_slot slot_of_resource(const sp_ctx *c, const char *name, pg_res_kind *kind)
{
    const pg_pass_desc *d = c->in->desc;
    const pg_resource_desc *rd = pg_pipeline_find_resource(c->in->pipeline, name);
    if (rd) *kind = rd->kind;
    int i = pg_sp_find_in(d->writes, d->n_writes, name);
    if (i >= 0 && c->write_use[i] > 0) return c->p->bindings[c->write_use[i] - 1].slot;
    i = pg_sp_find_in(d->reads, d->n_reads, name);
    if (i >= 0 && c->read_use[i] > 0) return c->p->bindings[c->read_use[i] - 1].slot;
    return PG_SLOT_NONE;
}

static pg_result dispatch_groups(sp_ctx *c, const cJSON *g)
{
    c->p->dispatch = SP_DISPATCH_GROUPS;
    bool ok = cJSON_IsArray(g) && cJSON_GetArraySize(g) >= 1 && cJSON_GetArraySize(g) <= 3;
    for (int k = 0; k < 3; k++) c->p->groups[k] = 1;
    for (int k = 0; ok && k < cJSON_GetArraySize(g); k++) {
        const cJSON *v = cJSON_GetArrayItem(g, k);
        ok = cJSON_IsNumber(v) && v->valuedouble >= 1 && v->valuedouble <= 65535 && v->valuedouble == floor(v->valuedouble);
        if (ok) c->p->groups[k] = (uint32_t)v->valuedouble;
    }
    if (!ok) return pg_sp_fail(c, PG_ERR_SCHEMA, "dispatch.groups", "expected 1 to 3 whole numbers in 1..65535");
    return PG_OK;
}

pg_result pg_sp_read_dispatch(sp_ctx *c)
{
    const cJSON *dv = cJSON_GetObjectItemCaseSensitive(c->in->desc->options, "dispatch");
    if (c->p->form != SP_COMPUTE) {
        if (dv) return pg_sp_fail(c, PG_ERR_SCHEMA, "dispatch", "only a compute shader has a dispatch size");
        return PG_OK;
    }
    for (int k = 0; k < 3; k++) c->p->local[k] = c->refl.local_size[k] ? c->refl.local_size[k] : 1;
    c->p->shared_bytes = c->refl.shared_bytes;
    const char *name = NULL;
    bool want_image = true;
    if (!dv) { /* default: per pixel of the first image the pass writes through a binding */
        for (uint32_t k = 0; k < c->p->n_bindings && !name; k++)
            if (pg_slot_is_write(c->p->bindings[k].slot) && c->p->bindings[k].type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE)
                name = c->in->desc->writes[pg_slot_index(c->p->bindings[k].slot)];
        if (!name)
            return pg_sp_fail(c, PG_ERR_SCHEMA, "dispatch",
                           "no written image to dispatch over: give {\"image\": R}, {\"buffer\": R} or {\"groups\": [x, y, z]}");
    } else if (cJSON_IsObject(dv) && cJSON_GetArraySize(dv) == 1 && cJSON_IsString(dv->child) &&
               (!strcmp(dv->child->string, "image") || !strcmp(dv->child->string, "buffer"))) {
        name = dv->child->valuestring;
        want_image = !strcmp(dv->child->string, "image");
    } else if (cJSON_IsObject(dv) && cJSON_GetArraySize(dv) == 1 && !strcmp(dv->child->string, "groups")) {
        return dispatch_groups(c, dv->child);
    } else {
        return pg_sp_fail(c, PG_ERR_SCHEMA, "dispatch", "expected {\"image\": R}, {\"buffer\": R} or {\"groups\": [x, y, z]}");
    }
    pg_res_kind kind = PG_RES_IMAGE;
    c->p->dispatch_slot = slot_of_resource(c, name, &kind);
    if (!pg_slot_ok(c->p->dispatch_slot) || (kind == PG_RES_IMAGE) != want_image)
        return pg_sp_fail(c, PG_ERR_SCHEMA, "dispatch", "'%s' is not %s bound by this pass", name,
                       want_image ? "an image" : "a buffer");
    c->p->dispatch = want_image ? SP_DISPATCH_IMAGE : SP_DISPATCH_BUFFER;
    if (!want_image) {
        const pg_resource_desc *rd = pg_pipeline_find_resource(c->in->pipeline, name);
        c->p->dispatch_stride = rd && rd->stride ? rd->stride : 4;
    }
    return PG_OK;
}

void pg_sp_explain(sp_ctx *c)
{
    const sp_params *p = c->p;
    char what[160];
    if (p->form == SP_COMPUTE && p->dispatch == SP_DISPATCH_GROUPS)
        snprintf(what, sizeof what, "local %ux%ux%u, %ux%ux%u groups", p->local[0], p->local[1], p->local[2],
                 p->groups[0], p->groups[1], p->groups[2]);
    else if (p->form == SP_COMPUTE)
        snprintf(what, sizeof what, "local %ux%ux%u, one thread per %s of '%s'", p->local[0], p->local[1], p->local[2],
                 p->dispatch == SP_DISPATCH_IMAGE ? "pixel" : "element",
                 pg_slot_is_write(p->dispatch_slot) ? c->in->desc->writes[pg_slot_index(p->dispatch_slot)]
                                                    : c->in->desc->reads[pg_slot_index(p->dispatch_slot)]);
    else
        snprintf(what, sizeof what, "%u target(s), blend %s%s", p->n_targets, k_blends[p->blend],
                 p->form == SP_DRAW ? ", the scene's draws" : "");
    pg_decl_explain(c->out, "user %s shader %s: %s; %u binding(s), %u push-constant byte(s)", c->form_key, c->rel, what,
                    p->n_bindings, p->push_size);
}
