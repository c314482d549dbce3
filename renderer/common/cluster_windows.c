/* cluster_windows.c - the light lists bound in windows (cluster_windows.h). */
#include "cluster_windows.h"

#include <stdio.h>
#include <stdlib.h>

/* the largest power of two of bytes one binding spans, at most 2^31 */
static uint64_t binding_window(const pg_gpu *gpu)
{
    uint64_t w = 256;
    while (w * 2 <= gpu->max_storage_buffer_range && w < (1ull << 31)) w *= 2;
    return w;
}

uint64_t pg_list_window_bytes(const pg_gpu *gpu)
{
    uint64_t w = binding_window(gpu);
    const char *e = getenv("PASSGRAPH_LIST_WINDOW_BYTES");
    if (e && *e) {
        char *end = NULL;
        unsigned long long v = strtoull(e, &end, 10);
        if (end && !*end && v >= (1ull << 16) && v <= w && (v & (v - 1)) == 0) w = v;
    }
    return w;
}

uint64_t pg_list_max_bytes(const pg_gpu *gpu)
{
    uint64_t windows = PG_LIST_WINDOWS_MAX;
    /* a reader's stage binds up to 16 other storage buffers (lights, records, materials, ...) */
    if (gpu->max_stage_storage_buffers < 16 + windows)
        windows = gpu->max_stage_storage_buffers > 17 ? gpu->max_stage_storage_buffers - 16 : 1;
    uint64_t most = windows * pg_list_window_bytes(gpu);
    if (gpu->max_buffer_size && most > gpu->max_buffer_size) most = gpu->max_buffer_size;
    if (gpu->max_allocation_size && most > gpu->max_allocation_size) most = gpu->max_allocation_size;
    if (most > (1ull << 34) - 256) most = (1ull << 34) - 256;
    return most & ~(uint64_t)255;
}

uint32_t pg_list_windows(const pg_gpu *gpu, uint64_t bytes)
{
    uint64_t w = pg_list_window_bytes(gpu);
    bool forced = w < binding_window(gpu); /* PASSGRAPH_LIST_WINDOW_BYTES */
    if (bytes <= w || (!forced && bytes <= gpu->max_storage_buffer_range)) return 1;
    uint64_t k = (bytes + w - 1) / w;
    return k <= 1 ? 1 : (k > UINT32_MAX ? UINT32_MAX : (uint32_t)k);
}

uint32_t pg_list_window_defines(const pg_gpu *gpu, uint64_t bytes, char buf[2][40], const char **defs)
{
    uint32_t k = pg_list_windows(gpu, bytes);
    if (k <= 1) return 0;
    uint32_t shift = 0;
    for (uint64_t w = pg_list_window_bytes(gpu) / 4; w > 1; w /= 2) shift++;
    snprintf(buf[0], sizeof buf[0], "PG_LIST_WINDOWS=%u", k);
    snprintf(buf[1], sizeof buf[1], "PG_LIST_WINDOW_SHIFT=%u", shift);
    defs[0] = buf[0];
    defs[1] = buf[1];
    return 2;
}
