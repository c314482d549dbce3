#version 460
// scene.vert - transforms scene vertices (already in world space) for forward and G-buffer
// passes, camera-relative (see common.glsl).
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_tangent;
layout(location = 0) out vec3 v_rel; // camera-relative position (world - camera)
layout(location = 1) out vec3 v_normal;
layout(location = 2) out vec2 v_uv;
layout(location = 3) out vec4 v_tangent;

void main()
{
    v_rel = in_position - frame.camera_pos.xyz;
    v_normal = in_normal;
    v_uv = in_uv;
    v_tangent = in_tangent;
    gl_Position = frame.proj * vec4(PG_REL_TO_VIEW(v_rel), 1.0);
}
