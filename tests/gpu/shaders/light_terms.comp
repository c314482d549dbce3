#version 460
// light_terms.comp - the light sums of shaders/lighting.glsl on given inputs (test_gpu_light_terms.c):
// one invocation a case, two lights a case, summed three ways: pg_accumulate_light_rel_select (the
// tiled loop's form), pg_accumulate_light_rel (the per-pixel loops' form, with its early return) and,
// where the light model has it (PG_LAMBERT_PAIRS), pg_accumulate_lambert_pair. The light model is the
// defines the test compiles it with (none: Lambert; PG_GLTF_FALLOFF, PG_BLINN_PHONG, PG_PBR).
#include "common.glsl"
#include "lighting.glsl"

layout(local_size_x = 64) in;

// A light as the tiled loop stores it: a = (camera-relative centre, 1 / R_falloff^2), b = (colour, R^2).
struct Case {
    vec4 P;        // xyz: the shaded point (camera-relative)
    vec4 N;        // xyz: its unit normal
    vec4 V;        // xyz: unit direction to the eye
    vec4 albedo;   // rgb: base colour, w: Blinn-Phong's exponent
    vec4 mat;      // metallic, roughness (pbr), the diffuse sum
                   // before the two lights (the rounding of a sum depends on the order of its terms), 1 / dmin^2
    vec4 a0, b0, a1, b1;
};

layout(std430, set = 0, binding = 0) readonly buffer Cases { Case cases[]; };
// 6 a case: the select form's diffuse and specular sums, the early-return form's, the pairs' (w of
// the last: 1 where the light model has them)
layout(std430, set = 0, binding = 1) writeonly buffer Sums { vec4 sums[]; };

layout(push_constant) uniform Push { uint count; } pc;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    Case c = cases[i];
    Surface s;
    s.albedo = c.albedo.rgb;
    s.alpha = 1.0;
    s.normal = c.N.xyz;
    s.specular = c.mat.x;
#ifdef PG_BLINN_PHONG
    s.shininess = c.albedo.w;
#else
    s.shininess = c.mat.y;
#endif
    s.emissive = vec3(0.0);
    s.occlusion = 1.0;
    vec3 P = c.P.xyz, N = c.N.xyz, V = c.V.xyz;
    float inv_md2 = c.mat.w;
    PgLightMat m = pg_light_mat(s, V);
    vec4 point = vec4(0.0, 0.0, 0.0, 1.0);   // a point light's spot record
    PgShade sel = pg_shade_zero(), br = pg_shade_zero(), pair = pg_shade_zero();
    sel.diffuse = br.diffuse = pair.diffuse = vec3(c.mat.z);
    float has_pairs = 0.0;
    pg_accumulate_light_rel_select(c.a0.xyz, c.b0.w, c.a0.w, c.b0.rgb, point, P, N, V, m, inv_md2, sel);
    pg_accumulate_light_rel_select(c.a1.xyz, c.b1.w, c.a1.w, c.b1.rgb, point, P, N, V, m, inv_md2, sel);
    pg_accumulate_light_rel(c.a0.xyz, c.b0.w, c.a0.w, c.b0.rgb, point, P, N, V, m, inv_md2, br);
    pg_accumulate_light_rel(c.a1.xyz, c.b1.w, c.a1.w, c.b1.rgb, point, P, N, V, m, inv_md2, br);
#ifdef PG_LAMBERT_PAIRS
    pg_accumulate_lambert_pair(c.a0, c.b0, c.a1, c.b1, P, N, inv_md2, pair);
    has_pairs = 1.0;
#endif
    sums[6u * i + 0u] = vec4(sel.diffuse, 0.0);
    sums[6u * i + 1u] = vec4(sel.specular, 0.0);
    sums[6u * i + 2u] = vec4(br.diffuse, 0.0);
    sums[6u * i + 3u] = vec4(br.specular, 0.0);
    sums[6u * i + 4u] = vec4(pair.diffuse, 0.0);
    sums[6u * i + 5u] = vec4(pair.specular, has_pairs);
}
