#version 460
// visibility.frag - the visibility pass (renderer/passes/visibility.c): writes the 32-bit id of the
// triangle seen at each pixel, (draw << tri_bits) | gl_PrimitiveID, and nothing else (depth comes
// from the depth test). The push constant's second word holds draw << tri_bits.
// PG_ALPHA_MASK (the second pipeline, compiled only when the scene has alpha-mask materials): the
// material's alpha test discards first, exactly as the other scene-drawing passes do.
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
layout(push_constant) uniform DrawPush { uint material; uint key; } draw;
#ifdef PG_ALPHA_MASK
#define PG_SURFACE_NO_PUSH
#include "surface_inputs.glsl"
#include "surface.glsl"
#endif
layout(location = 0) out uint vis_id;

void main()
{
#ifdef PG_ALPHA_MASK
    pg_surface_material(pg_surface_input(), draw.material); // discards below the cutoff
#endif
    vis_id = draw.key | uint(gl_PrimitiveID);
}
