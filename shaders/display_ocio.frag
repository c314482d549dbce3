#version 460
// display_ocio.frag - scene-linear HDR -> display through an OpenColorIO processor
// (renderer/passes/display_ocio.c): exposure (a multiply in scene-linear), then OCIO's display/view
// transform, whose GLSL is generated at run time from the config and included below. The output
// is already encoded for the display: write it to a UNORM (or float) target, not an _srgb one.
layout(set = 1, binding = 0) uniform sampler2D hdr;
layout(push_constant) uniform Push { float exposure; } pc;
layout(location = 0) in vec2 v_uv;
layout(location = 0) out vec4 out_color;

// vec4 ocio_display(vec4 scene_linear); its LUT samplers (if any) use set 1, bindings 1, 2, ...
#include "ocio_display.glsl"

void main()
{
    ivec2 size = textureSize(hdr, 0);
    ivec2 texel = clamp(ivec2(v_uv * vec2(size)), ivec2(0), size - 1);
    vec3 c = texelFetch(hdr, texel, 0).rgb * pc.exposure;
    c = mix(c, vec3(0.0), isnan(c));
    c = clamp(c, vec3(-1e30), vec3(1e30)); // +-inf would turn into NaN inside the transform
    out_color = vec4(ocio_display(vec4(c, 1.0)).rgb, 1.0);
}
