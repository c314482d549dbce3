#version 460
// cluster_lists.comp - light assignment, steps 2 and 4 of 4 (renderer/passes/cluster_assign.c). One
// workgroup per (cluster, segment of seg_words words: many workgroups per cluster at high light
// counts, so the GPU has enough of them in flight) walks the 32-light words of its candidates (tile mask AND slice mask from
// cluster_bin.comp; with PG_BRUTE_FORCE every light is a candidate: the oracle), applies the exact
// test (pg_sphere_intersects_aabb against pg_cluster_aabb) to each candidate and
//   - without PG_FILL (count): writes the number of hits of its segment;
//   - with PG_FILL: writes its hits, in ascending light order, at record.x + the hits of the
//     cluster's earlier segments, as long as they are within the first record.y.
// Both variants visit candidates in the same order and apply the same test, so the fill stores
// exactly the lights the count counted. Words are handed to lanes in order and combined with an
// exclusive prefix sum, so the lists come out ascending.
// PG_SPOT_LIGHTS: a spot light's sphere bounds its lit set (its ball within its cone), and the light
// is also dropped from a cluster when its ball misses the box or its cone misses the bounding sphere
// of the box (pg_cone_reaches_sphere): it adds exactly 0 to every point there.
// PG_ONE_SUBGROUP: the workgroup is exactly one full subgroup (the pipeline requires the size;
// gpu->exact_subgroups): subgroup operations only, no barrier. Otherwise a 64-wide workgroup and
// a shared-memory scan in gl_LocalInvocationIndex order.
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
#include "cluster.glsl"
#include "cluster_light.glsl"

#ifdef PG_ONE_SUBGROUP
layout(local_size_x_id = 0) in;
#else
layout(local_size_x = 64) in;
#endif
layout(set = 1, binding = 6, std430) readonly buffer Spheres { vec4 spheres[]; }; // cluster_bin.comp
layout(set = 1, binding = 1, std430) readonly buffer Records { uvec4 records[]; };
// per (cluster, segment): the count step writes the hits of the segment; the scan step turns
// them into exclusive prefixes within the cluster, which the fill step starts from
layout(set = 1, binding = 7, std430) buffer Segments { uint segments[]; };
#ifdef PG_FILL
#define PG_LISTS_SET 1
#define PG_LISTS_WRITE
#include "cluster_list_windows.glsl"
#endif
#ifndef PG_BRUTE_FORCE
layout(set = 1, binding = 3, std430) readonly buffer TileMasks { uint tile_masks[]; };
layout(set = 1, binding = 4, std430) readonly buffer SliceMasks { uint slice_masks[]; };
#endif
layout(push_constant) uniform Push { uint words; uint segments; uint seg_words; } pc;

// candidates of a word tested per round: their sphere loads are issued together (a lane's
// candidates were loaded one after another, each waiting for the last)
#ifndef PG_CANDIDATE_LOADS
#define PG_CANDIDATE_LOADS 4
#endif
// consecutive mask words a lane walks per round (lanes in order, so the lists stay ascending):
// fewer rounds, each waiting once for PG_LANE_WORDS words instead of once per word
#ifndef PG_LANE_WORDS
#define PG_LANE_WORDS 4
#endif

#ifndef PG_ONE_SUBGROUP
shared uint s_scan[64];
#endif

// Exclusive prefix of v over the workgroup in lane order, and the total.
void scan(uint v, out uint excl, out uint total)
{
#ifdef PG_ONE_SUBGROUP
    excl = subgroupExclusiveAdd(v);
    total = subgroupAdd(v);
#else
    uint lid = gl_LocalInvocationIndex;
    s_scan[lid] = v;
    barrier();
    for (uint d = 1u; d < 64u; d <<= 1u) {
        uint add = lid >= d ? s_scan[lid - d] : 0u;
        barrier();
        s_scan[lid] += add;
        barrier();
    }
    excl = s_scan[lid] - v;
    total = s_scan[63];
    barrier();
#endif
}

void main()
{
    const uvec3 grid = uvec3(GRID_X, GRID_Y, GRID_Z);
    uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    uint cluster = group / pc.segments, seg = group % pc.segments;
    if (cluster >= grid.x * grid.y * grid.z) return;  // the whole workgroup leaves together
    uvec3 c = uvec3(cluster % grid.x, (cluster / grid.x) % grid.y, cluster / (grid.x * grid.y));
    vec3 bmin, bmax;
    pg_cluster_aabb(c, grid, frame.inv_proj, frame.clip.x, frame.clip.y, PG_ORTHO, bmin, bmax);
#ifdef PG_SPOT_LIGHTS
    vec3 box_c = 0.5 * (bmin + bmax);                // the box's bounding sphere, for the cone test
    float box_r = 0.5 * length(bmax - bmin);
#endif
#ifdef PG_ONE_SUBGROUP
    uint lane = gl_SubgroupInvocationID, width = gl_SubgroupSize;
#else
    uint lane = gl_LocalInvocationIndex, width = 64u;
#endif
    uint count = frame.counts.x;
    uint words = pc.words;
#ifndef PG_BRUTE_FORCE
    uint tile_base = (c.y * grid.x + c.x) * words, slice_base = c.z * words;
#endif
    uint seg_index = cluster * pc.segments + seg;
    uint w_begin = seg * pc.seg_words, w_end = min(words, w_begin + pc.seg_words);
#ifdef PG_FILL
    uvec4 rec = records[cluster];
    uint keep = rec.y;
    uint running = segments[seg_index];              // hits of the cluster's earlier segments
    if (running >= keep) return;
#else
    uint running = 0u;
#endif
    for (uint w0 = w_begin; w0 < w_end; w0 += width * PG_LANE_WORDS) {
        uint wl = w0 + lane * PG_LANE_WORDS;        // this lane's words: wl .. wl + PG_LANE_WORDS - 1
        uint m[PG_LANE_WORDS], hits[PG_LANE_WORDS];
        for (int j = 0; j < PG_LANE_WORDS; j++) {   // every mask load of the round in flight together
            uint w = wl + uint(j);
#ifdef PG_BRUTE_FORCE
            uint n = min(count - min(count, w * 32u), 32u);
            m[j] = w >= w_end ? 0u : n >= 32u ? ~0u : ((1u << n) - 1u);
#else
            m[j] = w < w_end ? tile_masks[tile_base + w] & slice_masks[slice_base + w] : 0u;
#endif
        }
        uint n_hits = 0u;
        for (int j = 0; j < PG_LANE_WORDS; j++) {
            uint w = wl + uint(j);
            uint mm = m[j];
            hits[j] = 0u;
            while (mm != 0u) {   // PG_CANDIDATE_LOADS candidates at a time: their loads in flight together
                uint bits[PG_CANDIDATE_LOADS];
                vec4 sph[PG_CANDIDATE_LOADS];
                for (int q = 0; q < PG_CANDIDATE_LOADS; q++) {
                    bits[q] = mm != 0u ? uint(findLSB(mm)) : 32u;
                    mm &= mm - 1u;   // 0 stays 0
                }
                for (int q = 0; q < PG_CANDIDATE_LOADS; q++)
                    sph[q] = bits[q] < 32u ? spheres[(w * 32u + bits[q]) * PG_LIGHT_RECORD_VEC4] : vec4(0.0);
#ifdef PG_SPOT_LIGHTS
                vec4 cone[PG_CANDIDATE_LOADS], ball[PG_CANDIDATE_LOADS];
                for (int q = 0; q < PG_CANDIDATE_LOADS; q++) {
                    uint base = (w * 32u + bits[q]) * PG_LIGHT_RECORD_VEC4;
                    cone[q] = bits[q] < 32u ? spheres[base + 1u] : vec4(2.0);
                    ball[q] = bits[q] < 32u ? spheres[base + 2u] : vec4(0.0);
                }
#endif
                for (int q = 0; q < PG_CANDIDATE_LOADS; q++)
                    if (bits[q] < 32u && pg_sphere_intersects_aabb(sph[q].xyz, sph[q].w, bmin, bmax)
#ifdef PG_SPOT_LIGHTS
                        && pg_sphere_intersects_aabb(ball[q].xyz, ball[q].w, bmin, bmax)
                        && pg_cone_reaches_sphere(cone[q], ball[q].xyz, box_c, box_r)
#endif
                       )
                        hits[j] |= 1u << bits[q];
            }
            n_hits += bitCount(hits[j]);
        }
        uint excl, total;
        scan(n_hits, excl, total);
#ifdef PG_FILL
        uint slot = running + excl;
        for (int j = 0; j < PG_LANE_WORDS; j++) {
            uint h = hits[j];
            while (h != 0u && slot < keep) {
                int b = findLSB(h);
                h &= h - 1u;
                PG_LIST_WRITE(rec.x + slot, (wl + uint(j)) * 32u + uint(b));
                slot++;
            }
        }
#endif
        running += total;
#ifdef PG_FILL
        if (running >= keep) break;                   // uniform: every lane has the same total
#endif
    }
#ifndef PG_FILL
    if (lane == 0u) segments[seg_index] = running;
#endif
}
