// lighting.glsl - the reference point-light model (CIS 565):
//   contribution = color * max(dot(N, L), 0) * clamp(1 - (d/R)^4, 0, 1) / max(d^2, dmin^2)
// d >= R contributes exactly 0 (this also makes R = 0 contribute 0 instead of 0/0); the
// 1/d^2 term is bounded by 1/dmin^2 (dmin = frame.light_params.w = PG_LIGHT_MIN_DISTANCE) so a
// light lying on the surface gives a finite value. Blinn-Phong adds
//   specular * max(dot(N, H), 0)^shininess * the same attenuation (only where N.L > 0).
//
// Evaluated with one transcendental per light in range (issue 13 item 3): (d/R)^4 = (d^2 / R^2)^2
// with 1/R^2 known per light, and 1/d (for L and for 1/d^2 = (1/d)^2) from one inversesqrt,
// instead of a square root and three divisions. The same model; only the rounding differs (C twin
// and its bounds: tests/test_numeric.c att_float). Every shading pass calls
// pg_accumulate_light_rel with the same operations, so their sums stay bit-identical.

struct PgShade {
    vec3 diffuse;
    vec3 specular;
};

// 1/R^2 of a light, capped at FLT_MAX: R^2 below 2^-128 (R < ~1e-19) gives a finite factor, never
// 0 * Inf (such a light reaches only points within R of it, where the falloff stays in [0, 1]).
float pg_light_inv_r2(float R2)
{
    return min(1.0 / R2, 3.40282347e+38);
}

// One light, as the inner loops read it: rel = its centre camera-relative (world - cam), R2 = R^2,
// inv_r2 = pg_light_inv_r2(R2). P camera-relative; md2 = dmin^2, inv_md2 = 1 / dmin^2.
void pg_accumulate_light_rel(vec3 rel, float R2, float inv_r2, vec3 color, vec3 P, vec3 N, vec3 V,
                             float shininess, float md2, float inv_md2, inout PgShade acc)
{
    vec3 Ld = rel - P;
    float d2 = dot(Ld, Ld);
    if (!(d2 < R2)) return;               // outside range (and R = 0, and NaN)
    float t = d2 * inv_r2;                // (d/R)^2
    float falloff = clamp(1.0 - t * t, 0.0, 1.0);
    float rs = inversesqrt(d2);           // 1/d: +Inf at d = 0 (or d^2 flushed to 0)
    bool dir = rs <= 3.40282347e+38;      // false: the light is on the point, taken as head-on (L = N)
    float att = falloff * (d2 >= md2 ? rs * rs : inv_md2);
#ifdef PG_BLINN_PHONG
    vec3 L = dir ? Ld * rs : N;
    float ndl = max(dot(N, L), 0.0);
#else
    float ndl = dir ? max(dot(N, Ld) * rs, 0.0) : max(dot(N, N), 0.0);
#endif
    acc.diffuse += color * (ndl * att);
#ifdef PG_BLINN_PHONG
    if (ndl > 0.0) {
        vec3 H = normalize(L + V);
        acc.specular += color * (pow(max(dot(N, H), 0.0), shininess) * att);
    }
#endif
}

// P is camera-relative (world - cam); the light is moved into the same frame first.
void pg_accumulate_light(Light light, vec3 cam, vec3 P, vec3 N, vec3 V, float shininess, float min_dist,
                         inout PgShade acc)
{
    float R = light.pos_radius.w;
    float R2 = R * R;
    float md2 = min_dist * min_dist;
    pg_accumulate_light_rel(light.pos_radius.xyz - cam, R2, pg_light_inv_r2(R2), light.color.rgb, P, N, V,
                            shininess, md2, 1.0 / md2, acc);
}

// The colour of a shaded point from its summed light terms: every shading pass ends with this
// (shading.glsl, reference_lighting.comp), so they combine with the same operations.
vec3 pg_shade_combine(Surface s, PgShade acc, vec3 ambient)
{
    return s.albedo * (acc.diffuse + ambient) + s.specular * acc.specular + s.emissive;
}
