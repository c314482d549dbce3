// surface.glsl - material evaluation shared by forward and G-buffer fragment shaders and by the
// compute passes that rebuild a surface from a triangle id (visibility_surface.glsl).
// Variants (each compiled in only when the scene needs it; renderer/common/scene_draw.c picks them):
//   PG_ALPHA_MASK      discard below the cutoff
//   PG_NORMAL_MAPS     tangent-space normal maps
//   PG_VERTEX_COLORS   COLOR_0 multiplied into the base colour (vertex stream 1)
//   PG_UV1             textures may read TEXCOORD_1 (vertex stream 2)
//   PG_UV_TRANSFORM    KHR_texture_transform matrices per texture slot
//   PG_EMISSIVE        emissive factor and texture
//   PG_PBR             the glTF metallic-roughness model: specular = metallic, shininess = roughness,
//                      occlusion (lighting.glsl); with PG_METALLIC_ROUGHNESS_TEXTURES and
//                      PG_OCCLUSION_TEXTURES their textures
//   PG_UNLIT           KHR_materials_unlit materials: emissive = base colour, nothing else lit
//   TEXTURE_COUNT      size of the scene's texture array
// Every texture is sampled with textureGrad and SurfaceInput.duv0/duv1, the screen-space
// derivatives of TEXCOORD_0/1 taken before any branch (fragment shaders: dFdx/dFdy in
// pg_surface_input(); compute: from the triangle, visibility_surface.glsl), carried through the
// slot's transform. Implicit derivatives of a coordinate computed inside the material's branches
// are not reliable: on lavapipe a transformed or TEXCOORD_1 coordinate sampled that way gave noise
// and seams along triangle edges (tests/gpu/test_gpu_surface.c check_boxes).
// For compute (a material per pixel):
//   PG_SURFACE_GRADS   the material index varies per invocation
//   PG_NONUNIFORM_TEXTURES  the texture index is nonuniformEXT (device feature); otherwise each
//                      invocation walks the texture array (pg_slot_sample)
//   PG_SURFACE_NO_PUSH the includer declares the push constants (DrawPush is not declared)
//   PG_SCENE_SET       descriptor set of the scene's materials and textures (default 1)
// The fragment inputs come from surface_inputs.glsl (pg_surface_input()).
#ifndef PG_SCENE_SET
#define PG_SCENE_SET 1
#endif
layout(set = PG_SCENE_SET, binding = 0, std430) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = PG_SCENE_SET, binding = 1) uniform sampler2D textures[TEXTURE_COUNT];
#ifndef PG_SURFACE_NO_PUSH
// ambient: the pass's option "ambient" (a run-time value, the same for every draw; read by
// forward.frag as PG_AMBIENT)
layout(push_constant) uniform DrawPush { uint material; float ambient; } draw;
#endif

// Texture slots (core/scene/scene.h PG_TEXSLOT_*)
const int PG_SLOT_BASE = 0;
const int PG_SLOT_NORMAL = 1;
const int PG_SLOT_EMISSIVE = 2;
const int PG_SLOT_METALLIC_ROUGHNESS = 3;
const int PG_SLOT_OCCLUSION = 4;

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

// d(uv)/dx in xy, d(uv)/dy in zw of the coordinate slot reads: the set's derivatives through the
// linear part of its transform.
vec4 pg_slot_grad(GpuMaterial m, int slot, SurfaceInput si)
{
    vec4 d = si.duv0;
#ifdef PG_UV1
    if ((m.tex2.y & (1 << slot)) != 0) d = si.duv1;
#endif
#ifdef PG_UV_TRANSFORM
    vec2 r0 = m.uv_xform[2 * slot].xy, r1 = m.uv_xform[2 * slot + 1].xy;
    d = vec4(dot(r0, d.xy), dot(r1, d.xy), dot(r0, d.zw), dot(r1, d.zw));
#endif
    return d;
}

// Texture t (an index into textures[], t >= 0 when want) of a slot; vec4(1) when !want.
vec4 pg_slot_sample(bool want, int t, GpuMaterial m, int slot, SurfaceInput si)
{
#if defined(PG_SURFACE_GRADS) && defined(PG_NONUNIFORM_TEXTURES)
    vec4 g = pg_slot_grad(m, slot, si);
    return want ? textureGrad(textures[nonuniformEXT(t)], pg_slot_uv(m, slot, si), g.xy, g.zw) : vec4(1.0);
#elif defined(PG_SURFACE_GRADS)
    // Without the device's shaderSampledImageArrayNonUniformIndexing (lavapipe) the index must be
    // dynamically uniform: every invocation walks the array and samples where the index is its
    // own (a loop counter is uniform). Costs a compare per texture of the scene per sample.
    vec4 r = vec4(1.0);
    vec2 uv = pg_slot_uv(m, slot, si);
    vec4 g = pg_slot_grad(m, slot, si);
    if (want)
        for (int i = 0; i < TEXTURE_COUNT; i++)
            if (i == t) r = textureGrad(textures[i], uv, g.xy, g.zw);
    return r;
#else
    // a fragment shader: t is the draw's (dynamically uniform)
    vec4 g = pg_slot_grad(m, slot, si);
    return want ? textureGrad(textures[t], pg_slot_uv(m, slot, si), g.xy, g.zw) : vec4(1.0);
#endif
}

// The base colour (factor x texture x COLOR_0) of material m at a surface point.
vec4 pg_surface_base(GpuMaterial m, SurfaceInput si)
{
    vec4 base = m.base_color;
    vec4 tb = pg_slot_sample(m.tex.x >= 0, m.tex.x, m, PG_SLOT_BASE, si);
    if (m.tex.x >= 0) base *= tb;
#ifdef PG_VERTEX_COLORS
    base *= si.color;
#endif
    return base;
}

// false where an alpha-mask material's alpha test drops the point (what PG_ALPHA_MASK discards).
bool pg_surface_alpha_kept(GpuMaterial m, vec4 base)
{
    return !(m.tex.z == 1 && base.a < m.params.x);
}

// The material of index `material` at a surface point.
Surface pg_surface_material(SurfaceInput si, uint material)
{
    GpuMaterial m = materials[material];
    vec4 base = pg_surface_base(m, si);
#ifdef PG_ALPHA_MASK
    if (!pg_surface_alpha_kept(m, base)) discard;
#endif
    vec3 N = si.normal;
    float nl = length(N);
    N = nl > 1e-20 ? N / nl : vec3(0.0, 1.0, 0.0);
#ifdef PG_NORMAL_MAPS
    vec4 tangent = si.tangent;
    bool mapped = m.tex.y >= 0 && dot(tangent.xyz, tangent.xyz) > 1e-12;
    vec3 T = vec3(0.0);
    float tl = 0.0;
    if (mapped) {
        T = tangent.xyz - N * dot(N, tangent.xyz);
        tl = length(T);
        mapped = tl > 1e-6;
    }
    vec4 tn4 = pg_slot_sample(mapped, m.tex.y, m, PG_SLOT_NORMAL, si);
    if (mapped) {
        T /= tl;
        vec3 B = cross(N, T) * (tangent.w < 0.0 ? -1.0 : 1.0);
        vec3 tn = tn4.xyz * 2.0 - 1.0;
        tn.xy *= m.params.y;
        vec3 n2 = T * tn.x + B * tn.y + N * tn.z;
        float l2 = length(n2);
        if (l2 > 1e-6) N = n2 / l2;
    }
#endif
    if (!si.front_facing) N = -N; // light the side the camera sees
    Surface s;
    s.albedo = base.rgb;
    s.alpha = base.a;
    s.normal = N;
    s.occlusion = 1.0;
#ifdef PG_PBR
    float metallic = m.pbr.x, roughness = m.pbr.y;
#ifdef PG_METALLIC_ROUGHNESS_TEXTURES
    vec4 tmr = pg_slot_sample(m.tex3.x >= 0, m.tex3.x, m, PG_SLOT_METALLIC_ROUGHNESS, si);
    if (m.tex3.x >= 0) {     // the glTF channels: G roughness, B metallic
        roughness *= tmr.g;
        metallic *= tmr.b;
    }
#endif
#ifdef PG_OCCLUSION_TEXTURES
    vec4 tao = pg_slot_sample(m.tex3.y >= 0, m.tex3.y, m, PG_SLOT_OCCLUSION, si);
    if (m.tex3.y >= 0) s.occlusion = 1.0 + m.pbr.z * (tao.r - 1.0); // the glTF strength
#endif
    s.specular = metallic;
    s.shininess = roughness;
#else
    s.specular = m.params.z;
    s.shininess = m.params.w;
#endif
    s.emissive = vec3(0.0);
#ifdef PG_EMISSIVE
    s.emissive = m.emissive.rgb;
    vec4 te = pg_slot_sample(m.tex2.x >= 0, m.tex2.x, m, PG_SLOT_EMISSIVE, si);
    if (m.tex2.x >= 0) s.emissive *= te.rgb;
#endif
#ifdef PG_UNLIT
    if (m.pbr.w > 0.5) { // KHR_materials_unlit: the base colour is the result (an emission, no light)
        s.emissive = base.rgb;
        s.albedo = vec3(0.0);
#ifdef PG_PBR
        s.specular = 1.0; // a black metal: F0 = 0, c_diff = 0; occlusion < 0 drops the grazing Fresnel term too (pg_pbr_lit)
        s.shininess = 1.0;
        s.occlusion = -1.0;
#else
        s.specular = 0.0;
#endif
    }
#endif
    return s;
}

#ifndef PG_SURFACE_NO_PUSH
// The draw's material (the push constant) at this fragment.
Surface pg_surface(SurfaceInput si)
{
    return pg_surface_material(si, draw.material);
}
#endif
