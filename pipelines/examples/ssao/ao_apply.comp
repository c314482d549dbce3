#version 460
// ao_apply.comp - the SSAO example's composite (pipelines/examples/ssao/ssao.json): the lighting
// pass ran without the pass ambient; this adds the Lambert ambient term scaled by the occlusion:
// dst = hdr + albedo (ambient + frame ambient) ao - albedo frame ambient (the lighting pass already
// added albedo x frame ambient, unoccluded). AO_ONLY: dst = ao as grey.
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 2, binding = 0) uniform sampler2D hdr_image;
layout(set = 2, binding = 1) uniform sampler2D ao_image;
layout(set = 2, binding = 2) uniform sampler2D albedo;
layout(set = 2, binding = 3) uniform sampler2D positions;
layout(set = 2, binding = 4, rgba16f) uniform writeonly image2D dst;
layout(push_constant) uniform Params {
    float ambient;
} params;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(dst)))) return;
    float ao = texelFetch(ao_image, p, 0).r;
#ifdef AO_ONLY
    imageStore(dst, p, vec4(vec3(ao), 1.0));
#else
    vec3 c = texelFetch(hdr_image, p, 0).rgb;
    if (texelFetch(positions, p, 0).w != 0.0) {
        vec3 a = texelFetch(albedo, p, 0).rgb;
        c += a * ((params.ambient + frame.clip.z) * ao - frame.clip.z);
    }
    imageStore(dst, p, vec4(pg_hdr_sanitize(c), 1.0));
#endif
}
