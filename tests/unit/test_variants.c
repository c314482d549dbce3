/* test_variants.c - KHR_materials_variants (scene/scene_gltf_variants.cpp) on the CPU with
 * tests/corpus/gltf/variants/shoe.gltf (gen_variants.py): the body and lace primitives draw the
 * materials of the defaults and of each variant, chosen by index or name (white/black, red/black,
 * blue/black, blue/yellow); the variant line names them; an unknown variant, a variant for the
 * built-in atrium, refused with the list. Bad mappings are MANIFEST lines of the glTF corpus. */
#include <stdio.h>
#include <string.h>

#include "scene.h"
#include "test_util.h"

#define SHOE PG_TEST_DIR "/corpus/gltf/variants/shoe.gltf"

/* the material names of the shoe's primitives 1 (body) and 2 (lace); primitive 0 is the floor */
static void expect(const char *variant, const char *body, const char *lace, int index)
{
    pg_scene_load_opts o = {.gltf_scene = -1, .gltf_variant = variant};
    pg_scene *s = NULL;
    pg_error err = {0};
    if (pg_scene_load_ex(SHOE, &o, &s, &err)) {
        CHECK_MSG(0, "--variant %s: %s", variant ? variant : "(none)", err.msg);
        return;
    }
    CHECK(s->n_primitives == 3 && s->n_gltf_variants == 3 && s->gltf_variant == index);
    if (s->n_primitives == 3) {
        const char *b = s->materials[s->primitives[1].material].name, *l = s->materials[s->primitives[2].material].name;
        CHECK_MSG(!strcmp(b, body) && !strcmp(l, lace), "--variant %s: body %s, lace %s (want %s, %s)",
                  variant ? variant : "(none)", b, l, body, lace);
        printf("--variant %-8s body %-5s lace %s\n", variant ? variant : "(none)", b, l);
    }
    char line[1024];
    CHECK(pg_scene_variant_line(s, line, sizeof line) && strstr(line, "has 3 material variants (0 'red', 1 'blue', 2 "
                                                                      "'midnight')"));
    CHECK_MSG(index < 0 ? strstr(line, "drawing the default materials; --variant N|NAME draws one") != NULL
                        : strstr(line, "(--variant)") != NULL,
              "%s", line);
    CHECK(s->n_warnings == 0);
    pg_scene_free(s);
}

static void refused(const char *scene, const char *variant, const char *want)
{
    pg_scene_load_opts o = {.gltf_scene = -1, .gltf_variant = variant};
    pg_scene *s = NULL;
    pg_error err = {0};
    CHECK(pg_scene_load_ex(scene, &o, &s, &err) == PG_ERR_INVALID_ARG && s == NULL);
    CHECK_MSG(strstr(err.msg, want) != NULL, "--variant %s: '%s' lacks '%s'", variant, err.msg, want);
}

int main(void)
{
    expect(NULL, "white", "black", -1);
    expect("", "white", "black", -1);
    expect("red", "red", "black", 0);
    expect("1", "blue", "black", 1);
    expect("midnight", "blue", "yellow", 2);
    refused(SHOE, "green", "--variant 'green': not a variant of the file (3: 0 'red', 1 'blue', 2 'midnight')");
    refused(SHOE, "3", "not a variant of the file");
    refused("default", "red", "--variant red: the built-in atrium is not a glTF file");
    refused(PG_TEST_DIR "/corpus/gltf/instancing/grove.gltf", "0",
            "--variant '0': the file has no material variants (KHR_materials_variants)");
    return pg_test_finish("test_variants");
}
