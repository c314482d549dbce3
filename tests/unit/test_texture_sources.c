/* test_texture_sources.c - the texture-source extensions (scene/scene_gltf_texture_sources.cpp and
 * the WebP decoder of scene_gltf_images.cpp) on the CPU, with tests/corpus/gltf/webp/ (gen_webp.py,
 * from features/box_plain.gltf):
 * - box_webp.gltf (EXT_texture_webp used, a magenta PNG as the core fallback) draws the WebP image:
 *   its texture is, byte for byte and at every mip level, box_plain's PNG checker; no warning;
 * - box_webp_required.gltf (required, no fallback, the WebP in a bufferView) likewise;
 * - box_basisu.gltf (KHR_texture_basisu used, its image an undecodable KTX2 stub) loads, draws the
 *   core PNG (the same bytes) and says so in exactly one warning line.
 * The refusals (a truncated WebP, a basisu texture without fallback, a source out of range) are
 * MANIFEST lines of the glTF corpus (test_scene).
 */
#include <stdio.h>
#include <string.h>

#include "scene.h"
#include "test_scene_file.h"
#include "test_util.h"

static bool same_texture(const pg_scene *a, const pg_scene *b)
{
    if (a->n_textures != 1 || b->n_textures != 1) return false;
    const pg_texture *x = &a->textures[0], *y = &b->textures[0];
    return x->n_mips == y->n_mips && x->data_size == y->data_size && x->srgb == y->srgb &&
           !memcmp(x->data, y->data, x->data_size) && x->mips[0].width == 16 && x->mips[0].height == 16;
}

int main(void)
{
    pg_scene *plain = pg_test_load_gltf("features", "box_plain.gltf");
    static const char *const files[] = {"box_webp.gltf", "box_webp_required.gltf", "box_basisu.gltf"};
    for (size_t i = 0; plain && i < sizeof files / sizeof files[0]; i++) {
        pg_scene *s = pg_test_load_gltf("webp", files[i]);
        if (!s) continue;
        CHECK_MSG(same_texture(s, plain), "%s: its texture is not box_plain's checker", files[i]);
        const bool basisu = strstr(files[i], "basisu") != NULL;
        const uint32_t want = basisu ? 1 : 0;
        CHECK_MSG(s->n_warnings == want, "%s: %u warnings (%s)", files[i], s->n_warnings,
                  s->n_warnings ? s->warnings[0] : "");
        if (basisu && s->n_warnings == 1)
            CHECK_MSG(strstr(s->warnings[0], "extensionsUsed: 'KHR_texture_basisu' ignored: its images are not "
                                             "decoded; each texture's fallback source image is drawn") != NULL,
                      "%s", s->warnings[0]);
        printf("%s: the checker of box_plain.gltf, %u mip levels, %u warning(s)\n", files[i], s->textures[0].n_mips,
               s->n_warnings);
        pg_scene_free(s);
    }
    pg_scene_free(plain);
    return pg_test_finish("test_texture_sources");
}
