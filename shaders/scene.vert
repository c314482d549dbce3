#version 460
// scene.vert - transforms scene vertices (already in world space) for forward and G-buffer
// passes, camera-relative (see common.glsl). Streams: binding 0 pg_vertex (locations 0-3);
// PG_VERTEX_COLORS: binding 1 COLOR_0 (location 4, vec4); PG_UV1: binding 2 TEXCOORD_1
// (location 5, vec2). The outputs match surface_inputs.glsl.
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
layout(location = 0) in vec3 in_position;
#ifdef PG_POSITION_ONLY
// The visibility pass's opaque pipeline (scene_draw.c position_only_opaque): its fragment shader
// reads no input, so only the position is fetched and only gl_Position is written.
precise gl_Position;

void main()
{
    gl_Position = frame.proj * vec4(PG_REL_TO_VIEW(in_position - frame.camera_pos.xyz), 1.0);
}
#else
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_tangent;
#ifdef PG_VERTEX_COLORS
layout(location = 4) in vec4 in_color;
layout(location = 4) out vec4 v_color;
#endif
#ifdef PG_UV1
layout(location = 5) in vec2 in_uv1;
layout(location = 5) out vec2 v_uv1;
#endif
layout(location = 0) out vec3 v_rel; // camera-relative position (world - camera)
layout(location = 1) out vec3 v_normal;
layout(location = 2) out vec2 v_uv;
layout(location = 3) out vec4 v_tangent;
// The depth pre-pass (depth_prepass.c) and the shading pass that tests its depth EQUAL run this
// shader in two pipelines: the position must come out bit-identical in both. `precise` forbids
// contracting its arithmetic (FMA fusion that could differ between the two compiled pipelines);
// `invariant gl_Position` would say the same but glslang puts it on a gl_PerVertex member, which
// the validation layer's SPIR-V check reports.
precise gl_Position;

void main()
{
    v_rel = in_position - frame.camera_pos.xyz;
    v_normal = in_normal;
    v_uv = in_uv;
    v_tangent = in_tangent;
#ifdef PG_VERTEX_COLORS
    v_color = in_color;
#endif
#ifdef PG_UV1
    v_uv1 = in_uv1;
#endif
    gl_Position = frame.proj * vec4(PG_REL_TO_VIEW(v_rel), 1.0);
}
#endif
