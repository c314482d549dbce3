/* graph_execute.h - runs a compiled plan on a pg_gpu.
 *
 * pg_runtime_set_plan() creates the physical resources (each plan block is packed again with the
 * real memory requirements, core/graph/alias_pack.c, into one VkDeviceMemory, or more when its members
 * have no memory type in common; resources are bound at their offsets) and one instance of every
 * executed pass. They are kept across frames and plans: the plan signature has three parts,
 * memory (output size; every resource's size, format, usage, lifetime, block), pipelines (scene,
 * settings, passes with their variants, bindings and options other than run-time values) and
 * run-time values (options a pass type lists in runtime_options). A new plan re-creates what its
 * parts need: new memory -> everything, or only the resources that differ (with the other members
 * of their blocks) when they keep their names and blocks (pg_rebuild_kind); new pipelines -> the
 * pass instances only (resources keep their handles and contents); new values -> nothing (the
 * passes' update() re-reads them). pg_runtime_render() records one command buffer per plan batch
 * (one batch for a one-queue plan; async compute: core/graph/graph_queues.c): for each pass in
 * order the plan's barriers, a debug label, the pass's commands and timestamps; ownership-transfer
 * halves at the batch's start and end; in the last batch the final output transitions and, if
 * asked, copies of the outputs to host-visible buffers. The batches are submitted in order to
 * their queues with timeline semaphores (pg_plan_batch waits); the last one signals the frame's
 * fence.
 */
#ifndef PG_GRAPH_EXECUTE_H
#define PG_GRAPH_EXECUTE_H

#include "graph.h"
#include "vk_context.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pg_phys_resource {
    pg_res_kind kind;
    VkImage image;
    VkImageView view;
    VkFormat format;
    pg_format pg_fmt;
    uint32_t width, height;
    VkBuffer buffer;
    VkDeviceSize size;
    VkDeviceMemory own_memory; /* non-null when not in a shared block */
    VkDeviceMemory memory;     /* what it is bound to (own_memory or a shared block) */
    VkDeviceSize memory_offset, memory_size; /* the bytes it occupies there */
    uint64_t content_tag;      /* what a pass last wrote into a kept (persistent) resource, its own
                                * tag (pg_ctx_content_tag); 0 whenever the resource is (re)created */
} pg_phys_resource;

typedef struct pg_pass_create_ctx {
    pg_gpu *gpu;
    const pg_graph_plan *plan;
    const pg_plan_pass *pass;
    const pg_pass_desc *desc;         /* options etc. */
    const pg_pipeline *pipeline;
    const void *user;                 /* the caller's block (pg_user_block.data; the renderer's
                                       * uploaded scene), opaque to the runtime */
    VkDescriptorSetLayout frame_layout; /* set 0: FrameUniforms */
    const pg_phys_resource *slots[2 * PG_MAX_SLOTS]; /* same order as pass->slots */
    uint32_t width, height;           /* output size */
    /* Application settings: key/value strings the graph forwards to every pass unread (e.g.
     * "ocio.config"); see pg_session_desc.settings. Read them with pg_ctx_setting(). */
    const pg_param_override *settings;
    uint32_t n_settings;
} pg_pass_create_ctx;

/* The plan slot of a handle declare returned (reads first, then writes; see pg_slot). */
static inline uint32_t pg_plan_slot_of(const pg_plan_pass *pass, pg_slot s)
{
    return pg_slot_is_write(s) ? pass->decl.n_reads + pg_slot_index(s) : pg_slot_index(s);
}
/* In create and record (either context): the physical resource bound to a slot handle, whether
 * the slot is unused in this configuration (pg_decl_mark_unused), and the pass's params block
 * as declare filled it (type T, pg_pass_type.params_size bytes). */
#define pg_ctx_res(ctx, s) ((ctx)->slots[pg_plan_slot_of((ctx)->pass, (s))])
#define pg_ctx_unused(ctx, s) ((ctx)->pass->slots[pg_plan_slot_of((ctx)->pass, (s))].decl.unused)
#define PG_PARAMS(ctx, T) ((const T *)(const void *)(ctx)->pass->decl.params)

/* The value of an application setting (the last one with that key), or NULL when absent. */
const char *pg_ctx_setting(const pg_pass_create_ctx *ctx, const char *key);

typedef struct pg_pass_record_ctx {
    pg_gpu *gpu;
    VkCommandBuffer cmd;
    const pg_plan_pass *pass;
    const pg_phys_resource *slots[2 * PG_MAX_SLOTS];
    const void *user;                 /* as pg_pass_create_ctx.user */
    VkDescriptorSet frame_set;
    const void *frame;                /* CPU copy of the per-frame block set 0 holds (opaque to the
                                       * runtime: its layout is the passes' own, passes/frame.h) */
    uint32_t frame_size;              /* its bytes (pg_runtime_create's frame_block_size) */
    uint32_t width, height;
    pg_error *record_error;           /* the first contract break found while recording (e.g. by
                                       * pg_pass_begin_rendering); set -> the frame fails with it */
} pg_pass_record_ctx;

/* record(): the content tag of the resource bound to a write slot (pg_phys_resource.content_tag),
 * writable by the pass: a pass that fills a persistent resource from an input that rarely changes
 * stores the input's identity there and records nothing while it matches (the resource is kept
 * with its contents by a new plan of the same memory, and re-created with tag 0 otherwise). */
static inline uint64_t *pg_ctx_content_tag(const pg_pass_record_ctx *ctx, pg_slot s)
{
    return (uint64_t *)&((pg_phys_resource *)ctx->slots[pg_plan_slot_of(ctx->pass, s)])->content_tag;
}

/* Begins dynamic rendering on the pass's attachment slots (indices into ctx->slots: colour
 * slots, then depth_slot or -1) and checks each load op against the slot's declared access: a
 * full write (color_write, depth_write) must clear (clears != NULL, clear_depth), a read-modify-
 * write or read (color_rmw, depth_rmw, depth_read) must load, any other access is not an
 * attachment. A break is recorded in ctx->record_error ("pass 'P': slot 'S' is declared
 * color_write (a full write) but rendering begins with LOAD_OP_LOAD ..."); rendering begins
 * anyway so the command buffer stays valid. The size is the first attachment's. */
void pg_pass_begin_rendering(const pg_pass_record_ctx *ctx, uint32_t n_color, const uint32_t *color_slots,
                             const VkClearColorValue *clears, int depth_slot, bool clear_depth, float depth_clear);

typedef struct pg_grow_event {
    char resource[PG_NAME_MAX];
    uint64_t old_bytes, new_bytes;
} pg_grow_event;

typedef struct pg_frame_stats {
    uint32_t n_passes;
    char pass_names[PG_MAX_PASSES][PG_NAME_MAX];
    double pass_ms[PG_MAX_PASSES];    /* GPU time from timestamps (includes the pass's barriers) */
    double pass_start_ms[PG_MAX_PASSES]; /* its first timestamp less the frame's first (both
                                       * queues on one timebase: see README, async compute) */
    uint8_t pass_queue[PG_MAX_PASSES];/* pg_queue it ran on */
    uint32_t n_batches;               /* submissions this frame */
    double gpu_total_ms;              /* first to last timestamp of the frame (both queues) */
    double cpu_ms;                    /* host time of pg_runtime_render less wait_ms: record,
                                       * submit, reading stats */
    double wait_ms;                   /* host time blocked on fences in this call */
    uint64_t frame;                   /* this frame's number (0, 1, ... per runtime) */
    uint32_t in_flight;               /* frames in flight it was rendered with */
    /* pass_ms/gpu_total_ms are those of frame gpu_frame: this frame when the call waited for
     * it (1 in flight, or readback), else the last one seen finished (usually frame - 1) */
    uint64_t gpu_frame;
    /* false: another frame was still in flight, so the pass reports (counters, notes, growth)
     * were not read this frame (they are after a new plan or a growth and at least every 8th
     * frame: pg_runtime_stats.report_waits) */
    bool reports_valid;
    bool timestamps_valid;
    /* counters reported by passes (pg_pass_type.report), e.g. cluster overflow */
    uint32_t n_counters;
    struct {
        char pass[PG_NAME_MAX];
        char name[32];
        uint64_t value;
    } counters[32];
    /* "grow" buffers re-created larger after this frame because a pass found them too small
     * (pg_report_grow): this frame was incomplete and the next one will not be. Filled by
     * pg_runtime_apply_growth (pg_runtime_render leaves it empty). */
    uint32_t n_grown;
    pg_grow_event grown[4];
    /* notes from passes and from the runtime (e.g. a growth the device refused) */
    uint32_t n_notes;
    char notes[4][160];
    /* pg_session_render: times this frame was rendered again after a growth (the stats are the
     * last rendering's; n_grown/grown then list every growth of all renderings) */
    uint32_t rerenders;
} pg_frame_stats;

/* The sum of every pass's counter of that name in st (pg_pass_report counters are generic: the
 * runtime does not know what they mean; e.g. "overflow_dropped", the light references the
 * clustered passes lost). 0 when none. */
uint64_t pg_frame_counter_sum(const pg_frame_stats *st, const char *name);
/* Does a pass of st report a counter of that name (even 0)? */
bool pg_frame_counter_has(const pg_frame_stats *st, const char *name);
/* What a pg_runtime_set_plan() re-created (pg_runtime_stats.last_rebuild). */
typedef enum pg_rebuild_kind {
    PG_REBUILD_NONE = 0,   /* same plan signature and values: nothing */
    PG_REBUILD_VALUES,     /* only run-time option values (pg_pass_type.runtime_options): the
                            * passes' update() re-read them, no Vulkan object re-created */
    PG_REBUILD_PIPELINES,  /* same memory: resources (handles, contents) kept, pass instances
                            * (pipelines, descriptor sets) re-created */
    PG_REBUILD_RESOURCES,  /* only resources with their own allocation (no memory block, not an
                            * output) changed, e.g. the light buffer for a new light count: those
                            * and the pass instances re-created, the rest kept */
    PG_REBUILD_MEMORY,     /* new physical resources and pass instances */
} pg_rebuild_kind;
/* "none", "values", "pipelines", "resources", "memory" */
const char *pg_rebuild_kind_name(pg_rebuild_kind k);

typedef struct pg_runtime_stats {
    uint32_t resource_creations;      /* times physical resources were (re)built */
    /* pg_runtime_set_plan() outcomes, over the runtime's life (see pg_rebuild_kind) */
    uint32_t memory_rebuilds, resource_rebuilds, pipeline_rebuilds, value_updates;
    /* the last set_plan that re-created pass instances: how many it created and how many it kept
     * (a PG_REBUILD_PIPELINES keeps the instances of the passes whose type, variant, options,
     * slots and queue are unchanged, e.g. every pass but the one whose shader was edited) */
    uint32_t last_passes_created, last_passes_kept;
    pg_rebuild_kind last_rebuild;     /* the last set_plan's */
    uint64_t memory_bytes_transient;  /* actual VkDeviceMemory for transient blocks */
    uint64_t memory_bytes_unaliased;  /* sum of transient resources' memory requirements */
    uint32_t blocks_fallback;         /* plan blocks split at run time (no common memory
                                       * type, or alignment padding: alias_pack.h) */
    uint32_t grow_events;             /* "grow" buffers re-created larger, over the runtime's life */
    uint64_t grow_bytes;              /* current bytes of all "grow" buffers */
    uint64_t frames_submitted;
    uint32_t fence_waits;             /* waits on an earlier frame's fence that found it unsignalled */
    uint32_t sync_waits;              /* waits for the frame just submitted (1 in flight, readback) */
    uint32_t reports_skipped;         /* frames whose pass reports were not read (see reports_valid) */
    uint32_t report_waits;            /* waits for the frames in flight so the pass reports could be
                                       * read: after a new plan or a growth, and at least every 8th
                                       * frame (with 2 in flight the passes' counters have one copy) */
    uint64_t frame_barriers;          /* full barriers recorded at a queue's first batch of a frame:
                                       * every queue's with frames in flight, the compute queue's
                                       * always (graph_execute_record.c record_batch) */
} pg_runtime_stats;

typedef struct pg_runtime pg_runtime;

/* frame_block_size: bytes of the per-frame block (set 0, binding 0: a uniform buffer) the
 * caller hands to every pg_runtime_render; the runtime copies it and never reads it. */
pg_result pg_runtime_create(pg_gpu *gpu, uint32_t frame_block_size, pg_runtime **out, pg_error *err);
void pg_runtime_destroy(pg_runtime *rt);
/* Application settings handed to every pass's create (pg_pass_create_ctx.settings). Borrowed:
 * they must stay alive until the runtime is destroyed. Call before pg_runtime_set_plan(); they
 * are part of the physical signature, so a plan set after a change re-creates the passes. */
void pg_runtime_set_settings(pg_runtime *rt, const pg_param_override *settings, uint32_t n_settings);
/* A frame prologue: work on data the caller owns outside the graph (the renderer's animated
 * material table), recorded at the start of every frame's first graphics-queue batch, before any
 * pass (after the frames-in-flight barrier). It gets the frame's block (as handed to
 * pg_runtime_render) and returns whether it wrote anything with transfer commands; then a barrier
 * makes those writes visible to every later command of the frame on that queue (and, through the
 * queue's semaphores, to the compute-queue batches that wait for a graphics batch). The prologue
 * orders its writes after earlier reads itself. fn NULL: none (the default). */
typedef bool (*pg_frame_prologue_fn)(void *user, VkCommandBuffer cmd, const void *frame_block);
void pg_runtime_set_frame_prologue(pg_runtime *rt, pg_frame_prologue_fn fn, void *user);
/* What the caller hands every pass instance besides the plan (pg_pass_create_ctx.user): an
 * opaque block (the renderer's uploaded scene) and its generation. The runtime never reads the
 * block; a new generation re-creates the pass instances (the caller bumps it whenever the block's
 * contents change), an equal one keeps them. */
typedef struct pg_user_block {
    const void *data;
    uint64_t generation;
} pg_user_block;

/* plan, pipeline and user.data are borrowed and must stay alive until the next set_plan/destroy.
 * On failure the runtime holds no plan (set one again before rendering), except when only the
 * run-time values changed and a pass's update() refused one: it then keeps the plan it had, with
 * that plan's values (pg_runtime_output_image tells which). */
pg_result pg_runtime_set_plan(pg_runtime *rt, const pg_graph_plan *plan, const pg_pipeline *pipeline,
                              pg_user_block user, uint32_t width, uint32_t height, pg_error *err);
#define PG_MAX_FRAMES_IN_FLIGHT 2
/* Frames in flight (1, the default, or 2). With 2, frame k uses its own command buffer, fence,
 * frame-uniform buffer and descriptor set, timestamp pool and readback staging (slot k % 2), and
 * pg_runtime_render waits only for frame k - 2's fence. The frames share the graph's resources
 * (persistent and transient memory): each frame's commands begin with a full barrier, so the GPU
 * runs consecutive frames one after the other while the host records ahead. Waits for the
 * device first. */
pg_result pg_runtime_set_frames_in_flight(pg_runtime *rt, uint32_t n, pg_error *err);
/* Test-only: leave out that frame-start full barrier (tests/test_gpu_canary.c proves that
 * synchronization validation then reports the hazard between two frames in flight). */
void pg_runtime_test_drop_frame_barrier(pg_runtime *rt, bool drop);
/* The GPU times of frame `frame` (pg_frame_stats.frame) once its fence was seen signalled, among
 * the last 4 such frames of the current plan; false otherwise. pass_ms: one per executed pass. */
bool pg_runtime_gpu_times(const pg_runtime *rt, uint64_t frame, double *total_ms, double *pass_ms);
/* Waits for every frame in flight (their timestamps become the next stats' GPU times). */
pg_result pg_runtime_wait_idle(pg_runtime *rt, pg_error *err);
/* Renders one frame; waits for it when 1 frame is in flight or readback is set (else only for
 * the frame that used the same slot, see pg_runtime_set_frames_in_flight). readback: copy the
 * outputs for pg_runtime_output(). It never allocates memory or re-creates pass instances: when
 * the pass reports it read ask a "grow" buffer for more room (pg_report_grow), the request is
 * kept as pending growth (pg_runtime_growth_pending) for pg_runtime_apply_growth. */
pg_result pg_runtime_render(pg_runtime *rt, const void *frame_block, bool readback,
                            pg_frame_stats *stats, pg_error *err);
/* true when the last pass reports read asked a "grow" buffer for more room and that growth was
 * not applied yet (the frame they came from was incomplete: a pass had less room than it needed). */
bool pg_runtime_growth_pending(const pg_runtime *rt);
/* Between frames: applies the pending growth (waits for the frames in flight, re-creates each
 * buffer larger and the pass instances bound to it; a size the device refuses keeps the old
 * buffer and leaves a note). stats: the stats of the frame the requests came from (or NULL):
 * each growth is added to its grown list (n_grown), a refusal's note to its notes. Nothing
 * pending: does nothing. A new plan drops the requests of the old one. */
pg_result pg_runtime_apply_growth(pg_runtime *rt, pg_frame_stats *stats, pg_error *err);
/* Pixels of the last read-back frame: which = 0 the output, 1 the hdr_output (NULL if none). */
const void *pg_runtime_output(const pg_runtime *rt, int which, uint32_t *w, uint32_t *h, pg_format *fmt);
pg_runtime_stats pg_runtime_get_stats(const pg_runtime *rt);
/* Copies bytes [offset, offset + size) of the buffer resource `name` as the last frame left it
 * into dst (for tests and debugging; waits for the device). Transient buffers hold what the
 * frame wrote unless another resource aliased them later in the frame (render with aliasing
 * off to be sure). Fails for an unknown, culled or image resource or a range past its end. */
pg_result pg_runtime_read_buffer(pg_runtime *rt, const char *name, uint64_t offset, uint64_t size, void *dst,
                                 pg_error *err);
/* Current size in bytes of a buffer resource (a "grow" buffer may exceed the plan's size); 0
 * when unknown or culled. */
uint64_t pg_runtime_buffer_size(const pg_runtime *rt, const char *name);
/* The physical resource a handle of the runtime's current plan names (pg_plan_find_resource on
 * the plan given to pg_runtime_set_plan). A handle of an earlier plan (before a pipeline switch,
 * a resize, a new light count) is refused: PG_ERR_INVALID_ARG "stale resource handle ...". */
pg_result pg_runtime_resource(const pg_runtime *rt, pg_res_handle h, const pg_phys_resource **out,
                              pg_error *err);
/* The physical image of the output (which 0) or hdr_output (1), in TRANSFER_SRC_OPTIMAL layout
 * after each frame (NULL if none). For the viewer's blit to the window. */
const pg_phys_resource *pg_runtime_output_image(const pg_runtime *rt, int which);
/* What the runtime's device offers for async compute, for pg_compile_desc.queues: two queues
 * when pg_gpu has a compute queue (a separate one, or the emulated one) and timeline semaphores;
 * async_off as given (--async-compute off). */
pg_queue_caps pg_runtime_queue_caps(const pg_runtime *rt, bool async_off);
/* The physical resource of plan->resources[index] (NULL when out of range), for tests. */
const pg_phys_resource *pg_runtime_resource_at(const pg_runtime *rt, int index);

#ifdef __cplusplus
}
#endif
#endif
