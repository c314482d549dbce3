/* light_compute.h - what a compute pass with one thread per light shares (light_animate,
 * stochastic_lights): one descriptor set of storage buffers (set 1, after the frame block's set
 * 0), a layout, a compute pipeline built from a shader with the pass's declared defines, and a
 * dispatch of 64 lights a workgroup over the frame's light count. */
#ifndef PG_LIGHT_COMPUTE_H
#define PG_LIGHT_COMPUTE_H

#include "graph_execute.h"
#include "pass_set.h"

typedef struct pg_light_compute {
    pg_pass_set set;
    VkPipelineLayout layout;
    VkPipeline pipeline;
} pg_light_compute;

/* buffers[n]: the resources of set 1's storage-buffer bindings 0..n-1 (n <= 4); shader: a file of
 * shaders/, compiled with the pass's declared defines. */
pg_result pg_light_compute_create(const pg_pass_create_ctx *ctx, const char *shader,
                                  const pg_phys_resource *const *buffers, uint32_t n, pg_light_compute *out,
                                  pg_error *err);
/* Binds and dispatches ceil(count / 64) workgroups (2D, so any count fits 65535 a dimension) for
 * the frame's light count (records nothing with 0 lights). */
void pg_light_compute_record(const pg_light_compute *lc, const pg_pass_record_ctx *ctx);
void pg_light_compute_destroy(pg_light_compute *lc, pg_gpu *gpu);

#endif
