/* scene_features.h - what a scene (and the frame's settings) can use; passes read it in declare()
 * to leave out shader features and work the scene cannot need. */
#ifndef PG_SCENE_FEATURES_H
#define PG_SCENE_FEATURES_H

#include <stdbool.h>
#include <stdint.h>

typedef struct pg_scene_features {
    bool has_textures;    /* any base-colour texture */
    bool has_normal_maps; /* any material with a normal map (and tangents) */
    bool has_alpha_mask;  /* any alpha-mask material */
    uint32_t light_count;
} pg_scene_features;

#endif
