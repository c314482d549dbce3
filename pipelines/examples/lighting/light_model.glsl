// light_model.glsl - the light model of the user lighting example (pipelines/examples/lighting/),
// included by lighting.comp and lighting_tiled.comp from their own folder:
//   colour x max(N.L, 0) x f(d),   f(d) = max(1 - (d/R)^2, 0)^2 / (1 + d^2),
// R = the light's range (pos_radius.w): a softened inverse square that reaches 0 at the range.
// Written as the built-in passes write theirs (lighting.glsl pg_light_term): from d^2 and a 1/R^2
// the caller computes once per light (once per tile in the tiled loop), one inversesqrt for the
// direction and one division for the falloff; no length(), no d/R.
#ifndef EXAMPLE_LIGHT_MODEL_GLSL
#define EXAMPLE_LIGHT_MODEL_GLSL

// d = light centre - point (any common origin), R2 = R^2, inv_r2 = 1 / R^2; N unit.
vec3 example_light(vec3 d, float R2, float inv_r2, vec3 color, vec3 N)
{
    float d2 = dot(d, d);
    if (!(d2 < R2) || !(d2 > 0.0)) return vec3(0.0); // out of range (R = 0, NaN), or on the point
    float w = 1.0 - d2 * inv_r2;
    float ndl = max(dot(N, d) * inversesqrt(d2), 0.0);
    return color * (ndl * (w * w / (1.0 + d2)));
}

#endif
