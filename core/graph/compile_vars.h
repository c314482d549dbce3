/* compile_vars.h - named compile variables: the caller's facts that a plan depends on (e.g. the
 * renderer's "lights" and scene features "has_alpha_mask"), handed to pg_graph_compile and to
 * every declare(). The graph knows none of their meanings: a buffer count term names one
 * (["lights", 32] in a pipeline file), and pass types read the ones they know (pg_var). */
#ifndef PG_COMPILE_VARS_H
#define PG_COMPILE_VARS_H

#include <stdbool.h>
#include <stdint.h>

#include "pg_common.h"

#ifdef __cplusplus
extern "C" {
#endif

#define PG_MAX_COMPILE_VARS 32
#define PG_VAR_NAME_MAX 32

typedef struct pg_compile_var {
    char name[PG_VAR_NAME_MAX];
    int64_t value;
} pg_compile_var;

/* A value type (a pg_compile_desc copies it); {0} is the empty set. */
typedef struct pg_compile_vars {
    uint32_t n;
    pg_compile_var v[PG_MAX_COMPILE_VARS];
} pg_compile_vars;

/* Sets (or replaces) a variable. PG_ERR_INVALID_ARG for a name that is empty, too long or not an
 * identifier ([a-z_][a-z0-9_]*), PG_ERR_LIMIT when the set is full. */
pg_result pg_vars_set(pg_compile_vars *vars, const char *name, int64_t value, pg_error *err);
/* The variable's entry, or NULL when the caller did not set it. */
const pg_compile_var *pg_vars_find(const pg_compile_vars *vars, const char *name);
/* Its value, or def when unset. */
int64_t pg_vars_get(const pg_compile_vars *vars, const char *name, int64_t def);
/* Whether s is a variable name: [a-z_][a-z0-9_]*, shorter than PG_VAR_NAME_MAX. */
bool pg_var_name_ok(const char *s);

#ifdef __cplusplus
}
#endif
#endif
