#version 460
// cluster_assign.comp - one workgroup per cluster: test every light's sphere against the
// cluster's view-space AABB (conservative: the AABB contains the cluster's frustum piece) and
// append the hits in ascending light order (a ballot prefix sum per chunk of 64 lights), so the
// lists - and which lights an overflowing cluster keeps (the lowest indices) - are deterministic.
// cluster_counts holds the raw count (may exceed MAX_LIGHTS); shaders clamp. Overflow statistics
// go to a small host-visible buffer the pass reads back after the frame.
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
#include "cluster.glsl"

layout(local_size_x = 64) in;
layout(set = 1, binding = 0, std430) readonly buffer Lights { Light lights[]; };
layout(set = 1, binding = 1, std430) writeonly buffer ClusterCounts { uint cluster_counts[]; };
layout(set = 1, binding = 2, std430) writeonly buffer ClusterLights { uint cluster_lights[]; };
layout(set = 1, binding = 3, std430) buffer Stats {
    uint overflow_clusters; // clusters with more lights than MAX_LIGHTS
    uint overflow_dropped;  // light references beyond MAX_LIGHTS (not shaded)
    uint max_count;         // largest raw count
    uint total_refs;        // stored light references
} stats;

shared uint s_group_hits[64];
shared uint s_base;

void main()
{
    const uvec3 grid = uvec3(GRID_X, GRID_Y, GRID_Z);
    uint cluster = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    if (cluster >= grid.x * grid.y * grid.z) return; // whole workgroup leaves together
    uvec3 c = uvec3(cluster % grid.x, (cluster / grid.x) % grid.y, cluster / (grid.x * grid.y));
    vec3 bmin, bmax;
    pg_cluster_aabb(c, grid, frame.inv_proj, frame.clip.x, frame.clip.y, bmin, bmax);
    if (gl_LocalInvocationIndex == 0u) s_base = 0u;
    barrier();
    uint count = frame.counts.x;
    vec3 cam = frame.camera_pos.xyz;
    mat3 rot = mat3(frame.view);
    for (uint start = 0u; start < count; start += 64u) {
        uint i = start + gl_LocalInvocationIndex;
        bool hit = false;
        if (i < count) {
            Light L = lights[i];
            // camera-relative first: keeps precision for scenes far from the origin
            vec3 rel = L.pos_radius.xyz - cam;
            vec3 pv = rot * rel;
            // pad for the float error of the transform (|rel| * a few ulp)
            float r = L.pos_radius.w;
            float pad = r > 0.0 ? 1e-4 * r + 4e-7 * (length(rel) + length(L.pos_radius.xyz)) : 0.0;
            hit = pg_sphere_intersects_aabb(pv, r + pad, bmin, bmax);
        }
        uvec4 ballot = subgroupBallot(hit);
        uint before_in_group = subgroupBallotExclusiveBitCount(ballot);
        if (subgroupElect()) s_group_hits[gl_SubgroupID] = subgroupBallotBitCount(ballot);
        barrier();
        uint slot = s_base;
        for (uint g = 0u; g < gl_SubgroupID; g++) slot += s_group_hits[g];
        slot += before_in_group;
        if (hit && slot < uint(MAX_LIGHTS)) cluster_lights[cluster * uint(MAX_LIGHTS) + slot] = i;
        barrier();
        if (gl_LocalInvocationIndex == 0u) {
            uint t = 0u;
            for (uint g = 0u; g < gl_NumSubgroups; g++) t += s_group_hits[g];
            s_base += t;
        }
        barrier();
    }
    if (gl_LocalInvocationIndex == 0u) {
        uint n = s_base;
        cluster_counts[cluster] = n;
        uint kept = min(n, uint(MAX_LIGHTS));
        if (n > uint(MAX_LIGHTS)) {
            atomicAdd(stats.overflow_clusters, 1u);
            atomicAdd(stats.overflow_dropped, n - uint(MAX_LIGHTS));
        }
        atomicMax(stats.max_count, n);
        atomicAdd(stats.total_refs, kept);
    }
}
