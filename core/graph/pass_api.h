/* pass_api.h - the contract between the graph core and a pass type.
 *
 * Each pass type lives in its own file under passes/ and exports one const pg_pass_type.
 * The core never includes a specific pass; passes/pass_list.c lists the built-in ones.
 *
 *   declare  pure: from the options, the scene features and the output size, say what each
 *            read/write slot is (access, shader stages, format classes), which shader variant is
 *            needed, and what was left out and why. No Vulkan. Called by pg_graph_compile().
 *            It parses the options once into the type's params block (pg_decl_params; the
 *            slot handles pg_decl_read/pg_decl_write return go there too), which the later
 *            stages receive as ctx->params: nothing is parsed twice, no slot index is computed.
 *   create   build Vulkan objects (pipelines, samplers, descriptor layouts) for a compiled graph.
 *   record   record commands for one frame; the graph already placed every barrier.
 *   destroy  free what create made. Must accept a partially created instance.
 * The slot lists a type shows in messages are the ones declare produced (nothing written twice).
 */
#ifndef PG_PASS_API_H
#define PG_PASS_API_H

#include "pg_common.h"
#include "pipeline.h"
#include "compile_vars.h"

#ifdef __cplusplus
extern "C" {
#endif

struct cJSON;

/* How a pass touches one resource. The graph derives stages, access masks, layouts and usage
 * flags from it (core/graph/graph_sync.c). */
typedef enum pg_access {
    PG_ACCESS_COLOR_WRITE = 0,  /* colour attachment, cleared or fully overwritten */
    PG_ACCESS_COLOR_RMW,        /* colour attachment, loaded then written (blending) */
    PG_ACCESS_DEPTH_WRITE,      /* depth attachment, cleared then tested and written */
    PG_ACCESS_DEPTH_RMW,        /* depth attachment, loaded, tested and written */
    PG_ACCESS_DEPTH_READ,       /* depth attachment, test only (read-only layout) */
    PG_ACCESS_SAMPLED,          /* sampled image (texture()) in the slot's stages */
    PG_ACCESS_STORAGE_READ,     /* storage image / storage buffer, read */
    PG_ACCESS_STORAGE_WRITE,    /* storage image / buffer, every element written */
    PG_ACCESS_STORAGE_RW,       /* storage image / buffer, read and written */
    PG_ACCESS_UNIFORM,          /* uniform buffer */
    PG_ACCESS_TRANSFER_SRC,
    PG_ACCESS_TRANSFER_DST,     /* fully overwritten by a copy/clear */
    PG_ACCESS_INDIRECT,         /* indirect draw/dispatch arguments */
    PG_ACCESS_VERTEX_INPUT,     /* a vertex buffer (vertex attribute fetch) */
    PG_ACCESS_COUNT
} pg_access;

enum {
    PG_STAGE_VERTEX = 1u << 0,
    PG_STAGE_FRAGMENT = 1u << 1,
    PG_STAGE_COMPUTE = 1u << 2,
};

/* A slot handle: what pg_decl_read/pg_decl_write return; the pass keeps it in its params block
 * and resolves it in create/record with pg_ctx_res() (core/runtime/graph_execute.h). The zero
 * handle (PG_SLOT_NONE) is no slot (e.g. an optional slot the pipeline did not bind). */
typedef struct pg_slot {
    uint16_t ref; /* 0: none; else 1 + index, + PG_MAX_SLOTS for a write slot */
} pg_slot;
#define PG_SLOT_NONE ((pg_slot){0})
static inline bool pg_slot_ok(pg_slot s) { return s.ref != 0; }
static inline bool pg_slot_is_write(pg_slot s) { return s.ref > PG_MAX_SLOTS; }
/* The slot's index among the pass's reads (or writes). */
static inline uint32_t pg_slot_index(pg_slot s) { return (uint32_t)(s.ref - 1) % PG_MAX_SLOTS; }

typedef struct pg_slot_decl {
    char name[PG_NAME_MAX];   /* "color", "depth", "lights", ... (for messages and dumps) */
    pg_res_kind kind;         /* image or buffer expected */
    pg_access access;
    uint32_t stages;          /* PG_STAGE_* for shader accesses; ignored for attachments/transfer */
    uint32_t formats;         /* pg_format_class mask accepted (images) */
    bool unused;              /* bound but not touched in this configuration (e.g. cluster
                               * lists with 0 lights): no dependency, barrier or lifetime, so
                               * the producer can be culled. Set with pg_decl_mark_unused(). */
    bool initializes;         /* a write slot whose access reads (COLOR_RMW, DEPTH_RMW,
                               * STORAGE_RW) but the pass itself writes every element before it
                               * reads any (a clear, a first dispatch that stores without
                               * loading): a valid first use of a transient, and a full write for
                               * aliasing. Set with pg_decl_mark_initializes(). */
    bool partial;             /* a write slot (STORAGE_WRITE, TRANSFER_DST) that leaves part of
                               * the resource unwritten (e.g. a list filled up to a count); its
                               * readers read only what it wrote. Not a full write: it never joins
                               * a memory block after another resource. pg_decl_mark_partial(). */
} pg_slot_decl;

#define PG_MAX_DEFINES 32
#define PG_MAX_PASS_EXPLAIN 16 /* explanation lines of one pass (declare) */
#define PG_MAX_PASS_PARAMS 1536 /* bytes of a pass type's params block (pg_pass_type.params_size) */
#define PG_MAX_PASS_INSTANCE (64u << 20) /* bytes of a pass instance's state (pg_pass_type.instance_size) */
#define PG_MAX_RUNTIME_PARAMS 4 /* run-time value fields of one params block (pg_decl_runtime_param) */
typedef struct pg_pass_decl {
    uint32_t n_reads, n_writes;
    pg_slot_decl reads[PG_MAX_SLOTS];  /* same order as pg_pass_desc.reads */
    pg_slot_decl writes[PG_MAX_SLOTS];
    bool side_effects;                 /* keep even if nothing reads its writes */
    /* shader variant: NAME or NAME=VALUE defines the pass will compile with */
    uint32_t n_defines;
    char defines[PG_MAX_DEFINES][PG_NAME_MAX];
    /* what the pass left out for this scene and why ("no alpha-mask materials: no discard") */
    uint32_t n_explain;
    char explain[PG_MAX_PASS_EXPLAIN][PG_EXPLAIN_MAX];
    /* not needed for this scene at all (e.g. no BLEND materials: no transparent pass): the
     * compiler culls it with skip_reason, even with side effects; its writes then keep the value
     * of the previous writer and what only it reads is culled too. Set with pg_decl_skip(). */
    bool skip;
    char skip_reason[PG_EXPLAIN_MAX];
    /* the type's params block (pg_pass_type.params_size bytes, zeroed before declare): the
     * options parsed once and the slot handles, filled by declare through pg_decl_params(); part
     * of the plan (pure data), handed to create/update/record as ctx->params */
    PG_ALIGNAS(16) unsigned char params[PG_MAX_PASS_PARAMS];
    /* the fields of params that hold run-time values (pg_pass_type.runtime_options): the
     * runtime's pass signature hashes the params block without them, its value signature only
     * them, so a new value reaches update() and re-creates nothing */
    uint32_t n_runtime_params;
    struct {
        uint16_t offset, size;
    } runtime_params[PG_MAX_RUNTIME_PARAMS];
} pg_pass_decl;

typedef struct pg_declare_in {
    const pg_pass_desc *desc;          /* name, options (cJSON object), bound reads/writes */
    const pg_pipeline *pipeline;       /* resource formats etc. */
    const pg_compile_vars *vars;       /* the caller's compile variables (pg_compile_desc.vars) */
    uint32_t output_width, output_height; /* the size the graph is compiled for (>= 1) */
} pg_declare_in;

/* A compile variable's value in declare(), 0 when the caller did not set it. */
static inline int64_t pg_var(const pg_declare_in *in, const char *name)
{
    return pg_vars_get(in->vars, name, 0);
}

/* Runtime types (defined in core/vk/vk_context.h, core/runtime/graph_execute.h, core/runtime/scene_gpu.h). */
struct pg_gpu;
struct pg_pass_create_ctx;
struct pg_pass_record_ctx;
struct pg_pass_report;

typedef struct pg_pass_type {
    const char *name;        /* the "type" string in pipeline JSON */
    const char *summary;     /* one line for --help / dumps */
    size_t instance_size;    /* bytes of per-instance state handed to create/record/destroy
                              * (<= PG_MAX_PASS_INSTANCE: larger data belongs in Vulkan memory or
                              * allocations of create()) */
    size_t params_size;      /* bytes of its params block (<= PG_MAX_PASS_PARAMS; 0: none) */
    pg_result (*declare)(const pg_declare_in *in, pg_pass_decl *out, pg_error *err);
    pg_result (*create)(void *self, const struct pg_pass_create_ctx *ctx, pg_error *err);
    void (*record)(void *self, const struct pg_pass_record_ctx *ctx);
    void (*destroy)(void *self, struct pg_gpu *gpu);
    /* Optional: counters the pass measured in the frame that just finished (called after the
     * frame's fence), e.g. cluster overflow. */
    void (*report)(void *self, struct pg_pass_report *out);
    /* Optional: NULL-terminated option keys that are run-time values (e.g. "exposure"): they
     * select no shader variant and size nothing, so a new value re-creates no Vulkan object;
     * pg_runtime_set_plan() keeps the instance and calls update() with the new plan's params
     * block (declare parsed the new values into it). A type that lists any must have update(). */
    const char *const *runtime_options;
    pg_result (*update)(void *self, const void *params, pg_error *err);
} pg_pass_type;

#define PG_MAX_PASS_COUNTERS 12
#define PG_MAX_PASS_GROWS 2
#define PG_MAX_PASS_NOTES 2
typedef struct pg_pass_report {
    uint32_t n;
    struct {
        char name[32];
        uint64_t value;
    } counters[PG_MAX_PASS_COUNTERS];
    /* A write slot of a "grow" buffer was too small for this frame: the runtime re-creates it
     * with at least `needed` bytes (geometric growth, at most `max` bytes) before the next frame,
     * re-creates the passes bound to it, and tells the caller that this frame was incomplete. */
    uint32_t n_grow;
    struct {
        uint32_t slot;         /* index into the pass's plan slots (reads first, then writes) */
        uint64_t needed, max;
    } grow[PG_MAX_PASS_GROWS];
    /* One-line notes for the user (e.g. "list budget clamped to the device limit") */
    uint32_t n_notes;
    char notes[PG_MAX_PASS_NOTES][160];
} pg_pass_report;
/* Adds a counter (ignored when full). */
void pg_report_add(pg_pass_report *r, const char *name, uint64_t value);
/* Asks for a larger "grow" buffer (see pg_pass_report.grow; ignored when full). */
void pg_report_grow(pg_pass_report *r, uint32_t slot, uint64_t needed, uint64_t max);
/* Adds a note (ignored when full). */
void pg_report_note(pg_pass_report *r, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

typedef struct pg_pass_registry {
    uint32_t count;
    const pg_pass_type *types[64];
} pg_pass_registry;

const pg_pass_type *pg_registry_find(const pg_pass_registry *reg, const char *name);
/* Adds a type (tests register fake ones). Returns PG_ERR_LIMIT when full. */
pg_result pg_registry_add(pg_pass_registry *reg, const pg_pass_type *type, pg_error *err);

/* ---- helpers for declare() implementations (core/graph/pass_options.c) ---- */
/* Adds a slot (kind, access, stages and format classes as above) and returns its handle (the
 * zero handle when the pass declares more than PG_MAX_SLOTS; pg_decl_check_counts reports it). */
pg_slot pg_decl_read(pg_pass_decl *d, const char *name, pg_res_kind kind, pg_access access,
                     uint32_t stages, uint32_t formats);
pg_slot pg_decl_write(pg_pass_decl *d, const char *name, pg_res_kind kind, pg_access access,
                      uint32_t stages, uint32_t formats);
/* The declared slot of a handle (NULL for PG_SLOT_NONE or a handle of another declaration). */
pg_slot_decl *pg_decl_slot(pg_pass_decl *d, pg_slot s);
/* declare(): the pipeline resource bound to a declared slot, for checks that need only the plan (a
 * format, a buffer's count) and belong in declare, not create. NULL when the slot is not bound, names no
 * resource of the pipeline or one of another kind: the graph's own checks report those. where (may be
 * NULL) gets the slot's JSON key, "reads[i]" or "writes[i]". */
const pg_resource_desc *pg_decl_slot_resource(const pg_declare_in *in, pg_slot s, pg_res_kind kind, char *where,
                                              size_t where_size);
/* A shader define NAME (or NAME=VALUE) of the pass's variant, built from values, never parsed
 * back: create reads its params, and hands the list to the shader compiler (pg_pass_defines). */
void pg_decl_define(pg_pass_decl *d, const char *define);
void pg_decl_define_int(pg_pass_decl *d, const char *name, int64_t value);
/* NAME=VALUE as a GLSL float literal (17 significant digits, ".0" after an integral value): for a
 * value past what an int literal holds. */
void pg_decl_define_float(pg_pass_decl *d, const char *name, double value);
/* The pass's params block (size bytes, at most PG_MAX_PASS_PARAMS; NULL when larger):
 *   my_params *p = pg_decl_params(out, sizeof *p); */
void *pg_decl_params(pg_pass_decl *d, size_t size);
/* Marks a field of the params block as a run-time value (see pg_pass_decl.runtime_params): every
 * option a type lists in runtime_options is parsed into such a field. */
void pg_decl_runtime_param(pg_pass_decl *d, const void *field, size_t size);
/* Marks a slot unused and records why in the explanation. */
void pg_decl_mark_unused(pg_pass_decl *d, pg_slot s, const char *why);
/* Marks a write slot as initialised by the pass itself / as written partially (see
 * pg_slot_decl.initializes and .partial). */
void pg_decl_mark_initializes(pg_pass_decl *d, pg_slot s);
void pg_decl_mark_partial(pg_pass_decl *d, pg_slot s);
/* The shader defines declare chose (NAME or NAME=VALUE), for the shader compiler: fills out
 * (max entries) and returns how many. */
uint32_t pg_decl_define_list(const pg_pass_decl *d, const char **out, uint32_t max);
void pg_decl_explain(pg_pass_decl *d, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* declare(): this pass is not needed for this scene; the reason is shown as its cull reason
 * (--explain, dump). The slots must still be declared (they are validated and ordered). */
void pg_decl_skip(pg_pass_decl *d, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* Checks that the bound counts match the type's slots; error names desc->file/json_path. */
pg_result pg_decl_check_counts(const pg_pass_desc *desc, const pg_pass_decl *d,
                               const pg_pass_type *type, pg_error *err);

/* Option readers: missing key -> default; wrong type or out of range -> PG_ERR_SCHEMA naming
 * "FILE: passes[i].options.KEY: cause". Unknown keys are reported by pg_opt_check_known(). */
pg_result pg_opt_float(const pg_pass_desc *desc, const char *key, double def, double min,
                       double max, double *out, pg_error *err);
pg_result pg_opt_int(const pg_pass_desc *desc, const char *key, int64_t def, int64_t min,
                     int64_t max, int64_t *out, pg_error *err);
pg_result pg_opt_bool(const pg_pass_desc *desc, const char *key, bool def, bool *out,
                      pg_error *err);
/* choices is a NULL-terminated list; *out gets the index of the chosen value. */
pg_result pg_opt_enum(const pg_pass_desc *desc, const char *key, const char *const *choices,
                      int def, int *out, pg_error *err);
/* A string option copied into out (out_size bytes with the NUL); longer strings are refused. */
pg_result pg_opt_string(const pg_pass_desc *desc, const char *key, const char *def, char *out, size_t out_size,
                        pg_error *err);
/* known is a NULL-terminated list of accepted option keys. */
pg_result pg_opt_check_known(const pg_pass_desc *desc, const char *const *known, pg_error *err);

#ifdef __cplusplus
}
#endif
#endif
