/* default_view.h - the camera and lights a scene gets when the user names none (the tools' and
 * the tests' default view). */
#ifndef PG_DEFAULT_VIEW_H
#define PG_DEFAULT_VIEW_H

#include <stddef.h>

#include "scenario.h"
#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The default camera and light set-up for a scene (before a scenario is applied), README "Scenes":
 *   camera: --camera auto -> pg_camera_frame_object; --camera N|NAME -> that glTF camera
 *   (pg_scene_find_camera / pg_camera_from_scene; unknown: an error); none given:
 *   the built-in atrium ("default") keeps its interior view (pg_camera_default_for_scene), a glTF
 *   with cameras uses its first one (perspective or orthographic), else auto framing. Every glTF is treated as an object: interiors
 *   (Sponza) take a scenario or --camera.
 *   lights: the atrium -> pg_light_setup_default (inside the bounds); a glTF ->
 *   pg_light_setup_object (around the bounds).
 * camera_why / lights_why (may be NULL) get one line each. */
pg_result pg_scene_default_view(const pg_scene *scene, const char *camera_spec, float aspect, uint32_t count,
                              uint32_t seed, pg_camera *camera, pg_light_setup *lights, char *camera_why,
                              size_t camera_why_size, char *lights_why, size_t lights_why_size, pg_error *err);

/* The glTF camera index pg_scene_default_view uses for (scene, camera_spec), or -1 when its camera
 * is not a glTF camera (auto framing, the atrium's view, an unknown name). */
int pg_scene_default_camera(const pg_scene *scene, const char *camera_spec);

#ifdef __cplusplus
}
#endif
#endif
