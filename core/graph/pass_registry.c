/* pass_registry.c - the pass type registry and the slot helpers declare() implementations use.
 *
 * The helpers never fail at the call site (declare() code stays short); instead an overflow is
 * recorded in the declaration and reported by the compiler:
 *   - more than PG_MAX_SLOTS reads or writes: the count is set to PG_MAX_SLOTS + 1 (nothing is
 *     written past the arrays) and pg_decl_check_counts() fails with PG_ERR_LIMIT;
 *   - more than PG_MAX_DEFINES defines, or a define longer than PG_NAME_MAX - 1: n_defines is set
 *     to PG_MAX_DEFINES + 1 and pg_graph_compile() fails with PG_ERR_LIMIT (a silently dropped
 *     define would build the wrong shader variant);
 *   - explanation lines past the 8th are dropped and the last one says so (they are information,
 *     not behaviour).
 * The option readers (pg_opt_*) live in core/graph/pass_options.c.
 */
#include "pass_api.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

const pg_pass_type *pg_registry_find(const pg_pass_registry *reg, const char *name)
{
    if (!reg || !name) return NULL;
    for (uint32_t i = 0; i < reg->count && i < 64; i++)
        if (reg->types[i] && reg->types[i]->name && strcmp(reg->types[i]->name, name) == 0)
            return reg->types[i];
    return NULL;
}

pg_result pg_registry_add(pg_pass_registry *reg, const pg_pass_type *type, pg_error *err)
{
    if (!reg || !type || !type->name || !type->name[0] || !type->declare)
        return pg_fail(err, PG_ERR_INVALID_ARG,
                       "pg_registry_add: a pass type needs a name and a declare function");
    if (!pg_ident_ok(type->name))
        return pg_fail(err, PG_ERR_INVALID_ARG,
                       "pass type name '%.80s%s' cannot be written in a pipeline: a type name matches "
                       "[A-Za-z0-9_]+, at most %d characters", type->name, strlen(type->name) > 80 ? "..." : "",
                       PG_NAME_MAX - 1);
    if (type->runtime_options && type->runtime_options[0] && !type->update)
        return pg_fail(err, PG_ERR_INVALID_ARG,
                       "pass type '%s' lists run-time options ('%s', ...) but has no update()", type->name,
                       type->runtime_options[0]);
    if (type->params_size > PG_MAX_PASS_PARAMS)
        return pg_fail(err, PG_ERR_LIMIT, "pass type '%s': its params block is %zu bytes, more than %d",
                       type->name, type->params_size, PG_MAX_PASS_PARAMS);
    if (type->instance_size > PG_MAX_PASS_INSTANCE)
        return pg_fail(err, PG_ERR_LIMIT,
                       "pass type '%s': its instance_size is %zu bytes, more than %u (allocate large state in "
                       "create())", type->name, type->instance_size, PG_MAX_PASS_INSTANCE);
    if (pg_registry_find(reg, type->name))
        return pg_fail(err, PG_ERR_INVALID_ARG, "pass type '%s' is registered twice", type->name);
    const uint32_t cap = (uint32_t)(sizeof reg->types / sizeof reg->types[0]);
    if (reg->count >= cap)
        return pg_fail(err, PG_ERR_LIMIT, "pass registry full (%u types): cannot add '%s'", cap,
                       type->name);
    reg->types[reg->count++] = type;
    return PG_OK;
}

static pg_slot add_slot(pg_slot_decl *slots, uint32_t *n, bool write, const char *name, pg_res_kind kind,
                        pg_access access, uint32_t stages, uint32_t formats)
{
    if (*n >= PG_MAX_SLOTS) { /* overflow marker, see the file comment */
        *n = PG_MAX_SLOTS + 1;
        return PG_SLOT_NONE;
    }
    const pg_slot h = {(uint16_t)(1 + *n + (write ? PG_MAX_SLOTS : 0))};
    pg_slot_decl *s = &slots[(*n)++];
    memset(s, 0, sizeof *s);
    pg_strlcpy(s->name, name ? name : "?", sizeof s->name);
    s->kind = kind;
    s->access = access;
    s->stages = stages;
    s->formats = formats;
    return h;
}

pg_slot pg_decl_read(pg_pass_decl *d, const char *name, pg_res_kind kind, pg_access access,
                     uint32_t stages, uint32_t formats)
{
    return d ? add_slot(d->reads, &d->n_reads, false, name, kind, access, stages, formats) : PG_SLOT_NONE;
}

pg_slot pg_decl_write(pg_pass_decl *d, const char *name, pg_res_kind kind, pg_access access,
                      uint32_t stages, uint32_t formats)
{
    return d ? add_slot(d->writes, &d->n_writes, true, name, kind, access, stages, formats) : PG_SLOT_NONE;
}

pg_slot_decl *pg_decl_slot(pg_pass_decl *d, pg_slot s)
{
    if (!d || !pg_slot_ok(s)) return NULL;
    const uint32_t i = pg_slot_index(s);
    if (pg_slot_is_write(s)) return i < d->n_writes && i < PG_MAX_SLOTS ? &d->writes[i] : NULL;
    return i < d->n_reads && i < PG_MAX_SLOTS ? &d->reads[i] : NULL;
}

const pg_resource_desc *pg_decl_slot_resource(const pg_declare_in *in, pg_slot s, pg_res_kind kind, char *where,
                                              size_t where_size)
{
    if (!in || !in->desc || !in->pipeline || !pg_slot_ok(s)) return NULL;
    const pg_pass_desc *d = in->desc;
    const uint32_t i = pg_slot_index(s);
    const bool w = pg_slot_is_write(s);
    if (i >= (w ? d->n_writes : d->n_reads)) return NULL;
    if (where && where_size) snprintf(where, where_size, "%s[%u]", w ? "writes" : "reads", i);
    const pg_resource_desc *rd = pg_pipeline_find_resource(in->pipeline, w ? d->writes[i] : d->reads[i]);
    return rd && rd->kind == kind ? rd : NULL;
}

void *pg_decl_params(pg_pass_decl *d, size_t size)
{
    return d && size <= sizeof d->params ? d->params : NULL;
}

void pg_decl_runtime_param(pg_pass_decl *d, const void *field, size_t size)
{
    const unsigned char *f = field;
    if (!d || f < d->params || f + size > d->params + sizeof d->params) return;
    if (d->n_runtime_params >= PG_MAX_RUNTIME_PARAMS) {
        d->n_runtime_params = PG_MAX_RUNTIME_PARAMS + 1; /* the overflow marker: a compile error */
        return;
    }
    d->runtime_params[d->n_runtime_params].offset = (uint16_t)(f - d->params);
    d->runtime_params[d->n_runtime_params].size = (uint16_t)size;
    d->n_runtime_params++;
}

void pg_decl_define_int(pg_pass_decl *d, const char *name, int64_t value)
{
    char def[PG_NAME_MAX];
    if (snprintf(def, sizeof def, "%s=%lld", name, (long long)value) >= (int)sizeof def) {
        if (d) d->n_defines = PG_MAX_DEFINES + 1; /* too long: the overflow marker */
        return;
    }
    pg_decl_define(d, def);
}

void pg_decl_define_float(pg_pass_decl *d, const char *name, double value)
{
    char def[PG_NAME_MAX];
    int n = snprintf(def, sizeof def, "%s=%.17g", name, value);
    if (n > 0 && n < (int)sizeof def && !strpbrk(def + strlen(name) + 1, ".eEni")) /* integral: a float literal */
        n = snprintf(def + n, sizeof def - (size_t)n, ".0") + n;
    if (n < 0 || n >= (int)sizeof def) {
        if (d) d->n_defines = PG_MAX_DEFINES + 1; /* too long: the overflow marker */
        return;
    }
    pg_decl_define(d, def);
}

uint32_t pg_decl_define_list(const pg_pass_decl *d, const char **out, uint32_t max)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < d->n_defines && i < PG_MAX_DEFINES && n < max; i++) out[n++] = d->defines[i];
    return n;
}

void pg_decl_define(pg_pass_decl *d, const char *define)
{
    if (!d || !define) return;
    if (d->n_defines >= PG_MAX_DEFINES) {
        d->n_defines = PG_MAX_DEFINES + 1;
        return;
    }
    if (!pg_strlcpy(d->defines[d->n_defines], define, sizeof d->defines[0])) {
        d->defines[d->n_defines][0] = 0;
        d->n_defines = PG_MAX_DEFINES + 1;
        return;
    }
    d->n_defines++;
}

void pg_decl_explain(pg_pass_decl *d, const char *fmt, ...)
{
    if (!d || !fmt) return;
    const uint32_t cap = (uint32_t)(sizeof d->explain / sizeof d->explain[0]);
    if (d->n_explain >= cap) {
        pg_strlcpy(d->explain[cap - 1], "(more explanations left out)", sizeof d->explain[0]);
        return;
    }
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(d->explain[d->n_explain], sizeof d->explain[0], fmt, ap);
    va_end(ap);
    d->n_explain++;
}

void pg_decl_skip(pg_pass_decl *d, const char *fmt, ...)
{
    if (!d || !fmt) return;
    d->skip = true;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(d->skip_reason, sizeof d->skip_reason, fmt, ap);
    va_end(ap);
    if (!d->skip_reason[0]) pg_strlcpy(d->skip_reason, "not needed for this scene", sizeof d->skip_reason);
}

static void slot_names(const pg_slot_decl *slots, uint32_t n, char *buf, size_t size)
{
    size_t len = 0;
    buf[0] = 0;
    if (n == 0) {
        snprintf(buf, size, "none");
        return;
    }
    for (uint32_t i = 0; i < n && i < PG_MAX_SLOTS && len < size; i++) {
        int w = snprintf(buf + len, size - len, "%s%s", i ? ", " : "", slots[i].name);
        if (w < 0) break;
        len += (size_t)w;
    }
}

static const char *path_or(const char *p, const char *fallback)
{
    return p && p[0] ? p : fallback;
}

pg_result pg_decl_check_counts(const pg_pass_desc *desc, const pg_pass_decl *d,
                               const pg_pass_type *type, pg_error *err)
{
    const char *file = path_or(desc->file, "<pipeline>");
    const char *jp = path_or(desc->json_path, "passes[?]");
    const char *tname = type && type->name ? type->name : desc->type;
    if (d->n_reads > PG_MAX_SLOTS || d->n_writes > PG_MAX_SLOTS)
        return pg_fail(err, PG_ERR_LIMIT,
                       "%s: %s: pass type '%s' declares more than %d %s slots", file, jp, tname,
                       PG_MAX_SLOTS, d->n_reads > PG_MAX_SLOTS ? "read" : "write");
    char names[PG_MAX_SLOTS * (PG_NAME_MAX + 2) + 8];
    if (desc->n_reads != d->n_reads) {
        slot_names(d->reads, d->n_reads, names, sizeof names);
        return pg_fail(err, PG_ERR_SCHEMA,
                       "%s: %s.reads: pass type '%s' expects %u read%s (%s) with these options, "
                       "got %u",
                       file, jp, tname, d->n_reads, d->n_reads == 1 ? "" : "s", names,
                       desc->n_reads);
    }
    if (desc->n_writes != d->n_writes) {
        slot_names(d->writes, d->n_writes, names, sizeof names);
        return pg_fail(err, PG_ERR_SCHEMA,
                       "%s: %s.writes: pass type '%s' expects %u write%s (%s) with these "
                       "options, got %u",
                       file, jp, tname, d->n_writes, d->n_writes == 1 ? "" : "s", names,
                       desc->n_writes);
    }
    return PG_OK;
}

void pg_decl_mark_unused(pg_pass_decl *d, pg_slot s, const char *why)
{
    pg_slot_decl *sd = pg_decl_slot(d, s);
    if (!sd) return;
    sd->unused = true;
    pg_decl_explain(d, "slot '%s' unused: %s", sd->name, why);
}

void pg_decl_mark_initializes(pg_pass_decl *d, pg_slot s)
{
    pg_slot_decl *sd = pg_slot_is_write(s) ? pg_decl_slot(d, s) : NULL;
    if (sd) sd->initializes = true;
}

void pg_decl_mark_partial(pg_pass_decl *d, pg_slot s)
{
    pg_slot_decl *sd = pg_slot_is_write(s) ? pg_decl_slot(d, s) : NULL;
    if (sd) sd->partial = true;
}

void pg_report_add(pg_pass_report *r, const char *name, uint64_t value)
{
    if (r->n >= PG_MAX_PASS_COUNTERS) return;
    pg_strlcpy(r->counters[r->n].name, name, sizeof r->counters[r->n].name);
    r->counters[r->n].value = value;
    r->n++;
}

void pg_report_grow(pg_pass_report *r, uint32_t slot, uint64_t needed, uint64_t max)
{
    if (r->n_grow >= PG_MAX_PASS_GROWS) return;
    r->grow[r->n_grow].slot = slot;
    r->grow[r->n_grow].needed = needed;
    r->grow[r->n_grow].max = max;
    r->n_grow++;
}

void pg_report_note(pg_pass_report *r, const char *fmt, ...)
{
    if (r->n_notes >= PG_MAX_PASS_NOTES) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(r->notes[r->n_notes], sizeof r->notes[r->n_notes], fmt, ap);
    va_end(ap);
    r->n_notes++;
}
