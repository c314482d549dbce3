// octahedral.glsl - octahedral unit-vector encoding (Cigolle et al. 2014, "A Survey of Efficient
// Representations for Independent Unit Vectors"), for the packed G-buffer normal.
// No #version. renderer/common/cluster_math.c is the C twin (same formulas and order, float32);
// tests/test_numeric.c measures the angular error per bit depth over millions of directions.
//
// The fold of the lower hemisphere uses a sign that is +1 for +0.0 and -0.0 (never 0), so the
// axis directions round-trip: -Z encodes to (1,1) and every corner (+-1,+-1) decodes to -Z.
#ifndef PG_OCTAHEDRAL_GLSL
#define PG_OCTAHEDRAL_GLSL

// n (any length, normally unit) -> [-1,1]^2. Zero, NaN or infinite components -> (0,0), which
// decodes to +Z (a defined unit result rather than NaN).
vec2 pg_oct_encode(vec3 n)
{
    float s = abs(n.x) + abs(n.y) + abs(n.z);
    if (!(s > 0.0 && s <= 3.40282347e+38)) return vec2(0.0);
    vec2 p = n.xy / s;
    if (n.z < 0.0) {
        vec2 sg = vec2(p.x >= 0.0 ? 1.0 : -1.0, p.y >= 0.0 ? 1.0 : -1.0);
        p = (1.0 - abs(p.yx)) * sg;
    }
    return p;
}

// [-1,1]^2 -> unit vector. e is clamped to [-1,1] first (NaN -> 0); for any input the folded
// vector has |x|+|y|+|z| = 1, so its length is >= 1/sqrt(3) and normalize never divides by 0:
// the result is always a finite unit vector.
vec3 pg_oct_decode(vec2 e)
{
    e = vec2(e.x > -1.0 ? (e.x < 1.0 ? e.x : 1.0) : (e.x <= -1.0 ? -1.0 : 0.0),
             e.y > -1.0 ? (e.y < 1.0 ? e.y : 1.0) : (e.y <= -1.0 ? -1.0 : 0.0));
    vec3 v = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    float t = max(-v.z, 0.0);
    v.x += v.x >= 0.0 ? -t : t;
    v.y += v.y >= 0.0 ? -t : t;
    return normalize(v);
}

// 32-bit packed normal: two unorm16 of (encode * 0.5 + 0.5); packUnorm2x16 rounds
// round(clamp(c, 0, 1) * 65535). Max angular error sqrt(18)/65535 = 6.5e-5 rad (0.0037 deg), at
// the face centres (test_numeric prints the table per bit depth). Exact halves (e.g. e = 0 ->
// 32767.5) may round either way on a GPU; both neighbours decode within 1.6e-5 rad.
uint pg_oct_pack_unorm16(vec3 n)
{
    return packUnorm2x16(pg_oct_encode(n) * 0.5 + 0.5);
}

vec3 pg_oct_unpack_unorm16(uint p)
{
    return pg_oct_decode(unpackUnorm2x16(p) * 2.0 - 1.0);
}

#endif // PG_OCTAHEDRAL_GLSL
