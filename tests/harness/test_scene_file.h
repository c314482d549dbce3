/* test_scene_file.h - loading a file of tests/corpus/gltf/ in a test that links the scene library
 * (header-only: test_util.c links only the base library). */
#ifndef PG_TEST_SCENE_FILE_H
#define PG_TEST_SCENE_FILE_H

#include <stdio.h>

#include "scene.h"
#include "test_util.h"

/* tests/corpus/gltf/<dir>/<rel>, loaded; NULL and a failed check when it does not load */
static inline pg_scene *pg_test_load_gltf(const char *dir, const char *rel)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/corpus/gltf/%s/%s", PG_TEST_DIR, dir, rel);
    pg_scene *s = NULL;
    pg_error err = {0};
    if (pg_scene_load_gltf(path, &s, &err)) {
        CHECK_MSG(0, "%s/%s: %s", dir, rel, err.msg);
        return NULL;
    }
    return s;
}

#endif
