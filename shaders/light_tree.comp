#version 460
// light_tree.comp - the light tree of the lightcut pipeline, rebuilt every frame
// (renderer/passes/light_tree.c runs the steps in order, a barrier between each):
//   step 0 keys   per leaf slot i < np: (Morton code of the light's centre in the frame's light
//                 box, 10 bits an axis; i) for a light that can contribute, (0xFFFFFFFF, i) for
//                 a slot past the light count or a light that contributes nothing (radius <= 0
//                 or not finite, a position or colour not finite, a colour of 0)
//   step 1 sort   one compare-exchange step (k, j) of a bitonic sort of the keys (unique: the
//                 index breaks ties, so the order does not depend on execution order)
//   step 2 leaves node np + i = the light of sorted key i (or an empty node)
//   step 3 merge  the nodes of one level [k, 2k) from their children 2n, 2n + 1
// Node (4 x vec4, 64 bytes; root 1, leaves np .. 2np - 1, an implicit complete binary tree):
//   [0] xyz min of the light centres, w the largest radius
//   [1] xyz max of the light centres, w the number of lights
//   [2] rgb the sum of the colours (already times intensity), w the largest falloff range (Light.color.w)
//   [3] xyz the colour-luminance-weighted centroid (the node's representative light); a leaf's is
//       its light's centre ([0].xyz), so with PG_SPOT_LIGHTS a leaf keeps its spot record here
//       (lighting.glsl) and the merge reads a leaf child's centre from [0]
// An empty node has min +3e38, max -3e38, radius 0, colour 0: it reaches nothing.
#include "common.glsl"
FRAME_UNIFORMS_BLOCK

layout(local_size_x = 64) in;
layout(set = 1, binding = 0, std430) readonly buffer Lights { Light lights[]; };
layout(set = 1, binding = 1, std430) buffer Tree { vec4 tree[]; };
layout(set = 1, binding = 2, std430) buffer Keys { uvec2 keys[]; };
layout(push_constant) uniform Push { uint step; uint k; uint j; uint np; } pc;

uint spread10(uint v) // 10 bits -> every third bit of 30
{
    v &= 0x3FFu;
    v = (v | (v << 16)) & 0x030000FFu;
    v = (v | (v << 8)) & 0x0300F00Fu;
    v = (v | (v << 4)) & 0x030C30C3u;
    v = (v | (v << 2)) & 0x09249249u;
    return v;
}

bool contributes(Light L)
{
    vec3 p = L.pos_radius.xyz, c = L.color.rgb;
    float r = L.pos_radius.w;
    bool finite = !any(isnan(p)) && !any(isinf(p)) && !any(isnan(c)) && !any(isinf(c)) && !isnan(r) && !isinf(r);
    return finite && r > 0.0 && (c.r > 0.0 || c.g > 0.0 || c.b > 0.0);
}

void write_node(uint n, vec4 a, vec4 b, vec4 c, vec4 d)
{
    tree[4u * n] = a;
    tree[4u * n + 1u] = b;
    tree[4u * n + 2u] = c;
    tree[4u * n + 3u] = d;
}

void main()
{
    uint i = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 64u;
    uint n_lights = frame.counts.x;
    if (pc.step == 0u) {
        if (i >= pc.np) return;
        uint code = 0xFFFFFFFFu;
        if (i < n_lights && contributes(lights[i])) {
            vec3 lo = frame.light_box_min.xyz, hi = frame.light_box_max.xyz;
            vec3 t = clamp((lights[i].pos_radius.xyz - lo) / max(hi - lo, vec3(1e-30)), 0.0, 1.0);
            uvec3 q = uvec3(t * 1023.0 + 0.5);
            code = (spread10(q.x) << 2) | (spread10(q.y) << 1) | spread10(q.z);
        }
        keys[i] = uvec2(code, i);
    } else if (pc.step == 1u) {
        if (i >= pc.np) return;
        uint p = i ^ pc.j;
        if (p <= i) return;
        uvec2 a = keys[i], b = keys[p];
        bool a_greater = a.x > b.x || (a.x == b.x && a.y > b.y);
        bool ascending = (i & pc.k) == 0u;
        if (a_greater == ascending) {
            keys[i] = b;
            keys[p] = a;
        }
    } else if (pc.step == 2u) {
        if (i >= pc.np) return;
        uvec2 key = keys[i];
        if (key.x == 0xFFFFFFFFu) {
            write_node(pc.np + i, vec4(vec3(3e38), 0.0), vec4(vec3(-3e38), 0.0), vec4(0.0), vec4(0.0));
        } else {
            Light L = lights[key.y];
#ifdef PG_SPOT_LIGHTS
            vec4 rep = lights[n_lights + key.y].pos_radius; // a leaf's [3]: its spot record
#else
            vec4 rep = vec4(L.pos_radius.xyz, 0.0);
#endif
            write_node(pc.np + i, L.pos_radius, vec4(L.pos_radius.xyz, 1.0), vec4(L.color.rgb, L.color.w), rep);
        }
    } else {
        if (i >= pc.k) return;
        uint n = pc.k + i, a = 2u * n, b = a + 1u;
        vec4 amin = tree[4u * a], amax = tree[4u * a + 1u], ac = tree[4u * a + 2u], ar = tree[4u * a + 3u];
        vec4 bmin = tree[4u * b], bmax = tree[4u * b + 1u], bc = tree[4u * b + 2u], br = tree[4u * b + 3u];
        if (a >= pc.np) { // leaf children: their centres (their [3] may hold spot records)
            ar.xyz = amin.xyz;
            br.xyz = bmin.xyz;
        }
        float la = pg_luminance(ac.rgb), lb = pg_luminance(bc.rgb);
        vec3 rep = la + lb > 0.0 ? (la * ar.xyz + lb * br.xyz) / (la + lb) : 0.5 * (ar.xyz + br.xyz);
        write_node(n, vec4(min(amin.xyz, bmin.xyz), max(amin.w, bmin.w)), vec4(max(amax.xyz, bmax.xyz), amax.w + bmax.w),
                   vec4(ac.rgb + bc.rgb, max(ac.w, bc.w)), vec4(rep, 0.0));
    }
}
