#version 460
// visibility_resolve.comp - the visibility_resolve pass (renderer/passes/visibility_resolve.c): rebuilds
// each pixel's surface from its triangle id (visibility_surface.glsl), evaluates the material
// (surface.glsl) and writes the packed G-buffer that deferred_lighting reads with packing
// "packed" (gbuffer_layout.h: oct16 normal | sRGB8 albedo + spec8 | shininess f32 | view depth
// f32), as gbuffer.frag writes it; PG_RESOLVE_FLOAT: the float G-buffer instead (camera-relative
// position, normal, albedo: rgba32f each, as gbuffer.frag with position_space "camera", which
// reference_lighting.comp reads); PG_RESOLVE_EMISSIVE: also the emissive target (rgba16f, rgba32f
// with PG_RESOLVE_FLOAT). Pixels where nothing was drawn get zeros (w 0 in the float position).
// Set 1: binding 0 the id image, then the targets (1 packed, or 3 float), the emissive target
// (PG_RESOLVE_EMISSIVE), then the vertex streams; set 2: the scene's materials and textures.
#extension GL_EXT_nonuniform_qualifier : require
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
#include "depth_reconstruct.glsl"
#include "octahedral.glsl"
#include "gbuffer_pack.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 1, binding = 0) uniform usampler2D g_vis;
#ifdef PG_RESOLVE_FLOAT
layout(set = 1, binding = 1, rgba32f) uniform writeonly image2D g_position;
layout(set = 1, binding = 2, rgba32f) uniform writeonly image2D g_normal;
layout(set = 1, binding = 3, rgba32f) uniform writeonly image2D g_albedo;
#define PG_RESOLVE_TARGETS 3
#define PG_RESOLVE_EMISSIVE_FORMAT rgba32f
#define g_target g_position
#else
layout(set = 1, binding = 1, rgba32ui) uniform writeonly uimage2D g_packed;
#define PG_RESOLVE_TARGETS 1
#define PG_RESOLVE_EMISSIVE_FORMAT rgba16f
#define g_target g_packed
#endif
#ifdef PG_RESOLVE_EMISSIVE
layout(set = 1, binding = PG_RESOLVE_TARGETS + 1, PG_RESOLVE_EMISSIVE_FORMAT) uniform writeonly image2D g_emissive;
#define PG_VIS_BINDING (PG_RESOLVE_TARGETS + 2)
#else
#define PG_VIS_BINDING (PG_RESOLVE_TARGETS + 1)
#endif
#define PG_VIS_SET 1
#include "surface.glsl"
#include "visibility_surface.glsl"

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(g_target);
    if (px.x >= size.x || px.y >= size.y) return;
    uint vis = texelFetch(g_vis, px, 0).r;
#ifdef PG_RESOLVE_FLOAT
    vec4 gp = vec4(0.0), gn = vec4(0.0), ga = vec4(0.0);
#else
    uvec4 g = uvec4(0u);
#endif
    vec3 emissive = vec3(0.0);
    if (vis != PG_VIS_NONE) {
        SurfaceInput si;
        uint material;
        vec3 P;
        pg_vis_fetch(vis, vec2(px) + 0.5, vec2(size), si, material, P);
        Surface s = pg_surface_material(si, material);
#ifdef PG_RESOLVE_FLOAT
        pg_gbuffer_float(s, P, gp, gn, ga); // camera-relative, as gbuffer.frag's position_space "camera"
#else
        g = pg_gbuffer_packed(s, -PG_REL_TO_VIEW(P).z); // as gbuffer.frag writes it
#endif
        emissive = s.emissive;
    }
#ifdef PG_RESOLVE_FLOAT
    imageStore(g_position, px, gp);
    imageStore(g_normal, px, gn);
    imageStore(g_albedo, px, ga);
#else
    imageStore(g_packed, px, g);
#endif
#ifdef PG_RESOLVE_EMISSIVE
    imageStore(g_emissive, px, vec4(emissive, 0.0));
#endif
}
