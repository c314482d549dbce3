// cluster_list_windows.glsl - the light lists (cluster_lights, light indices) at binding 2 of set
// PG_LISTS_SET: one buffer, or with PG_LIST_WINDOWS (renderer/common/cluster_windows.h: lists larger
// than one storage-buffer binding spans) an array of that many windows of 2^PG_LIST_WINDOW_SHIFT
// entries each, the window of an index picked by a switch on constant array indices (no
// descriptor-indexing feature needed). Define PG_LISTS_SET, and PG_LISTS_WRITE for the writer
// (cluster_lists.comp; readers get readonly lists), then read with PG_LIST_READ(i) or write with
// PG_LIST_WRITE(i, v).
#ifndef PG_LIST_WINDOWS
#ifdef PG_LISTS_WRITE
layout(set = PG_LISTS_SET, binding = 2, std430) writeonly buffer ClusterLights { uint cluster_lights[]; };
#define PG_LIST_WRITE(i, v) (cluster_lights[i] = (v))
#else
layout(set = PG_LISTS_SET, binding = 2, std430) readonly buffer ClusterLights { uint cluster_lights[]; };
#define PG_LIST_READ(i) cluster_lights[i]
#endif
#else
#if PG_LIST_WINDOWS > 8
#error "PG_LIST_WINDOWS: at most 8 windows"
#endif
#ifdef PG_LISTS_WRITE
layout(set = PG_LISTS_SET, binding = 2, std430) writeonly buffer ClusterLights { uint e[]; } pg_lw[PG_LIST_WINDOWS];
#define PG_LW_CASE(k) case k: pg_lw[k].e[j] = v; break;
void pg_list_write(uint i, uint v)
#else
layout(set = PG_LISTS_SET, binding = 2, std430) readonly buffer ClusterLights { uint e[]; } pg_lw[PG_LIST_WINDOWS];
#define PG_LW_CASE(k) case k: return pg_lw[k].e[j];
uint pg_list_read(uint i)
#endif
{
    uint j = i & ((1u << PG_LIST_WINDOW_SHIFT) - 1u);
    switch (int(i >> PG_LIST_WINDOW_SHIFT)) {
    PG_LW_CASE(0)
    PG_LW_CASE(1)
#if PG_LIST_WINDOWS > 2
    PG_LW_CASE(2)
#endif
#if PG_LIST_WINDOWS > 3
    PG_LW_CASE(3)
#endif
#if PG_LIST_WINDOWS > 4
    PG_LW_CASE(4)
#endif
#if PG_LIST_WINDOWS > 5
    PG_LW_CASE(5)
#endif
#if PG_LIST_WINDOWS > 6
    PG_LW_CASE(6)
#endif
#if PG_LIST_WINDOWS > 7
    PG_LW_CASE(7)
#endif
    default: break;
    }
#ifndef PG_LISTS_WRITE
    return 0u;
#endif
}
#undef PG_LW_CASE
#ifdef PG_LISTS_WRITE
#define PG_LIST_WRITE(i, v) pg_list_write(i, v)
#else
#define PG_LIST_READ(i) pg_list_read(i)
#endif
#endif
