// visibility_streams.glsl - the scene's vertex streams as the visibility-buffer compute passes read
// them (visibility_surface.glsl, the compute rasterizer's visibility_raster.glsl).
// renderer/common/visibility_common.h binds, in set PG_VIS_SET from binding PG_VIS_BINDING on:
//   +0 the scene's vertices (pg_vertex: 12 floats), +1 its indices, +2 the draw table (uvec4 per
//   draw: first index, vertex offset, material, flags with bit 0 double-sided and bit 1 alpha mask),
//   then COLOR_0 (vec4 per vertex, only with PG_VERTEX_COLORS) and TEXCOORD_1 (vec2 per vertex, only
//   with PG_UV1).
#ifndef PG_VISIBILITY_STREAMS_GLSL
#define PG_VISIBILITY_STREAMS_GLSL
layout(set = PG_VIS_SET, binding = PG_VIS_BINDING + 0, std430) readonly buffer VisVertices { float vis_vertices[]; };
layout(set = PG_VIS_SET, binding = PG_VIS_BINDING + 1, std430) readonly buffer VisIndices { uint vis_indices[]; };
layout(set = PG_VIS_SET, binding = PG_VIS_BINDING + 2, std430) readonly buffer VisDraws { uvec4 vis_draws[]; };
#ifdef PG_VERTEX_COLORS
layout(set = PG_VIS_SET, binding = PG_VIS_BINDING + 3, std430) readonly buffer VisColors { vec4 vis_colors[]; };
#define PG_VIS_UV1_BINDING (PG_VIS_BINDING + 4)
#else
#define PG_VIS_UV1_BINDING (PG_VIS_BINDING + 3)
#endif
#ifdef PG_UV1
layout(set = PG_VIS_SET, binding = PG_VIS_UV1_BINDING, std430) readonly buffer VisUv1 { vec2 vis_uv1[]; };
#endif

const uint PG_VIS_NONE = 0xffffffffu; // cleared id: nothing drawn

vec3 pg_vis_vec3(uint v, uint o) { return vec3(vis_vertices[12u * v + o], vis_vertices[12u * v + o + 1u], vis_vertices[12u * v + o + 2u]); }
vec2 pg_vis_vec2(uint v, uint o) { return vec2(vis_vertices[12u * v + o], vis_vertices[12u * v + o + 1u]); }
vec4 pg_vis_vec4(uint v, uint o)
{
    return vec4(vis_vertices[12u * v + o], vis_vertices[12u * v + o + 1u], vis_vertices[12u * v + o + 2u],
                vis_vertices[12u * v + o + 3u]);
}
#endif
