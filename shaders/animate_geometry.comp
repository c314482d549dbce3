#version 460
// animate_geometry.comp - the scene's vertices at the frame's pose, one thread a vertex: morph
// targets added in mesh space, then the blended joint matrices (a skinned vertex) or its node's
// world matrix (a rigid one); normals by the cofactor matrix, tangents by the upper 3x3, both
// renormalised; a mirroring matrix flips the tangent's handedness. A static vertex is copied.
// The CPU twin is scene/animation.c pg_anim_deform (same order of operations, same rules).
// Layouts: renderer/scene_gpu_anim.h.
layout(local_size_x = 64) in;

// 12 floats a vertex: position xyz, normal xyz, uv, tangent xyzw (scene.h pg_vertex)
layout(set = 0, binding = 0, std430) writeonly buffer Out { float outv[]; };
layout(set = 0, binding = 1, std430) readonly buffer Local { float localv[]; };
// per vertex: prim (0xFFFFFFFF: static), joints 0|1 << 16, joints 2|3 << 16, 0; weights; with
// PG_ANIM_INFLUENCES8 (a skin with JOINTS_1) also joints 4|5 << 16, joints 6|7 << 16, 0, 0; weights 4-7
struct VertexInfo {
    uvec4 info;
    vec4 weights;
#ifdef PG_ANIM_INFLUENCES8
    uvec4 info2;
    vec4 weights2;
#endif
};
layout(set = 0, binding = 2, std430) readonly buffer Info { VertexInfo vinfo[]; };
// per moving primitive: (node, skinned, targets, target base), (first vertex, vertices, weight base, 0)
struct Prim {
    uvec4 a;
    uvec4 b;
};
layout(set = 0, binding = 3, std430) readonly buffer Prims { Prim prims[]; };
struct Delta {
    vec4 position, normal, tangent;
};
layout(set = 0, binding = 4, std430) readonly buffer Deltas { Delta deltas[]; };
// the pose: node world matrices, then joint matrices, then morph weights (as floats)
layout(set = 0, binding = 5, std430) readonly buffer Pose { float pose[]; };

layout(push_constant) uniform Push {
    uint n_vertices;
    uint joint_base;  // first float of the joint matrices
    uint weight_base; // first float of the weights
} pc;

mat4 pose_matrix(uint first)
{
    return mat4(pose[first + 0], pose[first + 1], pose[first + 2], pose[first + 3], pose[first + 4], pose[first + 5],
                pose[first + 6], pose[first + 7], pose[first + 8], pose[first + 9], pose[first + 10],
                pose[first + 11], pose[first + 12], pose[first + 13], pose[first + 14], pose[first + 15]);
}

void main()
{
    uint v = gl_GlobalInvocationID.x;
    if (v >= pc.n_vertices) return;
    uint o = v * 12u;
    VertexInfo vi = vinfo[v];
    if (vi.info.x == 0xFFFFFFFFu) {
        for (uint k = 0u; k < 12u; k++) outv[o + k] = localv[o + k];
        return;
    }
    Prim pr = prims[vi.info.x];
    vec3 p = vec3(localv[o], localv[o + 1u], localv[o + 2u]);
    vec3 n = vec3(localv[o + 3u], localv[o + 4u], localv[o + 5u]);
    vec4 t = vec4(localv[o + 8u], localv[o + 9u], localv[o + 10u], localv[o + 11u]);
    uint i = v - pr.b.x;
    for (uint k = 0u; k < pr.a.z; k++) {
        float w = pose[pc.weight_base + pr.b.z + k];
        if (w == 0.0) continue;
        Delta d = deltas[pr.a.w + k * pr.b.y + i];
        p += w * d.position.xyz;
        n += w * d.normal.xyz;
        t.xyz += w * d.tangent.xyz;
    }
    mat4 m;
    if (pr.a.y != 0u) {
        uint j[4] = uint[4](vi.info.y & 0xFFFFu, vi.info.y >> 16, vi.info.z & 0xFFFFu, vi.info.z >> 16);
        m = mat4(0.0);
        for (int k = 0; k < 4; k++) {
            float w = vi.weights[k];
            if (w == 0.0) continue;
            m += w * pose_matrix(pc.joint_base + j[k] * 16u);
        }
#ifdef PG_ANIM_INFLUENCES8
        uint j2[4] = uint[4](vi.info2.x & 0xFFFFu, vi.info2.x >> 16, vi.info2.y & 0xFFFFu, vi.info2.y >> 16);
        for (int k = 0; k < 4; k++) {
            float w = vi.weights2[k];
            if (w == 0.0) continue;
            m += w * pose_matrix(pc.joint_base + j2[k] * 16u);
        }
#endif
    } else {
        m = pose_matrix(pr.a.x * 16u);
    }
    vec3 wp = (m * vec4(p, 1.0)).xyz;
    mat3 a = mat3(m);
    // cofactor matrix: columns are cross products of the other two columns
    mat3 cof = mat3(cross(a[1], a[2]), cross(a[2], a[0]), cross(a[0], a[1]));
    float det = dot(a[0], cof[0]);
    float sg = det < 0.0 ? -1.0 : 1.0;
    vec3 wn = sg * (cof * n);
    vec3 wt = a * t.xyz;
    float nl = length(wn), tl = length(wt);
    wn = nl > 1e-30 ? wn / nl : vec3(0.0, 1.0, 0.0);
    wt = tl > 1e-30 ? wt / tl : vec3(0.0);
    outv[o] = wp.x;
    outv[o + 1u] = wp.y;
    outv[o + 2u] = wp.z;
    outv[o + 3u] = wn.x;
    outv[o + 4u] = wn.y;
    outv[o + 5u] = wn.z;
    outv[o + 6u] = localv[o + 6u];
    outv[o + 7u] = localv[o + 7u];
    outv[o + 8u] = wt.x;
    outv[o + 9u] = wt.y;
    outv[o + 10u] = wt.z;
    outv[o + 11u] = t.w * sg;
}
