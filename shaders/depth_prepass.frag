#version 460
// depth_prepass.frag - the fragment stage of the depth pre-pass (renderer/passes/depth_prepass.c): no
// colour output. Opaque draws: empty (the depth comes from the rasterizer). PG_ALPHA_MASK (the
// masked pipeline, made only with the pass's test "equal" and only when the scene has alpha-mask
// draws): the same material evaluation as the shading passes (surface.glsl), whose discard is the
// only effect kept, so the pre-pass depth holds the fragments the shading pass would keep; the
// shading pass then tests EQUAL and draws those draws without discard. The opaque pipeline reads
// no input (with test "less" its vertex shader writes the position alone: PG_POSITION_ONLY).
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
#ifdef PG_ALPHA_MASK
#include "surface_inputs.glsl"
#include "surface.glsl"
#endif

void main()
{
#ifdef PG_ALPHA_MASK
    Surface s = pg_surface(pg_surface_input());
#endif
}
