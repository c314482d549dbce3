#version 460
// display_ocio.comp - display_ocio's compute variant (option stage "compute", renderer/passes/display_ocio.c):
// the same exposure, OCIO display/view transform and clamps as display_ocio.frag, one invocation per
// display pixel, written with imageStore (PG_LDR_FORMAT: the ldr image's format qualifier). On GPUs
// whose raster hardware is a small part of the chip (H100/H200) a full-screen fragment pass costs
// several times this.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 1, binding = 0) uniform sampler2D hdr;
layout(push_constant) uniform Push { float exposure; } pc;

// vec4 ocio_display(vec4 scene_linear); its LUT samplers (if any) use set 1, bindings 1 .. N
#include "ocio_display.glsl"

// after the LUTs: binding PG_LDR_BINDING = 1 + N
layout(set = 1, binding = PG_LDR_BINDING, PG_LDR_FORMAT) uniform writeonly image2D ldr_out;

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    ivec2 out_size = imageSize(ldr_out);
    if (px.x >= out_size.x || px.y >= out_size.y) return;
    // the texel display_ocio.frag reads: its v_uv is the pixel centre over the target's size
    vec2 uv = (vec2(px) + 0.5) / vec2(out_size);
    ivec2 size = textureSize(hdr, 0);
    ivec2 texel = clamp(ivec2(uv * vec2(size)), ivec2(0), size - 1);
    vec3 c = texelFetch(hdr, texel, 0).rgb * pc.exposure;
    c = mix(c, vec3(0.0), isnan(c));
    c = clamp(c, vec3(-1e30), vec3(1e30)); // +-inf would turn into NaN inside the transform
    imageStore(ldr_out, px, vec4(ocio_display(vec4(c, 1.0)).rgb, 1.0));
}
