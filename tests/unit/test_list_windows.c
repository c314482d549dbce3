/* test_list_windows.c - the light lists' windows (renderer/common/cluster_windows.h) from a
 * device's limits, without a GPU: the window is the largest power of two one binding spans (at most
 * 2^31), PASSGRAPH_LIST_WINDOW_BYTES only shrinks it to a power of two from 64 KiB, a buffer one
 * binding spans stays one window, larger ones take one window each, the lists' ceiling is 8 windows
 * within the buffer, allocation, per-stage and 32-bit index limits, and the shader defines name the
 * count and the shift. test_gpu_clustered renders through the windows. */
#include <stdlib.h>
#include <string.h>

#include "cluster_windows.h"
#include "test_util.h"

static pg_gpu device(uint64_t range, uint64_t max_buffer, uint64_t max_alloc, uint32_t stage_buffers)
{
    pg_gpu g;
    memset(&g, 0, sizeof g);
    g.max_storage_buffer_range = range;
    g.max_buffer_size = max_buffer;
    g.max_allocation_size = max_alloc;
    g.max_stage_storage_buffers = stage_buffers;
    return g;
}

int main(void)
{
    unsetenv("PASSGRAPH_LIST_WINDOW_BYTES");
    const uint64_t MiB = 1ull << 20, GiB = 1ull << 30;
    /* lavapipe: 128 MiB bindings, 4 GiB buffers, 2 GiB allocations */
    pg_gpu lvp = device(128 * MiB, 4 * GiB - 1, 2 * GiB, 1u << 20);
    CHECK(pg_list_window_bytes(&lvp) == 128 * MiB);
    CHECK(pg_list_max_bytes(&lvp) == 1 * GiB);
    CHECK(pg_list_windows(&lvp, 590 * 1024) == 1);
    CHECK(pg_list_windows(&lvp, 128 * MiB) == 1);
    CHECK(pg_list_windows(&lvp, 128 * MiB + 4) == 2);
    CHECK(pg_list_windows(&lvp, 216764160) == 2);
    char buf[2][40];
    const char *defs[2] = {NULL, NULL};
    CHECK(pg_list_window_defines(&lvp, 100 * MiB, buf, defs) == 0 && defs[0] == NULL);
    CHECK(pg_list_window_defines(&lvp, 300 * MiB, buf, defs) == 2);
    CHECK(defs[0] && strcmp(defs[0], "PG_LIST_WINDOWS=3") == 0);
    CHECK(defs[1] && strcmp(defs[1], "PG_LIST_WINDOW_SHIFT=25") == 0); /* 2^25 entries of 4 bytes */
    /* a 4 GiB - 1 binding (NVIDIA): 2 GiB windows, but a list it spans stays one binding */
    pg_gpu nv = device(4 * GiB - 1, UINT64_MAX, UINT64_MAX, 1u << 20);
    CHECK(pg_list_window_bytes(&nv) == 2 * GiB);
    CHECK(pg_list_windows(&nv, 3477059328ull) == 1);
    CHECK(pg_list_windows(&nv, 5 * GiB) == 3);
    CHECK(pg_list_max_bytes(&nv) == 16 * GiB - 256); /* 32-bit indices of 4-byte entries */
    /* an allocation limit and a small per-stage limit lower the ceiling */
    pg_gpu small = device(128 * MiB, UINT64_MAX, 300 * MiB, 19);
    CHECK(pg_list_max_bytes(&small) == (300 * MiB & ~(uint64_t)255));
    small.max_allocation_size = UINT64_MAX;
    CHECK(pg_list_max_bytes(&small) == 3 * 128 * MiB); /* 19 - 16 other storage buffers */
    small.max_stage_storage_buffers = 4;
    CHECK(pg_list_max_bytes(&small) == 128 * MiB);
    /* a binding range that is no power of two */
    pg_gpu odd = device(100 * MiB, UINT64_MAX, UINT64_MAX, 1u << 20);
    CHECK(pg_list_window_bytes(&odd) == 64 * MiB);
    CHECK(pg_list_windows(&odd, 100 * MiB) == 1);
    CHECK(pg_list_windows(&odd, 100 * MiB + 256) == 2);
    /* the test override: a power of two from 64 KiB up to the window; anything else is ignored */
    setenv("PASSGRAPH_LIST_WINDOW_BYTES", "524288", 1);
    CHECK(pg_list_window_bytes(&lvp) == 512 * 1024);
    CHECK(pg_list_windows(&lvp, 590 * 1024) == 2);
    CHECK(pg_list_windows(&lvp, 512 * 1024) == 1);
    CHECK(pg_list_max_bytes(&lvp) == 4 * MiB);
    const char *bad[] = {"1000000", "32768", "268435456", "abc", "524288x", "-524288", ""};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        setenv("PASSGRAPH_LIST_WINDOW_BYTES", bad[i], 1);
        CHECK_MSG(pg_list_window_bytes(&lvp) == 128 * MiB, "override '%s' was not ignored", bad[i]);
        CHECK_MSG(pg_list_windows(&lvp, 100 * MiB) == 1, "override '%s' split a list one binding spans", bad[i]);
    }
    unsetenv("PASSGRAPH_LIST_WINDOW_BYTES");
    return pg_test_finish("test_list_windows");
}
