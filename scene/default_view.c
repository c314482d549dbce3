/* default_view.c - the default camera and light set-up of a scene (scene/default_view.h). */
#include "default_view.h"

#include <stdio.h>
#include <string.h>

int pg_scene_default_camera(const pg_scene *scene, const char *camera_spec)
{
    if (!scene || (camera_spec && !strcmp(camera_spec, "auto"))) return -1;
    if (camera_spec) {
        uint32_t ci = 0;
        pg_error e = {0};
        return pg_scene_find_camera(scene, camera_spec, &ci, &e) ? -1 : (int)ci;
    }
    return !strcmp(scene->path, "default") || scene->n_cameras == 0 ? -1 : 0;
}

pg_result pg_scene_default_view(const pg_scene *scene, const char *camera_spec, float aspect, uint32_t count,
                              uint32_t seed, pg_camera *camera, pg_light_setup *lights, char *camera_why,
                              size_t camera_why_size, char *lights_why, size_t lights_why_size, pg_error *err)
{
    char cw[256] = "", lw[256] = "";
    bool atrium = scene && !strcmp(scene->path, "default");
    bool want_auto = camera_spec && !strcmp(camera_spec, "auto");
    pg_camera cam;
    if (camera_spec && !want_auto) {
        uint32_t ci = 0;
        pg_result r = pg_scene_find_camera(scene, camera_spec, &ci, err);
        if (!r) r = pg_camera_from_scene(scene, ci, aspect, &cam, err);
        if (r) return r;
        snprintf(cw, sizeof cw, "camera: glTF camera %u '%s' (node '%s', %s), selected by --camera %s", ci,
                 scene->cameras[ci].name, scene->cameras[ci].node_name,
                 scene->cameras[ci].type == PG_CAMERA_ORTHOGRAPHIC ? "orthographic" : "perspective", camera_spec);
    } else if (!want_auto && atrium) {
        cam = pg_camera_default_for_scene(scene, aspect);
        snprintf(cw, sizeof cw, "camera: interior view of the built-in atrium (inside the bounds, looking along +X)");
    } else {
        if (pg_scene_default_camera(scene, NULL) == 0 && !want_auto) {
            pg_result r = pg_camera_from_scene(scene, 0, aspect, &cam, err);
            if (r) return r;
            snprintf(cw, sizeof cw, "camera: glTF camera 0 '%s' (node '%s', %s), the scene's first camera; "
                     "--camera auto frames the bounds instead", scene->cameras[0].name, scene->cameras[0].node_name,
                     scene->cameras[0].type == PG_CAMERA_ORTHOGRAPHIC ? "orthographic" : "perspective");
        } else {
            float r = 0, d = 0;
            cam = pg_camera_frame_object(scene, aspect, &r, &d);
            snprintf(cw, sizeof cw, "camera: auto framing (%s: bounds radius %.3g, distance %.3g, fov_y 45)",
                     want_auto ? "--camera auto" : "object, no glTF camera", r, d);
        }
    }
    pg_light_setup ls;
    if (atrium) {
        ls = pg_light_setup_default(scene, count, seed);
        snprintf(lw, sizeof lw, "lights: generated point lights, interior box (bounds shrunk by 2%%), radius %.3g, "
                 "intensity %.3g", ls.radius, ls.intensity);
    } else {
        ls = pg_light_setup_object(scene, count, seed);
        snprintf(lw, sizeof lw,
                 "lights: generated point lights, object box (bounds grown by 0.6 x radius per side, none within "
                 "%.2g x radius of the bounds), radius %.3g, intensity %.3g, ambient %.3g",
                 (double)PG_OBJECT_LIGHT_GAP, ls.radius, ls.intensity, ls.ambient);
    }
    *camera = cam;
    *lights = ls;
    if (camera_why && camera_why_size) pg_strlcpy(camera_why, cw, camera_why_size);
    if (lights_why && lights_why_size) pg_strlcpy(lights_why, lw, lights_why_size);
    return PG_OK;
}
