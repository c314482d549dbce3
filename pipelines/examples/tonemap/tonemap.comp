#version 460
// tonemap.comp - the tone mapper of pipelines/examples/tonemap/tonemap.json as a compute pass
// (tonemap_stage=compute): the curve of tonemap.frag, one thread a pixel, into the rgba8 output as
// a storage image.
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 2, binding = 0) uniform sampler2D hdr_image;
layout(set = 2, binding = 1, rgba8) uniform writeonly image2D ldr_image;
layout(push_constant) uniform Params {
    float exposure;
    float white;
} params;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(ldr_image)))) return;
    vec3 c = pg_hdr_sanitize(texelFetch(hdr_image, p, 0).rgb) * params.exposure;
    float L = pg_luminance(c);
    float scale = L > 0.0 ? (1.0 + L / (params.white * params.white)) / (1.0 + L) : 1.0;
    imageStore(ldr_image, p, vec4(pg_srgb_encode(c * scale), 1.0));
}
