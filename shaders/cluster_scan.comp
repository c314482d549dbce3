#version 460
// cluster_scan.comp - light assignment, step 3 of 4 (renderer/passes/cluster_assign.c), in two
// dispatches. PG_SEGMENT_SCAN: one workgroup per cluster sums the hits of the cluster's segments
// (count step) into its raw count (record.z) and turns the segment counts into prefixes for the
// fill step (in parallel: one workgroup walking every cluster's segments took 0.43 ms at
// 1,000,000 lights on an H200). Then one workgroup turns the raw counts into list offsets and
// stored counts:
//   stored_c = min(raw_c, cap) with cap the per-cluster limit (push constant; 0 = none, the
//   default: exact);
//   if the stored references exceed the list buffer (capacity, in elements), every cluster keeps
//   its first min(stored_c, k) lights for the largest k that fits (deterministic, lowest light
//   indices first, fair between clusters), and the rest is counted as dropped;
//   record.x = exclusive prefix sum of what is kept, record.y = what is kept.
// Statistics for the host (read back after the frame): the references needed (after the cap),
// stored, dropped, overflowing clusters, the largest raw count. Sums saturate at 2^32 - 1.
#include "common.glsl"
FRAME_UNIFORMS_BLOCK

#ifdef PG_SEGMENT_SCAN
#define WG 64u
layout(local_size_x = 64) in;
#else
#define WG 256u
layout(local_size_x = 256) in;
#endif
layout(set = 1, binding = 1, std430) buffer Records { uvec4 records[]; };
layout(set = 1, binding = 5, std430) buffer Stats {
    uint needed;            // references the lists need (after the per-cluster cap)
    uint stored;            // references stored
    uint dropped;           // raw references not stored (cap + capacity)
    uint overflow_clusters; // clusters that store fewer lights than reach them
    uint max_count;         // largest raw count
    uint dropped_cap;       // dropped by the per-cluster cap alone
    uint fair_cap;          // the k applied when the capacity was short (0xffffffff: none)
    uint capacity;          // the list capacity this frame had (elements)
} stats;
layout(set = 1, binding = 7, std430) buffer Segments { uint segments[]; };
layout(push_constant) uniform Push { uint clusters; uint capacity; uint cap; uint segments; } pc;

shared uint s_red[WG];

uint sat_add(uint a, uint b)
{
    uint s = a + b;
    return s < a ? 0xffffffffu : s;
}

uint reduce_sum(uint v)
{
    uint lid = gl_LocalInvocationIndex;
    s_red[lid] = v;
    barrier();
    for (uint d = WG / 2u; d > 0u; d >>= 1u) {
        if (lid < d) s_red[lid] = sat_add(s_red[lid], s_red[lid + d]);
        barrier();
    }
    uint r = s_red[0];
    barrier();
    return r;
}

uint reduce_max(uint v)
{
    uint lid = gl_LocalInvocationIndex;
    s_red[lid] = v;
    barrier();
    for (uint d = WG / 2u; d > 0u; d >>= 1u) {
        if (lid < d) s_red[lid] = max(s_red[lid], s_red[lid + d]);
        barrier();
    }
    uint r = s_red[0];
    barrier();
    return r;
}

uint stored_of(uint raw)
{
    return pc.cap != 0u ? min(raw, pc.cap) : raw;
}

#ifdef PG_SEGMENT_SCAN
// raw count of cluster c = the sum of its segments' hits; the segments become exclusive prefixes
void main()
{
    uint lid = gl_LocalInvocationIndex;
    uint c = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    if (c >= pc.clusters) return;                    // the whole workgroup leaves together
    uint base = c * pc.segments, running = 0u;
    for (uint g0 = 0u; g0 < pc.segments; g0 += WG) {
        uint g = g0 + lid;
        uint h = g < pc.segments ? segments[base + g] : 0u;
        s_red[lid] = h;
        barrier();
        for (uint d = 1u; d < WG; d <<= 1u) {         // inclusive scan (a cluster's hits fit in 32 bits)
            uint add = lid >= d ? s_red[lid - d] : 0u;
            barrier();
            s_red[lid] += add;
            barrier();
        }
        if (g < pc.segments) segments[base + g] = running + s_red[lid] - h;
        running += s_red[WG - 1u];
        barrier();
    }
    if (lid == 0u) records[c] = uvec4(0u, 0u, running, 0u);
}
#else
void main()
{
    uint lid = gl_LocalInvocationIndex;
    uint n = pc.clusters;
    uint per = (n + WG - 1u) / WG;
    uint first = min(lid * per, n), last = min(first + per, n);
    uint s_stored = 0u, s_raw = 0u, m_raw = 0u, m_stored = 0u;
    for (uint c = first; c < last; c++) {
        uint raw = records[c].z;
        uint st = stored_of(raw);
        s_stored = sat_add(s_stored, st);
        s_raw = sat_add(s_raw, raw);
        m_raw = max(m_raw, raw);
        m_stored = max(m_stored, st);
    }
    uint total_stored = reduce_sum(s_stored);
    uint total_raw = reduce_sum(s_raw);
    uint max_raw = reduce_max(m_raw);
    uint max_stored = reduce_max(m_stored);

    // fair per-cluster limit when the capacity is short: largest k with sum(min(stored, k)) <= capacity
    uint k = 0xffffffffu;
    if (total_stored > pc.capacity) {
        uint lo = 0u, hi = max_stored;
        while (lo < hi) {                               // uniform: every invocation has lo, hi
            uint mid = lo + (hi - lo + 1u) / 2u;
            uint part = 0u;
            for (uint c = first; c < last; c++) part = sat_add(part, min(stored_of(records[c].z), mid));
            if (reduce_sum(part) <= pc.capacity) lo = mid;
            else hi = mid - 1u;
        }
        k = lo;
    }

    // offsets: exclusive prefix over clusters of what each keeps
    uint part = 0u, over = 0u;
    for (uint c = first; c < last; c++) part += min(stored_of(records[c].z), k);
    s_red[lid] = part;
    barrier();
    for (uint d = 1u; d < WG; d <<= 1u) {             // inclusive scan (fits: kept <= capacity)
        uint add = lid >= d ? s_red[lid - d] : 0u;
        barrier();
        s_red[lid] += add;
        barrier();
    }
    uint offset = s_red[lid] - part;
    uint total_kept = s_red[WG - 1u];
    barrier();
    for (uint c = first; c < last; c++) {
        uint raw = records[c].z;
        uint keep = min(stored_of(raw), k);
        records[c] = uvec4(offset, keep, raw, 0u);
        offset += keep;
        if (keep < raw) over++;
    }
    uint overflow = reduce_sum(over);
    if (lid == 0u) {
        stats.needed = total_stored;
        stats.stored = total_kept;
        stats.dropped = total_raw == 0xffffffffu ? 0xffffffffu : total_raw - total_kept;
        stats.overflow_clusters = overflow;
        stats.max_count = max_raw;
        stats.dropped_cap = total_raw == 0xffffffffu ? 0xffffffffu : total_raw - total_stored;
        stats.fair_cap = k;
        stats.capacity = pc.capacity;
    }
}
#endif
