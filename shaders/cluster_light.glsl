// cluster_light.glsl - what the light-assignment shaders share: the view-space sphere a light is
// tested with, and the layout of the per-cluster records. Include after common.glsl (with
// FRAME_UNIFORMS_BLOCK) and cluster.glsl.
//
// Per-cluster record (cluster_counts buffer, 16 bytes per cluster, index pg_cluster_index):
//   x offset of the cluster's list in cluster_lights, y lights stored there (what shading reads),
//   z lights that reach the cluster (raw count; y < z only when a per-cluster cap or the memory
//   budget dropped some: counted as overflow), w 0.
// Lists hold light indices in ascending order, so shading sums lights in the same order as naive.
#ifndef PG_CLUSTER_LIGHT_GLSL
#define PG_CLUSTER_LIGHT_GLSL

// vec4s per light in the assignment's spheres buffer: the sphere, and with PG_SPOT_LIGHTS the cone
// (pg_light_view_cone) and the ball (pg_light_view_sphere: apex and range; the sphere is then the
// bound of the ball within the cone, pg_cone_bound_sphere)
#ifdef PG_SPOT_LIGHTS
#define PG_LIGHT_RECORD_VEC4 3u
#else
#define PG_LIGHT_RECORD_VEC4 1u
#endif

// The sphere a light is tested against the cluster boxes with: centre in view space (taken
// camera-relative first, which keeps precision far from the origin), radius padded for the float
// error of that transform (|rel| * a few ulp). w <= 0 or NaN: the light reaches nothing (it
// contributes exactly 0 in the shading model).
vec4 pg_light_view_sphere(Light L)
{
    vec3 rel = L.pos_radius.xyz - frame.camera_pos.xyz;
    vec3 pv = mat3(frame.view) * rel;
    float r = L.pos_radius.w;
    float pad = r > 0.0 ? 1e-4 * r + 4e-7 * (length(rel) + length(L.pos_radius.xyz)) : 0.0;
    return vec4(pv, r + pad);
}

#ifdef PG_SPOT_LIGHTS
// The angle a cone test widens a spot light's outer cone by: far above the float rounding of the
// shading's cone factor and of the tests' angles.
const float PG_CONE_MARGIN = 2e-3;

// A spot light's cone in view space, from its spot record sp (lighting.glsl: axis x scale, offset =
// -cos(outer) x scale; the light adds exactly 0 where the angle from its axis exceeds the outer
// cone): (unit axis, cos(outer)). A light without a cone (record (0, 0, 0, 1)), a cone wider than a
// half-space or a NaN record gives w = 2: no cone test.
vec4 pg_light_view_cone(vec4 sp)
{
    float scale = length(sp.xyz);
    float cos_outer = -sp.w / scale;
    if (!(scale > 0.0) || !(cos_outer >= 0.0) || !(scale < 3.0e38)) return vec4(0.0, 0.0, 0.0, 2.0);
    vec3 axis = mat3(frame.view) * (sp.xyz / scale);
    return vec4(normalize(axis), min(cos_outer, 1.0));
}

// false when no point of the sphere (c, r) lies within the cone (pg_light_view_cone) of a light at
// `apex` (the same space): f(P) = cos(outer) |P x axis| - sin(outer) (P . axis), P relative to the
// apex, is the distance from P to the cone's boundary line in the plane of P and the axis, positive
// exactly where the angle of P from the axis exceeds the outer cone (outer <= 90 degrees). f is
// 1-Lipschitz, so f(c) > r puts the whole sphere outside the cone, where the light adds exactly 0.
// The margin, 2e-3 rad of angle (2e-3 |c - apex|) plus float rounding of the positions, lies far
// above the rounding of the shading's cone factor and of this test.
bool pg_cone_reaches_sphere(vec4 cone, vec3 apex, vec3 c, float r)
{
    if (!(cone.w <= 1.0)) return true;                 // no cone
    vec3 v = c - apex;
    float axial = dot(v, cone.xyz);
    float radial = length(cross(v, cone.xyz));         // no cancellation near the axis
    float sin_outer = sqrt(max(1.0 - cone.w * cone.w, 0.0));
    float f = cone.w * radial - sin_outer * axial;
    float margin = PG_CONE_MARGIN * length(v) + 1e-5 * (length(apex) + length(c)) + 1e-6;
    return !(f > r + margin);                          // NaN keeps the light
}

// A sphere holding every point a spot light lights: its ball (sph: view-space centre and padded
// radius r, pg_light_view_sphere; r_raw its unpadded range) within its cone (widened by
// PG_CONE_MARGIN to a). Up to 45 degrees the sphere through the apex and the rim of the cone's cap
// (centre apex + axis r / (2 cos a), radius r / (2 cos a)); from 45 to 60 degrees the sphere of
// the rim (centre apex + axis r cos a, radius r sin a); past 60 degrees, or without a cone, the ball,
// which is then the smaller. Both contain the apex, the rim and the cap. The pad the ball carries
// for the apex's rounding (sph.w - r_raw) is added again in full (the formulas scale it down), and
// the rounding of the centre.
vec4 pg_cone_bound_sphere(vec4 sph, float r_raw, vec4 cone)
{
    if (!(cone.w <= 1.0) || !(sph.w > 0.0)) return sph;
    float a = acos(cone.w) + PG_CONE_MARGIN;
    if (!(a < 1.0471975)) return sph;                  // 60 degrees
    float ca = cos(a), sa = sin(a);
    float r = sph.w;
    float off = a <= 0.78539816 ? r / (2.0 * ca) : r * ca;
    float rb = a <= 0.78539816 ? off : r * sa;
    vec3 c = sph.xyz + cone.xyz * off;
    float pad = max(sph.w - r_raw, 0.0) + 1e-5 * rb + 1e-6 * (length(c) + length(sph.xyz));
    return vec4(c, rb + pad);
}
#endif

#endif
