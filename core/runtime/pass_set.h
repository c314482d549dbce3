/* pass_set.h - a pass-private descriptor set over the graph's physical resources (the slots a
 * pass was given in pg_pass_create_ctx), for passes' create(). */
#ifndef PG_PASS_SET_H
#define PG_PASS_SET_H

#include "graph_execute.h"
#include "vk_context.h"

#ifdef __cplusplus
extern "C" {
#endif

#define PG_SET_MAX_WINDOWS 8

/* One binding of a pass-private descriptor set. */
typedef struct pg_set_binding {
    VkDescriptorType type;          /* STORAGE_BUFFER, UNIFORM_BUFFER, COMBINED_IMAGE_SAMPLER, STORAGE_IMAGE */
    const pg_phys_resource *res;
    VkSampler sampler;              /* for COMBINED_IMAGE_SAMPLER */
    VkImageLayout layout;           /* for images; 0 -> SHADER_READ_ONLY / GENERAL by type */
} pg_set_binding;

typedef struct pg_pass_set {
    VkDescriptorSetLayout layout;
    VkDescriptorPool pool;
    VkDescriptorSet set;
} pg_pass_set;

/* Bindings are numbered 0..n-1, visible to all stages; n = 0 makes an empty set. */
pg_result pg_pass_set_create(pg_gpu *gpu, uint32_t n, const pg_set_binding *bindings, const char *name,
                             pg_pass_set *out, pg_error *err);
/* The same with the binding numbers given (numbers[i] for bindings[i]; distinct). */
pg_result pg_pass_set_create_numbered(pg_gpu *gpu, uint32_t n, const pg_set_binding *bindings, const uint32_t *numbers,
                                      const char *name, pg_pass_set *out, pg_error *err);
/* The same, with storage buffer i bound as an array of windows[i] descriptors (windows NULL, or an
 * entry 0 or 1: one descriptor): element k covers bytes [k window, (k + 1) window) of its buffer, the
 * last up to the buffer's end (window: at most gpu->max_storage_buffer_range, a multiple of
 * minStorageBufferOffsetAlignment; at most PG_SET_MAX_WINDOWS windows). For a buffer larger than one
 * binding may span. Every function here refuses (PG_ERR_LIMIT) a storage buffer bound as one
 * descriptor that is larger than gpu->max_storage_buffer_range. */
pg_result pg_pass_set_create_windowed(pg_gpu *gpu, uint32_t n, const pg_set_binding *bindings, const uint32_t *numbers,
                                      const uint32_t *windows, VkDeviceSize window, const char *name,
                                      pg_pass_set *out, pg_error *err);
void pg_pass_set_destroy(pg_gpu *gpu, pg_pass_set *s);

#ifdef __cplusplus
}
#endif
#endif
