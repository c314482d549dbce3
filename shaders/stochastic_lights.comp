#version 460
// stochastic_lights.comp - stochastic light culling (after Tokuyoshi & Harada, "Stochastic Light
// Culling", JCGT 5(1), 2016): every light gets a random range from one uniform number xi of its own
// (a hash of light index, frame.noise.x = sample index and frame.noise.y = seed). With the light's
// luminance I, its attenuation A(d) = clamp(1 - (d/R)^4, 0, 1) / max(d^2, dmin^2) (lighting.glsl) and
// the threshold tau (PG_SC_TAU_MICRO, millionths as a float literal), the light is kept at a point at distance d with
// probability p(d) = min(1, I A(d) / tau), i.e. where I A(d) >= xi tau: inside the range
// r(xi) = sup { d in [0, R] : I A(d) >= xi tau } (A decreases with d: bisection, 40 steps, the upper
// end kept so the range never falls short). The shading pass divides a kept light's contribution
// by p(d) (lighting.glsl, PG_STOCHASTIC_CULL), so every pixel's expectation is the exact sum; where
// I A >= tau (p = 1) the light is exact, beyond it a light adds either 0 or at most tau x its BRDF
// factor: no fireflies. R is where the light stops (pos_radius.w), the window's range Rf its
// color.w (equal for generated lights; PG_GLTF_FALLOFF squares the window, as lighting.glsl does).
// Output per light: pos_radius = (position, r(xi)) (what the cluster assignment tests), color =
// (rgb, Rf) (what the falloff uses).
#include "common.glsl"
FRAME_UNIFORMS_BLOCK

layout(local_size_x = 64) in;
layout(set = 1, binding = 0, std430) readonly buffer Lights { Light lights[]; };
layout(set = 1, binding = 1, std430) writeonly buffer Culled { Light culled[]; };

float attenuation(float d, float Rf, float md)
{
    float t = (d * d) / (Rf * Rf);
    float w = clamp(1.0 - t * t, 0.0, 1.0);
#ifdef PG_GLTF_FALLOFF
    w *= w;
#endif
    return w / max(d * d, md * md);
}

void main()
{
    uint i = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 64u;
    if (i >= frame.counts.x) return;
    Light L = lights[i];
    float R = L.pos_radius.w, Rf = L.color.w;
    float I = pg_luminance(L.color.rgb);
    float tau = float(PG_SC_TAU_MICRO) * 1e-6;
    float md = frame.light_params.w;
    // xi in (0, 1]
    float xi = float((pg_pcg(i + pg_pcg(frame.noise.x + pg_pcg(frame.noise.y ^ 0x5bd1e995u))) >> 8) + 1u) * (1.0 / 16777216.0);
    float r = R;
    if (R > 0.0 && I > 0.0 && !isinf(R) && !isnan(R)) {
        float want = xi * tau / I; // keep where A(d) >= want
        if (attenuation(0.0, Rf, md) < want) {
            r = 0.0;               // kept nowhere
        } else if (attenuation(R * 0.999999, Rf, md) >= want) {
            r = R;                 // kept everywhere it reaches
        } else {
            float lo = 0.0, hi = R;
            // a range spanning many orders of magnitude (a file light without a range: up to 3e38)
            // is first narrowed by geometric means, so 40 halvings then reach float precision
            for (int k = 0; k < 96 && hi > 1e4 * max(lo, md); k++) {
                float mid = sqrt(max(lo, md)) * sqrt(hi);
                if (attenuation(mid, Rf, md) >= want) lo = mid;
                else hi = mid;
            }
            for (int k = 0; k < 40; k++) {
                float mid = 0.5 * (lo + hi);
                if (attenuation(mid, Rf, md) >= want) lo = mid;
                else hi = mid;
            }
            r = hi;
        }
    }
    culled[i].pos_radius = vec4(L.pos_radius.xyz, r);
    culled[i].color = L.color;
#ifdef PG_SPOT_LIGHTS
    culled[frame.counts.x + i] = lights[frame.counts.x + i]; // the spot records follow the lights
#endif
}
