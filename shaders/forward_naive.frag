#version 460
// forward_naive.frag - the exact reference: every light for every fragment.
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
#include "surface.glsl"
#include "lighting.glsl"
layout(set = 2, binding = 0, std430) readonly buffer Lights { Light lights[]; };
layout(location = 0) in vec3 v_world;
layout(location = 1) in vec3 v_normal;
layout(location = 2) in vec2 v_uv;
layout(location = 3) in vec4 v_tangent;
layout(location = 0) out vec4 out_color;

void main()
{
    Surface s = pg_surface(v_normal, v_uv, v_tangent, gl_FrontFacing);
    vec3 V = normalize(frame.camera_pos.xyz - v_world);
    PgShade acc;
    acc.diffuse = vec3(0.0);
    acc.specular = vec3(0.0);
    uint count = frame.counts.x;
    float min_dist = frame.light_params.w;
    for (uint i = 0u; i < count; i++)
        pg_accumulate_light(lights[i], v_world, s.normal, V, s.shininess, min_dist, acc);
    vec3 c = s.albedo * (acc.diffuse + vec3(PG_AMBIENT)) + s.specular * acc.specular;
    out_color = vec4(pg_hdr_sanitize(c), 1.0);
}
