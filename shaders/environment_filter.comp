#version 450
// environment_filter.comp - fills the filtered environment (environment.glsl's layout) from the
// scene's equirect source levels: one invocation per output texel.
//   diffuse E(n)/pi: the sum over every texel of the source level at most 64 texels wide of
//     radiance x max(n.l, 0) x the texel's solid angle, / pi (a quadrature of the integral, no noise);
//   split-sum table: A, B by GGX half-vector sampling, C by cosine sampling (PG_ENV_LUT_SAMPLES
//     Hammersley points each), for V at acos(n.v) from N;
//   prefiltered radiance: level 0 is the source read at the level nearest 256 texels wide; level
//     k > 0 (roughness k / (levels - 1)) the GGX lobe with n = v = r (Karis 2013): PG_ENV_SPEC_SAMPLES
//     half vectors, each sample read at the source level whose texels match its share of the lobe's
//     solid angle (filtered importance sampling, Krivanek and Colbert 2008), weighted by n.l.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(local_size_x = 64) in;

layout(set = 0, binding = 0, std430) readonly buffer Source { vec4 env_src[]; };   // scene levels
layout(set = 0, binding = 1, std430) writeonly buffer Filtered { vec4 env_out[]; }; // the resource
layout(push_constant) uniform Push { uint width, height, levels; } pc; // the source's level 0 and count

#define PG_ENV_FETCH(i) env_src[i]
#include "environment.glsl"

#ifndef PG_ENV_LUT_SAMPLES
#define PG_ENV_LUT_SAMPLES 512u
#endif
#ifndef PG_ENV_LOD_BIAS
#define PG_ENV_LOD_BIAS 1.0
#endif
#ifndef PG_ENV_SPEC_SAMPLES
#define PG_ENV_SPEC_SAMPLES 256u
#endif

// The source's levels (environment.glsl pg_env_src_*) with this dispatch's sizes.
uvec3 src_level(uint k) { return pg_env_src_level(k, pc.width, pc.height); }
vec3 src_bilinear(uint k, vec2 uv) { return pg_env_src_bilinear(k, uv, pc.width, pc.height, pc.levels); }
vec3 src_lod(vec3 d, float lod) { return pg_env_src_lod(d, lod, pc.width, pc.height, pc.levels); }

vec3 filter_irradiance(vec3 n)
{
    uint k = 0u;
    while (k + 1u < pc.levels && src_level(k).y > 64u) k++;
    uvec3 l = src_level(k);
    vec3 sum = vec3(0.0);
    float dphi = 2.0 * PG_ENV_PI / float(l.y);
    for (uint j = 0u; j < l.z; j++) {
        float ct = cos(PG_ENV_PI * float(j) / float(l.z)), cb = cos(PG_ENV_PI * float(j + 1u) / float(l.z));
        float domega = dphi * (ct - cb);
        for (uint i = 0u; i < l.y; i++) {
            vec3 d = pg_env_uv_to_dir(vec2((float(i) + 0.5) / float(l.y), (float(j) + 0.5) / float(l.z)));
            float c = dot(n, d);
            if (c > 0.0) sum += env_src[l.x + j * l.y + i].rgb * (c * domega);
        }
    }
    return sum / PG_ENV_PI;
}

vec3 filter_lut(float nv, float rough)
{
    float a = pg_env_alpha(rough);
    vec3 N = vec3(0.0, 0.0, 1.0), V = vec3(sqrt(max(1.0 - nv * nv, 0.0)), 0.0, nv);
    float A = 0.0, B = 0.0, C = 0.0;
    for (uint i = 0u; i < PG_ENV_LUT_SAMPLES; i++) {
        vec2 xi = pg_env_hammersley(i, PG_ENV_LUT_SAMPLES);
        vec3 H = pg_env_ggx_half(N, a, xi);
        float vh = dot(V, H);
        vec3 L = 2.0 * vh * H - V;
        float nl = L.z, nh = H.z;
        if (nl > 0.0 && vh > 0.0) {
            float g = pg_env_smith_v(nl, nv, a) * 4.0 * vh * nl / nh;
            float w = pow(clamp(1.0 - vh, 0.0, 1.0), 5.0); // vh rounds past 1: pow(< 0) is NaN
            A += (1.0 - w) * g;
            B += w * g;
        }
        vec3 Ld = pg_env_cosine_dir(N, xi);
        float vhd = clamp(dot(V, normalize(V + Ld)), 0.0, 1.0);
        C += 1.0 - pow(1.0 - vhd, 5.0);
    }
    return vec3(A, B, C) / float(PG_ENV_LUT_SAMPLES);
}

vec3 filter_specular(vec3 r, uint level)
{
    uint k0 = 0u;
    while (k0 + 1u < pc.levels && src_level(k0 + 1u).y >= PG_ENV_SPEC_W) k0++;
    if (level == 0u) return src_bilinear(k0, pg_env_dir_to_uv(r));
    float a = pg_env_alpha(float(level) / float(PG_ENV_SPEC_LEVELS - 1u));
    float texel = 4.0 * PG_ENV_PI / (float(pc.width) * float(pc.height)); // level 0's mean texel
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (uint i = 0u; i < PG_ENV_SPEC_SAMPLES; i++) {
        vec3 H = pg_env_ggx_half(r, a, pg_env_hammersley(i, PG_ENV_SPEC_SAMPLES));
        float rh = dot(r, H);
        vec3 L = 2.0 * rh * H - r;
        float nl = dot(r, L);
        if (nl <= 0.0) continue;
        // pdf of L with n = v: D(n.h) n.h / (4 v.h) = D / 4
        float nh = max(rh, 1e-4), d = a * a / (PG_ENV_PI * pow(nh * nh * (a * a - 1.0) + 1.0, 2.0));
        float omega = 1.0 / (float(PG_ENV_SPEC_SAMPLES) * d * 0.25);
        float lod = max(0.5 * log2(omega / texel) + PG_ENV_LOD_BIAS, 0.0);
        sum += src_lod(L, lod) * nl;
        weight += nl;
    }
    return weight > 0.0 ? sum / weight : vec3(0.0);
}

void main()
{
    uint t = gl_GlobalInvocationID.x;
    if (t >= PG_ENV_TEXELS) return;
    vec3 c;
    if (t < PG_ENV_LUT_OFF) {
        uint i = t % PG_ENV_IRR_W, j = t / PG_ENV_IRR_W;
        c = filter_irradiance(pg_env_uv_to_dir(vec2((float(i) + 0.5) / float(PG_ENV_IRR_W),
                                                    (float(j) + 0.5) / float(PG_ENV_IRR_H))));
    } else if (t < PG_ENV_SPEC_OFF) {
        uint e = t - PG_ENV_LUT_OFF;
        float n = float(PG_ENV_LUT_N);
        c = filter_lut((float(e % PG_ENV_LUT_N) + 0.5) / n, (float(e / PG_ENV_LUT_N) + 0.5) / n);
    } else {
        uint level = 0u;
        while (level + 1u < PG_ENV_SPEC_LEVELS && t >= pg_env_spec_offset(level + 1u)) level++;
        uvec2 sz = pg_env_spec_size(level);
        uint e = t - pg_env_spec_offset(level), w = sz.x, h = sz.y;
        c = filter_specular(pg_env_uv_to_dir(vec2((float(e % w) + 0.5) / float(w), (float(e / w) + 0.5) / float(h))),
                            level);
    }
    env_out[t] = vec4(c, 1.0);
}
