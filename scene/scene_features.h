/* scene_features.h - what a scene's materials and streams use; the renderer hands them to the
 * compiler as compile variables (renderer/common/scene_vars.h) and its passes leave out shader
 * features and work the scene cannot need. */
#ifndef PG_SCENE_FEATURES_H
#define PG_SCENE_FEATURES_H

#include <stdbool.h>
#include <stdint.h>

/* The light models of the shading passes (their option `shading`; renderer/common/shading_common.h). */
enum { PG_SHADING_LAMBERT = 0, PG_SHADING_BLINN_PHONG = 1, PG_SHADING_PBR = 2, PG_SHADING_AUTO = 3 };

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
    bool has_metallic_roughness_tex; /* any metallicRoughnessTexture (sampled by the pbr model) */
    bool has_occlusion_tex; /* any occlusionTexture (sampled by the pbr model) */
    bool has_unlit;       /* any KHR_materials_unlit material (drawn as emission: has_emissive too) */
    bool has_environment; /* scene->environment is set: the environment_filter pass fills the
                             filtered environment and the shading passes read it */
    bool has_animation;   /* scene->anim is set: some drawn primitive is skinned, morphed or on an
                             animated node; the geometry_animate pass deforms the vertices */
    uint32_t vertices;    /* scene->n_vertices (the compile variable "vertices": the size of the
                             deformed vertex buffer when has_animation, else 0) */
    uint8_t auto_shading; /* PG_SHADING_LAMBERT / _BLINN_PHONG / _PBR: the model a pass's shading
                             "auto" picks: pbr for a glTF file's materials, lambert for the
                             generated scenes; a scenario's "shading" sets it (the tools) */
} pg_scene_features;

#endif
