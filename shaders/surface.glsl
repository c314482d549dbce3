// surface.glsl - material evaluation shared by forward and G-buffer fragment shaders.
// Variants: PG_ALPHA_MASK (discard below the cutoff), PG_NORMAL_MAPS (tangent-space normal
// maps), TEXTURE_COUNT (size of the scene's texture array).
layout(set = 1, binding = 0, std430) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = 1, binding = 1) uniform sampler2D textures[TEXTURE_COUNT];
layout(push_constant) uniform DrawPush { uint material; } draw;

Surface pg_surface(vec3 world_normal, vec2 uv, vec4 tangent, bool front_facing)
{
    GpuMaterial m = materials[draw.material];
    vec4 base = m.base_color;
    if (m.tex.x >= 0) base *= texture(textures[m.tex.x], uv);
#ifdef PG_ALPHA_MASK
    if (m.tex.z == 1 && base.a < m.params.x) discard;
#endif
    vec3 N = world_normal;
    float nl = length(N);
    N = nl > 1e-20 ? N / nl : vec3(0.0, 1.0, 0.0);
#ifdef PG_NORMAL_MAPS
    if (m.tex.y >= 0 && dot(tangent.xyz, tangent.xyz) > 1e-12) {
        vec3 T = tangent.xyz - N * dot(N, tangent.xyz);
        float tl = length(T);
        if (tl > 1e-6) {
            T /= tl;
            vec3 B = cross(N, T) * (tangent.w < 0.0 ? -1.0 : 1.0);
            vec3 tn = texture(textures[m.tex.y], uv).xyz * 2.0 - 1.0;
            tn.xy *= m.params.y;
            vec3 n2 = T * tn.x + B * tn.y + N * tn.z;
            float l2 = length(n2);
            if (l2 > 1e-6) N = n2 / l2;
        }
    }
#endif
    if (!front_facing) N = -N; // light the side the camera sees
    Surface s;
    s.albedo = base.rgb;
    s.normal = N;
    s.specular = m.params.z;
    s.shininess = m.params.w;
    return s;
}
