// gbuffer_pack.glsl - what the G-buffer layouts store beyond the plain channels, shared by their
// writers (gbuffer.frag, visibility_resolve.comp) and readers (deferred_lighting.comp,
// reference_lighting.comp): the pbr model's occlusion, the float layout's channels and the packed
// layout's words. Include after common.glsl and octahedral.glsl.

// The pbr model's occlusion in the G-buffers (gbuffer.frag, visibility_resolve.comp; read by
// deferred_lighting.comp, reference_lighting.comp). Surface.occlusion is in [0, 1], or -1 for an unlit
// surface (lighting.glsl pg_pbr_lit). unorm channels (oct16's normal w, packed's third word) hold
// occlusion / 2 in [0, 0.5] and 1 for unlit; the float position's w holds 1 + occlusion in [1, 2]
// (> 0: drawn) and 3 for unlit.
float pg_gb_occlusion_unorm(float occ)
{
    return occ < 0.0 ? 1.0 : 0.5 * clamp(occ, 0.0, 1.0);
}

float pg_gb_occlusion_from_unorm(float v)
{
    return v > 0.75 ? -1.0 : 2.0 * v;
}

float pg_gb_occlusion_float(float occ)
{
    return occ < 0.0 ? 3.0 : 1.0 + occ;
}

float pg_gb_occlusion_from_float(float w)
{
    return w > 2.5 ? -1.0 : max(w - 1.0, 0.0);
}

// The float layout (gbuffer_layout.h "float"), as gbuffer.frag and visibility_resolve.comp (packing
// "float") write it: the position given (camera-relative, or world) with w 1 where drawn (pbr: 1 +
// occlusion, pg_gb_occlusion_float), the normal with the shininess (pbr: roughness), the albedo with
// the specular weight (pbr: metallic).
void pg_gbuffer_float(Surface s, vec3 position, out vec4 g_pos, out vec4 g_nrm, out vec4 g_alb)
{
#ifdef PG_PBR
    g_pos = vec4(position, pg_gb_occlusion_float(s.occlusion));
#else
    g_pos = vec4(position, 1.0);
#endif
    g_nrm = vec4(s.normal, s.shininess);
    g_alb = vec4(s.albedo, s.specular);
}

// The packed layout (gbuffer_layout.h): oct16 normal | sRGB8 albedo + specular (pbr: metallic) in 8
// bits | shininess as f32 (pbr: unorm16 roughness | unorm16 occlusion) | view depth f32.
uvec4 pg_gbuffer_packed(Surface s, float view_depth)
{
    return uvec4(pg_oct_pack_unorm16(s.normal), packUnorm4x8(vec4(pg_srgb_encode(s.albedo), clamp(s.specular, 0.0, 1.0))),
#ifdef PG_PBR
                 packUnorm2x16(vec2(s.shininess, pg_gb_occlusion_unorm(s.occlusion))),
#else
                 floatBitsToUint(s.shininess),
#endif
                 floatBitsToUint(view_depth));
}
