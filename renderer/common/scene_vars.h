/* scene_vars.h - the renderer's compile variables: the light count and the scene's features,
 * named, so the graph compiler can size buffers (["lights", 32]) and the pass types' declare()
 * can leave out what the scene does not use, without the graph knowing lights or scenes. */
#ifndef PG_SCENE_VARS_H
#define PG_SCENE_VARS_H

#include "pass_api.h"
#include "scene_features.h"

#ifdef __cplusplus
extern "C" {
#endif

#define PG_VAR_LIGHTS "lights" /* the number of light records (count terms ["lights", N]): the light
                                  count, twice it in a scene with spot lights (each light's spot
                                  record follows the lights: lights[count + i], lighting.glsl) */

/* Sets "lights", one 0/1 variable per scene feature ("has_textures", "has_normal_maps",
 * "has_alpha_mask", "has_blend", "has_emissive", "has_vertex_colors", "has_uv1",
 * "has_uv_transform", "has_file_lights", "has_spot_lights", "has_metallic_roughness_tex",
 * "has_occlusion_tex", "has_unlit") and "auto_shading" (PG_SHADING_*, the model shading "auto"
 * picks); features may be NULL (none: Lambert). */
pg_result pg_scene_vars_set(pg_compile_vars *vars, const pg_scene_features *features, uint32_t lights,
                            pg_error *err);
/* In declare(): the scene features the caller set (missing variables read as false). */
pg_scene_features pg_scene_features_of(const pg_declare_in *in);
/* In declare(): the light records (the light count, twice it with spot lights; 0 when unset). */
static inline uint32_t pg_lights_of(const pg_declare_in *in)
{
    return (uint32_t)pg_var(in, PG_VAR_LIGHTS);
}

#ifdef __cplusplus
}
#endif
#endif
