/* vk_context.h - the Vulkan device passgraph renders with: instance (validation optional),
 * physical device choice, one graphics+compute queue, Vulkan 1.3 with synchronization2 and
 * dynamic rendering (or Vulkan 1.2 with the extensions those came from, e.g. under RenderDoc 1.24,
 * which reports devices as 1.2), debug names, one-shot command helpers and plain buffer/image
 * allocation.
 *
 * Validation: with desc.validation the Khronos layer runs with synchronization validation on;
 * every message it sends is printed to stderr and counted (gpu->validation_messages), so tests
 * can fail on any. Validation requires the messenger: when the layer or VK_EXT_debug_utils is
 * missing, pg_gpu_create fails (it never runs with validation that nothing counts).
 */
#ifndef PG_VK_CONTEXT_H
#define PG_VK_CONTEXT_H

#include <stdio.h>
#include <vulkan/vulkan.h>

#include "pg_common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The Vulkan 1.3 commands passgraph records, resolved by pg_gpu_create through the loader
 * (vkGetInstanceProcAddr, so they dispatch per device): the core names on a 1.3 device, the
 * names of the extensions they were promoted from on a 1.2 device (VK_KHR_synchronization2,
 * VK_KHR_dynamic_rendering, VK_EXT_extended_dynamic_state). The macros route every call site
 * that includes this header through them; tests/renderdoc_test.sh checks that the executable
 * has no direct reference to the core symbols left. */
extern PFN_vkCmdPipelineBarrier2 pg_vk_CmdPipelineBarrier2;
extern PFN_vkQueueSubmit2 pg_vk_QueueSubmit2;
extern PFN_vkCmdWriteTimestamp2 pg_vk_CmdWriteTimestamp2;
extern PFN_vkCmdBeginRendering pg_vk_CmdBeginRendering;
extern PFN_vkCmdEndRendering pg_vk_CmdEndRendering;
extern PFN_vkCmdSetCullMode pg_vk_CmdSetCullMode;
extern PFN_vkCmdSetFrontFace pg_vk_CmdSetFrontFace;
#define vkCmdPipelineBarrier2 pg_vk_CmdPipelineBarrier2
#define vkQueueSubmit2 pg_vk_QueueSubmit2
#define vkCmdWriteTimestamp2 pg_vk_CmdWriteTimestamp2
#define vkCmdBeginRendering pg_vk_CmdBeginRendering
#define vkCmdEndRendering pg_vk_CmdEndRendering
#define vkCmdSetCullMode pg_vk_CmdSetCullMode
#define vkCmdSetFrontFace pg_vk_CmdSetFrontFace

typedef struct pg_gpu_desc {
    bool validation;          /* enable VK_LAYER_KHRONOS_validation + sync validation and the
                               * counting messenger; fails if either is unavailable */
    int device_index;         /* -1: pick automatically (discrete > integrated > cpu) */
    const char *device_match; /* optional substring of the device name */
    bool quiet;               /* do not print the chosen device */
    /* windowed use (the viewer): extra instance extensions (e.g. from GLFW), VK_KHR_swapchain on
     * the device, and a queue family that can present (asked through present_ok) */
    const char *const *instance_extensions;
    uint32_t n_instance_extensions;
    bool swapchain;
    bool (*present_ok)(VkInstance instance, VkPhysicalDevice phys, uint32_t family, void *user);
    void *present_user;
    /* async compute (--async-compute): no_compute_queue creates none; emulate_compute_queue
     * (the test switch) uses the graphics VkQueue as the "compute queue" too, so the two-queue
     * plan (batches, timeline semaphores; one family: no ownership transfer) runs on a device
     * with one queue, e.g. lavapipe */
    bool no_compute_queue;
    bool emulate_compute_queue;
} pg_gpu_desc;

typedef struct pg_gpu {
    VkInstance instance;
    VkDebugUtilsMessengerEXT messenger;
    VkPhysicalDevice phys;
    VkDevice device;
    VkQueue queue;
    uint32_t queue_family;
    /* the second, compute-capable queue (VK_NULL_HANDLE: none; then single_queue_why says why):
     * a queue of a compute family without graphics if the device has one, else a second queue of
     * the graphics family; with pg_gpu_desc.emulate_compute_queue the graphics queue itself */
    VkQueue compute_queue;
    uint32_t compute_family;
    bool compute_emulated;
    VkCommandPool compute_cmd_pool;  /* of compute_family (cmd_pool when it is queue_family) */
    uint32_t compute_timestamp_valid_bits;
    char single_queue_why[96];
    bool timeline_semaphores;        /* Vulkan 1.2 timelineSemaphore, enabled */
    VkPhysicalDeviceProperties props;
    VkPhysicalDeviceMemoryProperties mem_props;
    VkCommandPool cmd_pool;      /* for one-shot commands */
    float timestamp_period_ns;   /* ns per tick */
    uint32_t timestamp_valid_bits;
    bool debug_utils;
    bool validation;
    /* true when the device is used as Vulkan 1.2 plus extensions (its API version is 1.2, or
     * PASSGRAPH_VULKAN_1_2=1 forces this path on a 1.3 device); shaders then target SPIR-V 1.5 */
    bool vulkan12;
    /* subgroups: size (VkPhysicalDeviceSubgroupProperties) and whether a compute pipeline can
     * require one full subgroup of exactly that size per workgroup (subgroupSizeControl +
     * computeFullSubgroups enabled, compute in requiredSubgroupSizeStages, size in range) */
    uint32_t subgroup_size;
    bool exact_subgroups;
    /* geometryShader enabled: fragment shaders may read gl_PrimitiveID (the visibility pass) */
    bool primitive_id_in_fragment;
    /* shaderSampledImageArrayNonUniformIndexing enabled: a compute invocation may index the
     * scene's texture array with its own value (nonuniformEXT) */
    bool nonuniform_sampled_arrays;
    /* shaderInt64 and shaderBufferInt64Atomics enabled: 64-bit atomics on storage buffers (the
     * visibility pass's compute rasterizer) */
    bool int64_atomics;
    bool shader_int64;        /* shaderInt64 enabled (64-bit integers in shaders) */
    uint64_t max_storage_buffer_range; /* bytes one storage-buffer binding may span */
    uint64_t max_buffer_size;          /* bytes one buffer may hold (maxBufferSize; Vulkan 1.2: UINT64_MAX) */
    uint64_t max_allocation_size;      /* bytes one memory allocation may hold (maxMemoryAllocationSize) */
    uint32_t max_stage_storage_buffers; /* storage-buffer descriptors one shader stage may access */
    uint32_t validation_messages; /* errors + warnings reported by the validation layer */
    uint32_t validation_errors;
    uint32_t sync_hazards;        /* of those, synchronization validation's (SYNC-HAZARD-*) */
    int64_t live_memory_objects;  /* VkDeviceMemory allocated through passgraph and not freed */
    /* every pipeline is created with this cache (core/vk/pipeline_cache.c; VK_NULL_HANDLE when the
     * caches are off, pg_cache.h); pipeline_cache_loaded: bytes read from its file (0: cold) */
    VkPipelineCache pipeline_cache;
    size_t pipeline_cache_loaded;
    uint64_t pipeline_cache_sum;
    /* PASSGRAPH_PIPELINE_STATS=1 on a device with VK_KHR_pipeline_executable_properties: every
     * pipeline reports its statistics (pipeline_stats.h); NULL otherwise */
    PFN_vkGetPipelineExecutablePropertiesKHR exec_props;
    PFN_vkGetPipelineExecutableStatisticsKHR exec_stats;
    PFN_vkSetDebugUtilsObjectNameEXT set_object_name;
    PFN_vkCmdBeginDebugUtilsLabelEXT cmd_begin_label;
    PFN_vkCmdEndDebugUtilsLabelEXT cmd_end_label;
} pg_gpu;

pg_result pg_gpu_create(const pg_gpu_desc *desc, pg_gpu **out, pg_error *err);
void pg_gpu_destroy(pg_gpu *gpu);
/* Called by pg_gpu_create / pg_gpu_destroy: load (or start) gpu->pipeline_cache, and save it
 * when it changed. Failures are notes on stderr. */
void pg_pipeline_cache_open(pg_gpu *gpu);
void pg_pipeline_cache_close(pg_gpu *gpu);
/* Prints the Vulkan devices (index, name, type, API version) to f. */
pg_result pg_gpu_list_devices(FILE *f, pg_error *err);

/* Debug name for any Vulkan object (no-op without VK_EXT_debug_utils). */
void pg_gpu_name(pg_gpu *gpu, VkObjectType type, uint64_t handle, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

const char *pg_vk_result_name(VkResult r);
/* Fault injection for robustness tests: with PASSGRAPH_FAULT_AT=k in the environment, the k-th
 * checked Vulkan call (counting from 1, in execution order) is not made and reports
 * VK_ERROR_DEVICE_LOST instead, so every error path can be exercised. With
 * PASSGRAPH_FAULT_CALL=TEXT every checked call whose name contains TEXT fails (e.g. "(grow)": the
 * enlargement of a grow buffer, which reports VK_ERROR_OUT_OF_DEVICE_MEMORY there). Returns true
 * to fail. */
bool pg_vk_fault_next(const char *call);
/* Evaluates a Vulkan call; on failure fills err with the call text and VkResult and returns. */
#define PG_VK_TRY(err, call)                                                                 \
    do {                                                                                     \
        VkResult pg_vk_r_ = pg_vk_fault_next(#call) ? VK_ERROR_DEVICE_LOST : (call);         \
        if (pg_vk_r_ != VK_SUCCESS)                                                          \
            return pg_fail((err), PG_ERR_VULKAN, "%s failed: %s (%s:%d)", #call,             \
                           pg_vk_result_name(pg_vk_r_), __FILE__, __LINE__);                 \
    } while (0)

/* PG_VK_TRY with `cleanup` run before the return (what the function made before `call`) */
#define PG_VK_TRY_OR(err, call, cleanup)                                                     \
    do {                                                                                     \
        VkResult pg_vk_r_ = pg_vk_fault_next(#call) ? VK_ERROR_DEVICE_LOST : (call);         \
        if (pg_vk_r_ != VK_SUCCESS) {                                                        \
            cleanup;                                                                         \
            return pg_fail((err), PG_ERR_VULKAN, "%s failed: %s (%s:%d)", #call,             \
                           pg_vk_result_name(pg_vk_r_), __FILE__, __LINE__);                 \
        }                                                                                    \
    } while (0)

uint32_t pg_gpu_memory_type(const pg_gpu *gpu, uint32_t type_bits, VkMemoryPropertyFlags want);
/* Every VkDeviceMemory passgraph makes goes through these two (so long runs can prove the count
 * stays flat). */
VkResult pg_gpu_alloc_memory(pg_gpu *gpu, const VkMemoryAllocateInfo *info, VkDeviceMemory *out);
void pg_gpu_free_memory(pg_gpu *gpu, VkDeviceMemory mem);
/* Memory for a resource only the device touches: a device-local type among type_bits where one
 * fits, else any that fits; VK_ERROR_OUT_OF_DEVICE_MEMORY when none does. */
/* The size of the device's largest DEVICE_LOCAL memory heap (0 if none). */
uint64_t pg_gpu_device_local_bytes(const pg_gpu *gpu);
VkResult pg_gpu_alloc_device_memory(pg_gpu *gpu, VkDeviceSize size, uint32_t type_bits, VkDeviceMemory *out);
/* Resident set size of this process in bytes (0 if unknown). */
uint64_t pg_process_rss(void);

typedef struct pg_buffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    VkDeviceSize size;
    void *mapped; /* non-NULL when host visible */
} pg_buffer;

/* host_visible: HOST_VISIBLE|HOST_COHERENT, persistently mapped; else DEVICE_LOCAL. */
/* The same with both_queues: VK_SHARING_MODE_CONCURRENT over the graphics and compute families
 * when they differ (data written once and read by passes on either queue: the scene's buffers;
 * an exclusive buffer read first on another family without an ownership transfer has undefined
 * contents). pg_buffer_create: both_queues = host_visible. */
pg_result pg_buffer_create_ex(pg_gpu *gpu, VkDeviceSize size, VkBufferUsageFlags usage, bool host_visible,
                              bool both_queues, const char *name, pg_buffer *out, pg_error *err);
pg_result pg_buffer_create(pg_gpu *gpu, VkDeviceSize size, VkBufferUsageFlags usage,
                           bool host_visible, const char *name, pg_buffer *out, pg_error *err);
void pg_buffer_destroy(pg_gpu *gpu, pg_buffer *b);

typedef struct pg_image {
    VkImage image;
    VkDeviceMemory memory;
    VkImageView view;
    VkFormat format;
    uint32_t width, height, mips;
} pg_image;

pg_result pg_image_create(pg_gpu *gpu, VkFormat format, uint32_t w, uint32_t h, uint32_t mips,
                          VkImageUsageFlags usage, const char *name, pg_image *out,
                          pg_error *err);
void pg_image_destroy(pg_gpu *gpu, pg_image *img);
VkImageAspectFlags pg_vk_aspect(VkFormat f);
/* false for integer and depth/stencil formats: a blit from an RGBA8 UNORM image cannot write them */
bool pg_vk_format_blits_from_unorm(VkFormat f);

/* One-shot commands: begin returns a recording command buffer; end submits, waits, frees. */
pg_result pg_gpu_begin_once(pg_gpu *gpu, VkCommandBuffer *out, pg_error *err);
pg_result pg_gpu_end_once(pg_gpu *gpu, VkCommandBuffer cmd, pg_error *err);

/* Small synchronization2 helpers (niagara style). */
/* A whole-buffer barrier (no queue family transfer). */
VkBufferMemoryBarrier2 pg_buffer_barrier(VkBuffer buffer, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                                         VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access);
VkImageMemoryBarrier2 pg_image_barrier(VkImage image, VkImageAspectFlags aspect,
                                       VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                                       VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access,
                                       VkImageLayout old_layout, VkImageLayout new_layout);
void pg_cmd_barriers(VkCommandBuffer cmd, uint32_t n_images, const VkImageMemoryBarrier2 *images,
                     uint32_t n_buffers, const VkBufferMemoryBarrier2 *buffers);
/* One global memory barrier (every resource) from the source stages/access to the destination ones. */
void pg_cmd_memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                           VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access);

#ifdef __cplusplus
}
#endif
#endif
