/* shader_pass_declare.h - what the two halves of the `shader` pass type's declare share:
 * shader_pass_declare.c (form, defines, compile, reflection, bindings) and shader_pass_slots.c
 * (push-constant params, targets and depth, the slots, the dispatch, the explanation). */
#ifndef PG_SHADER_PASS_DECLARE_H
#define PG_SHADER_PASS_DECLARE_H

#include "shader_pass.h"
#include "spirv_reflect.h"

typedef struct sp_ctx {
    const pg_declare_in *in;
    pg_pass_decl *out;
    sp_params *p;
    pg_error *err;
    const char *form_key; /* "compute" | "fullscreen" | "draw" */
    const char *rel;      /* the shader file as the JSON names it */
    pg_spv_reflection refl;
    /* what each of the pass's reads / writes is used as: 1 + binding index, or one of SP_USE_* */
    int read_use[PG_MAX_SLOTS], write_use[PG_MAX_SLOTS];
    pg_access binding_access[SP_MAX_BINDINGS];
    int binding_refl[SP_MAX_BINDINGS]; /* index into refl.bindings */
    int target_of_write[PG_MAX_SLOTS];  /* SP_USE_TARGET writes: the index in options.targets */
} sp_ctx;

/* pass read/write uses besides a binding (1 + its index) */
enum { SP_USE_NONE = 0, SP_USE_TARGET = -1, SP_USE_DEPTH = -2 };

/* "FILE: passes[i].options.SUB: pass 'P': MESSAGE" (sub NULL: "...options: ...") */
pg_result pg_sp_fail(const sp_ctx *c, pg_result code, const char *sub, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
/* storage_write / storage_rw */
bool pg_sp_access_writes(pg_access a);
/* Index of name in a pass's reads (writes) list, -1 if absent. */
int pg_sp_find_in(const char (*list)[PG_NAME_MAX], uint32_t n, const char *name);

/* shader_pass_util.c: above; shader_pass_slots.c: the steps after the bindings, in this order */
pg_result pg_sp_read_params(sp_ctx *c);
pg_result pg_sp_read_attachments(sp_ctx *c);
pg_result pg_sp_declare_slots(sp_ctx *c);
pg_result pg_sp_read_dispatch(sp_ctx *c);
void pg_sp_explain(sp_ctx *c);

#endif
