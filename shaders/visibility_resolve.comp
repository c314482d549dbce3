#version 460
// visibility_resolve.comp - the visibility_resolve pass (renderer/passes/visibility_resolve.c): rebuilds
// each pixel's surface from its triangle id (visibility_surface.glsl), evaluates the material
// (surface.glsl) and writes the packed G-buffer that deferred_lighting reads with packing
// "packed" (gbuffer_layout.h: oct16 normal | sRGB8 albedo + spec8 | shininess f32 | view depth
// f32), as gbuffer.frag writes it; PG_RESOLVE_EMISSIVE: also the emissive target (rgba16f).
// Pixels where nothing was drawn get zeros (the lighting pass tests the depth buffer).
// Set 1: binding 0 the id image, 1 the packed target, 2 emissive (PG_RESOLVE_EMISSIVE), then the
// vertex streams; set 2: the scene's materials and textures.
#extension GL_EXT_nonuniform_qualifier : require
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
#include "depth_reconstruct.glsl"
#include "octahedral.glsl"
#include "gbuffer_pack.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 1, binding = 0) uniform usampler2D g_vis;
layout(set = 1, binding = 1, rgba32ui) uniform writeonly uimage2D g_packed;
#ifdef PG_RESOLVE_EMISSIVE
layout(set = 1, binding = 2, rgba16f) uniform writeonly image2D g_emissive;
#define PG_VIS_BINDING 3
#else
#define PG_VIS_BINDING 2
#endif
#define PG_VIS_SET 1
#include "surface.glsl"
#include "visibility_surface.glsl"

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(g_packed);
    if (px.x >= size.x || px.y >= size.y) return;
    uint vis = texelFetch(g_vis, px, 0).r;
    uvec4 g = uvec4(0u);
    vec3 emissive = vec3(0.0);
    if (vis != PG_VIS_NONE) {
        SurfaceInput si;
        uint material;
        vec3 P;
        pg_vis_fetch(vis, vec2(px) + 0.5, vec2(size), si, material, P);
        Surface s = pg_surface_material(si, material);
        g = pg_gbuffer_packed(s, -PG_REL_TO_VIEW(P).z); // as gbuffer.frag writes it
        emissive = s.emissive;
    }
    imageStore(g_packed, px, g);
#ifdef PG_RESOLVE_EMISSIVE
    imageStore(g_emissive, px, vec4(emissive, 0.0));
#endif
}
