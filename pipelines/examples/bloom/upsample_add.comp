#version 460
// upsample_add.comp - bloom (pipelines/examples/bloom/bloom.json): dst = base + src, where src
// (half dst's size) is read with bilinear filtering at each dst texel's centre and base has dst's
// size.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 2, binding = 0) uniform sampler2D base;
layout(set = 2, binding = 1) uniform sampler2D src;
layout(set = 2, binding = 2, rgba16f) uniform writeonly image2D dst;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(dst);
    if (any(greaterThanEqual(p, size))) return;
    vec3 up = textureLod(src, (vec2(p) + 0.5) / vec2(size), 0.0).rgb;
    imageStore(dst, p, vec4(texelFetch(base, p, 0).rgb + up, 1.0));
}
