/* scene_gpu_material.c - a material as the shaders read it (pg_gpu_material, scene_gpu.h): the
 * upload writes every material with it, the frame prologue the animated ones. */
#include <string.h>

#include "scene_gpu.h"

void pg_gpu_material_from(const pg_material *s, pg_gpu_material *out)
{
    pg_gpu_material g;
    memset(&g, 0, sizeof g);
    memcpy(g.base_color, s->base_color, sizeof g.base_color);
    /* texture i of the scene is image i+1 on the GPU (0 is white) */
    g.tex[0] = s->base_color_tex >= 0 ? s->base_color_tex + 1 : -1;
    g.tex[1] = s->normal_tex >= 0 ? s->normal_tex + 1 : -1;
    g.tex[2] = (int32_t)s->alpha_mode;
    g.tex[3] = s->double_sided ? 1 : 0;
    g.params[0] = s->alpha_cutoff;
    g.params[1] = s->normal_scale;
    g.params[2] = s->specular;
    g.params[3] = s->shininess;
    memcpy(g.emissive, s->emissive, sizeof s->emissive);
    g.tex2[0] = s->emissive_tex >= 0 ? s->emissive_tex + 1 : -1;
    g.pbr[0] = s->metallic;
    g.pbr[1] = s->roughness;
    g.pbr[2] = s->occlusion_strength;
    g.pbr[3] = s->unlit ? 1.0f : 0.0f;
    g.tex3[0] = s->metallic_roughness_tex >= 0 ? s->metallic_roughness_tex + 1 : -1;
    g.tex3[1] = s->occlusion_tex >= 0 ? s->occlusion_tex + 1 : -1;
    for (int t = 0; t < PG_TEXSLOT_COUNT; t++) {
        if (s->tex_coord[t] == 1) g.tex2[1] |= 1 << t;
        for (int k = 0; k < 3; k++) {
            g.uv_xform[t][0][k] = s->uv_transform[t][k];
            g.uv_xform[t][1][k] = s->uv_transform[t][3 + k];
        }
    }
    memcpy(out, &g, sizeof g);
}
