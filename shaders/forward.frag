#version 460
// forward.frag - forward shading: naive (every light) or, with PG_CLUSTERED, only the lights of
// the fragment's cluster. Same surface and light model as the deferred path.
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
#include "surface.glsl"
#include "lighting.glsl"
#ifdef PG_CLUSTERED
#include "cluster.glsl"
#endif
#include "shading.glsl"
layout(location = 0) in vec3 v_rel;
layout(location = 1) in vec3 v_normal;
layout(location = 2) in vec2 v_uv;
layout(location = 3) in vec4 v_tangent;
layout(location = 0) out vec4 out_color;

void main()
{
    Surface s = pg_surface(v_normal, v_uv, v_tangent, gl_FrontFacing);
    float view_depth = -PG_REL_TO_VIEW(v_rel).z;
    out_color = vec4(pg_hdr_sanitize(pg_shade_point(s, v_rel, view_depth, gl_FragCoord.xy)), 1.0);
}
