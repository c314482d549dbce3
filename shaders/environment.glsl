// environment.glsl - the environment light: equirectangular radiance and its filtered forms.
//
// Directions and texels as scene/environment.h states them (world space, +Y up):
//   u = 0.5 + atan(d.x, -d.z) / (2 pi), v = acos(d.y) / pi; texel (i, j) of a w x h level has its
//   centre at ((i + 0.5) / w, (j + 0.5) / h); bilinear between texel centres, u wrapping, v clamped.
//   A rotation r about +Y (frame.environment.y) reads the stored radiance of Ry(-r) d.
// The includer defines PG_ENV_FETCH(i): the vec4 texel at element i of the buffer it reads (the
// scene's source levels in environment_filter.comp and reference_lighting.comp, the filtered
// environment in the shading passes).
//
// The filtered environment (the graph resource "environment", written by environment_filter.comp;
// vec4 elements; renderer/common/environment_layout.h mirrors the numbers):
//   [PG_ENV_IRR_OFF, +32 x 16)   diffuse: E(n) / pi, E the irradiance of a surface facing n
//   [PG_ENV_LUT_OFF, +32 x 32)   split-sum factors at (n.v, roughness): x A, y B (the specular lobe
//                                is F0 A + B for a white environment), z C (the diffuse factor:
//                                the cosine-weighted mean of 1 - (1 - V.H)^5)
//   [PG_ENV_SPEC_OFF, ...)       prefiltered radiance, PG_ENV_SPEC_LEVELS levels; level k is
//                                (256 >> k) x (128 >> k), at least 64 x 32, for roughness
//                                k / (levels - 1)
#ifndef PG_ENVIRONMENT_GLSL
#define PG_ENVIRONMENT_GLSL

const float PG_ENV_PI = 3.14159265358979;
const uint PG_ENV_IRR_W = 32u, PG_ENV_IRR_H = 16u, PG_ENV_IRR_OFF = 0u;
const uint PG_ENV_LUT_N = 32u, PG_ENV_LUT_OFF = 512u;
const uint PG_ENV_SPEC_W = 256u, PG_ENV_SPEC_H = 128u, PG_ENV_SPEC_LEVELS = 9u, PG_ENV_SPEC_OFF = 1536u;
const uint PG_ENV_SPEC_MIN_W = 64u; // no level is smaller than 64 x 32 (bilinear near the poles)
const uint PG_ENV_TEXELS = 56832u;  // PG_ENV_SPEC_OFF + the specular levels

// Size of specular level k: (256 >> k) x (128 >> k), at least 64 x 32.
uvec2 pg_env_spec_size(uint k)
{
    return uvec2(max(PG_ENV_SPEC_W >> k, PG_ENV_SPEC_MIN_W), max(PG_ENV_SPEC_H >> k, PG_ENV_SPEC_MIN_W / 2u));
}

// Element offset of specular level k.
uint pg_env_spec_offset(uint k)
{
    uint off = PG_ENV_SPEC_OFF;
    for (uint i = 0u; i < k; i++) {
        uvec2 s = pg_env_spec_size(i);
        off += s.x * s.y;
    }
    return off;
}

vec2 pg_env_dir_to_uv(vec3 d)
{
    float u = 0.5 + atan(d.x, -d.z) * (0.5 / PG_ENV_PI);
    return vec2(u - floor(u), acos(clamp(d.y, -1.0, 1.0)) * (1.0 / PG_ENV_PI));
}

vec3 pg_env_uv_to_dir(vec2 uv)
{
    float phi = 2.0 * PG_ENV_PI * (uv.x - 0.5), theta = PG_ENV_PI * uv.y;
    return vec3(sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi));
}

// Ry(-r) d: the stored direction of world direction d under the rotation r.
vec3 pg_env_unrotate(vec3 d, float r)
{
    float c = cos(r), s = sin(r);
    return vec3(d.x * c - d.z * s, d.y, d.x * s + d.z * c);
}

// Bilinear texel of a w x h equirect level at element offset off.
vec3 pg_env_bilinear(uint off, uint w, uint h, vec2 uv)
{
    float x = uv.x * float(w) - 0.5;
    float y = clamp(uv.y * float(h) - 0.5, 0.0, float(h - 1u));
    float x0 = floor(x), y0 = floor(y);
    float fx = x - x0, fy = y - y0;
    int iw = int(w);
    uint i0 = uint((int(x0) % iw + iw) % iw), i1 = uint((int(x0) + 1 + iw) % iw);
    uint j0 = uint(y0), j1 = min(j0 + 1u, h - 1u);
    vec3 a = mix(PG_ENV_FETCH(off + j0 * w + i0).rgb, PG_ENV_FETCH(off + j0 * w + i1).rgb, fx);
    vec3 b = mix(PG_ENV_FETCH(off + j1 * w + i0).rgb, PG_ENV_FETCH(off + j1 * w + i1).rgb, fx);
    return mix(a, b, fy);
}

// The scene's source levels (scene/environment.h: level 0 w x h, each next level halved, at least
// 1 x 1, one after the other): level k's element offset, width and height.
uvec3 pg_env_src_level(uint k, uint w, uint h)
{
    uint off = 0u;
    for (uint i = 0u; i < k; i++) {
        off += w * h;
        w = max(w / 2u, 1u);
        h = max(h / 2u, 1u);
    }
    return uvec3(off, w, h);
}

// Source radiance at uv, bilinear in source level k (clamped to the `levels` there are).
vec3 pg_env_src_bilinear(uint k, vec2 uv, uint w, uint h, uint levels)
{
    uvec3 l = pg_env_src_level(min(k, levels - 1u), w, h);
    return pg_env_bilinear(l.x, l.y, l.z, uv);
}

// Source radiance toward unit direction d (stored axes) at a fractional level (linear between two).
vec3 pg_env_src_lod(vec3 d, float lod, uint w, uint h, uint levels)
{
    vec2 uv = pg_env_dir_to_uv(d);
    float l = clamp(lod, 0.0, float(levels - 1u));
    uint l0 = uint(l);
    return mix(pg_env_src_bilinear(l0, uv, w, h, levels), pg_env_src_bilinear(l0 + 1u, uv, w, h, levels),
               l - float(l0));
}

// The view direction the environment term uses: V itself, or where an interpolated or normal-mapped
// normal faces away from the eye (N.V < 0.01) V bent toward N until N.V = 0.01, so the reflected
// direction and the half vectors stay above the surface (the split-sum and the reference's Monte
// Carlo see the same V; the point lights' model clamps N.V instead, lighting.glsl).
vec3 pg_env_view(vec3 N, vec3 V)
{
    float nv = dot(N, V);
    return nv >= 0.01 ? V : normalize(V + (0.01 - nv) * N);
}

#ifdef PG_ENVIRONMENT_FILTERED
// Diffuse radiance for albedo 1 from the environment around unit normal n (world space).
vec3 pg_env_irradiance(vec3 n)
{
    vec2 uv = pg_env_dir_to_uv(pg_env_unrotate(n, frame.environment.y));
    return pg_env_bilinear(PG_ENV_IRR_OFF, PG_ENV_IRR_W, PG_ENV_IRR_H, uv);
}

// Prefiltered radiance toward unit direction r at a perceptual roughness (linear between levels).
vec3 pg_env_specular(vec3 r, float roughness)
{
    vec2 uv = pg_env_dir_to_uv(pg_env_unrotate(r, frame.environment.y));
    float l = clamp(roughness, 0.0, 1.0) * float(PG_ENV_SPEC_LEVELS - 1u);
    uint l0 = min(uint(l), PG_ENV_SPEC_LEVELS - 1u), l1 = min(l0 + 1u, PG_ENV_SPEC_LEVELS - 1u);
    uvec2 s0 = pg_env_spec_size(l0), s1 = pg_env_spec_size(l1);
    vec3 a = pg_env_bilinear(pg_env_spec_offset(l0), s0.x, s0.y, uv);
    vec3 b = pg_env_bilinear(pg_env_spec_offset(l1), s1.x, s1.y, uv);
    return mix(a, b, l - float(l0));
}

// The split-sum factors (A, B, C) at n.v and roughness (bilinear, clamped to the table).
vec3 pg_env_lut(float n_dot_v, float roughness)
{
    float n = float(PG_ENV_LUT_N);
    float x = clamp(n_dot_v * n - 0.5, 0.0, n - 1.0), y = clamp(roughness * n - 0.5, 0.0, n - 1.0);
    uint i0 = uint(x), j0 = uint(y), i1 = min(i0 + 1u, PG_ENV_LUT_N - 1u), j1 = min(j0 + 1u, PG_ENV_LUT_N - 1u);
    float fx = x - float(i0), fy = y - float(j0);
    vec3 a = mix(PG_ENV_FETCH(PG_ENV_LUT_OFF + j0 * PG_ENV_LUT_N + i0).xyz,
                 PG_ENV_FETCH(PG_ENV_LUT_OFF + j0 * PG_ENV_LUT_N + i1).xyz, fx);
    vec3 b = mix(PG_ENV_FETCH(PG_ENV_LUT_OFF + j1 * PG_ENV_LUT_N + i0).xyz,
                 PG_ENV_FETCH(PG_ENV_LUT_OFF + j1 * PG_ENV_LUT_N + i1).xyz, fx);
    return mix(a, b, fy);
}

// The environment's light leaving a shaded point toward the eye (V: unit, to the eye), times
// frame.environment.x. Lambert and Blinn-Phong: albedo x E(n)/pi (no specular term). PG_PBR: the
// split-sum (Karis 2013) of the glTF BRDF: c_diff (1 - F0) C E(n)/pi + prefiltered(R, roughness)
// (F0 A + B), times the occlusion (0 for an unlit surface).
vec3 pg_env_light(Surface s, vec3 V)
{
    vec3 N = s.normal;
    V = pg_env_view(N, V);
#ifdef PG_PBR
    float nv = clamp(dot(N, V), 0.0, 1.0);
    float rough = clamp(s.shininess, 0.0, 1.0);
    vec3 f0 = mix(vec3(0.04), s.albedo, s.specular);
    vec3 cdiff = s.albedo * (1.0 - s.specular);
    vec3 abc = pg_env_lut(nv, rough);
    // the lobe's dominant direction (Lagarde and de Rousiers 2014, "Moving Frostbite to PBR", 4.9.3):
    // rough lobes lean from R toward N
    float a = rough * rough, smooth_ = 1.0 - a;
    vec3 R = normalize(mix(N, reflect(-V, N), smooth_ * (sqrt(smooth_) + a)));
    vec3 spec = pg_env_specular(R, rough) * (f0 * abc.x + abc.y);
    vec3 diff = cdiff * (1.0 - f0) * abc.z * pg_env_irradiance(N);
    return frame.environment.x * max(s.occlusion, 0.0) * (diff + spec);
#else
    return frame.environment.x * s.albedo * pg_env_irradiance(N);
#endif
}
#endif // PG_ENVIRONMENT_FILTERED

// ---- sampling (environment_filter.comp, reference_lighting.comp) ----
// GGX alpha of a perceptual roughness, clamped as lighting.glsl's pg_pbr_alpha.
float pg_env_alpha(float roughness)
{
    float r = clamp(roughness, 0.045, 1.0);
    return r * r;
}

// Height-correlated Smith visibility V = G / (4 n.l n.v) in its plain form (lighting.glsl's pbr term).
float pg_env_smith_v(float nl, float nv, float a)
{
    float a2 = a * a;
    float gv = nl * sqrt(nv * nv * (1.0 - a2) + a2), gl = nv * sqrt(nl * nl * (1.0 - a2) + a2);
    return gv + gl > 0.0 ? 0.5 / (gv + gl) : 0.0;
}

// Hammersley point i of n: (i / n, radical inverse of i).
vec2 pg_env_hammersley(uint i, uint n)
{
    return vec2((float(i) + 0.5) / float(n), float(bitfieldReverse(i)) * 2.3283064365386963e-10);
}

// A unit vector around n from (cos theta, phi) (an orthonormal frame of n, Frisvad/Duff et al. 2017).
vec3 pg_env_around(vec3 n, float cos_t, float phi)
{
    float sn = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (sn + n.z), b = n.x * n.y * a;
    vec3 t = vec3(1.0 + sn * n.x * n.x * a, sn * b, -sn * n.x);
    vec3 bt = vec3(b, sn + n.y * n.y * a, -n.y);
    float sin_t = sqrt(max(1.0 - cos_t * cos_t, 0.0));
    return normalize(t * (sin_t * cos(phi)) + bt * (sin_t * sin(phi)) + n * cos_t);
}

// A GGX half vector around n for alpha a (the distribution D(n.h) n.h) from xi in [0, 1)^2.
vec3 pg_env_ggx_half(vec3 n, float a, vec2 xi)
{
    float cos_t = sqrt((1.0 - xi.y) / (1.0 + (a * a - 1.0) * xi.y));
    return pg_env_around(n, cos_t, 2.0 * PG_ENV_PI * xi.x);
}

// A cosine-distributed direction around n from xi.
vec3 pg_env_cosine_dir(vec3 n, vec2 xi)
{
    return pg_env_around(n, sqrt(1.0 - xi.y), 2.0 * PG_ENV_PI * xi.x);
}

#endif
