#version 460
// visibility_raster_resolve.comp - the compute rasterizer's last step (visibility_raster.glsl): each
// pixel's kept key becomes its id (0xFFFFFFFF where nothing was drawn) and its depth (1, the depth
// buffer's clear value, there), which the pass then copies into the depth image.
#include "visibility_raster.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 1, binding = 4, r32ui) uniform writeonly uimage2D raster_vis_id;
layout(set = 1, binding = 5, std430) writeonly buffer RasterDepth { float raster_depth[]; };

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = pg_raster_size();
    if (px.x >= size.x || px.y >= size.y) return;
    uint i = uint(px.y) * uint(size.x) + uint(px.x);
    uint64_t k = raster_keys[i];
    uint id = uint(k & 0xffffffffUL);
    imageStore(raster_vis_id, px, uvec4(id));
    raster_depth[i] = id == PG_VIS_NONE ? 1.0 : uintBitsToFloat(uint(k >> 32));
}
