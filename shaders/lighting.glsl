// lighting.glsl - the reference point-light model (CIS 565):
//   contribution = color * max(dot(N, L), 0) * clamp(1 - (d/R)^4, 0, 1) / max(d^2, dmin^2)
// d >= R contributes exactly 0 (this also makes R = 0 contribute 0 instead of 0/0); the
// 1/d^2 term is bounded by 1/dmin^2 (dmin = frame.light_params.w = PG_LIGHT_MIN_DISTANCE) so a
// light lying on the surface gives a finite value. Blinn-Phong adds
//   specular * max(dot(N, H), 0)^shininess * the same attenuation (only where N.L > 0).

struct PgShade {
    vec3 diffuse;
    vec3 specular;
};

// P is camera-relative (world - cam); the light is moved into the same frame first.
void pg_accumulate_light(Light light, vec3 cam, vec3 P, vec3 N, vec3 V, float shininess, float min_dist,
                         inout PgShade acc)
{
    vec3 Ld = (light.pos_radius.xyz - cam) - P;
    float d2 = dot(Ld, Ld);
    float R = light.pos_radius.w;
    if (!(d2 < R * R)) return;            // outside range (and R = 0, and NaN)
    float d = sqrt(d2);
    float ratio = d / R;
    float r2 = ratio * ratio;
    float falloff = clamp(1.0 - r2 * r2, 0.0, 1.0);
    float att = falloff / max(d2, min_dist * min_dist);
    vec3 L = d > 0.0 ? Ld / d : N;        // light exactly on the point: treat as head-on
    float ndl = max(dot(N, L), 0.0);
    acc.diffuse += light.color.rgb * (ndl * att);
#ifdef PG_BLINN_PHONG
    if (ndl > 0.0) {
        vec3 H = normalize(L + V);
        acc.specular += light.color.rgb * (pow(max(dot(N, H), 0.0), shininess) * att);
    }
#endif
}

// The colour of a shaded point from its summed light terms: every shading pass ends with this
// (shading.glsl, reference_lighting.comp), so they combine with the same operations.
vec3 pg_shade_combine(Surface s, PgShade acc, vec3 ambient)
{
    return s.albedo * (acc.diffuse + ambient) + s.specular * acc.specular + s.emissive;
}
