/* graph_compile_internal.h - the graph compiler's working state and the helpers its files
 * share; not part of the graph library's interface (only core/graph/graph_*.c of the compiler
 * include it).
 *
 *   graph_compile.c     pg_graph_compile(): inputs, 1. declare, 2. validate, immediate mode,
 *                       explanations
 *   graph_compile_ctx.c messages and lookups every phase uses (a leaf: it calls no phase)
 *   graph_order.c       3. order (dependencies, cycles), 4. cull
 *   graph_lifetimes.c   5. sizes and lifetimes, 6. alias (placement in blocks)
 *   graph_barriers.c    7. barriers (the frame walk; graph_sync.c gives the access masks)
 */
#ifndef PG_GRAPH_COMPILE_INTERNAL_H
#define PG_GRAPH_COMPILE_INTERNAL_H

#include "graph.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
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

/* graph_compile_ctx.c */
const char *pg_gc_pass_file(const compile_ctx *c, int i);
void pg_gc_pass_path(const compile_ctx *c, int i, char *buf, size_t size);
void pg_gc_slot_path(const compile_ctx *c, int i, int s, char *buf, size_t size);
const char *pg_gc_res_file(const compile_ctx *c, int r);
void pg_gc_res_path(const compile_ctx *c, int r, char *buf, size_t size);
/* snprintf that may truncate on purpose (names are bounded, messages are not worth failing) */
void pg_gc_fmt_into(char *dst, size_t size, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
void pg_gc_add_explain(pg_graph_plan *plan, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
int pg_gc_find_pass(const pg_pipeline *pl, const char *name);
pass_use *pg_gc_find_use(compile_ctx *c, int p, int r);

/* graph_order.c */
pg_result pg_gc_phase_order(compile_ctx *c);
pg_result pg_gc_phase_cull(compile_ctx *c);

/* graph_lifetimes.c */
pg_result pg_gc_phase_lifetimes(compile_ctx *c);
void pg_gc_phase_alias(compile_ctx *c);

/* graph_barriers.c */
void pg_gc_phase_barriers(compile_ctx *c);

#endif
