/* shader_pass_util.c - what both halves of the `shader` pass type's declare call
 * (shader_pass_declare.h): the error message format and small lookups. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "shader_pass_declare.h"

pg_result pg_sp_fail(const sp_ctx *c, pg_result code, const char *sub, const char *fmt, ...)
{
    char msg[PG_ERROR_MSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    const pg_pass_desc *d = c->in->desc;
    return pg_fail(c->err, code, "%s: %s.options%s%s: pass '%s': %s", d->file, d->json_path, sub ? "." : "",
                   sub ? sub : "", d->name, msg);
}

bool pg_sp_access_writes(pg_access a)
{
    return a == PG_ACCESS_STORAGE_WRITE || a == PG_ACCESS_STORAGE_RW;
}

/* Index of name in the pass's reads (writes) list, -1 if absent. */
int pg_sp_find_in(const char (*list)[PG_NAME_MAX], uint32_t n, const char *name)
{
    for (uint32_t i = 0; i < n; i++)
        if (!strcmp(list[i], name)) return (int)i;
    return -1;
}

