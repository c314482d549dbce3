#version 460
// depth_prepass.frag - the fragment stage of the depth pre-pass (passes/depth_prepass.c): no
// colour output. Opaque draws: empty (depth only). PG_ALPHA_MASK (the masked pipeline, made only
// when the scene has alpha-mask draws): the same material evaluation as forward/G-buffer
// (surface.glsl), whose discard is the only effect kept, so the pre-pass depth holds exactly the
// fragments the shading pass keeps; the shading pass then tests EQUAL and needs no discard.
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
#include "surface_inputs.glsl"
#include "surface.glsl"

void main()
{
#ifdef PG_ALPHA_MASK
    Surface s = pg_surface(pg_surface_input());
#endif
}
