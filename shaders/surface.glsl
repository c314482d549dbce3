// surface.glsl - material evaluation shared by forward and G-buffer fragment shaders.
// Variants (each compiled in only when the scene needs it; passes/scene_draw.c picks them):
//   PG_ALPHA_MASK      discard below the cutoff
//   PG_NORMAL_MAPS     tangent-space normal maps
//   PG_VERTEX_COLORS   COLOR_0 multiplied into the base colour (vertex stream 1)
//   PG_UV1             textures may read TEXCOORD_1 (vertex stream 2)
//   PG_UV_TRANSFORM    KHR_texture_transform matrices per texture slot
//   PG_EMISSIVE        emissive factor and texture
//   TEXTURE_COUNT      size of the scene's texture array
// The fragment inputs come from surface_inputs.glsl (pg_surface_input()).
layout(set = 1, binding = 0, std430) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = 1, binding = 1) uniform sampler2D textures[TEXTURE_COUNT];
// ambient: the pass's option "ambient" (a run-time value, the same for every draw; read by
// forward.frag as PG_AMBIENT)
layout(push_constant) uniform DrawPush { uint material; float ambient; } draw;

// Texture slots (core/scene/scene.h PG_TEXSLOT_*)
const int PG_SLOT_BASE = 0;
const int PG_SLOT_NORMAL = 1;
const int PG_SLOT_EMISSIVE = 2;

// The texture coordinate a slot of material m reads: TEXCOORD_0 or _1, then its transform.
vec2 pg_slot_uv(GpuMaterial m, int slot, SurfaceInput si)
{
    vec2 uv = si.uv0;
#ifdef PG_UV1
    if ((m.tex2.y & (1 << slot)) != 0) uv = si.uv1;
#endif
#ifdef PG_UV_TRANSFORM
    vec3 h = vec3(uv, 1.0);
    uv = vec2(dot(m.uv_xform[2 * slot].xyz, h), dot(m.uv_xform[2 * slot + 1].xyz, h));
#endif
    return uv;
}

Surface pg_surface(SurfaceInput si)
{
    GpuMaterial m = materials[draw.material];
    vec4 base = m.base_color;
    if (m.tex.x >= 0) base *= texture(textures[m.tex.x], pg_slot_uv(m, PG_SLOT_BASE, si));
#ifdef PG_VERTEX_COLORS
    base *= si.color;
#endif
#ifdef PG_ALPHA_MASK
    if (m.tex.z == 1 && base.a < m.params.x) discard;
#endif
    vec3 N = si.normal;
    float nl = length(N);
    N = nl > 1e-20 ? N / nl : vec3(0.0, 1.0, 0.0);
#ifdef PG_NORMAL_MAPS
    vec4 tangent = si.tangent;
    if (m.tex.y >= 0 && dot(tangent.xyz, tangent.xyz) > 1e-12) {
        vec3 T = tangent.xyz - N * dot(N, tangent.xyz);
        float tl = length(T);
        if (tl > 1e-6) {
            T /= tl;
            vec3 B = cross(N, T) * (tangent.w < 0.0 ? -1.0 : 1.0);
            vec3 tn = texture(textures[m.tex.y], pg_slot_uv(m, PG_SLOT_NORMAL, si)).xyz * 2.0 - 1.0;
            tn.xy *= m.params.y;
            vec3 n2 = T * tn.x + B * tn.y + N * tn.z;
            float l2 = length(n2);
            if (l2 > 1e-6) N = n2 / l2;
        }
    }
#endif
    if (!si.front_facing) N = -N; // light the side the camera sees
    Surface s;
    s.albedo = base.rgb;
    s.alpha = base.a;
    s.normal = N;
    s.specular = m.params.z;
    s.shininess = m.params.w;
    s.emissive = vec3(0.0);
#ifdef PG_EMISSIVE
    s.emissive = m.emissive.rgb;
    if (m.tex2.x >= 0) s.emissive *= texture(textures[m.tex2.x], pg_slot_uv(m, PG_SLOT_EMISSIVE, si)).rgb;
#endif
    return s;
}
