#version 460
// deferred_lighting.comp - one thread per pixel: rebuild the surface from the G-buffer of one
// packing variant, then shade with the lights of its cluster (shading.glsl, same model and same
// summation order as forward). Background pixels (cleared depth) are black, as in forward.
// PG_TILE_LIGHTS (option tile_lights, default on): the PG_TILE x PG_TILE workgroup first culls each cluster's
// list against the bounding box of its pixels and shares the kept lights through shared memory
// (pg_shade_tile in shading.glsl): the same sum, far fewer light evaluations.
// PG_DEFERRED_EMISSIVE: the G-buffer's emissive target (binding HDR_BINDING + 1) is the surface's
// s.emissive, added once by pg_shade_combine as in forward.
// PG_GBUFFER_VISIBILITY (packing "visibility"): no G-buffer; the pixel's triangle id (binding 1)
// names the triangle, and the surface is rebuilt from it and the material evaluated here
// (visibility_surface.glsl, surface.glsl: the scene's materials and textures in set 3, its
// vertex streams in set 1 after hdr).
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#ifdef PG_GBUFFER_VISIBILITY
#extension GL_EXT_nonuniform_qualifier : require
#endif
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
#include "lighting.glsl"
#include "cluster.glsl"
#include "octahedral.glsl"
#include "gbuffer_pack.glsl"
#include "depth_reconstruct.glsl"
#include "gbuffer_read.glsl"

#ifndef PG_TILE
#define PG_TILE 8
#endif
// One-dimensional workgroup of PG_TILE x PG_TILE invocations (invocation i is pixel (i % PG_TILE,
// i / PG_TILE) of the tile, the same numbering as a PG_TILE x PG_TILE workgroup's
// gl_LocalInvocationIndex): with full subgroups required (PG_TILE_SUBGROUPS), Vulkan asks the
// workgroup's X size to be a multiple of the subgroup size (VUID-...-pNext-02757: 8 is not, on a
// GPU with 32-wide subgroups; 64 and 256 are).
layout(local_size_x = PG_TILE * PG_TILE) in;
layout(set = 1, binding = 0) uniform sampler2D g_depth;
#if defined(PG_GBUFFER_FLOAT)
layout(set = 1, binding = 1) uniform sampler2D g_position;
layout(set = 1, binding = 2) uniform sampler2D g_normal;
layout(set = 1, binding = 3) uniform sampler2D g_albedo;
#define HDR_BINDING 4
#elif defined(PG_GBUFFER_OCT16)
layout(set = 1, binding = 1) uniform sampler2D g_normal;
layout(set = 1, binding = 2) uniform sampler2D g_albedo;
#define HDR_BINDING 3
#elif defined(PG_GBUFFER_VISIBILITY)
layout(set = 1, binding = 1) uniform usampler2D g_vis;
#define HDR_BINDING 2
#define PG_VIS_SET 1
#define PG_VIS_BINDING 3
#else
layout(set = 1, binding = 1) uniform usampler2D g_packed;
#define HDR_BINDING 2
#endif
layout(set = 1, binding = HDR_BINDING, PG_HDR_FORMAT) uniform writeonly image2D hdr_out;
#ifdef PG_DEFERRED_EMISSIVE
layout(set = 1, binding = HDR_BINDING + 1) uniform sampler2D g_emissive;
#endif

layout(push_constant) uniform Push { float ambient; } pc; // the pass option "ambient"
#define PG_AMBIENT pc.ambient
#include "shading.glsl"
#ifdef PG_GBUFFER_VISIBILITY
#include "surface.glsl"
#include "visibility_surface.glsl"
#endif

#if defined(PG_TILE_LIGHTS) && defined(PG_CLUSTERED) && defined(PG_HAS_LIGHTS) && PG_DEBUG_VIEW == 0
#define PG_TILED 1   // the workgroup shades together (pg_shade_tile): no early return before it
#endif

// the invocation's light evaluations into the frame's 64-bit count: one atomic per subgroup
void pg_count_flush()
{
#if defined(PG_COUNT_EVALS) && defined(PG_HAS_LIGHTS)
    uint s = subgroupAdd(pg_evals);
    if (subgroupElect() && s != 0u) {
        uint old = atomicAdd(evals_lo, s);
        if (old > 0xFFFFFFFFu - s) atomicAdd(evals_hi, 1u);
    }
#endif
}

void main()
{
    ivec2 size = imageSize(hdr_out);
    uint lin = gl_LocalInvocationIndex;
    ivec2 px = ivec2(gl_WorkGroupID.xy) * PG_TILE + ivec2(int(lin % uint(PG_TILE)), int(lin / uint(PG_TILE)));
    bool inside = px.x < size.x && px.y < size.y;
#ifdef PG_GBUFFER_VISIBILITY
    uint vis = inside ? texelFetch(g_vis, px, 0).r : PG_VIS_NONE;
    bool lit = vis != PG_VIS_NONE;
#else
    float depth = inside ? texelFetch(g_depth, px, 0).r : 1.0;
    bool lit = depth < 1.0;
#endif
#ifndef PG_TILED
    if (!inside) return;
    if (!lit) {
        imageStore(hdr_out, px, vec4(0.0, 0.0, 0.0, 1.0));
        return;
    }
#endif
    vec2 frag = vec2(px) + 0.5;
    vec2 uv = frag / vec2(size);
    Surface s = pg_surface_default();
    vec3 P = vec3(0.0); // camera-relative
    float view_depth = 0.0;
    if (lit) {
#if defined(PG_GBUFFER_FLOAT)
    pg_gbuffer_read_float(texelFetch(g_position, px, 0), texelFetch(g_normal, px, 0), texelFetch(g_albedo, px, 0), s, P,
                          view_depth);
#elif defined(PG_GBUFFER_VISIBILITY)
    SurfaceInput si;
    uint material;
    pg_vis_fetch(vis, frag, vec2(size), si, material, P);
    s = pg_surface_material(si, material);
    view_depth = -PG_REL_TO_VIEW(P).z;
#elif defined(PG_GBUFFER_OCT16)
    pg_gbuffer_read_oct16(depth, uv, texelFetch(g_normal, px, 0), texelFetch(g_albedo, px, 0), s, P, view_depth);
#else
    pg_gbuffer_read_packed(texelFetch(g_packed, px, 0), uv, s, P, view_depth);
#endif
#ifdef PG_DEFERRED_EMISSIVE
    s.emissive = texelFetch(g_emissive, px, 0).rgb;
#endif
    }
#ifdef PG_TILED
    vec3 c = pg_shade_tile(lit, s, P, view_depth, frag);
    if (inside) imageStore(hdr_out, px, vec4(lit ? pg_hdr_sanitize(c) : vec3(0.0), 1.0));
#else
    vec3 c = pg_shade_point(s, P, view_depth, frag);
    imageStore(hdr_out, px, vec4(pg_hdr_sanitize(c), 1.0));
#endif
    pg_count_flush();
}
