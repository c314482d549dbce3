/* compile_vars.c - named compile variables (compile_vars.h). */
#include "compile_vars.h"

#include <string.h>

bool pg_var_name_ok(const char *s)
{
    if (!s || !s[0] || strlen(s) >= PG_VAR_NAME_MAX) return false;
    if (!((s[0] >= 'a' && s[0] <= 'z') || s[0] == '_')) return false;
    for (const char *c = s; *c; c++)
        if (!((*c >= 'a' && *c <= 'z') || (*c >= '0' && *c <= '9') || *c == '_')) return false;
    return true;
}

const pg_compile_var *pg_vars_find(const pg_compile_vars *vars, const char *name)
{
    if (!vars || !name) return NULL;
    for (uint32_t i = 0; i < vars->n && i < PG_MAX_COMPILE_VARS; i++)
        if (!strcmp(vars->v[i].name, name)) return &vars->v[i];
    return NULL;
}

int64_t pg_vars_get(const pg_compile_vars *vars, const char *name, int64_t def)
{
    const pg_compile_var *v = pg_vars_find(vars, name);
    return v ? v->value : def;
}

pg_result pg_vars_set(pg_compile_vars *vars, const char *name, int64_t value, pg_error *err)
{
    if (!pg_var_name_ok(name))
        return pg_fail(err, PG_ERR_INVALID_ARG, "compile variable '%s': not a name ([a-z_][a-z0-9_]*, at most %d "
                       "characters)", name ? name : "(null)", PG_VAR_NAME_MAX - 1);
    pg_compile_var *v = (pg_compile_var *)pg_vars_find(vars, name);
    if (!v) {
        if (vars->n >= PG_MAX_COMPILE_VARS)
            return pg_fail(err, PG_ERR_LIMIT, "compile variable '%s': more than %d variables", name,
                           PG_MAX_COMPILE_VARS);
        v = &vars->v[vars->n++];
        pg_strlcpy(v->name, name, sizeof v->name);
    }
    v->value = value;
    return PG_OK;
}
