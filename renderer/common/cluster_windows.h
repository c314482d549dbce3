/* cluster_windows.h - the light lists (the cluster_lights buffer) bound in windows. A list buffer
 * larger than one storage-buffer binding may span (gpu->max_storage_buffer_range: 128 MiB on
 * lavapipe, 4 GiB on NVIDIA) is bound as an array of up to PG_LIST_WINDOWS_MAX descriptors over
 * consecutive windows of the one buffer, and the shaders pick an index's window with a branch on
 * constant array indices (shaders/cluster_list_windows.glsl: no descriptor-indexing feature). The
 * writer (cluster_assign) and every reader derive the same windows from the buffer's size, and a
 * grown buffer re-creates them all. One window: the plain binding and shader of before. */
#ifndef PG_CLUSTER_WINDOWS_H
#define PG_CLUSTER_WINDOWS_H

#include "pass_set.h" /* PG_SET_MAX_WINDOWS; bind with pg_pass_set_create_windowed */

#define PG_LIST_WINDOWS_MAX PG_SET_MAX_WINDOWS

/* The window: the largest power of two of bytes one binding spans (at most 2^31), or the value of
 * PASSGRAPH_LIST_WINDOW_BYTES when it is a power of two from 2^16 up to that (a test's way to get
 * several windows from small lists; other values are ignored). */
uint64_t pg_list_window_bytes(const pg_gpu *gpu);

/* The most bytes the lists may take on this device: PG_LIST_WINDOWS_MAX windows (fewer where the
 * device's per-stage storage-buffer limit is small), at most one buffer's and one allocation's
 * size, below 2^34 (32-bit indices of 4-byte entries), a multiple of 256. */
uint64_t pg_list_max_bytes(const pg_gpu *gpu);

/* How many windows a list buffer of `bytes` takes: 1 when one binding spans it (unless
 * PASSGRAPH_LIST_WINDOW_BYTES sets a smaller window), else one per window. */
uint32_t pg_list_windows(const pg_gpu *gpu, uint64_t bytes);

/* The shader defines for a list buffer of `bytes`, appended to defs (returns how many: 0 for one
 * window; else PG_LIST_WINDOWS=K and PG_LIST_WINDOW_SHIFT=log2(window / 4), written into buf). */
uint32_t pg_list_window_defines(const pg_gpu *gpu, uint64_t bytes, char buf[2][40], const char **defs);


#endif
