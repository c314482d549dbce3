#version 460
// lighting.comp - a user lighting pass over the cluster lists (pipelines/examples/lighting/
// lighting.json). Per pixel of the float G-buffer: find the pixel's cluster as the built-in passes
// do (cluster.glsl), then sum its lights with this example's own model,
//   c = albedo x (sum over the list of colour x max(N.L, 0) x f(d) + ambient + frame ambient),
//   f(d) = max(1 - (d/R)^2, 0)^2 / (1 + d^2),   R = the light's range (pos_radius.w),
// a softened inverse square that reaches 0 at the range (light_model.glsl, shared with
// lighting_tiled.comp). tests/gpu/test_gpu_user_passes.c evaluates it on the CPU.
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
#include "cluster.glsl"
#include "octahedral.glsl"
#include "gbuffer_pack.glsl"
#include "depth_reconstruct.glsl"
#include "gbuffer_read.glsl"
#include "light_model.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 2, binding = 0, std430) readonly buffer Lights { Light lights[]; };
layout(set = 2, binding = 1, std430) readonly buffer ClusterRecords { uvec4 cluster_records[]; };
layout(set = 2, binding = 2, std430) readonly buffer ClusterLights { uint cluster_lights[]; };
layout(set = 2, binding = 3) uniform sampler2D positions; // world position, w = 0 where no surface
layout(set = 2, binding = 4) uniform sampler2D normals;
layout(set = 2, binding = 5) uniform sampler2D albedo;
layout(set = 2, binding = 6, rgba16f) uniform writeonly image2D hdr_out;
layout(push_constant) uniform Params {
    float ambient;
} params;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(hdr_out)))) return;
    vec4 position = texelFetch(positions, p, 0);
    if (position.w == 0.0) {
        imageStore(hdr_out, p, vec4(0.0, 0.0, 0.0, 1.0));
        return;
    }
    // the surface as the built-in deferred pass rebuilds it (gbuffer_read.glsl; packing "float")
    Surface s;
    vec3 rel; // camera-relative position
    float view_depth;
    pg_gbuffer_read_float(position, texelFetch(normals, p, 0), texelFetch(albedo, p, 0), s, rel, view_depth);
    vec3 N = normalize(s.normal);
    vec3 P = position.xyz;
    uvec3 grid = uvec3(GRID_X, GRID_Y, GRID_Z);
    uvec3 cc = pg_cluster_coord(vec2(p) + 0.5, vec2(frame.counts.zw), view_depth, frame.clip.x, frame.clip.y, grid);
    uvec4 rec = cluster_records[pg_cluster_index(cc, grid)];
    vec3 sum = vec3(0.0);
    for (uint k = 0u; k < rec.y; k++) {
        Light L = lights[cluster_lights[rec.x + k]];
        vec3 d = L.pos_radius.xyz - P;
        float R2 = L.pos_radius.w * L.pos_radius.w;
        if (!(dot(d, d) < R2)) continue; // most lights of a list miss the pixel: the test first, 1/R^2 after
        sum += example_light(d, R2, 1.0 / R2, L.color.rgb, N);
    }
    vec3 c = s.albedo * (sum + params.ambient + frame.clip.z);
    imageStore(hdr_out, p, vec4(pg_hdr_sanitize(c), 1.0));
}
