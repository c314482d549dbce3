/* fuzz_gltf.c - libFuzzer target for pg_scene_load_gltf (core/scene/scene_gltf*.cpp: GLB container,
 * JSON pre-validation, tinygltf, our stb image callback, node walk, accessors, materials, mips).
 *
 * Each input is written to a private temporary directory as input.glb when it starts with the
 * GLB magic "glTF", else as input.gltf, and loaded from there. The directory also holds small
 * companion files an input may refer to by uri: fz.bin (a 44-byte triangle: 3 float positions +
 * 3 uint16 indices + padding), fz.png (a 2x2 RGBA PNG), and a copy of the .bin/.png files of
 * tests/corpus/gltf/ (so the corpus seeds that use external files load as they do in the tests).
 *
 * Invariants checked on a scene that loads (abort = a finding): at least one triangle; every
 * primitive's index range inside the index array and every index (plus vertex_offset) inside the
 * vertex array; materials and texture references in range; finite positions, normals and uvs;
 * mip chains inside their texture's allocation. On failure: result code in range, err.code equal,
 * a non-empty message. ASan/UBSan/LSan catch the rest. */
#include "scene.h"

#include <math.h>
#include <stdint.h>

#include "fuzz_common.h"

#ifndef PG_SOURCE_DIR
#define PG_SOURCE_DIR "."
#endif

static char g_gltf_path[512], g_glb_path[512];

static const unsigned char k_png_2x2[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44,
    0x52, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x02, 0x08, 0x06, 0x00, 0x00, 0x00, 0xf4,
    0x78, 0xd4, 0xfa, 0x00, 0x00, 0x00, 0x16, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0xf8,
    0xcf, 0xc0, 0xf0, 0x1f, 0x08, 0x19, 0x18, 0xfe, 0x03, 0x21, 0x03, 0x03, 0x00, 0x4b, 0xf4,
    0x07, 0xf9, 0x3f, 0xe5, 0xd5, 0x6a, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae,
    0x42, 0x60, 0x82};

static int keep_companion(const char *name)
{
    return fuzz_ends_with(name, ".bin") || fuzz_ends_with(name, ".png");
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    const char *dir = fuzz_dir("gltf");
    fuzz_copy_dir(PG_SOURCE_DIR "/tests/corpus/gltf", dir, keep_companion);
    char p[600];
    /* positions (0,0,0) (1,0,0) (0,1,0), indices 0 1 2, 2 bytes padding: 44 bytes */
    float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint16_t idx[4] = {0, 1, 2, 0};
    unsigned char bin[44];
    memcpy(bin, pos, 36);
    memcpy(bin + 36, idx, 8);
    snprintf(p, sizeof p, "%s/fz.bin", dir);
    fuzz_write(p, bin, sizeof bin);
    snprintf(p, sizeof p, "%s/fz.png", dir);
    fuzz_write(p, k_png_2x2, sizeof k_png_2x2);
    snprintf(g_gltf_path, sizeof g_gltf_path, "%s/input.gltf", dir);
    snprintf(g_glb_path, sizeof g_glb_path, "%s/input.glb", dir);
    return 0;
}

static void check_scene(const pg_scene *s)
{
    if (!s->n_vertices || !s->n_indices || !s->n_primitives || !s->n_materials)
        fuzz_die("loaded scene is empty: %u vertices, %u indices, %u primitives, %u materials",
                 s->n_vertices, s->n_indices, s->n_primitives, s->n_materials);
    for (uint32_t i = 0; i < s->n_primitives; i++) {
        const pg_primitive *pr = &s->primitives[i];
        if ((uint64_t)pr->first_index + pr->index_count > s->n_indices)
            fuzz_die("primitive %u indices %u+%u past %u", i, pr->first_index, pr->index_count,
                     s->n_indices);
        if (pr->index_count % 3) fuzz_die("primitive %u: %u indices", i, pr->index_count);
        if (pr->material >= s->n_materials)
            fuzz_die("primitive %u material %u of %u", i, pr->material, s->n_materials);
        for (uint32_t k = 0; k < pr->index_count; k++) {
            int64_t v = (int64_t)pr->vertex_offset + s->indices[pr->first_index + k];
            if (v < 0 || v >= (int64_t)s->n_vertices)
                fuzz_die("primitive %u index %u -> vertex %lld of %u", i, k, (long long)v,
                         s->n_vertices);
        }
    }
    for (uint32_t i = 0; i < s->n_materials; i++) {
        const pg_material *m = &s->materials[i];
        if (m->base_color_tex < -1 || m->base_color_tex >= (int)s->n_textures ||
            m->normal_tex < -1 || m->normal_tex >= (int)s->n_textures)
            fuzz_die("material %u textures %d/%d of %u", i, m->base_color_tex, m->normal_tex,
                     s->n_textures);
    }
    for (uint32_t i = 0; i < s->n_vertices; i++) {
        const pg_vertex *v = &s->vertices[i];
        for (int k = 0; k < 3; k++)
            if (!isfinite(v->position[k]) || !isfinite(v->normal[k]))
                fuzz_die("vertex %u not finite", i);
        if (!isfinite(v->uv[0]) || !isfinite(v->uv[1])) fuzz_die("vertex %u uv not finite", i);
    }
    for (uint32_t i = 0; i < s->n_textures; i++) {
        const pg_texture *t = &s->textures[i];
        if (t->n_mips < 1 || t->n_mips > PG_MAX_MIPS) fuzz_die("texture %u: %u mips", i, t->n_mips);
        for (uint32_t m = 0; m < t->n_mips; m++) {
            const pg_mip *mp = &t->mips[m];
            size_t off = (size_t)(mp->rgba - t->data);
            if (mp->rgba < t->data || off + (size_t)mp->width * mp->height * 4 > t->data_size)
                fuzz_die("texture %u mip %u outside its allocation", i, m);
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = size >= 4 && memcmp(data, "glTF", 4) == 0 ? g_glb_path : g_gltf_path;
    fuzz_write(path, data, size);
    pg_scene *s = (pg_scene *)g_glb_path; /* any non-NULL value: must be reset */
    pg_error err = {0};
    pg_result r = pg_scene_load_gltf(path, &s, &err);
    if ((int)r < 0 || r >= PG_ERR_COUNT) fuzz_die("result %d out of range", (int)r);
    if ((r == PG_OK) != (s != NULL)) fuzz_die("result %s, scene %p", pg_result_name(r), (void *)s);
    if (r != PG_OK) {
        if (!memchr(err.msg, 0, sizeof err.msg)) fuzz_die("message not terminated");
        if (err.code != r || !err.msg[0])
            fuzz_die("returned %s, err.code %s, message '%s'", pg_result_name(r),
                     pg_result_name(err.code), err.msg);
    } else {
        check_scene(s);
    }
    pg_scene_free(s);
    unlink(path);
    return 0;
}
