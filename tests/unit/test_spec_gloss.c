/* test_spec_gloss.c - KHR_materials_pbrSpecularGlossiness approximated as metallic-roughness
 * (scene/scene_gltf.cpp material_spec_gloss) with tests/corpus/gltf/features/spec_gloss.gltf
 * (gen_features.py): a material with only the extension draws its diffuse factor as the base
 * colour, roughness = 1 - glossiness, metallic 0; its diffuseTexture becomes the base colour texture
 * with its KHR_texture_transform; a material that also has pbrMetallicRoughness draws that; one
 * warning line says what is approximated, none for KHR_xmp_json_ld (metadata). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "scene.h"
#include "test_scene_file.h"
#include "test_util.h"

static bool near(float a, double b) { return fabs(a - b) <= 1e-6; }

int main(void)
{
    pg_scene *s = pg_test_load_gltf("features", "spec_gloss.gltf");
    if (s) {
        CHECK(s->n_materials >= 3);
        const pg_material *f = &s->materials[0], *t = &s->materials[1], *c = &s->materials[2];
        CHECK_MSG(near(f->base_color[0], 0.8) && near(f->base_color[1], 0.2) && near(f->base_color[2], 0.1) &&
                      near(f->base_color[3], 1.0) && near(f->roughness, 0.25) && f->metallic == 0.0f &&
                      f->base_color_tex < 0,
                  "sg_factor: base (%g, %g, %g, %g), roughness %g, metallic %g, texture %d", f->base_color[0],
                  f->base_color[1], f->base_color[2], f->base_color[3], f->roughness, f->metallic, f->base_color_tex);
        CHECK_MSG(t->base_color_tex >= 0 && t->has_uv_transform[PG_TEXSLOT_BASE] &&
                      near(t->uv_transform[PG_TEXSLOT_BASE][0], 2.0) && near(t->base_color[0], 1.0) &&
                      near(t->roughness, 0.0) && t->metallic == 0.0f,
                  "sg_texture: texture %d, transform %d (%g), base %g, roughness %g", t->base_color_tex,
                  t->has_uv_transform[PG_TEXSLOT_BASE], t->uv_transform[PG_TEXSLOT_BASE][0], t->base_color[0],
                  t->roughness);
        CHECK_MSG(near(c->base_color[0], 0.1) && near(c->base_color[1], 0.8) && near(c->metallic, 0.5) &&
                      near(c->roughness, 0.4),
                  "core_and_sg: base (%g, %g), metallic %g, roughness %g: not its core material", c->base_color[0],
                  c->base_color[1], c->metallic, c->roughness);
        CHECK_MSG(s->n_warnings == 1 && strstr(s->warnings[0], "extensionsUsed: 'KHR_materials_pbrSpecularGlossiness' "
                                                               "approximated: materials without pbrMetallicRoughness"),
                  "%u warnings (%s)", s->n_warnings, s->n_warnings ? s->warnings[0] : "");
        printf("spec_gloss.gltf: base (%.2f, %.2f, %.2f), roughness %.2f; textured; core kept; %s\n", f->base_color[0],
               f->base_color[1], f->base_color[2], f->roughness, s->n_warnings ? s->warnings[0] : "");
    }
    pg_scene_free(s);
    return pg_test_finish("test_spec_gloss");
}
