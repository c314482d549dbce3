#version 460
// gbuffer.frag - writes the G-buffer of one packing variant (one of PG_GBUFFER_FLOAT,
// PG_GBUFFER_OCT16, PG_GBUFFER_PACKED); see renderer/passes/gbuffer.c for the layouts.
// PG_PBR (the pbr light model): the specular channel holds metallic, the shininess channel roughness
// (oct16: unorm16 roughness itself, not /512; packed: unorm16 roughness | unorm16 occlusion in the
// third word), and the occlusion goes in the float position's w (1 + occlusion) or oct16's normal w
// (gbuffer_pack.glsl: an unlit surface's -1 is stored as a value past the range).
// PG_GBUFFER_EMISSIVE: the optional emissive target after the variant's targets (rgba16f/rgba32f,
// scene-linear s.emissive; the pass defines it only when bound and the scene has emissive materials).
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
#include "surface_inputs.glsl"
#include "surface.glsl"
#include "octahedral.glsl"
#include "gbuffer_pack.glsl"
#if defined(PG_GBUFFER_FLOAT)
layout(location = 0) out vec4 g_position; // world position (rgba32f, or rgba16f to show its failure);
                                          // PG_GBUFFER_CAMERA_POSITION: camera-relative, as shaded
                                          // by forward (w = 1; cleared 0 where nothing is drawn)
layout(location = 1) out vec4 g_normal;   // xyz normal, w shininess
layout(location = 2) out vec4 g_albedo;   // rgb albedo, a specular
#elif defined(PG_GBUFFER_OCT16)
layout(location = 0) out vec4 g_normal;   // rgba16 unorm: octahedral normal xy, shininess / 512
layout(location = 1) out vec4 g_albedo;   // rgba8 sRGB: albedo, a specular
#else
layout(location = 0) out uvec4 g_packed;  // oct16 normal | sRGB8 albedo + spec8 | shininess f32 | view depth f32
#endif
#ifdef PG_GBUFFER_EMISSIVE
#if defined(PG_GBUFFER_FLOAT)
layout(location = 3) out vec4 g_emissive;
#elif defined(PG_GBUFFER_OCT16)
layout(location = 2) out vec4 g_emissive;
#else
layout(location = 1) out vec4 g_emissive;
#endif
#endif

void main()
{
    Surface s = pg_surface(pg_surface_input());
#if defined(PG_GBUFFER_FLOAT)
#ifdef PG_GBUFFER_CAMERA_POSITION
    pg_gbuffer_float(s, v_rel, g_position, g_normal, g_albedo); // exactly the position forward.frag shades
#else
    pg_gbuffer_float(s, v_rel + frame.camera_pos.xyz, g_position, g_normal, g_albedo); // world space, as the classic layout
#endif
#elif defined(PG_GBUFFER_OCT16)
#ifdef PG_PBR
    g_normal = vec4(pg_oct_encode(s.normal) * 0.5 + 0.5, clamp(s.shininess, 0.0, 1.0), pg_gb_occlusion_unorm(s.occlusion));
#else
    g_normal = vec4(pg_oct_encode(s.normal) * 0.5 + 0.5, clamp(s.shininess / 512.0, 0.0, 1.0), 0.0);
#endif
    g_albedo = vec4(clamp(s.albedo, 0.0, 1.0), clamp(s.specular, 0.0, 1.0));
#else
    g_packed = pg_gbuffer_packed(s, -PG_REL_TO_VIEW(v_rel).z);
#endif
#ifdef PG_GBUFFER_EMISSIVE
    g_emissive = vec4(s.emissive, 0.0); // as forward adds it (0 without PG_EMISSIVE's factor)
#endif
}
