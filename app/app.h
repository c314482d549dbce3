/* app.h - what every GPU subcommand sets up from the common options: device, scene (and its GPU
 * copy), light set-up, camera, pass registry. */
#ifndef PG_APP_H
#define PG_APP_H

#include "cli.h"
#include "frame.h"
#include "pass_api.h"
#include "plugins.h"
#include "render_session.h"
#include "scenario.h"
#include "scene.h"
#include "scene_gpu.h"
#include "default_view.h"
#include "vk_context.h"

typedef struct pg_app {
    pg_cli_common opt;            /* a copy of the options; opt.settings / opt.n_settings are the
                                   * application settings (OCIO config, display, view) every session
                                   * of the command gets: see pg_app_session_desc() */
    pg_gpu *gpu;
    pg_scene *scene;
    pg_scene_gpu *scene_gpu;
    pg_scenario scenario;
    bool has_scenario;
    pg_light_setup lights;
    pg_camera camera;
    pg_pass_registry registry;    /* the built-in pass types, then the plug-ins' (--plugin) */
    pg_plugins plugins;
    char pipeline_path[PG_PATH_MAX];
    char scene_path[PG_PATH_MAX];
    char camera_why[256];         /* "camera: ..." one line: which camera was chosen and why */
    char lights_why[768];         /* "lights: ..." one line */
    char env_why[PG_PATH_MAX + 160]; /* "environment: ..." one line */
    int animation;                /* the glTF animation played (--animation; scene/animation.h) */
    bool object_lights;           /* the intensity is pg_light_setup_object's (it depends on the
                                     light count): no scenario intensity, no --intensity */
} pg_app;

/* with_gpu false: no device (dump/explain-only paths). */
pg_result pg_app_open(pg_app *app, const pg_cli_common *opt, bool with_gpu, pg_error *err);
/* window_bits (may be NULL): instance extensions, swapchain and present_ok for a window. */
pg_result pg_app_open_ex(pg_app *app, const pg_cli_common *opt, bool with_gpu, const pg_gpu_desc *window_bits,
                         pg_error *err);
void pg_app_close(pg_app *app);
pg_frame_info pg_app_frame(const pg_app *app);
/* A session description for the app's pipeline with the command line's --set overrides, the
 * application settings (--ocio-config, --display, --ocio-view / --view) and --no-aliasing.
 * Borrowed pointers into app->opt: valid while app is. */
pg_session_desc pg_app_session_desc(const pg_app *app);
/* The light references a frame dropped (the passes' "overflow_dropped" counters; 0: the frame
 * is exact). When some were dropped, prints one line to stderr: "<cmd>: warning: <what> is not
 * exact: N light references dropped ..." (an "error:" line when require_exact is set). */
/* --explain's lines on what lights the frame and how, "explain: " each, to f: the camera, the
 * lights (their source: generated, a scenario, the command line; a file's KHR_lights_punctual
 * lights are named as not used yet), the glTF scene drawn when the file has several, the shading
 * model of the session's pipeline (its `shading` parameter, when it has one; `label` names the
 * side, may be NULL) and the environment (none: passgraph has no environment light yet). */
/* The environment light of a scene before its upload, from app->opt.environment (--environment
 * FILE.hdr|default|none; by default the neutral sky for a glTF file without lights and without a
 * scenario); app->env_why says which and why. Errors name the file (pg_environment_load). */
pg_result pg_app_attach_environment(pg_app *app, struct pg_scene *scene, pg_error *err);
/* The played animation from --animation (app->animation; an unknown one is an error listing the
 * file's) and the scene posed on the CPU at --time (pg_scene_pose: vertices, file lights, bounds),
 * so framing and the static upload follow the animation. Before the upload and the default view. */
/* pg_session_create on the app's device and scene, after loading the plug-ins the pipeline file
 * lists ("plugins", renderer/plugins.h) into the app's registry. */
pg_result pg_app_session_create(pg_app *app, const pg_session_desc *desc, pg_session **out, pg_error *err);
pg_result pg_app_pose_scene(pg_app *app, struct pg_scene *scene, pg_error *err);
/* A warning on stderr when --ocio-config, --display or --ocio-view was given and the plan runs no
 * display_ocio pass (they changed nothing, silently) */
void pg_app_note_unused_colour(const pg_app *app, const struct pg_graph_plan *plan, const char *tool);
void pg_app_print_explain_lighting(const pg_app *app, const pg_session *s, const char *label, FILE *f);
uint64_t pg_app_check_exact(const char *cmd, const char *what, const pg_frame_stats *st, bool require_exact);

#endif
