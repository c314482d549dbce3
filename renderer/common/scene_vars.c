/* scene_vars.c - the renderer's compile variables (scene_vars.h). */
#include "scene_vars.h"

#include <stddef.h>

/* one table for both directions: name <-> field of pg_scene_features */
static const struct {
    const char *name;
    size_t offset;
} k_features[] = {
    {"has_textures", offsetof(pg_scene_features, has_textures)},
    {"has_normal_maps", offsetof(pg_scene_features, has_normal_maps)},
    {"has_alpha_mask", offsetof(pg_scene_features, has_alpha_mask)},
    {"has_blend", offsetof(pg_scene_features, has_blend)},
    {"has_emissive", offsetof(pg_scene_features, has_emissive)},
    {"has_vertex_colors", offsetof(pg_scene_features, has_vertex_colors)},
    {"has_uv1", offsetof(pg_scene_features, has_uv1)},
    {"has_uv_transform", offsetof(pg_scene_features, has_uv_transform)},
    {"has_file_lights", offsetof(pg_scene_features, has_file_lights)},
    {"has_spot_lights", offsetof(pg_scene_features, has_spot_lights)},
    {"has_metallic_roughness_tex", offsetof(pg_scene_features, has_metallic_roughness_tex)},
    {"has_occlusion_tex", offsetof(pg_scene_features, has_occlusion_tex)},
    {"has_unlit", offsetof(pg_scene_features, has_unlit)},
    {"has_environment", offsetof(pg_scene_features, has_environment)},
    {"has_animation", offsetof(pg_scene_features, has_animation)},
};
#define PG_VAR_AUTO_SHADING "auto_shading"

#define N_FEATURES (sizeof k_features / sizeof k_features[0])

pg_result pg_scene_vars_set(pg_compile_vars *vars, const pg_scene_features *features, uint32_t lights,
                            pg_error *err)
{
    /* spot lights: a spot record follows the lights (lighting.glsl), so the buffers hold twice */
    uint64_t records = features && features->has_spot_lights ? 2ull * lights : lights;
    pg_result r = pg_vars_set(vars, PG_VAR_LIGHTS, records, err);
    for (size_t i = 0; !r && i < N_FEATURES; i++) {
        const bool on = features && *(const bool *)((const char *)features + k_features[i].offset);
        r = pg_vars_set(vars, k_features[i].name, on, err);
    }
    /* the deformed vertex buffer (pipelines/fragments/geometry.json: count ["vertices"]) */
    if (!r) r = pg_vars_set(vars, "vertices", features && features->has_animation ? features->vertices : 0, err);
    if (!r) r = pg_vars_set(vars, PG_VAR_AUTO_SHADING, features ? features->auto_shading : PG_SHADING_LAMBERT, err);
    return r;
}

pg_scene_features pg_scene_features_of(const pg_declare_in *in)
{
    pg_scene_features f = {0};
    for (size_t i = 0; i < N_FEATURES; i++)
        *(bool *)((char *)&f + k_features[i].offset) = pg_var(in, k_features[i].name) != 0;
    int64_t a = pg_var(in, PG_VAR_AUTO_SHADING);
    f.auto_shading = (uint8_t)(a == PG_SHADING_BLINN_PHONG || a == PG_SHADING_PBR ? a : PG_SHADING_LAMBERT);
    return f;
}
