#version 460
// normals.frag - the draw form's example (pipelines/examples/normals/normals.json): the surface
// passgraph's material code builds (normal maps, double-sided faces, alpha-mask discard) shown as
// a colour, n x 0.5 + 0.5, as the built-in passes' debug view "normal" shows it.
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
#include "surface_inputs.glsl"
#include "surface.glsl"
layout(location = 0) out vec4 out_color;

void main()
{
    Surface s = pg_surface(pg_surface_input());
    out_color = vec4(s.normal * 0.5 + 0.5, 1.0);
}
