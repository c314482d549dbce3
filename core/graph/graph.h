/* graph.h - the compiled render graph: pure data produced by pg_graph_compile().
 *
 * Compile phases, run in this order (core/graph/graph_compile.c):
 *   1. declare    ask each pass type what its slots are (pure); unknown type -> error
 *   2. validate   slot counts, kinds (image/buffer), format class vs access, known resources
 *   3. order      dependency edges (reader after writer, write chains, "after"), stable
 *                 topological sort (ties keep declaration order); cycles reported with their path;
 *                 a transient whose first use reads it (read, blend, depth load, storage_rw) is an
 *                 error unless the slot says the pass initializes it (pg_slot_decl.initializes)
 *   4. cull       walk back from the outputs and side-effect passes (a pass that skipped itself
 *                 with pg_decl_skip never runs: its reason is its cull reason); every culled pass and
 *                 resource gets a reason
 *   5. lifetimes  first/last executed pass of each resource; outputs live to the end
 *   6. alias      transients are packed at offsets inside shared memory blocks, one block per
 *                 kind (core/graph/alias_pack.c, with estimated sizes and alignments); two resources
 *                 alive at the same time never share a byte, and a resource shares bytes with
 *                 an earlier one only if its first access fully overwrites it
 *   7. barriers   synchronization2 barriers for RAW, WAR, WAW and layout changes, including the
 *                 first use of an aliased resource (from UNDEFINED, after the previous occupant),
 *                 the frame-to-frame wrap of persistent resources (a persistent image only read
 *                 in one layout: a first-frame barrier out of UNDEFINED), and the final transition of the
 *                 outputs for readback
 *   8. queues     (core/graph/graph_queues.c; the queue of each pass is chosen between 5 and 6) each
 *                 pass's queue, submission batches (consecutive passes on one queue), the
 *                 cross-queue semaphore waits and queue-family ownership transfers
 * The plan makes no Vulkan calls; it only uses Vulkan's enum values so the executor can copy them.
 */
#ifndef PG_GRAPH_H
#define PG_GRAPH_H

#include "pass_api.h"
#include "pg_common.h"
#include "pipeline.h"
#include "compile_vars.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Synchronization facts for one access (core/graph/graph_sync.c). */
typedef struct pg_sync_info {
    uint64_t stages;   /* VkPipelineStageFlags2 */
    uint64_t access;   /* VkAccessFlags2 */
    uint32_t layout;   /* VkImageLayout (images only) */
    uint32_t usage;    /* VkImageUsageFlags or VkBufferUsageFlags */
    bool reads, writes;
    bool full_write;   /* overwrites every texel/byte without reading: safe first use after alias */
} pg_sync_info;

pg_sync_info pg_access_sync(pg_access access, uint32_t shader_stages, pg_res_kind kind,
                            pg_format format);
const char *pg_access_name(pg_access access);

typedef struct pg_barrier {
    int resource;          /* index into plan->resources */
    bool is_image;
    uint64_t src_stages, src_access, dst_stages, dst_access;
    uint32_t old_layout, new_layout;
    int alias_prev;        /* >= 0: first use after this resource occupied the same memory */
    bool wrap;             /* persistent resource: src is the end of the previous frame */
    bool first_frame;      /* recorded only while the resource holds nothing yet (its first
                            * frame, or after a plan that assumed another state): a persistent
                            * image only read, in one layout, leaves UNDEFINED for that layout */
    char why[48];          /* "RAW", "WAR", "WAW", "layout", "alias first use", "output" ... */
} pg_barrier;

/* ---- queues (core/graph/graph_queues.c; pg_queue_name in graph_names.c) ---- */
typedef enum pg_queue { PG_QUEUE_GRAPHICS = 0, PG_QUEUE_COMPUTE = 1 } pg_queue;
#define PG_QUEUE_COUNT 2
#define PG_MAX_BATCHES (PG_MAX_PASSES + 1)
#define PG_MAX_QFOTS (2 * PG_MAX_RESOURCES)
const char *pg_queue_name(pg_queue q); /* "graphics" / "compute" */

/* What the device offers, given to the compiler (the runtime fills it from the real device,
 * pg_runtime_queue_caps; zero = one queue). */
typedef struct pg_queue_caps {
    uint32_t n_queues;           /* 2: a compute-capable queue besides the graphics one */
    bool separate_family;        /* that queue is of another queue family: cross-queue uses of a
                                  * resource (EXCLUSIVE sharing) need ownership transfers */
    bool async_off;              /* --async-compute off: everything on the graphics queue */
    char why_single[96];         /* why there is one queue (shown in the dump), optional */
} pg_queue_caps;

/* One queue-family ownership transfer: a release barrier at the end of release_batch and the
 * matching acquire at the start of acquire_batch, with the same layouts in both (the Vulkan
 * rules for QFOT). The executor fills srcQueueFamilyIndex/dstQueueFamilyIndex from the real
 * families. Only planned when pg_queue_caps.separate_family. */
typedef struct pg_qfot {
    int resource;
    bool is_image;
    pg_queue src_queue, dst_queue;
    int release_batch, acquire_batch;
    int consumer_pass;           /* plan->passes index: first use on the acquiring queue */
    uint64_t src_stages, src_access; /* release: the accesses on the releasing queue */
    uint64_t dst_stages, dst_access; /* acquire: the consumer's first access */
    uint32_t old_layout, new_layout; /* identical in the release and the acquire */
} pg_qfot;

typedef struct pg_batch_wait {
    int batch;                   /* waits for this batch's signal (same frame) */
    uint64_t stages;             /* VkPipelineStageFlags2 of this batch that wait */
    char why[64];                /* "lights (RAW)", "join", ... */
} pg_batch_wait;

typedef struct pg_plan_batch {
    pg_queue queue;
    uint32_t first, count;       /* plan->order[first .. first + count); count 0: an empty
                                  * graphics batch that only joins the queues */
    uint32_t n_waits;
    pg_batch_wait waits[2];
    int prev_frame_wait;         /* >= 0: waits (ALL_COMMANDS) for this batch of the previous
                                  * frame: the first compute batch waits for the last graphics
                                  * batch that touches a resource the compute queue uses */
    bool last;                   /* the frame's last batch (graphics): final barriers, readback,
                                  * fence; it waits for the compute queue's last batch */
} pg_plan_batch;

typedef struct pg_plan_slot {
    int resource;          /* index into plan->resources */
    bool is_write;
    pg_slot_decl decl;
    pg_sync_info sync;
} pg_plan_slot;

typedef struct pg_plan_pass {
    char name[PG_NAME_MAX];
    const pg_pass_type *type;
    int desc_index;             /* index in pipeline->passes */
    bool culled;
    char cull_reason[PG_EXPLAIN_MAX];
    pg_pass_decl decl;
    uint32_t n_slots;           /* reads first, then writes */
    pg_plan_slot slots[2 * PG_MAX_SLOTS];
    pg_queue queue;             /* the queue it runs on */
    int batch;                  /* index in plan->batches; -1 when culled */
    char queue_reason[128];
    uint32_t n_barriers;        /* placed before the pass */
    pg_barrier barriers[PG_MAX_BARRIERS_PER_PASS];
} pg_plan_pass;

typedef struct pg_plan_resource {
    char name[PG_NAME_MAX];
    pg_res_kind kind;
    pg_lifetime_kind lifetime;
    pg_format format;
    uint32_t width, height;      /* images, resolved against the output size */
    uint64_t size_bytes;         /* images: estimate width*height*bpp; buffers: exact */
    uint32_t usage;              /* union of Vk*UsageFlags over surviving accesses */
    bool is_output;              /* output or hdr_output: lives to the end, read back */
    bool growable;               /* "grow": size_bytes is the initial size; own memory, never
                                  * aliased; the runtime may re-create it larger (pg_report_grow) */
    bool culled;
    char cull_reason[PG_EXPLAIN_MAX];
    int first_pass, last_pass;   /* positions in plan->order; -1 when unused; outputs'
                                  * last_pass is n_order (read back after the last pass) */
    int block;                   /* memory block (transients), -1 otherwise */
    uint64_t block_offset;       /* offset in the block, from estimated sizes and alignments
                                  * (PG_ALIAS_EST_*); the runtime re-packs each block with the
                                  * real memory requirements */
    bool may_inherit;            /* first access overwrites every byte: may start in bytes an
                                  * earlier resource of its block used */
    int desc_index;              /* index in pipeline->resources */
    uint8_t queues;              /* bit q: used by a pass on queue q; a transient used on both
                                  * queues gets its own memory (sharing across queues would race) */
} pg_plan_resource;

typedef struct pg_plan_block {
    pg_res_kind kind;
    pg_queue queue;              /* every member is used on this queue alone */
    uint64_t size_bytes;         /* highest end (offset + size) of its members, estimated */
    uint32_t n_members;
    int members[PG_MAX_RESOURCES]; /* by first use (ties: declaration index) */
} pg_plan_block;

/* Alignments the compiler assumes when it places resources without a device (the runtime uses
 * the real vkGet*MemoryRequirements). */
#define PG_ALIAS_EST_ALIGN_IMAGE 4096u
#define PG_ALIAS_EST_ALIGN_BUFFER 256u

typedef struct pg_compile_desc {
    const pg_pipeline *pipeline;
    const pg_pass_registry *registry;
    pg_compile_vars vars;            /* the caller's facts, by name: buffer count terms name them
                                      * (["lights", 32]) and declare() reads them (pg_var) */
    uint32_t output_width, output_height;
    bool disable_aliasing;           /* debugging switch: every transient gets its own memory */
    bool immediate;                  /* debugging mode (--immediate), for telling a graph bug from
                                      * a pass bug: passes run in declaration order where the
                                      * dependencies allow (the stable order phase 3 computes: no
                                      * other reordering), no aliasing, and before every pass a
                                      * full barrier (ALL_COMMANDS/MEMORY_WRITE ->
                                      * ALL_COMMANDS/MEMORY_READ|MEMORY_WRITE); layouts as usual */
    uint32_t output_layout;          /* VkImageLayout the outputs end in; 0 -> TRANSFER_SRC */
    uint64_t output_stages;          /* stages that read the outputs after the graph; 0 -> COPY
                                      * (read-back); the viewer adds BLIT to put it on screen */
    pg_queue_caps queues;            /* zero: one queue */
} pg_compile_desc;

typedef struct pg_graph_plan {
    uint32_t n_passes;                 /* all declared passes (culled included) */
    pg_plan_pass passes[PG_MAX_PASSES];/* same order as pipeline->passes */
    uint32_t n_order;                  /* executed passes */
    int order[PG_MAX_PASSES];          /* indices into passes[], execution order */
    uint32_t n_resources;
    pg_plan_resource resources[PG_MAX_RESOURCES]; /* same order as pipeline->resources */
    uint32_t n_blocks;
    pg_plan_block blocks[PG_MAX_RESOURCES];
    uint32_t n_final_barriers;         /* after the last pass: outputs -> output_layout */
    pg_barrier final_barriers[PG_MAX_RESOURCES];
    uint64_t transient_bytes_unaliased; /* sum of transient sizes */
    uint64_t transient_bytes_aliased;   /* sum of block sizes */
    int output, hdr_output;            /* resource indices (hdr_output -1 if none) */
    uint32_t n_explain;                /* what was left out and why (culls, omitted, features) */
    char explain[PG_MAX_EXPLAIN][PG_EXPLAIN_MAX];
    bool aliasing_disabled;
    uint64_t generation;               /* hash of the rest of the plan (see pg_res_handle); != 0 */
    bool async;                        /* the plan uses the compute queue */
    bool qfot;                         /* the queues are of different families: qfots[] used */
    char queue_note[PG_EXPLAIN_MAX];   /* why everything is on one queue, or "" */
    uint32_t n_batches;
    pg_plan_batch batches[PG_MAX_BATCHES];
    uint32_t n_qfots;
    pg_qfot qfots[PG_MAX_QFOTS];
    bool immediate;                    /* compiled with pg_compile_desc.immediate: every barrier's
                                        * masks are ALL_COMMANDS/MEMORY_*, and the executor adds a
                                        * global memory barrier before every pass */
} pg_graph_plan;

/* ---- typed, versioned handles (core/graph/graph_handle.c) ----
 * A handle names a resource or a pass of one plan: its index and that plan's generation, a 64-bit
 * hash of the plan's contents (pg_graph_plan.generation, never 0). Equal plans share it (the
 * index means the same thing in both); a handle from any other plan, e.g. one compiled before a
 * pipeline switch or a resize, is refused with PG_ERR_INVALID_ARG instead of indexing the wrong
 * thing. The zero handle is invalid. */
typedef struct pg_res_handle {
    uint32_t index;
    uint64_t generation;
} pg_res_handle;
typedef struct pg_pass_handle {
    uint32_t index;
    uint64_t generation;
} pg_pass_handle;

/* By name; unknown name: PG_ERR_UNKNOWN_RESOURCE / PG_ERR_UNKNOWN_PASS, *out zeroed. */
pg_result pg_plan_find_resource(const pg_graph_plan *plan, const char *name, pg_res_handle *out,
                                pg_error *err);
pg_result pg_plan_find_pass(const pg_graph_plan *plan, const char *name, pg_pass_handle *out,
                            pg_error *err);
/* The entry a handle names; a handle of another plan (or out of range, or zero):
 * PG_ERR_INVALID_ARG naming the handle and both generations, *out NULL. */
pg_result pg_plan_resource_get(const pg_graph_plan *plan, pg_res_handle h,
                               const pg_plan_resource **out, pg_error *err);
pg_result pg_plan_pass_get(const pg_graph_plan *plan, pg_pass_handle h, const pg_plan_pass **out,
                           pg_error *err);

/* Compiles; on success *out is a heap plan to free with pg_graph_plan_free(). */
pg_result pg_graph_compile(const pg_compile_desc *desc, pg_graph_plan **out, pg_error *err);
void pg_graph_plan_free(pg_graph_plan *plan);

/* Human-readable report (order, culls, lifetimes, blocks, barriers, totals). */
void pg_graph_plan_print(const pg_graph_plan *plan, const pg_pipeline *pipeline, void *FILE_ptr);

/* ---- short names for reports and dumps (core/graph/graph_names.c) ---- */
/* VkImageLayout -> "undefined", "general", "color_attachment", "shader_read_only", ...;
 * "?" for a value it does not know. The string is static. */
const char *pg_layout_name(uint32_t vk_image_layout);
/* VkPipelineStageFlags2 -> "color_output|fragment_shader"; "none" for 0; unknown bits as hex.
 * Always NUL-terminates buf (truncates when too small). */
void pg_stage_names(uint64_t stages, char *buf, size_t buf_size);
/* VkAccessFlags2 -> "color_attachment_write|shader_sampled_read"; "none" for 0. */
void pg_access_mask_names(uint64_t access, char *buf, size_t buf_size);
/* "image" / "buffer"; "transient" / "persistent" / "imported". */
const char *pg_res_kind_name(pg_res_kind kind);
const char *pg_lifetime_name(pg_lifetime_kind lifetime);
/* bytes as "512 B", "12.5 KiB", "3.25 MiB", "1.50 GiB" (the plan report's and the dumps' style).
 * buf gets at most size bytes, NUL included. */
void pg_fmt_bytes(uint64_t bytes, char *buf, size_t size);

#ifdef __cplusplus
}
#endif
#endif
