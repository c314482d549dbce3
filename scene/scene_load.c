/* scene_load.c - pg_scene_load(): "default" or a glTF path to the loader that builds it
 * (scene_default.c, scene_gltf.cpp). Above scene.c, which the loaders build with.
 */
#include "scene.h"
#include "scene_internal.h"

#include <string.h>

pg_result pg_scene_load(const char *path_or_default, pg_scene **out, pg_error *err)
{
    if (!out) return pg_fail(err, PG_ERR_INVALID_ARG, "pg_scene_load: out is NULL");
    *out = NULL;
    if (!path_or_default || !path_or_default[0])
        return pg_fail(err, PG_ERR_INVALID_ARG, "pg_scene_load: empty scene path");
    if (strcmp(path_or_default, "default") == 0) return pg_scene_create_default(out, err);
    return pg_scene_load_gltf(path_or_default, out, err);
}
