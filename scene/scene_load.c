/* scene_load.c - pg_scene_load(): "default" or a glTF path to the loader that builds it
 * (scene_default.c, scene_gltf.cpp). Above scene.c, which the loaders build with.
 */
#include "scene.h"
#include "scene_internal.h"

#include <stdio.h>
#include <string.h>

pg_result pg_scene_load_ex(const char *path_or_default, const pg_scene_load_opts *opts, pg_scene **out,
                           pg_error *err)
{
    if (!out) return pg_fail(err, PG_ERR_INVALID_ARG, "pg_scene_load: out is NULL");
    *out = NULL;
    if (!path_or_default || !path_or_default[0])
        return pg_fail(err, PG_ERR_INVALID_ARG, "pg_scene_load: empty scene path");
    if (strcmp(path_or_default, "default") == 0) {
        if (opts && opts->gltf_scene >= 0)
            return pg_fail(err, PG_ERR_INVALID_ARG,
                           "--gltf-scene %d: the built-in atrium is not a glTF file (give --scene FILE.gltf)",
                           opts->gltf_scene);
        if (opts && opts->gltf_variant && opts->gltf_variant[0])
            return pg_fail(err, PG_ERR_INVALID_ARG,
                           "--variant %s: the built-in atrium is not a glTF file (give --scene FILE.gltf)",
                           opts->gltf_variant);
        pg_result r = pg_scene_create_default(out, err);
        if (!r) (*out)->gltf_scene = -1;
        return r;
    }
    return pg_scene_load_gltf_ex(path_or_default, opts, out, err);
}

pg_result pg_scene_load(const char *path_or_default, pg_scene **out, pg_error *err)
{
    return pg_scene_load_ex(path_or_default, NULL, out, err);
}

bool pg_scene_choice_line(const pg_scene *scene, char *buf, size_t size)
{
    if (size) buf[0] = 0;
    if (!scene || scene->n_gltf_scenes < 2 || scene->gltf_scene < 0) return false;
    snprintf(buf, size, "%s has %u scenes; drawing scene %d '%s'%s; --gltf-scene N draws another", scene->path,
             scene->n_gltf_scenes, scene->gltf_scene, scene->gltf_scene_name,
             scene->gltf_scene_chosen  ? " (--gltf-scene)"
             : scene->gltf_scene_named ? " (the file's default)"
                                       : " (the first: the file names no default scene)");
    return true;
}

bool pg_scene_variant_line(const pg_scene *scene, char *buf, size_t size)
{
    if (size) buf[0] = 0;
    if (!scene || scene->n_gltf_variants == 0) return false;
    if (scene->gltf_variant >= 0)
        snprintf(buf, size, "%s has %u material variant%s (%s); drawing variant %d '%s' (--variant)", scene->path,
                 scene->n_gltf_variants, scene->n_gltf_variants == 1 ? "" : "s", scene->gltf_variant_list,
                 scene->gltf_variant, scene->gltf_variant_name);
    else
        snprintf(buf, size, "%s has %u material variant%s (%s); drawing the default materials; --variant N|NAME "
                 "draws one", scene->path, scene->n_gltf_variants, scene->n_gltf_variants == 1 ? "" : "s",
                 scene->gltf_variant_list);
    return true;
}
