#version 460
// ssao.comp - screen-space ambient occlusion (pipelines/examples/ssao/ssao.json). For each pixel
// with a surface, SAMPLES points are spread over the hemisphere of radius `radius` around its
// normal (a cosine-weighted pattern, turned by a per-pixel hash so neighbouring pixels see other
// directions). Each point is projected to the screen; it is occluded when the G-buffer surface
// there is nearer the camera than the point (by more than a small bias) and within the radius of
// the pixel's surface. ao = 1 - occluded / SAMPLES (1 = open).
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 2, binding = 0) uniform sampler2D positions; // world position, w = 0 where no surface
layout(set = 2, binding = 1) uniform sampler2D normals;
layout(set = 2, binding = 2, r32f) uniform writeonly image2D ao_out;
layout(push_constant) uniform Params {
    float radius;
} params;

#ifndef SAMPLES
#define SAMPLES 16
#endif

float view_depth_of(vec3 world)
{
    return -PG_REL_TO_VIEW(world - frame.camera_pos.xyz).z;
}

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(ao_out);
    if (any(greaterThanEqual(p, size))) return;
    vec4 P = texelFetch(positions, p, 0);
    if (P.w == 0.0) {
        imageStore(ao_out, p, vec4(1.0));
        return;
    }
    vec3 N = normalize(texelFetch(normals, p, 0).xyz);
    vec3 T = normalize(abs(N.y) < 0.99 ? cross(N, vec3(0.0, 1.0, 0.0)) : cross(N, vec3(1.0, 0.0, 0.0)));
    vec3 B = cross(N, T);
    float turn = float(pg_pcg(uint(p.x) * 7919u + uint(p.y) * 104729u) & 0xffffu) / 65536.0 * 6.2831853;
    float occluded = 0.0;
    for (int i = 0; i < SAMPLES; i++) {
        // a cosine-weighted point of the unit disc lifted onto the hemisphere, at a distance that
        // grows with i (more samples near the surface)
        float u = (float(i) + 0.5) / float(SAMPLES);
        float phi = float(i) * 2.3999632 + turn; // golden angle
        float r = sqrt(u);
        vec3 dir = vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - u)));
        float scale = params.radius * mix(0.1, 1.0, u * u);
        vec3 S = P.xyz + (T * dir.x + B * dir.y + N * dir.z) * scale;
        vec4 clip = frame.proj * vec4(PG_REL_TO_VIEW(S - frame.camera_pos.xyz), 1.0);
        if (clip.w <= 0.0) continue;
        vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
        if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) continue;
        vec4 Q = texelFetch(positions, ivec2(uv * vec2(size)), 0);
        if (Q.w == 0.0) continue;
        float dq = view_depth_of(Q.xyz), ds = view_depth_of(S);
        float in_range = distance(Q.xyz, P.xyz) < params.radius ? 1.0 : 0.0;
        occluded += (dq < ds - 0.02 * params.radius) ? in_range : 0.0;
    }
    imageStore(ao_out, p, vec4(1.0 - occluded / float(SAMPLES)));
}
