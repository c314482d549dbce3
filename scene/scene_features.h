/* scene_features.h - what a scene's materials and streams use; the renderer hands them to the
 * compiler as compile variables (renderer/common/scene_vars.h) and its passes leave out shader
 * features and work the scene cannot need. */
#ifndef PG_SCENE_FEATURES_H
#define PG_SCENE_FEATURES_H

#include <stdbool.h>
#include <stdint.h>

typedef struct pg_scene_features {
    bool has_textures;    /* any base-colour texture */
    bool has_normal_maps; /* any material with a normal map (and tangents) */
    bool has_alpha_mask;  /* any alpha-mask material */
    bool has_blend;       /* any alphaMode BLEND material (transparent pass) */
    bool has_emissive;    /* any material with a non-zero emissive factor */
    bool has_vertex_colors; /* scene->colors present (COLOR_0 on a drawn primitive) */
    bool has_uv1;         /* scene->uv1 present and a texture reads TEXCOORD_1 */
    bool has_uv_transform;/* any KHR_texture_transform on a used texture */
    bool has_file_lights; /* KHR_lights_punctual lights (scene->n_lights > 0): their table is
                             uploaded, light_animate reads it, shading uses the glTF falloff */
    bool has_spot_lights; /* some of them are spot lights: every light gets a spot record after the
                             lights (the "lights" variable counts records: twice the lights) */
} pg_scene_features;

#endif
