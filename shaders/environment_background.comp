#version 450
// environment_background.comp - the environment behind the scene: every pixel where nothing was
// drawn (the depth buffer still holds its clear value 1) gets the environment's radiance toward the
// pixel's view ray, x frame.environment.x (intensity) and rotated by frame.environment.y, read from
// the scene's source image at the level whose texels match the pixel's angle (trilinear between
// two levels of its mip chain: full resolution when the view is zoomed in, no aliasing when a pixel
// spans many texels): what a glTF viewer shows behind a model. Covered pixels are left as the
// shading pass wrote them. Perspective: the ray through the pixel's centre; orthographic: the view
// axis (every ray is parallel, so the background is one colour, from level 0).
// renderer/passes/environment_background.c.
#extension GL_GOOGLE_include_directive : require

#include "common.glsl"
FRAME_UNIFORMS_BLOCK
#include "depth_reconstruct.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 1, binding = 0) uniform sampler2D g_depth;
layout(set = 1, binding = 1, std430) readonly buffer EnvSource { vec4 env_src[]; }; // the scene's levels
layout(set = 1, binding = 2, PG_HDR_FORMAT) uniform image2D hdr;
layout(push_constant) uniform Push { uint width, height, levels; } pc; // the source's level 0 and count

#define PG_ENV_FETCH(i) env_src[i]
#include "environment.glsl"

// The world-space direction (camera-relative axes) of the view ray through pixel position uv.
vec3 pg_background_dir(vec2 uv)
{
    vec3 v = PG_ORTHO ? vec3(0.0, 0.0, -1.0) : pg_view_pos_from_view_depth(uv, 1.0, frame.proj);
    return normalize(PG_VIEW_TO_REL(v));
}

void main()
{
    ivec2 size = imageSize(hdr);
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= size.x || px.y >= size.y) return;
    if (texelFetch(g_depth, px, 0).r < 1.0) return; // a surface: the shading pass's colour stays
    vec2 s = vec2(size);
    vec3 d = pg_background_dir((vec2(px) + 0.5) / s);
    // the pixel's angle: to the rays through the next pixel across and down; level 0's texel spans
    // 2 pi / width radians (at the equator)
    float ang = max(length(pg_background_dir((vec2(px) + vec2(1.5, 0.5)) / s) - d),
                    length(pg_background_dir((vec2(px) + vec2(0.5, 1.5)) / s) - d));
    float lod = log2(max(ang * float(pc.width) / (2.0 * PG_ENV_PI), 1.0));
    vec3 c = frame.environment.x * pg_env_src_lod(pg_env_unrotate(d, frame.environment.y), lod, pc.width,
                                                  pc.height, pc.levels);
    imageStore(hdr, px, vec4(pg_hdr_sanitize(c), 1.0));
}
