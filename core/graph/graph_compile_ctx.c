/* graph_compile_ctx.c - what the compiler's phases share: the file and JSON path of a pass,
 * slot or resource for messages, explanations, and lookups. A leaf: the phases
 * (graph_compile.c, graph_order.c, graph_lifetimes.c, graph_barriers.c) call down to it and it
 * calls none of them.
 */
#include "graph_compile_internal.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* ------------------------------------------------------------------------------------------ */
/* messages                                                                                   */

const char *pg_gc_pass_file(const compile_ctx *c, int i)
{
    const pg_pass_desc *p = &c->pl->passes[i];
    if (p->file[0]) return p->file;
    if (c->pl->path[0]) return c->pl->path;
    return "<pipeline>";
}

void pg_gc_pass_path(const compile_ctx *c, int i, char *buf, size_t size)
{
    const pg_pass_desc *p = &c->pl->passes[i];
    if (p->json_path[0])
        snprintf(buf, size, "%s", p->json_path);
    else
        snprintf(buf, size, "passes[%d]", i);
}

/* "passes[i].reads[k]" or "passes[i].writes[k]" for plan slot s (reads first, then writes). */
void pg_gc_slot_path(const compile_ctx *c, int i, int s, char *buf, size_t size)
{
    char pp[PG_JSON_PATH_MAX + 16];
    pg_gc_pass_path(c, i, pp, sizeof pp);
    const uint32_t nr = c->pl->passes[i].n_reads;
    if ((uint32_t)s < nr)
        snprintf(buf, size, "%s.reads[%d]", pp, s);
    else
        snprintf(buf, size, "%s.writes[%d]", pp, s - (int)nr);
}

const char *pg_gc_res_file(const compile_ctx *c, int r)
{
    const pg_resource_desc *d = &c->pl->resources[r];
    if (d->file[0]) return d->file;
    if (c->pl->path[0]) return c->pl->path;
    return "<pipeline>";
}

void pg_gc_res_path(const compile_ctx *c, int r, char *buf, size_t size)
{
    const pg_resource_desc *d = &c->pl->resources[r];
    if (d->json_path[0])
        snprintf(buf, size, "%s", d->json_path);
    else
        snprintf(buf, size, "resources[%d]", r);
}

void pg_gc_fmt_into(char *dst, size_t size, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(dst, size, fmt, ap);
    va_end(ap);
}

void pg_gc_add_explain(pg_graph_plan *plan, const char *fmt, ...)
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

int pg_gc_find_pass(const pg_pipeline *pl, const char *name)
{
    for (uint32_t i = 0; i < pl->n_passes; i++)
        if (strcmp(pl->passes[i].name, name) == 0) return (int)i;
    return -1;
}

pass_use *pg_gc_find_use(compile_ctx *c, int p, int r)
{
    for (uint32_t k = 0; k < c->n_uses[p]; k++)
        if (c->uses[p][k].res == r) return &c->uses[p][k];
    return NULL;
}
