/* graph_execute_internal.h - the runtime's state (struct pg_runtime) and the helpers its files
 * share; not part of the runtime library's interface (only core/runtime/graph_execute*.c include
 * it).
 *
 * struct pg_runtime is made of parts; each part is written by one file (its owner) and only read
 * by the others:
 *
 *   graph_execute.c          create/destroy, settings, the lookup API     owns pg_rt_config
 *   graph_execute_plan.c     plan signatures, pg_runtime_set_plan()       owns pg_rt_current
 *   graph_execute_memory.c   physical resources, memory blocks, pass      owns pg_rt_memory
 *                            instances, "grow" buffers (pg_runtime_apply_growth)
 *   graph_execute_frames.c   frame slots, fences, command buffers, frame  owns pg_rt_frames
 *                            block upload, submission, frames in flight
 *   graph_execute_timing.c   timestamp queries, GPU times, their history  owns pg_rt_timing
 *   graph_execute_record.c   pg_runtime_render: recording (barriers,      owns pg_rt_reports
 *                            ownership transfers, passes), pass reports, frame stats
 *
 * The calls go one way (no two files call each other, nor round a longer loop):
 * graph_execute.c calls memory and frames; plan calls memory and record (pg_rt_reports_due);
 * record calls memory, frames and timing; memory calls frames and timing; frames calls timing;
 * timing calls none. (Check: nm -A --defined-only / --undefined-only on libpgruntime.a.)
 *
 * Exception: rt->stats (pg_runtime_stats, a public struct) is shared: each counter is written by
 * the file that does what it counts (memory: bytes, blocks, growths; plan: rebuild kinds; frames:
 * submits and waits; record: report waits and skips).
 */
#ifndef PG_GRAPH_EXECUTE_INTERNAL_H
#define PG_GRAPH_EXECUTE_INTERNAL_H

#include "graph_execute.h"

#include <stdbool.h>
#include <stdint.h>
#include <time.h>

/* Settings given at creation or by pg_runtime_set_settings. Owner: graph_execute.c. */
typedef struct pg_rt_config {
    pg_gpu *gpu;
    uint32_t frame_size;                /* bytes of the caller's per-frame block */
    const pg_param_override *settings;  /* borrowed, see pg_runtime_set_settings */
    uint32_t n_settings;
    pg_frame_prologue_fn prologue;      /* pg_runtime_set_frame_prologue */
    void *prologue_user;
} pg_rt_config;

/* The plan being run and its signatures. Owner: graph_execute_plan.c. */
typedef struct pg_rt_current {
    const pg_graph_plan *plan;
    const pg_pipeline *pipeline;
    pg_user_block user;       /* the caller's block and generation (pg_runtime_set_plan) */
    uint32_t width, height;
    uint64_t mem_sig, pipe_sig, val_sig; /* see memory_signature, pipeline_signature, value_signature */
    /* each pass's own part of pipe_sig (by plan pass index) and the part every pass shares (the
     * caller's block generation, the settings): a new plan of the same memory keeps the instances
     * of the passes whose part did not change (graph_execute_plan.c) */
    uint64_t pass_sig[PG_MAX_PASSES];
    char pass_name[PG_MAX_PASSES][PG_NAME_MAX];
    uint64_t shared_sig;
} pg_rt_current;

/* A growth a pass asked for in the last pass reports read (pg_report_grow), not applied yet. */
typedef struct pg_rt_grow_request {
    int resource;
    uint64_t needed, max;
} pg_rt_grow_request;
#define PG_RT_MAX_GROW_REQUESTS (PG_MAX_PASSES * PG_MAX_PASS_GROWS)

/* Physical resources, memory blocks, pass instances and "grow" buffers.
 * Owner: graph_execute_memory.c. */
typedef struct pg_rt_memory {
    bool built;                          /* resources and pass instances of cur.plan exist */
    pg_phys_resource res[PG_MAX_RESOURCES];
    bool persistent_initialized[PG_MAX_RESOURCES]; /* a frame has written it (frame-wrap barriers) */
    VkDeviceMemory block_memory[PG_MAX_RESOURCES];
    VkDeviceSize block_memory_size[PG_MAX_RESOURCES];
    int block_memory_of[PG_MAX_RESOURCES];   /* the plan block each block_memory belongs to */
    bool block_split[PG_MAX_RESOURCES];      /* plan block split at run time (blocks_fallback) */
    void *pass_state[PG_MAX_PASSES];         /* indexed like plan->passes */
    /* "grow" buffers: the size each one reached, by name, kept across plans so a new plan (a
     * new light count, a pipeline switch) starts from it instead of growing again; limit: a
     * size the device refused (later requests stay below it) */
    struct {
        char name[PG_NAME_MAX];
        uint64_t bytes, limit;
    } capacity[PG_MAX_RESOURCES];
    uint32_t n_capacity;
    char grow_note[160];                 /* last refused growth, repeated in every frame's stats */
    /* growth requests of the last pass reports read, in report order, applied between frames by
     * pg_runtime_apply_growth (cleared by it, by the next reports read and by a new plan) */
    pg_rt_grow_request pending[PG_RT_MAX_GROW_REQUESTS];
    uint32_t n_pending;
    /* persistent buffers carried over a memory rebuild (pg_rt_carry_persistent), indexed like the
     * new plan's resources, until pg_rt_build_memory puts them in place */
    pg_phys_resource carried[PG_MAX_RESOURCES];
    bool carried_set[PG_MAX_RESOURCES], carried_init[PG_MAX_RESOURCES];
} pg_rt_memory;

/* Frames in flight: everything the host writes or reads per frame has one copy per slot; frame
 * k uses slot k % n_in_flight and waits only for the fence of frame k - n_in_flight.
 * Owner: graph_execute_frames.c. */
typedef struct pg_rt_frames {
    VkDescriptorSetLayout frame_layout; /* set 0: the caller's frame block */
    VkDescriptorPool frame_pool;
    struct {
        VkDescriptorSet frame_set;
        pg_buffer frame_ubo;
        void *frame;               /* CPU copy of the frame block (frame_size bytes) */
        /* one command buffer per plan batch, from the pool of its queue's family (cmd_pool[b]) */
        VkCommandBuffer cmds[PG_MAX_BATCHES];
        VkCommandPool cmd_pool[PG_MAX_BATCHES];
        VkFence fence;
        bool pending;              /* submitted, results not collected yet */
        uint64_t frame_no;
        pg_buffer readback[2];     /* the output and hdr_output, copied when asked */
    } slot[PG_MAX_FRAMES_IN_FLIGHT];
    bool test_no_frame_barrier;    /* pg_runtime_test_drop_frame_barrier */
    uint32_t n_in_flight, cur;     /* cur: the slot of the last submitted frame */
    uint64_t frame_no;
    bool readback_valid[2];
    /* async compute: one timeline semaphore per queue (graphics, compute), the last value each
     * signalled, and the values the last frame's batches signalled (for the next frame's
     * prev_frame_wait; prev_gen: the plan they belong to) */
    VkSemaphore timeline[PG_QUEUE_COUNT];
    uint64_t tl_value[PG_QUEUE_COUNT];
    uint64_t prev_batch_value[PG_MAX_BATCHES];
    uint64_t prev_gen;
} pg_rt_frames;

typedef struct gpu_times {
    uint64_t frame;
    bool valid;
    double total_ms, pass_ms[PG_MAX_PASSES];
    double pass_start_ms[PG_MAX_PASSES]; /* from the frame's first timestamp (both queues) */
} gpu_times;

/* Timestamps: per frame slot and queue a pool of 2 per executed pass (begin before its barriers,
 * end after it), reset by the queue's first batch; the last batch of each queue copies its pool
 * to timestamps (graphics first, then compute). Owner: graph_execute_timing.c. */
typedef struct pg_rt_timing {
    struct {
        VkQueryPool queries, cqueries;
        pg_buffer timestamps;      /* the query results, copied at the end of the frame */
    } slot[PG_MAX_FRAMES_IN_FLIGHT];
    bool compute_stamps;           /* the compute family has timestamps */
    uint32_t qslot[PG_MAX_PASSES]; /* executed pass -> its index among its queue's passes */
    uint32_t n_on_queue[PG_QUEUE_COUNT];
    uint32_t n_queries;
    /* GPU times of the last frame whose fence was seen signalled */
    double gpu_pass_ms[PG_MAX_PASSES], gpu_total_ms;
    double gpu_pass_start_ms[PG_MAX_PASSES];
    bool gpu_valid;
    uint64_t gpu_frame;
    gpu_times gpu_hist[4]; /* the GPU times of the last frames collected, by frame number % 4 */
} pg_rt_timing;

/* When the pass reports are read. Owner: graph_execute_record.c. */
typedef struct pg_rt_reports {
    /* frames since the pass reports were last read; due: read them after the next frame even if
     * that means waiting (a new plan, a grown buffer) */
    uint32_t frames_unreported;
    bool due;
} pg_rt_reports;

struct pg_runtime {
    pg_rt_config cfg;
    pg_rt_current cur;
    pg_rt_memory mem;
    pg_rt_frames frames;
    pg_rt_timing timing;
    pg_rt_reports reports;
    pg_runtime_stats stats; /* shared, see the top of this file */
};

static inline double pg_rt_now_ms(void)
{
    return pg_time_s() * 1e3;
}

/* graph_execute_memory.c */
pg_result pg_rt_build_memory(pg_runtime *rt, pg_error *err);
pg_result pg_rt_build_passes(pg_runtime *rt, pg_error *err);
pg_result pg_rt_recreate_resources(pg_runtime *rt, const bool *changed, const bool *dirty, pg_error *err);
pg_result pg_rt_update_values(pg_runtime *rt, pg_error *err);
void pg_rt_destroy_passes(pg_runtime *rt);
void pg_rt_destroy_built(pg_runtime *rt);
void pg_rt_forget_contents(pg_runtime *rt, int resource);
void pg_rt_mark_persistent_written(pg_runtime *rt);
/* Before a memory rebuild for `next`: takes out of the built resources every persistent buffer with
 * its own memory that `next` has too (same name, size and usage, not growable, its own memory
 * there as well), with its contents and content tag, so pg_rt_destroy_built leaves it and
 * pg_rt_build_memory puts it in place. */
void pg_rt_carry_persistent(pg_runtime *rt, const pg_graph_plan *next);
void pg_rt_clear_growth(pg_runtime *rt);
void pg_rt_request_growth(pg_runtime *rt, int resource, uint64_t needed, uint64_t max);

/* graph_execute_frames.c */
pg_result pg_rt_frames_create(pg_runtime *rt, pg_error *err);
void pg_rt_frames_destroy(pg_runtime *rt);
pg_result pg_rt_frames_build_readback(pg_runtime *rt, pg_error *err);
void pg_rt_frames_destroy_readback(pg_runtime *rt);
void pg_rt_frames_forget(pg_runtime *rt);
pg_result pg_rt_frame_begin(pg_runtime *rt, const void *frame_block, uint32_t *slot, double *wait_ms,
                            pg_error *err);
pg_result pg_rt_frame_cmd(pg_runtime *rt, uint32_t f, uint32_t b, VkCommandBuffer *out, pg_error *err);
void pg_rt_frame_record_readback(pg_runtime *rt, VkCommandBuffer cmd, uint32_t f, bool readback);
void pg_rt_frame_drop_readback(pg_runtime *rt);
pg_result pg_rt_frame_submit(pg_runtime *rt, uint32_t f, pg_error *err);
pg_result pg_rt_frame_settle(pg_runtime *rt, uint32_t f, bool readback, double *wait_ms, bool *idle,
                             pg_error *err);

/* graph_execute_timing.c */
pg_result pg_rt_timing_build(pg_runtime *rt, pg_error *err);
void pg_rt_timing_destroy(pg_runtime *rt);
void pg_rt_timing_collect(pg_runtime *rt, uint32_t f, uint64_t frame_no);
void pg_rt_timing_begin(const pg_runtime *rt, VkCommandBuffer cmd, uint32_t f, pg_queue q);
void pg_rt_timing_stamp(const pg_runtime *rt, VkCommandBuffer cmd, uint32_t f, pg_queue q, uint32_t o, bool end);
void pg_rt_timing_copy(const pg_runtime *rt, VkCommandBuffer cmd, uint32_t f, pg_queue q);
void pg_rt_timing_fill_stats(const pg_runtime *rt, pg_frame_stats *stats);

/* graph_execute_record.c */
void pg_rt_reports_due(pg_runtime *rt);

#endif
