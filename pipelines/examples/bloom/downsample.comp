#version 460
// downsample.comp - bloom (pipelines/examples/bloom/bloom.json): each texel of dst is the mean of
// the 2x2 block of src it covers (texels past src's edge repeat the edge), so an image whose size
// halves evenly keeps its mean exactly.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 2, binding = 0) uniform sampler2D src;
layout(set = 2, binding = 1, rgba16f) uniform writeonly image2D dst;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(dst)))) return;
    ivec2 top = textureSize(src, 0) - 1;
    vec3 sum = vec3(0.0);
    for (int dy = 0; dy < 2; dy++)
        for (int dx = 0; dx < 2; dx++) sum += texelFetch(src, min(2 * p + ivec2(dx, dy), top), 0).rgb;
    imageStore(dst, p, vec4(sum * 0.25, 1.0));
}
