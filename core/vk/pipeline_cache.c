/* pipeline_cache.c - the VkPipelineCache every pipeline is created with, kept on disk per device
 * in <cache dir>/pipelines/<vendor>-<device>-<driver>-<pipelineCacheUUID>.bin (pg_cache.h). The
 * file is a pc_file_head (magic, size and hash of the data) and the data vkGetPipelineCacheData
 * gave; it is handed to the driver only when the hash matches and the data's own header names
 * this vendor, device and UUID. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pg_cache.h"
#include "vk_context.h"

#define PC_MAGIC "PGPLC01\n"

typedef struct pc_file_head {
    char magic[8];
    uint64_t bytes;
    uint64_t sum_a, sum_b;
} pc_file_head;

static bool cache_path(const pg_gpu *gpu, char *buf, size_t size, bool make_dir)
{
    char dir[PG_PATH_MAX];
    if (!pg_cache_dir(dir, sizeof dir)) return false;
    size_t l = strlen(dir);
    if (l + 12 >= sizeof dir) return false;
    memcpy(dir + l, "/pipelines", 11);
    if (make_dir && !pg_cache_mkdirs(dir)) {
        pg_cache_note("pipeline cache folder %s cannot be made; pipeline cache not saved", dir);
        return false;
    }
    char uuid[2 * VK_UUID_SIZE + 1];
    for (unsigned i = 0; i < VK_UUID_SIZE; i++) snprintf(uuid + 2 * i, 3, "%02x", gpu->props.pipelineCacheUUID[i]);
    return snprintf(buf, size, "%s/%04x-%04x-%08x-%s.bin", dir, gpu->props.vendorID, gpu->props.deviceID,
                    gpu->props.driverVersion, uuid) < (int)size;
}

/* The data's VkPipelineCacheHeaderVersionOne names this device. */
static bool header_matches(const pg_gpu *gpu, const unsigned char *d, size_t n)
{
    VkPipelineCacheHeaderVersionOne h;
    if (n < sizeof h) return false;
    memcpy(&h, d, sizeof h);
    return h.headerSize >= sizeof h && h.headerSize <= n && h.headerVersion == VK_PIPELINE_CACHE_HEADER_VERSION_ONE &&
           h.vendorID == gpu->props.vendorID && h.deviceID == gpu->props.deviceID &&
           !memcmp(h.pipelineCacheUUID, gpu->props.pipelineCacheUUID, VK_UUID_SIZE);
}

void pg_pipeline_cache_open(pg_gpu *gpu)
{
    gpu->pipeline_cache = VK_NULL_HANDLE;
    gpu->pipeline_cache_loaded = 0;
    if (!pg_cache_enabled()) return;
    char path[PG_PATH_MAX + 128];
    unsigned char *data = NULL;
    size_t bytes = 0;
    const void *init = NULL;
    size_t init_bytes = 0;
    if (cache_path(gpu, path, sizeof path, false) && (data = pg_cache_read(path, &bytes))) {
        pc_file_head h;
        bool ok = bytes >= sizeof h;
        if (ok) memcpy(&h, data, sizeof h);
        ok = ok && !memcmp(h.magic, PC_MAGIC, 8) && h.bytes == bytes - sizeof h;
        if (ok) {
            pg_hash128 sum = pg_hash128_init();
            pg_hash128_add(&sum, data + sizeof h, (size_t)h.bytes);
            ok = sum.a == h.sum_a && sum.b == h.sum_b;
        }
        if (!ok) pg_cache_note("pipeline cache file %s is corrupt; ignored", path);
        else if (!header_matches(gpu, data + sizeof h, (size_t)h.bytes))
            pg_cache_note("pipeline cache file %s was made for another device or driver; ignored", path);
        else {
            init = data + sizeof h;
            init_bytes = (size_t)h.bytes;
        }
    }
    VkPipelineCacheCreateInfo ci = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO,
        .initialDataSize = init_bytes,
        .pInitialData = init,
    };
    VkResult r = vkCreatePipelineCache(gpu->device, &ci, NULL, &gpu->pipeline_cache);
    if (r != VK_SUCCESS && init_bytes) {
        pg_cache_note("pipeline cache file %s refused by the driver (%s); ignored", path, pg_vk_result_name(r));
        ci.initialDataSize = 0;
        ci.pInitialData = NULL;
        init_bytes = 0;
        r = vkCreatePipelineCache(gpu->device, &ci, NULL, &gpu->pipeline_cache);
    }
    if (r != VK_SUCCESS) {
        pg_cache_note("vkCreatePipelineCache failed (%s); pipelines are created without a cache",
                      pg_vk_result_name(r));
        gpu->pipeline_cache = VK_NULL_HANDLE;
    } else {
        gpu->pipeline_cache_loaded = init_bytes;
        pg_gpu_name(gpu, VK_OBJECT_TYPE_PIPELINE_CACHE, (uint64_t)gpu->pipeline_cache, "passgraph pipeline cache");
        if (init_bytes) {
            pg_hash128 sum = pg_hash128_init();
            pg_hash128_add(&sum, init, init_bytes);
            gpu->pipeline_cache_sum = sum.a;
        }
    }
    free(data);
}

void pg_pipeline_cache_close(pg_gpu *gpu)
{
    if (!gpu->pipeline_cache) return;
    size_t n = 0;
    unsigned char *data = NULL;
    if (vkGetPipelineCacheData(gpu->device, gpu->pipeline_cache, &n, NULL) == VK_SUCCESS && n &&
        (data = malloc(n)) && vkGetPipelineCacheData(gpu->device, gpu->pipeline_cache, &n, data) == VK_SUCCESS) {
        pg_hash128 sum = pg_hash128_init();
        pg_hash128_add(&sum, data, n);
        char path[PG_PATH_MAX + 128];
        /* unchanged since it was loaded: nothing to write */
        if (!(gpu->pipeline_cache_loaded == n && gpu->pipeline_cache_sum == sum.a) &&
            cache_path(gpu, path, sizeof path, true)) {
            pc_file_head h = {.bytes = n, .sum_a = sum.a, .sum_b = sum.b};
            memcpy(h.magic, PC_MAGIC, 8);
            pg_cache_write(path, &h, sizeof h, data, n);
        }
    }
    free(data);
    vkDestroyPipelineCache(gpu->device, gpu->pipeline_cache, NULL);
    gpu->pipeline_cache = VK_NULL_HANDLE;
}
