/* view.h - what the files of `passgraph view` share (private to tools/): the viewer's state
 * (struct viewer) and the functions one file calls in another. cmd_view.c: options, start-up,
 * the frame loop, RenderDoc capture; view_pipelines.c: the pipeline list, parameter overrides,
 * (re)loading and the on-disk watch; view_colour.c: OpenColorIO display and view;
 * view_camera.c: camera choice and fly; view_ui.c: the ImGui panels; view_frame.c: the
 * difference view and one frame (render, blit, UI, screenshot, present); view_script.c: the
 * scripted --at actions. The window and swapchain are view_window.c's. */
#ifndef PG_TOOLS_VIEW_H
#define PG_TOOLS_VIEW_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <dirent.h>
#include <time.h>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "animation.h"
#include "scene_gpu_anim.h"
#include "app.h"
#include "bench_stats.h"
#include "commands.h"
#include "frame_metrics.h"
#include "image_compare.h"
#include "image_util.h"
#include "ocio.h"
#include "shader.h"
#include "ui.h"
#include "rdoc.h"
#include "view_window.h"

#define MAX_PIPELINES 64
#define MAX_OVERRIDES 32
#define HIST 240

#define MAX_ACTIONS 32
typedef struct view_action {
    uint32_t frame;
    char what[16];
    char arg[PG_PATH_MAX * 2];
} view_action;

#define VIEW_MAX_CAMS 64

typedef struct viewer {
    pg_app app;
    GLFWwindow *window;
    pg_view_window win;
    bool ui_ready;
    /* pipelines */
    int n_pipelines, current, requested;
    char paths[MAX_PIPELINES][PG_PATH_MAX];
    char names[MAX_PIPELINES][PG_NAME_MAX];
    const char *name_ptrs[MAX_PIPELINES];
    char extra_dir[PG_PATH_MAX];
    /* parameter overrides (kept across pipelines that declare the same parameter) */
    int n_ov;
    char ov_key[MAX_OVERRIDES][PG_NAME_MAX], ov_val[MAX_OVERRIDES][PG_NAME_MAX];
    pg_session *session, *naive;
    char error[PG_ERROR_MSG_MAX];
    bool bad_option; /* the start failed on a --set or --debug-view the pipelines refuse (exit 2) */
    bool reload;
    /* frame settings */
    int light_count;
    int failed_lights;     /* >= 0: the light count at which the graph's frame failed and was dropped
                            * (a buffer past a device limit): a new count loads it again */
    float radius, intensity, speed, time, ambient;
    float env_intensity, env_rotation_deg; /* the environment light's run-time knobs */
    int seed;
    bool paused;
    pg_camera camera, home;
    float yaw, pitch, move_speed;
    double last_x, last_y;
    bool looking;
    /* statistics */
    pg_frame_stats stats;
    float hist_total[HIST], hist_pass[PG_MAX_PASSES][HIST];
    int hist_pos, hist_n;
    double cpu_frame_ms;
    /* difference to the exact reference (pipelines/reference.json) */
    bool diff;
    pg_buffer diff_staging;
    pg_image diff_image;
    uint8_t *diff_rgba;
    float *hdr_a, *hdr_b;
    double diff_scale, diff_rmse;
    /* the FLIP mode of the difference view: LDR-FLIP of the two display images on the CPU */
    bool diff_flip, flip_said;
    float *flip_map;
    double flip_mean, flip_ms;
    /* hot reload */
    double watch_sig;
    double last_watch;
    uint32_t reloads;
    /* scripted mode */
    uint32_t frames_limit, cycle_every;
    uint32_t frames_in_flight;           /* of the displayed graph: 2 (default) or 1 */
    double frame_ms[512];                /* host time per drawn frame (the first 512), for the exit line */
    uint32_t n_frame_ms;
    bool cycle, random_params;
    char cycle_tried[PG_PATH_MAX]; /* the pipeline the last cycling step asked for while it has
                                    * not loaded ("": none, or it loaded) */
    uint64_t rss100;
    int64_t mem100;
    const char *screenshot_path;
    bool want_shot;
    /* RenderDoc: key C, the button or --at N:capture[=FILE.rdc] captures the next frame */
    pg_rdoc *rdoc;
    bool want_rdoc, key_c_down;
    char rdoc_file[PG_PATH_MAX], rdoc_status[640];
    char shot_file[PG_PATH_MAX];
    pg_buffer shot;
    /* the graph's 8-bit output copied (not converted) into an image whose sRGB-ness matches the
     * swapchain's, so the blit does not decode or encode it again (see present_source) */
    pg_image present_copy;
    /* colour management: the OCIO config (for the display / view lists) and the settings every
     * session gets; changing display or view makes a new session */
    pg_ocio_config *ocio;
    char ocio_error[PG_ERROR_MSG_MAX];
    char ocio_path[PG_PATH_MAX];
    char display[128], ocio_view[128];
    bool colour_chosen;         /* display/view given on the command line or picked: they go to
                                 * the sessions as settings (else the pipeline's options rule) */
    pg_param_override settings[3];
    uint32_t n_settings;
    char scene_input[PG_PATH_MAX];
    /* camera choice: 0 = the start view (app.camera_why), 1 = auto framing, 2+k = glTF camera k */
    int cam_choice, n_cam_items;
    /* a glTF camera on an animated node follows it as the clock plays (camera_follow): its index,
     * or -1 (none, or the fly camera moved); cam_start_gltf: the start view's glTF camera or -1 */
    int cam_follow, cam_start_gltf;
    char cam_items[VIEW_MAX_CAMS + 2][PG_NAME_MAX * 2 + 16];
    const char *cam_ptrs[VIEW_MAX_CAMS + 2];
    /* KHR_materials_variants: the combo's items ("default materials", then "N 'name'") */
#define VIEW_MAX_VARIANTS 32
    char var_items[VIEW_MAX_VARIANTS + 1][PG_NAME_MAX + 16];
    const char *var_ptrs[VIEW_MAX_VARIANTS + 1];
    /* the file's glTF scenes (the "glTF scene" combo): "N 'name'" */
#define VIEW_MAX_GLTF_SCENES 32
    char gscene_items[VIEW_MAX_GLTF_SCENES][PG_NAME_MAX + 16];
    const char *gscene_ptrs[VIEW_MAX_GLTF_SCENES];
    view_action actions[MAX_ACTIONS];
    int n_actions;
    uint32_t growths;           /* light-list (grow buffer) enlargements seen so far */
    char last_growth[160];
} viewer;

/* view_pipelines.c */
void scan_pipelines(viewer *v, const char *current_path);
void set_override(viewer *v, const char *key, const char *value);
/* PG_ERR_PARAM (err filled) when pipeline k declares `key` and refuses `value`, else PG_OK */
pg_result refused_by(const viewer *v, int k, const char *key, const char *value, pg_error *err);
/* Whether a pipeline of the viewer's list declares parameter key (one that does not load declares
 * nothing): --set and --at N:set refuse a key no pipeline knows. */
bool declared_by_any(const viewer *v, const char *key);
/* PG_ERR_PARAM (the first refusal's message, naming the pipeline and the value) when every listed
 * pipeline that declares key refuses value; PG_OK when one takes it. */
pg_result refused_by_all(const viewer *v, const char *key, const char *value, pg_error *err);
/* The --set values and the debug view against the pipelines of the list that declare their key: a
 * value none of them takes is PG_ERR_INVALID_ARG naming the option that gave it (sides.h). */
pg_result check_set_values(const viewer *v, const pg_cli_common *opt, pg_error *err);
/* The list's index of arg: a listed name (forward_plus.json) or a file (any path to a listed one, or
 * a pipeline elsewhere, which is added to the list); else an error naming arg. */
pg_result find_pipeline(viewer *v, const char *arg, int *index, pg_error *err);
pg_result open_session(viewer *v, const char *path, bool with_overrides, pg_session **out, pg_error *err);
void reload(viewer *v);
double watch_signature(const viewer *v);

/* view_colour.c */
void colour_init(viewer *v);
pg_result colour_choose(viewer *v, const char *display, const char *view, pg_error *err);
void colour_ui(viewer *v);

/* view_camera.c */
void camera_angles(viewer *v);
void camera_list(viewer *v, const char *start_label);
void camera_choose(viewer *v, int choice);
void camera_follow_set(viewer *v, int gltf_camera);
void camera_update(viewer *v, float dt);

/* view_ui.c */
void build_ui(viewer *v);
/* the scene reloaded with material variant `variant` (an index or a name; NULL or "": the default
 * materials), the camera and lights kept; an error leaves the scene as it was */
pg_result variant_choose(viewer *v, const char *variant, pg_error *err);
/* the file reloaded drawing its glTF scene `index` (scenes[index]; the variant kept), with that
 * scene's default view and lights; an error leaves the scene as it was */
pg_result gltf_scene_choose(viewer *v, int index, pg_error *err);

/* view_frame.c */
pg_result draw_frame(viewer *v, bool capture, pg_error *err);

/* view_script.c */
pg_result run_action(viewer *v, const view_action *a, pg_error *err);

#endif
