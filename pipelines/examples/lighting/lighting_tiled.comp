#version 460
// lighting_tiled.comp - the user lighting pass of pipelines/examples/lighting/lighting.json written
// as the built-in deferred pass's tiled loop is (loop=tiled): the same light model as lighting.comp,
// but each 8x8 workgroup takes the distinct clusters of its pixels one at a time (smallest index
// first), streams that cluster's list through shared memory 64 lights at a time, keeps only the
// lights whose sphere reaches the bounding box of the tile's pixels in that cluster (a light that
// reaches a pixel reaches the box: the others would add exactly 0), and the cluster's pixels sum
// the kept lights. A light also leaves the chunk when it lies behind every one of those pixels:
// dot(N_i, light - P_i) = dot(N_i, r) + dot(N_i, Pc - P_i) <= dot(a, r) + E |r| + H < 0, with Pc the
// box centre, r = light - Pc, a the normal of one of the pixels, E = max |N_i - a| and
// H = max dot(N_i, Pc - P_i): max(N.L, 0) is 0 at each of them, so it would add nothing. Each light
// is read once a tile instead of once a pixel, and tested once a tile instead of once a pixel; what
// the model needs of a light (its camera-relative centre, R^2, 1/R^2) is computed once a tile too, and
// the pixels evaluate light_model.glsl from it in camera-relative coordinates. The kept lights of a
// chunk are summed in the order the threads kept them, so a pixel's sum may differ from
// lighting.comp's in the last bits.
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
#include "cluster.glsl"
#include "octahedral.glsl"
#include "gbuffer_pack.glsl"
#include "depth_reconstruct.glsl"
#include "gbuffer_read.glsl"
#include "light_model.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 2, binding = 0, std430) readonly buffer Lights { Light lights[]; };
layout(set = 2, binding = 1, std430) readonly buffer ClusterRecords { uvec4 cluster_records[]; };
layout(set = 2, binding = 2, std430) readonly buffer ClusterLights { uint cluster_lights[]; };
layout(set = 2, binding = 3) uniform sampler2D positions; // world position, w = 0 where no surface
layout(set = 2, binding = 4) uniform sampler2D normals;
layout(set = 2, binding = 5) uniform sampler2D albedo;
layout(set = 2, binding = 6, rgba16f) uniform writeonly image2D hdr_out;
layout(push_constant) uniform Params {
    float ambient;
} params;

#define TILE_N 64u
shared uint s_cluster;       // the cluster the tile works on (the smallest still pending)
shared uint s_box[6];        // its pixels' camera-relative bounding box (order-preserving uints)
shared uint s_kept;          // lights of the current chunk that reach the box
shared uint s_first;         // the lowest invocation of the cluster: its normal is the axis a
shared float s_axis[3];
shared uint s_e, s_h;        // E (float bits, >= 0) and H (order-preserving uint)
shared vec4 s_light[2u * TILE_N];

uint to_ordered(float f) // float -> uint with the same order
{
    uint b = floatBitsToUint(f);
    return (b & 0x80000000u) != 0u ? ~b : b | 0x80000000u;
}

float from_ordered(uint u)
{
    return uintBitsToFloat((u & 0x80000000u) != 0u ? u & 0x7fffffffu : ~u);
}

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    uint lid = gl_LocalInvocationIndex;
    bool inside = all(lessThan(p, imageSize(hdr_out)));
    vec4 position = inside ? texelFetch(positions, p, 0) : vec4(0.0);
    bool lit = position.w != 0.0;
    Surface s = pg_surface_default();
    vec3 rel = vec3(0.0);
    float view_depth = 0.0;
    if (lit) pg_gbuffer_read_float(position, texelFetch(normals, p, 0), texelFetch(albedo, p, 0), s, rel, view_depth);
    vec3 N = normalize(s.normal);
    uvec3 grid = uvec3(GRID_X, GRID_Y, GRID_Z);
    uint ci = lit ? pg_cluster_index(pg_cluster_coord(vec2(p) + 0.5, vec2(frame.counts.zw), view_depth,
                                                      frame.clip.x, frame.clip.y, grid), grid)
                  : 0xffffffffu;
    bool pending = lit;
    vec3 sum = vec3(0.0);
    for (;;) { // every invocation runs every iteration: the barriers are in uniform control flow
        if (lid == 0u) {
            s_cluster = 0xffffffffu;
            s_box[0] = s_box[1] = s_box[2] = 0xffffffffu;
            s_box[3] = s_box[4] = s_box[5] = 0u;
            s_first = 0xffffffffu;
            s_e = 0u;
            s_h = 0u;
        }
        barrier();
        if (pending) atomicMin(s_cluster, ci);
        barrier();
        uint c = s_cluster;
        if (c == 0xffffffffu) break;
        bool mine = pending && ci == c;
        if (mine) {
            for (int k = 0; k < 3; k++) {
                atomicMin(s_box[k], to_ordered(rel[k]));
                atomicMax(s_box[3 + k], to_ordered(rel[k]));
            }
            atomicMin(s_first, lid);
        }
        barrier();
        vec3 bmin = vec3(from_ordered(s_box[0]), from_ordered(s_box[1]), from_ordered(s_box[2]));
        vec3 bmax = vec3(from_ordered(s_box[3]), from_ordered(s_box[4]), from_ordered(s_box[5]));
        vec3 pc = 0.5 * (bmin + bmax);
        if (lid == s_first) {
            s_axis[0] = N.x;
            s_axis[1] = N.y;
            s_axis[2] = N.z;
        }
        barrier();
        vec3 axis = vec3(s_axis[0], s_axis[1], s_axis[2]);
        if (mine) {
            atomicMax(s_e, floatBitsToUint(length(N - axis)));
            atomicMax(s_h, to_ordered(dot(N, pc - rel)));
        }
        barrier();
        float E = uintBitsToFloat(s_e), H = from_ordered(s_h);
        uvec4 rec = cluster_records[c];
        for (uint base = 0u; base < rec.y; base += TILE_N) {
            if (lid == 0u) s_kept = 0u;
            barrier();
            if (base + lid < rec.y) {
                Light L = lights[cluster_lights[rec.x + base + lid]];
                vec3 centre = L.pos_radius.xyz - frame.camera_pos.xyz;
                float pad = 1e-4 * L.pos_radius.w + 4e-7 * (length(centre) + length(L.pos_radius.xyz));
                vec3 r = centre - pc;
                float lr = length(r);
                bool behind = dot(axis, r) + E * lr + H < -1e-4 * (lr + length(pc) + 1.0);
                if (!behind && pg_sphere_intersects_aabb(centre, L.pos_radius.w + pad, bmin, bmax)) {
                    uint k = atomicAdd(s_kept, 1u); // camera-relative centre, 1/R^2; colour, R^2
                    float R2 = L.pos_radius.w * L.pos_radius.w;
                    s_light[2u * k] = vec4(centre, 1.0 / R2);
                    s_light[2u * k + 1u] = vec4(L.color.rgb, R2);
                }
            }
            barrier();
            if (mine)
                for (uint k = 0u; k < s_kept; k++) {
                    vec4 a = s_light[2u * k], b = s_light[2u * k + 1u];
                    sum += example_light(a.xyz - rel, b.w, a.w, b.rgb, N);
                }
            barrier();
        }
        if (mine) pending = false;
    }
    if (inside) {
        vec3 c = lit ? s.albedo * (sum + params.ambient + frame.clip.z) : vec3(0.0);
        imageStore(hdr_out, p, vec4(pg_hdr_sanitize(c), 1.0));
    }
}
