#version 460
// tonemap.frag - an example user pass (pipelines/examples/tonemap/tonemap.json): scene-linear HDR
// -> an 8-bit display image. Per pixel: c = exposure * hdr; L = luminance(c); the extended
// Reinhard curve L' = L (1 + L / white^2) / (1 + L) scales the colour by L' / L; the result is
// clamped to [0, 1] and sRGB-encoded (the target is UNORM rgba8). tests/gpu/test_gpu_user_passes.c
// evaluates the same formula on the CPU for every pixel.
#include "common.glsl"

layout(set = 2, binding = 0) uniform sampler2D hdr_image;
layout(push_constant) uniform Params {
    float exposure;
    float white;
} params;
layout(location = 0) in vec2 v_uv;
layout(location = 0) out vec4 out_color;

void main()
{
    ivec2 size = textureSize(hdr_image, 0);
    ivec2 texel = clamp(ivec2(gl_FragCoord.xy), ivec2(0), size - 1);
    vec3 c = pg_hdr_sanitize(texelFetch(hdr_image, texel, 0).rgb) * params.exposure;
    float L = pg_luminance(c);
    float scale = L > 0.0 ? (1.0 + L / (params.white * params.white)) / (1.0 + L) : 1.0;
    out_color = vec4(pg_srgb_encode(c * scale), 1.0);
}
