/* graph_execute_internal.h - the runtime's state (struct pg_runtime) and the helpers its files
 * share; not part of the runtime library's interface (only core/runtime/graph_execute*.c include
 * it).
 *
 *   graph_execute.c          create/destroy, settings, the lookup API (outputs, resources, buffers)
 *   graph_execute_plan.c     plan signatures, pg_runtime_set_plan() and its rebuild kinds
 *   graph_execute_memory.c   physical resources, memory blocks, pass instances, growable buffers
 *   graph_execute_record.c   recording (barriers, ownership transfers, rendering) and submission
 *                            (batches), timestamps, frames in flight, stats
 */
#ifndef PG_GRAPH_EXECUTE_INTERNAL_H
#define PG_GRAPH_EXECUTE_INTERNAL_H

#include "graph_execute.h"

#include <stdbool.h>
#include <stdint.h>
typedef struct gpu_times {
    uint64_t frame;
    bool valid;
    double total_ms, pass_ms[PG_MAX_PASSES];
    double pass_start_ms[PG_MAX_PASSES]; /* from the frame's first timestamp (both queues) */
} gpu_times;

struct pg_runtime {
    pg_gpu *gpu;
    const pg_graph_plan *plan;
    const pg_pipeline *pipeline;
    pg_user_block user;       /* the caller's block and generation (pg_runtime_set_plan) */
    uint32_t width, height;
    uint32_t frame_size;             /* bytes of the caller's per-frame block */
    uint64_t mem_sig, pipe_sig, val_sig; /* see memory_signature, pipeline_signature, value_signature */
    bool built;
    pg_phys_resource res[PG_MAX_RESOURCES];
    bool persistent_initialized[PG_MAX_RESOURCES];
    VkDeviceMemory block_memory[PG_MAX_RESOURCES];
    VkDeviceSize block_memory_size[PG_MAX_RESOURCES];
    int block_memory_of[PG_MAX_RESOURCES];   /* the plan block each block_memory belongs to */
    bool block_split[PG_MAX_RESOURCES];      /* plan block split at run time (blocks_fallback) */
    void *pass_state[PG_MAX_PASSES]; /* indexed like plan->passes */
    /* frame constants */
    VkDescriptorSetLayout frame_layout;
    VkDescriptorPool frame_pool;
    /* frames in flight: everything the host writes or reads per frame has one copy per slot;
     * frame k uses slot k % n_in_flight and waits only for the fence of frame k - n_in_flight */
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
        /* timestamps: per queue a pool of 2 per executed pass (begin before its barriers, end
         * after it), reset by the queue's first batch; the last batch of each queue copies its
         * pool to timestamps (graphics first, then compute) */
        VkQueryPool queries, cqueries;
        pg_buffer timestamps;      /* the query results, copied at the end of the frame */
        pg_buffer readback[2];
    } slot[PG_MAX_FRAMES_IN_FLIGHT];
    bool test_no_frame_barrier;    /* pg_runtime_test_drop_frame_barrier */
    uint32_t n_in_flight, cur;     /* cur: the slot of the last submitted frame */
    /* async compute: one timeline semaphore per queue (graphics, compute), the last value each
     * signalled, and the values the last frame's batches signalled (for the next frame's
     * prev_frame_wait; prev_gen: the plan they belong to) */
    VkSemaphore timeline[PG_QUEUE_COUNT];
    uint64_t tl_value[PG_QUEUE_COUNT];
    uint64_t prev_batch_value[PG_MAX_BATCHES];
    uint64_t prev_gen;
    bool compute_stamps;           /* the compute family has timestamps */
    uint32_t qslot[PG_MAX_PASSES]; /* executed pass -> its index among its queue's passes */
    uint32_t n_on_queue[PG_QUEUE_COUNT];
    uint64_t frame_no;
    uint32_t n_queries;
    bool readback_valid[2];
    /* GPU times of the last frame whose fence was seen signalled */
    double gpu_pass_ms[PG_MAX_PASSES], gpu_total_ms;
    double gpu_pass_start_ms[PG_MAX_PASSES];
    bool gpu_valid;
    uint64_t gpu_frame;
    gpu_times gpu_hist[4]; /* the GPU times of the last frames collected, by frame number % 4 */
    /* frames since the pass reports were last read; report_due: read them after the next frame
     * even if that means waiting (a new plan, a grown buffer) */
    uint32_t frames_unreported;
    bool report_due;
    pg_runtime_stats stats;
    const pg_param_override *settings; /* borrowed, see pg_runtime_set_settings */
    uint32_t n_settings;
    /* "grow" buffers: the size each one reached, by name, kept across plans so a new plan (a
     * new light count, a pipeline switch) starts from it instead of growing again; limit: a
     * size the device refused (later requests stay below it) */
    struct {
        char name[PG_NAME_MAX];
        uint64_t bytes, limit;
    } capacity[PG_MAX_RESOURCES];
    uint32_t n_capacity;
    char grow_note[160];               /* last refused growth, repeated in every frame's stats */
};
/* graph_execute.c */
void pg_rt_destroy_passes(pg_runtime *rt);
void pg_rt_destroy_built(pg_runtime *rt);

/* graph_execute_plan.c */
uint32_t pg_rt_capacity_slot(pg_runtime *rt, const char *name, bool add);

/* graph_execute_memory.c */
pg_result pg_rt_create_unbound(pg_runtime *rt, int i, pg_error *err);
VkMemoryRequirements pg_rt_requirements(pg_runtime *rt, int i);
pg_result pg_rt_build_block(pg_runtime *rt, uint32_t b, bool *bound, pg_error *err);
pg_result pg_rt_build_own(pg_runtime *rt, int i, pg_error *err);
pg_result pg_rt_build_memory(pg_runtime *rt, pg_error *err);
pg_result pg_rt_build_passes(pg_runtime *rt, pg_error *err);
pg_result pg_rt_grow_buffer(pg_runtime *rt, int ri, uint64_t needed, uint64_t max, pg_frame_stats *st,
                            pg_error *err);

/* graph_execute_record.c */
uint32_t pg_rt_queue_family(const pg_runtime *rt, pg_queue q);

#endif
