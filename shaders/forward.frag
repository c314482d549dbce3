#version 460
// forward.frag - forward shading: naive (every light) or, with PG_CLUSTERED, only the lights of
// the fragment's cluster. Same surface and light model as the deferred path. PG_TRANSPARENT
// (forward_transparent, BLEND draws): alpha = the surface's alpha, blended "over" by the pipeline.
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
#include "surface_inputs.glsl"
#include "surface.glsl"
#include "lighting.glsl"
#ifdef PG_CLUSTERED
#include "cluster.glsl"
#endif
#define PG_AMBIENT draw.ambient // the pass option, a push constant (surface.glsl)
#include "shading.glsl"
layout(location = 0) out vec4 out_color;

void main()
{
    Surface s = pg_surface(pg_surface_input());
    float view_depth = -PG_REL_TO_VIEW(v_rel).z;
#ifdef PG_TRANSPARENT
    float alpha = s.alpha >= 0.0 ? min(s.alpha, 1.0) : 0.0; // NaN or negative alpha adds nothing
#else
    float alpha = 1.0;
#endif
    out_color = vec4(pg_hdr_sanitize(pg_shade_point(s, v_rel, view_depth, gl_FragCoord.xy)), alpha);
}
