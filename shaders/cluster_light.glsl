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

#endif
