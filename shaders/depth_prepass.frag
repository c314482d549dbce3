#version 460
// depth_prepass.frag - the fragment stage of the depth pre-pass (passes/depth_prepass.c): no
// colour output, nothing to compute (the pre-pass draws only the opaque draws; the depth comes
// from the rasterizer, biased by the pipeline). The scene-draw inputs are declared so that the
// vertex shader's outputs have a consumer, as in every scene-draw pipeline.
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
#include "surface_inputs.glsl"
#include "surface.glsl"

void main()
{
}
