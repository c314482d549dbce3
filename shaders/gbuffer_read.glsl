// gbuffer_read.glsl - a pixel's surface rebuilt from each G-buffer packing (gbuffer_layout.h,
// gbuffer.frag writes them): the code the built-in deferred lighting pass runs, and part of the
// shader library user passes include (docs/user-passes.md). No #version; include after common.glsl
// (with FRAME_UNIFORMS_BLOCK), octahedral.glsl, gbuffer_pack.glsl and depth_reconstruct.glsl.
// Define PG_PBR when the G-buffer was written with the pbr model (metallic-roughness, occlusion).
// Each fills s (emissive 0, alpha 1: the emissive target is read separately), the camera-relative
// position P (world - camera) and the positive view depth. uv is the pixel centre / the image size.
#ifndef PG_GBUFFER_READ_GLSL
#define PG_GBUFFER_READ_GLSL

// A surface with every field set (the values of a background pixel).
Surface pg_surface_default()
{
    Surface s;
    s.albedo = vec3(0.0);
    s.normal = vec3(0.0, 0.0, 1.0);
    s.specular = 0.0;
    s.shininess = 1.0;
    s.alpha = 1.0;
    s.emissive = vec3(0.0);
    s.occlusion = 1.0;
    return s;
}

// packing "float": world position (w: 1 + occlusion under pbr), normal (w: shininess/roughness),
// albedo (a: specular/metallic).
void pg_gbuffer_read_float(vec4 position, vec4 normal, vec4 albedo, out Surface s, out vec3 P, out float view_depth)
{
    s = pg_surface_default();
    P = position.xyz - frame.camera_pos.xyz; // world -> camera-relative
    s.normal = normal.xyz;
    s.shininess = normal.w;
    s.albedo = albedo.rgb;
    s.specular = albedo.a;
#ifdef PG_PBR
    s.occlusion = pg_gb_occlusion_from_float(position.w);
#endif
    view_depth = -PG_REL_TO_VIEW(P).z;
}

// packing "oct16": the position from the depth buffer's value, normal (rgba16 unorm: octahedral xy,
// shininess / 512 or roughness, occlusion), albedo (rgba8 sRGB, decoded by the sampler).
void pg_gbuffer_read_oct16(float depth, vec2 uv, vec4 normal, vec4 albedo, out Surface s, out vec3 P,
                           out float view_depth)
{
    s = pg_surface_default();
    // via the linear view depth: finite for any near/far (unprojecting through inv_proj breaks
    // down when far/near > 2^24, where proj[10] rounds to -1)
    view_depth = PG_ORTHO ? pg_ortho_view_depth_from_depth(depth, frame.clip.x, frame.clip.y)
                          : pg_view_depth_from_depth(depth, frame.clip.x, frame.clip.y);
    vec3 pv = PG_ORTHO ? pg_ortho_view_pos_from_view_depth(uv, view_depth, frame.proj)
                       : pg_view_pos_from_view_depth(uv, view_depth, frame.proj);
    P = PG_VIEW_TO_REL(pv);
    s.normal = pg_oct_decode(normal.xy * 2.0 - 1.0);
#ifdef PG_PBR
    s.shininess = normal.z; // roughness
    s.occlusion = pg_gb_occlusion_from_unorm(normal.w);
#else
    s.shininess = normal.z * 512.0;
#endif
    s.albedo = albedo.rgb;
    s.specular = albedo.a;
}

// packing "packed" (one rgba32ui texel): oct16 normal | sRGB8 albedo + specular8 | shininess f32
// (pbr: roughness, occlusion unorm16) | view depth f32.
void pg_gbuffer_read_packed(uvec4 g, vec2 uv, out Surface s, out vec3 P, out float view_depth)
{
    s = pg_surface_default();
    s.normal = pg_oct_unpack_unorm16(g.x);
    vec4 a = unpackUnorm4x8(g.y);
    s.albedo = pg_srgb_decode(a.rgb);
    s.specular = a.a;
#ifdef PG_PBR
    vec2 ro = unpackUnorm2x16(g.z); // roughness, occlusion
    s.shininess = ro.x;
    s.occlusion = pg_gb_occlusion_from_unorm(ro.y);
#else
    s.shininess = uintBitsToFloat(g.z);
#endif
    view_depth = uintBitsToFloat(g.w);
    vec3 pv = PG_ORTHO ? pg_ortho_view_pos_from_view_depth(uv, view_depth, frame.proj)
                       : pg_view_pos_from_view_depth(uv, view_depth, frame.proj);
    P = PG_VIEW_TO_REL(pv);
}

#endif
