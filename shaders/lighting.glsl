// lighting.glsl - the light models: Lambert, the reference point-light model (CIS 565):
//   contribution = color * max(dot(N, L), 0) * clamp(1 - (d/R)^4, 0, 1) / max(d^2, dmin^2)
// With PG_GLTF_FALLOFF (a scene with KHR_lights_punctual lights) the window is squared, the
// extension's recommended falloff, for every light: clamp(1 - (d/R)^4, 0, 1)^2. The window's R is
// the light's color.w (Light, common.glsl), its cut-off range pos_radius.w.
// d >= R contributes exactly 0 (this also makes R = 0 contribute 0 instead of 0/0); the
// 1/d^2 term is bounded by 1/dmin^2 (dmin = frame.light_params.w = PG_LIGHT_MIN_DISTANCE) so a
// light lying on the surface gives a finite value. Blinn-Phong adds
//   specular * max(dot(N, H), 0)^shininess * max(dot(N, L), 0) * the same attenuation.
//
// Evaluated with one transcendental per light: (d/R)^4 = (d^2 / R^2)^2 with
// 1/R^2 known per light, 1/max(d^2, dmin^2) = min((1/d)^2, 1/dmin^2) and L = Ld/d from one
// inversesqrt, instead of a square root and three divisions. The same model; only the rounding
// differs (C twin and its bounds: tests/test_numeric.c att_float). Two forms share that arithmetic
// (pg_light_term): pg_accumulate_light_rel returns early for a light out of range or outside its
// cone (the per-pixel loops, where most lights of a list miss the pixel), pg_accumulate_light_rel_select evaluates
// every light and adds exactly 0 for one out of range (the tiled loop, whose lights were culled
// against the tile and mostly reach the pixel: no branch). Adding +0 leaves the sum bit-identical to
// skipping the light (light colours are finite and >= 0; the select, not a multiply, keeps an Inf
// or NaN of an out-of-range light out of the sum), so every shading pass sums bit-identically.

// Spot lights (PG_SPOT_LIGHTS, a scene with KHR_lights_punctual spot lights): every light i has a
// spot record after the lights, lights[frame.counts.x + i].pos_radius = (axis x scale, offset),
// with the extension's scale = 1 / max(cos(inner) - cos(outer), 1e-3) and offset = -cos(outer) x
// scale; the light is multiplied by clamp(dot(axis, -L) x scale + offset, 0, 1)^2. A light that is
// not a spot has (0, 0, 0, 1): a factor of exactly 1. The clusters bin the light's sphere (a
// superset of its cone). PG_SPOT_OF(i) is light i's record, (0, 0, 0, 1) without spot lights.
#ifdef PG_SPOT_LIGHTS
#define PG_SPOT_OF(i) (lights[frame.counts.x + (i)].pos_radius)
#else
#define PG_SPOT_OF(i) vec4(0.0, 0.0, 0.0, 1.0)
#endif
float pg_spot_factor(vec4 sp, vec3 Ld) // Ld = light - P
{
    float cd = -dot(sp.xyz, Ld) * inversesqrt(max(dot(Ld, Ld), 1e-37));
    float t = clamp(cd + sp.w, 0.0, 1.0);
    return t * t;
}

// The light sums of a point. Lambert and Blinn-Phong: diffuse = sum colour x N.L x att, specular =
// sum colour x (N.H)^shininess x att, which the material multiplies once (pg_shade_lights). PG_PBR
// (below): one sum, diffuse, with the pixel's material applied per light (specular stays 0).
struct PgShade {
    vec3 diffuse;
    vec3 specular;
};

PgShade pg_shade_zero()
{
    PgShade z;
    z.diffuse = vec3(0.0);
    z.specular = vec3(0.0);
    return z;
}

#ifdef PG_PBR
// ---- the glTF 2.0 metallic-roughness BRDF (PG_PBR: shading "pbr") ------------------------------
// The glTF 2.0 specification, Appendix B: with a = roughness^2, c_diff = base x (1 - metallic),
// F0 = mix(0.04, base, metallic), F = F0 + (1 - F0) (1 - V.H)^5:
//   f = (1 - F) c_diff / pi + F D V
//   D = a^2 / (pi ((N.H)^2 (a^2 - 1) + 1)^2)                                  (GGX / Trowbridge-Reitz)
//   V = 0.5 / (N.L sqrt((N.V)^2 (1 - a^2) + a^2) + N.V sqrt((N.L)^2 (1 - a^2) + a^2))
//                                                        (height-correlated Smith, Heitz 2014)
// A light of intensity I (the extension's candela) at distance d adds f x I x N.L / d^2 (x its
// window and cone). Light.color holds colour x I / pi (the Lambert models' units), so the term
// summed here is pi f x color x N.L x att. F is linear in F0 (F = F0 (1 - w) + w, w = (1 - V.H)^5),
// so with the pixel's constants kd = c_diff (1 - F0) and ks = F0 (PgPbrPixel) one light adds
//   diffuse += color (kd (1 - w) N.L att + ks (1 - w) pi D V N.L att + w pi D V N.L att)
// and pg_shade_lights multiplies the sum by pg_pbr_lit (0 for an unlit surface). One running sum
// instead of three whose material terms multiply once after the loop (measured on an H200 at 100,000
// lights: the visibility pipeline's frame 5.82 -> 5.43 ms, 72 -> 64 registers in its tiled loop;
// docs/decisions/pbr-light-sums.md).
// pi D = k^2 with k = a / (|N x H|^2 + (N.H)^2 a^2) (the same D; |N x H|^2 = 1 - (N.H)^2 computed
// without its cancellation near N.H = 1). Roughness is clamped to >= PG_PBR_MIN_ROUGHNESS (a = 0
// is a mirror: an infinite peak); N.V to >= 0 (a normal-mapped pixel may face away from the eye).
// N.H enters squared, unclamped: where N.H < 0 (only when N.V < 0: a normal map turned a pixel's
// normal away from the eye, a case the specification leaves open) the lobe is mirrored instead of
// cut, so the result stays finite (|N x H|^2 + (N.H)^2 a^2 >= a^2) and continuous in the normal,
// and G-buffer quantization cannot flip it.
// Bounds (the lightcut's): k^2 <= 1 / a^2, V N.L <= 0.5 / a, so pi D V N.L <= 0.5 / a^3.
// C twin: renderer/common/brdf.c (tests/unit/test_numeric.c).
const float PG_PBR_MIN_ROUGHNESS = 0.045;

// The weight of the light sum: 1, but 0 for an unlit surface (KHR_materials_unlit: Surface.occlusion
// < 0; base 0 and metallic 1 make c_diff = F0 = 0, and this removes the last term, Schlick's
// grazing reflection).
float pg_pbr_lit(Surface s)
{
    return s.occlusion < 0.0 ? 0.0 : 1.0;
}

// The material's two colours (Surface.albedo the base colour, Surface.specular the metallic):
// F0 = mix(0.04, base, metallic) and c_diff = base (1 - metallic). precise: the same rounding
// whether the material is a constant or read (see pg_shade_combine).
vec3 pg_pbr_f0(Surface s)
{
    precise vec3 f0 = mix(vec3(0.04), s.albedo, s.specular);
    return f0;
}

vec3 pg_pbr_cdiff(Surface s)
{
    precise vec3 cdiff = s.albedo * (1.0 - s.specular);
    return cdiff;
}

float pg_pbr_alpha(float roughness)
{
    float r = clamp(roughness, PG_PBR_MIN_ROUGHNESS, 1.0);
    return r * r;
}

// A pixel's constants of the light loop (pg_light_mat computes them once per pixel, outside the
// loop). fast_q (a^2 >= PG_PBR_FAST_Q_A2, roughness >= 0.5) picks q = |h|^2 - (N.h)^2 (1 - a^2),
// the same q for unit N, in 4 operations instead of the cross product's 11: its cancellation near
// N.H = 1 costs at most ~4 ulp x |h|^2 / q <= 4 ulp / a^2 = 64 ulp (4e-6) relative there, and the
// max with a^2 |h|^2 (q's lower bound) keeps the lightcut's bound. Smoother surfaces keep the cross
// product (at a = 0.002 the short form would be 4% off at the peak).
const float PG_PBR_FAST_Q_A2 = 0.0625;
struct PgPbrPixel {
    vec3 kd;     // c_diff (1 - F0): the diffuse term's colour
    vec3 ks;     // F0: the specular term's colour
    float a;     // GGX alpha = roughness^2 (clamped)
    float a2;
    float b2;    // 1 - a^2
    float ndv;   // max(N.V, 0)
    float gv;    // sqrt(ndv^2 (1 - a^2) + a^2): the view's factor of the Smith denominator
    bool fast_q;
};

// Surface.specular is the pbr model's metallic, Surface.shininess its roughness.
PgPbrPixel pg_pbr_pixel(Surface s, vec3 V)
{
    PgPbrPixel m;
    vec3 N = s.normal;
    m.ks = pg_pbr_f0(s);
    precise vec3 kd = pg_pbr_cdiff(s) * (1.0 - m.ks);
    m.kd = kd;
    m.a = pg_pbr_alpha(s.shininess);
    m.a2 = m.a * m.a;
    m.b2 = 1.0 - m.a2;
    m.ndv = max(dot(N, V), 0.0);
    m.gv = sqrt(m.ndv * m.ndv * m.b2 + m.a2);
    m.fast_q = m.a2 >= PG_PBR_FAST_Q_A2;
    return m;
}

// One light of colour c reaching the point from unit direction L with attenuation att (N.L > 0).
void pg_light_pbr(vec3 c, float att, vec3 L, vec3 N, vec3 V, PgPbrPixel m, inout PgShade acc)
{
    float ndl = max(dot(N, L), 0.0);
    // with the unnormalised half vector h = L + V (|h|^2 = 2 V.h for unit L, V): k = a |h|^2 / q,
    // q = |N x h|^2 + (N.h)^2 a^2, and V.H = sqrt(V.h / 2); pi D V N.L att = 0.5 N.L att (a |h|^2)^2 /
    // (q^2 den): one division and no normalisation of h (q = 0 only where L = -V: 0 there)
    vec3 h = L + V;
    float hh = dot(h, h);                    // 2 (1 + V.L) = 4 (V.H)^2
    float nh = dot(N, h);
    float q;                                 // >= a^2 |h|^2: finite, and continuous in N
    if (m.fast_q) {
        q = max(hh - nh * nh * m.b2, m.a2 * hh);
    } else {
        vec3 nxh = cross(N, h);
        q = dot(nxh, nxh) + nh * nh * m.a2;
    }
    float num = m.a * hh;
    float den = ndl * m.gv + m.ndv * sqrt(ndl * ndl * m.b2 + m.a2);
    float qd = q * q * den;
    float spec = qd > 0.0 ? 0.5 * ndl * att * num * num / qd : 0.0;
    float t = 1.0 - min(0.5 * sqrt(hh), 1.0); // 1 - V.H, V.H = |h| / 2
    float t2 = t * t;
    float w = t2 * t2 * t;
    float dw = ndl * att, sw = spec * w;
    acc.diffuse += c * (m.kd * (dw - dw * w) + m.ks * (spec - sw) + sw);
}
#endif

// A pixel's material inputs of the light loops, computed once per pixel (pg_light_mat): Blinn-Phong's
// exponent (Surface.shininess), and the pbr constants.
struct PgLightMat {
    float shininess;
#ifdef PG_PBR
    PgPbrPixel pbr;
#endif
};

PgLightMat pg_light_mat(Surface s, vec3 V)
{
    PgLightMat m;
    m.shininess = s.shininess;
#ifdef PG_PBR
    m.pbr = pg_pbr_pixel(s, V);
#endif
    return m;
}

// 1/R^2 of a light, capped at FLT_MAX: R^2 below 2^-128 (R < ~1e-19) gives a finite factor, never
// 0 * Inf (such a light reaches only points within R of it, where the falloff stays in [0, 1]).
float pg_light_inv_r2(float R2)
{
    return min(1.0 / R2, 3.40282347e+38);
}

// The diffuse weight max(dot(N, L), 0) * att of a light at Ld = light - P (d2 = |Ld|^2 < R^2 for a
// meaningful value), and its attenuation att and direction L (for Blinn-Phong).
float pg_light_term(vec3 Ld, float d2, float inv_r2, vec3 N, float inv_md2, out float att, out vec3 L)
{
    float t = d2 * inv_r2;                // (d/R)^2
    float falloff = clamp(1.0 - t * t, 0.0, 1.0);
#ifdef PG_GLTF_FALLOFF
    falloff *= falloff;
#endif
    float rs = inversesqrt(d2);           // 1/d: +Inf at d = 0 (or d^2 flushed to 0)
    bool dir = rs <= 3.40282347e+38;      // false: the light is on the point, taken as head-on (L = N)
    att = falloff * min(rs * rs, inv_md2);
#if defined(PG_BLINN_PHONG) || defined(PG_PBR)
    L = dir ? Ld * rs : N;
    float ndl = max(dot(N, L), 0.0);
#else
    L = N;                                // unused
    float ndl = dir ? max(dot(N, Ld) * rs, 0.0) : max(dot(N, N), 0.0);
#endif
    return ndl * att;
}

// Blinn-Phong's term of the light (nothing for Lambert), with N.L as a factor: it fades to 0 as the
// light grazes the surface instead of stopping at N.L = 0 (a step that a normal off by a rounding
// could put on either side: 11 display steps between an H100's naive and deferred_packed images).
void pg_light_specular(vec3 color, float att, vec3 L, vec3 N, vec3 V, float shininess, inout PgShade acc)
{
#ifdef PG_BLINN_PHONG
    float nl = dot(N, L);
    if (nl > 0.0) {
        vec3 H = normalize(L + V);
        acc.specular += color * (pow(max(dot(N, H), 0.0), shininess) * att * nl);
    }
#endif
}

#ifdef PG_STOCHASTIC_CULL
// Stochastic light culling (shaders/stochastic_lights.comp): a kept light counts 1/p times, p =
// min(1, lum(colour) att / tau) its probability of being kept at this point (the lists and the range
// test use the light's random range; att uses its true range). Unbiased: E = p x f/p = f.
float pg_sc_rescale(vec3 color, float att)
{
    float p = min(1.0, pg_luminance(color) * att / (float(PG_SC_TAU_MICRO) * 1e-6));
    return p > 0.0 ? 1.0 / p : 0.0;
}
#define PG_SC_COLOR(c, att) ((c) * pg_sc_rescale((c), (att)))
#else
#define PG_SC_COLOR(c, att) (c)
#endif

// One light, as the inner loops read it: rel = its centre camera-relative (world - cam), R2 = R^2,
// inv_r2 = pg_light_inv_r2(R2). P camera-relative; inv_md2 = 1 / dmin^2.
void pg_accumulate_light_rel(vec3 rel, float R2, float inv_r2, vec3 color, vec4 spot, vec3 P, vec3 N, vec3 V,
                             PgLightMat m, float inv_md2, inout PgShade acc)
{
    vec3 Ld = rel - P;
    float d2 = dot(Ld, Ld);
    if (!(d2 < R2)) return;               // outside range (and R = 0, and NaN)
#ifdef PG_SPOT_LIGHTS
    float cone = pg_spot_factor(spot, Ld);
    if (cone == 0.0) return;              // outside the cone: it would add exactly 0
#endif
    float att;
    vec3 L;
    float w = pg_light_term(Ld, d2, inv_r2, N, inv_md2, att, L);
    vec3 c = PG_SC_COLOR(color, att);     // the stochastic rescale sees the light without its cone
#ifdef PG_SPOT_LIGHTS
    c *= cone;
#endif
#ifdef PG_PBR
    if (w > 0.0) pg_light_pbr(c, att, L, N, V, m.pbr, acc);
#else
    acc.diffuse += c * w;
    pg_light_specular(c, att, L, N, V, m.shininess, acc);
#endif
}

// The same sum without a branch: a light out of range adds exactly 0.
void pg_accumulate_light_rel_select(vec3 rel, float R2, float inv_r2, vec3 color, vec4 spot, vec3 P, vec3 N, vec3 V,
                                    PgLightMat m, float inv_md2, inout PgShade acc)
{
    vec3 Ld = rel - P;
    float d2 = dot(Ld, Ld);
    bool in_range = d2 < R2;              // false outside range (and for R = 0, and NaN)
    float att;
    vec3 L;
    float w = pg_light_term(Ld, d2, inv_r2, N, inv_md2, att, L);
    vec3 c = PG_SC_COLOR(color, att);
#ifdef PG_SPOT_LIGHTS
    c *= pg_spot_factor(spot, Ld);
#endif
#ifdef PG_PBR
    if (in_range && w > 0.0) pg_light_pbr(c, att, L, N, V, m.pbr, acc);
#else
    acc.diffuse += c * (in_range ? w : 0.0);
    if (in_range) pg_light_specular(c, att, L, N, V, m.shininess, acc);
#endif
}

// Two lights of the tiled loop at once (Lambert without spot lights or the stochastic rescale: PG_LAMBERT_PAIRS):
// pg_accumulate_light_rel_select's arithmetic for each light, lane by lane of a vec2 (the same
// operations in the same order: the offset, d^2, the range test, the falloff, the clamped 1/d^2,
// N.L from the one inversesqrt, a light on the point taken head-on), light 0 added before light 1:
// the same sum, bit for bit (the tiled loop's tests compare it with the per-pixel loop; no scene puts a
// light exactly on a shaded point, so tests/gpu/test_gpu_light_terms.c compares both on given inputs,
// that case included, and with the model in double). A light is
// (a, b) as the tiled loop stores it: a = (rel, 1/R_falloff^2), b = (colour, R^2). Measured on an
// H100 (docs/performance.md#two-lights-at-a-time-in-the-tiled-loop): 2.1-3.2% off the lighting pass
// (on lavapipe 5-10% slower: kept for the GPU).
#if !defined(PG_SPOT_LIGHTS) && !defined(PG_PBR) && !defined(PG_BLINN_PHONG) && !defined(PG_STOCHASTIC_CULL)
#define PG_LAMBERT_PAIRS
void pg_accumulate_lambert_pair(vec4 a0, vec4 b0, vec4 a1, vec4 b1, vec3 P, vec3 N, float inv_md2, inout PgShade acc)
{
    vec2 lx = vec2(a0.x - P.x, a1.x - P.x), ly = vec2(a0.y - P.y, a1.y - P.y), lz = vec2(a0.z - P.z, a1.z - P.z);
    vec2 d2 = lx * lx + ly * ly + lz * lz;
    bvec2 in_range = lessThan(d2, vec2(b0.w, b1.w));
    vec2 t = d2 * vec2(a0.w, a1.w);
    vec2 falloff = clamp(1.0 - t * t, 0.0, 1.0);
#ifdef PG_GLTF_FALLOFF
    falloff *= falloff;
#endif
    vec2 rs = inversesqrt(d2);
    bvec2 dir = lessThanEqual(rs, vec2(3.40282347e+38));
    vec2 att = falloff * min(rs * rs, vec2(inv_md2));
    vec2 ndl = mix(vec2(max(dot(N, N), 0.0)), max((N.x * lx + N.y * ly + N.z * lz) * rs, 0.0), dir);
    vec2 w = mix(vec2(0.0), ndl * att, in_range);
    acc.diffuse += b0.rgb * w.x;
    acc.diffuse += b1.rgb * w.y;
}
#endif

// P is camera-relative (world - cam); the light is moved into the same frame first.
// spot: the light's spot record (PG_SPOT_OF)
void pg_accumulate_light(Light light, vec4 spot, vec3 cam, vec3 P, vec3 N, vec3 V, PgLightMat m, float min_dist,
                         inout PgShade acc)
{
    float R = light.pos_radius.w;
    float R2 = R * R;
    float md2 = min_dist * min_dist;
    float Rt = light.color.w; // the falloff's range (pos_radius.w: where the light stops)
    float inv_r2 = pg_light_inv_r2(Rt * Rt);
    pg_accumulate_light_rel(light.pos_radius.xyz - cam, R2, inv_r2, light.color.rgb, spot, P, N, V, m,
                            1.0 / md2, acc);
}

// The colour of a shaded point from its summed light terms: every shading pass ends with this
// (shading.glsl, reference_lighting.comp), so they combine with the same operations.
// The lights' part of a shaded point's colour (pg_shade_combine adds ambient and emission): also
// one light's contribution alone (RIS, lightcut).
vec3 pg_shade_lights(Surface s, PgShade acc)
{
#ifdef PG_PBR
    return pg_pbr_lit(s) * acc.diffuse;
#else
    return s.albedo * acc.diffuse + s.specular * acc.specular;
#endif
}

// PG_PBR: the ambient term is a uniform environment of that radiance, with the split-sum
// integral of the specular lobe taken as F0 (c_diff + F0) and scaled by the occlusion texture.
vec3 pg_shade_combine(Surface s, PgShade acc, vec3 ambient)
{
#ifdef PG_PBR
    vec3 f0 = pg_pbr_f0(s);
    vec3 cdiff = pg_pbr_cdiff(s);
    // precise (here and in pg_pbr_pixel): no fused multiply-adds, so a pass where occlusion or the
    // lit weight is a constant (forward without occlusion textures) rounds exactly as one that reads
    // them (the reference)
    precise vec3 c = pg_shade_lights(s, acc) + (cdiff + f0) * (ambient * max(s.occlusion, 0.0)) + s.emissive;
    return c;
#else
    return s.albedo * (acc.diffuse + ambient) + s.specular * acc.specular + s.emissive;
#endif
}
