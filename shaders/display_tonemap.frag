#version 460
// display_tonemap.frag - scene-linear HDR -> display, the simple alternative to display_ocio:
// exposure, then an operator (PG_TONEMAP 0 clamp, 1 Reinhard, 2 ACES fit); the sRGB encoding is
// done by an rgba8_srgb target, or here (PG_ENCODE_SRGB) for a UNORM target.
layout(set = 1, binding = 0) uniform sampler2D hdr;
layout(push_constant) uniform Push { float exposure; } pc;
layout(location = 0) in vec2 v_uv;
layout(location = 0) out vec4 out_color;

vec3 aces_fit(vec3 x)
{
    const float a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
    return clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0, 1.0);
}

void main()
{
    ivec2 size = textureSize(hdr, 0);
    ivec2 texel = clamp(ivec2(v_uv * vec2(size)), ivec2(0), size - 1);
    vec3 c = texelFetch(hdr, texel, 0).rgb * pc.exposure;
    // NaN to 0; negatives to 0 and +inf to the half range (a user pass may write them: Reinhard
    // made +inf black (inf / inf) and -2 white, the ACES fit made 1e30 black and -0.5 white); the
    // shipped shading writes [0, 65000] already (so its images are unchanged)
    c = clamp(mix(c, vec3(0.0), isnan(c)), 0.0, 65504.0);
#if PG_TONEMAP == 1
    c = c / (1.0 + c);
#elif PG_TONEMAP == 2
    c = aces_fit(c);
#else
    c = clamp(c, 0.0, 1.0);
#endif
#ifdef PG_ENCODE_SRGB
    c = clamp(c, 0.0, 1.0);
    c = mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
#endif
    out_color = vec4(c, 1.0);
}
