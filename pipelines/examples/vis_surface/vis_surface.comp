#version 460
// vis_surface.comp - pipelines/examples/vis_surface/vis_surface.json: a user compute pass that
// rebuilds the surface of each pixel from the visibility buffer with passgraph's shader library
// ("surface": "visibility" binds the scene's vertex streams in set 1 and its materials in set 3, and
// compiles the shader with the scene's material defines), then writes the surface's normal
// (n x 0.5 + 0.5) or, with SHOW_ALBEDO, its albedo: what the built-in visibility pipeline's debug
// views "normal" and "albedo" show. Pixels with nothing drawn are black.
#extension GL_EXT_nonuniform_qualifier : require
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
#include "depth_reconstruct.glsl"
#include "surface.glsl"
#include "visibility_surface.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 2, binding = 0) uniform usampler2D vis_ids;
layout(set = 2, binding = 1, rgba16f) uniform writeonly image2D hdr_out;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(hdr_out);
    if (any(greaterThanEqual(p, size))) return;
    uint id = texelFetch(vis_ids, p, 0).r;
    vec3 c = vec3(0.0);
    if (id != PG_VIS_NONE) {
        SurfaceInput si;
        uint material;
        vec3 P;
        pg_vis_fetch(id, vec2(p) + 0.5, vec2(size), si, material, P);
        Surface s = pg_surface_material(si, material);
#ifdef SHOW_ALBEDO
        c = s.albedo;
#else
        c = s.normal * 0.5 + 0.5;
#endif
    }
    imageStore(hdr_out, p, vec4(c, 1.0));
}
