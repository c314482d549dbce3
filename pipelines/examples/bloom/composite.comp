#version 460
// composite.comp - bloom (pipelines/examples/bloom/bloom.json): dst = (1 - s) hdr + s blur / levels,
// where blur (half size, read bilinearly) is the sum of `levels` blurred copies of the image that
// each keep its mean: the image's total energy is kept.
#include "common.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 2, binding = 0) uniform sampler2D hdr_image;
layout(set = 2, binding = 1) uniform sampler2D blur;
// HDR_FORMAT: the pipeline's hdr_format (rgba16f or rgba32f), handed over as a define
layout(set = 2, binding = 2, HDR_FORMAT) uniform writeonly image2D dst;
layout(push_constant) uniform Params {
    float strength;
    float levels;
} params;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(dst);
    if (any(greaterThanEqual(p, size))) return;
    vec3 b = textureLod(blur, (vec2(p) + 0.5) / vec2(size), 0.0).rgb / params.levels;
    vec3 c = texelFetch(hdr_image, p, 0).rgb;
    imageStore(dst, p, vec4(pg_hdr_sanitize(mix(c, b, params.strength)), 1.0));
}
