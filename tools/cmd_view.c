/* cmd_view.c - `passgraph view`: a window to fly through a scene lit by many lights, switch and
 * tune pipelines live (hot reload of pipeline JSON and shaders), and see per-pass GPU timings,
 * overflow, memory and its aliasing timeline, and debug views.
 *
 * Frame: the graph renders offscreen (its own submit + fence); then one command buffer blits the
 * graph's display image (or the difference-to-naive heatmap) into the swapchain image, draws the
 * UI over it in a render pass, optionally copies the result for a screenshot, and presents. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <dirent.h>
#include <time.h>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "app.h"
#include "bench_stats.h"
#include "commands.h"
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
    bool reload;
    /* frame settings */
    int light_count;
    float radius, intensity, speed, time, ambient;
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
    char cam_items[VIEW_MAX_CAMS + 2][PG_NAME_MAX * 2 + 16];
    const char *cam_ptrs[VIEW_MAX_CAMS + 2];
    view_action actions[MAX_ACTIONS];
    int n_actions;
    uint32_t growths;           /* light-list (grow buffer) enlargements seen so far */
    char last_growth[160];
} viewer;

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* ---------------------------------------------------------------- pipelines and parameters */

static int cmp_str(const void *a, const void *b)
{
    return strcmp((const char *)a, (const char *)b);
}

static void scan_dir(viewer *v, const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return;
    char found[MAX_PIPELINES][PG_PATH_MAX];
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) && n < MAX_PIPELINES) {
        size_t len = strlen(e->d_name);
        if (len < 6 || strcmp(e->d_name + len - 5, ".json")) continue;
        snprintf(found[n++], PG_PATH_MAX, "%s/%s", dir, e->d_name);
    }
    closedir(d);
    qsort(found, (size_t)n, PG_PATH_MAX, cmp_str);
    for (int i = 0; i < n && v->n_pipelines < MAX_PIPELINES; i++) {
        bool dup = false;
        for (int k = 0; k < v->n_pipelines; k++) dup |= !strcmp(v->paths[k], found[i]);
        if (dup) continue;
        pg_strlcpy(v->paths[v->n_pipelines], found[i], PG_PATH_MAX);
        const char *base = strrchr(found[i], '/');
        pg_strlcpy(v->names[v->n_pipelines], base ? base + 1 : found[i], PG_NAME_MAX);
        v->name_ptrs[v->n_pipelines] = v->names[v->n_pipelines];
        v->n_pipelines++;
    }
}

static void scan_pipelines(viewer *v, const char *current_path)
{
    v->n_pipelines = 0;
    char dir[PG_PATH_MAX];
    pg_data_path(dir, sizeof dir, "pipelines");
    scan_dir(v, dir);
    if (v->extra_dir[0]) scan_dir(v, v->extra_dir);
    v->current = -1;
    char want[PG_PATH_MAX], have[PG_PATH_MAX];
    for (int i = 0; current_path && i < v->n_pipelines; i++)
        if (realpath(current_path, want) && realpath(v->paths[i], have) && !strcmp(want, have)) v->current = i;
    if (v->current < 0 && current_path && v->n_pipelines < MAX_PIPELINES) { /* a file elsewhere */
        pg_strlcpy(v->paths[v->n_pipelines], current_path, PG_PATH_MAX);
        const char *base = strrchr(current_path, '/');
        pg_strlcpy(v->names[v->n_pipelines], base ? base + 1 : current_path, PG_NAME_MAX);
        v->name_ptrs[v->n_pipelines] = v->names[v->n_pipelines];
        v->current = v->n_pipelines++;
    }
    if (v->current < 0) v->current = 0;
}

static void set_override(viewer *v, const char *key, const char *value)
{
    for (int i = 0; i < v->n_ov; i++)
        if (!strcmp(v->ov_key[i], key)) {
            pg_strlcpy(v->ov_val[i], value, PG_NAME_MAX);
            return;
        }
    if (v->n_ov >= MAX_OVERRIDES) return;
    pg_strlcpy(v->ov_key[v->n_ov], key, PG_NAME_MAX);
    pg_strlcpy(v->ov_val[v->n_ov], value, PG_NAME_MAX);
    v->n_ov++;
}

/* Creates a session for path with the overrides the pipeline declares. */
static pg_result open_session(viewer *v, const char *path, bool with_overrides, pg_session **out, pg_error *err)
{
    pg_param_override ov[MAX_OVERRIDES];
    uint32_t n = 0;
    if (with_overrides) {
        pg_pipeline *probe = NULL;
        pg_result r = pg_pipeline_load(path, NULL, 0, &probe, err);
        if (r) return r;
        for (int i = 0; i < v->n_ov; i++)
            if (pg_pipeline_find_param(probe, v->ov_key[i])) ov[n++] = (pg_param_override){v->ov_key[i], v->ov_val[i]};
        pg_pipeline_free(probe);
    }
    pg_session_desc sd = {
        .pipeline_path = path,
        .overrides = ov,
        .n_overrides = n,
        .registry = &v->app.registry,
        .disable_aliasing = v->app.opt.no_aliasing,
        .immediate = v->app.opt.immediate,
        .async_off = v->app.opt.async_compute == PG_ASYNC_OFF,
        .output_stages = VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_BLIT_BIT,
        .settings = v->settings,
        .n_settings = v->n_settings,
    };
    pg_result r = pg_session_create(v->app.gpu, v->app.scene_gpu, &sd, out, err);
    /* the displayed graph keeps two frames in flight; the reference of the diff view reads back */
    if (!r && with_overrides && (r = pg_session_set_frames_in_flight(*out, v->frames_in_flight, err))) {
        pg_session_destroy(*out);
        *out = NULL;
    }
    return r;
}

/* Loads the requested pipeline; on failure keeps the running one and shows the error. */
static void reload(viewer *v)
{
    v->reload = false;
    pg_error err = {0};
    pg_session *s = NULL;
    int idx = v->requested;
    if (idx < 0 || idx >= v->n_pipelines) idx = v->current;
    if (open_session(v, v->paths[idx], true, &s, &err) == PG_OK) {
        /* compile now so a bad combination shows here and the old graph keeps running */
        pg_frame_info fi = pg_app_frame(&v->app);
        if (pg_session_compile(s, (uint32_t)v->light_count, v->win.extent.width, v->win.extent.height, &err)) {
            pg_session_destroy(s);
            s = NULL;
            (void)fi;
        }
    }
    if (!s) {
        snprintf(v->error, sizeof v->error, "%s", err.msg);
        fprintf(stderr, "passgraph view: %s\n", err.msg);
        v->requested = v->current;
        return;
    }
    pg_session_destroy(v->session);
    v->session = s;
    v->current = idx;
    v->requested = idx;
    v->cycle_tried[0] = 0; /* loaded: the cycle goes on from here */
    v->error[0] = 0;
    v->hist_n = 0;
    v->reloads++;
}

/* Sum of the modification times of everything a pipeline or shader edit touches. */
static double watch_signature(const viewer *v)
{
    const char *dirs[4];
    char a[PG_PATH_MAX], b[PG_PATH_MAX], c[PG_PATH_MAX];
    pg_data_path(a, sizeof a, "pipelines");
    pg_data_path(b, sizeof b, "pipelines/fragments");
    pg_data_path(c, sizeof c, "shaders");
    int n = 0;
    dirs[n++] = a;
    dirs[n++] = b;
    dirs[n++] = c;
    if (v->extra_dir[0]) dirs[n++] = v->extra_dir;
    double sig = 0;
    for (int i = 0; i < n; i++) {
        DIR *d = opendir(dirs[i]);
        if (!d) continue;
        struct dirent *e;
        while ((e = readdir(d))) {
            if (e->d_name[0] == '.') continue;
            char p[PG_PATH_MAX * 2];
            snprintf(p, sizeof p, "%s/%s", dirs[i], e->d_name);
            struct stat st;
            if (stat(p, &st) == 0 && S_ISREG(st.st_mode))
                sig += (double)st.st_mtim.tv_sec + st.st_mtim.tv_nsec * 1e-9 + (double)st.st_size * 1e-3;
        }
        closedir(d);
    }
    /* listed pipelines outside those folders (a --pipeline elsewhere); independent of which one
     * is selected, so switching is not mistaken for an edit */
    for (int i = 0; i < v->n_pipelines; i++) {
        bool inside = false;
        for (int k = 0; k < n; k++) inside |= strncmp(v->paths[i], dirs[k], strlen(dirs[k])) == 0;
        struct stat st;
        if (!inside && stat(v->paths[i], &st) == 0) sig += (double)st.st_mtim.tv_sec + st.st_mtim.tv_nsec * 1e-9;
    }
    return sig;
}

/* ---------------------------------------------------------------- colour (OpenColorIO) */

static void colour_settings(viewer *v)
{
    v->n_settings = 0;
    if (v->app.opt.ocio_config) v->settings[v->n_settings++] = (pg_param_override){"ocio.config", v->ocio_path};
    if (v->colour_chosen && v->display[0])
        v->settings[v->n_settings++] = (pg_param_override){"ocio.display", v->display};
    if (v->colour_chosen && v->ocio_view[0])
        v->settings[v->n_settings++] = (pg_param_override){"ocio.view", v->ocio_view};
}

/* Opens the config for its lists; the display and view start from the command line, else the
 * config's defaults. A config that does not load is shown in the window (the display pass reports
 * it too). */
static void colour_init(viewer *v)
{
    pg_ocio_resolve_path(v->app.opt.ocio_config, v->ocio_path, sizeof v->ocio_path);
    v->colour_chosen = v->app.opt.display || v->app.opt.ocio_view;
    pg_error err = {0};
    if (pg_ocio_open(v->ocio_path, &v->ocio, &err)) {
        snprintf(v->ocio_error, sizeof v->ocio_error, "%s", err.msg);
        v->ocio = NULL;
    } else if (pg_ocio_resolve(v->ocio, v->app.opt.display, v->app.opt.ocio_view, v->display, sizeof v->display,
                               v->ocio_view, sizeof v->ocio_view, &err)) {
        snprintf(v->ocio_error, sizeof v->ocio_error, "%s", err.msg);
    }
    if (!v->display[0] && v->app.opt.display) pg_strlcpy(v->display, v->app.opt.display, sizeof v->display);
    if (!v->ocio_view[0] && v->app.opt.ocio_view) pg_strlcpy(v->ocio_view, v->app.opt.ocio_view, sizeof v->ocio_view);
    colour_settings(v);
}

/* Picks a display (its default view unless `view` is one of its views) or a view; reloads. */
static pg_result colour_choose(viewer *v, const char *display, const char *view, pg_error *err)
{
    if (!v->ocio) return pg_fail(err, PG_ERR_INVALID_ARG, "%s", v->ocio_error[0] ? v->ocio_error : "no OCIO config");
    const char *d = display ? display : v->display;
    const char *w = view ? view : (display && !pg_ocio_has_view(v->ocio, display, v->ocio_view) ? NULL : v->ocio_view);
    char nd[sizeof v->display], nv[sizeof v->ocio_view];
    pg_result r = pg_ocio_resolve(v->ocio, d, w, nd, sizeof nd, nv, sizeof nv, err);
    if (r) return r;
    if (strcmp(nd, v->display) || strcmp(nv, v->ocio_view)) {
        pg_strlcpy(v->display, nd, sizeof v->display);
        pg_strlcpy(v->ocio_view, nv, sizeof v->ocio_view);
        v->colour_chosen = true;
        colour_settings(v);
        v->reload = true;
    }
    return PG_OK;
}

static void colour_ui(viewer *v)
{
    if (!pg_ui_header("Colour (OpenColorIO)", true)) return;
    if (!v->ocio) {
        pg_ui_text_colored(0xff5050ff, "OCIO config:");
        pg_ui_text_wrapped(v->ocio_error);
        return;
    }
    pg_ui_text_wrapped(pg_ocio_config_path(v->ocio));
    const char *items[32];
    int n = 0, cur = 0;
    for (uint32_t i = 0; i < pg_ocio_num_displays(v->ocio) && n < 32; i++) {
        items[n] = pg_ocio_display(v->ocio, i);
        if (items[n] && !strcmp(items[n], v->display)) cur = n;
        if (items[n]) n++;
    }
    pg_error err = {0};
    if (pg_ui_combo("display", &cur, items, n)) colour_choose(v, items[cur], NULL, &err);
    n = 0;
    cur = 0;
    for (uint32_t i = 0; i < pg_ocio_num_views(v->ocio, v->display) && n < 32; i++) {
        items[n] = pg_ocio_view(v->ocio, v->display, i);
        if (items[n] && !strcmp(items[n], v->ocio_view)) cur = n;
        if (items[n]) n++;
    }
    if (pg_ui_combo("view", &cur, items, n)) colour_choose(v, NULL, items[cur], &err);
    pg_ui_tooltip("the OCIO view transform from scene-linear to the display (a new session is made)");
    const pg_pipeline *pl = v->session ? v->session->pipeline : NULL;
    const pg_param *ex = pl ? pg_pipeline_find_param(pl, "exposure") : NULL;
    if (ex && ex->type == PG_PARAM_FLOAT) {
        float stops = ex->number > 0 ? (float)log2(ex->number) : 0.0f;
        if (pg_ui_slider_float("exposure EV", &stops, -10.0f, 10.0f, "%+.2f", false)) {
            char val[PG_NAME_MAX];
            snprintf(val, sizeof val, "%.9g", exp2((double)stops));
            set_override(v, "exposure", val);
            v->reload = true;
        }
        pg_ui_tooltip("the pipeline parameter 'exposure' (x 2^stops), a scene-linear multiply before the view");
    }
}

/* ---------------------------------------------------------------- camera */

static void camera_angles(viewer *v)
{
    float d[3] = {v->camera.target[0] - v->camera.position[0], v->camera.target[1] - v->camera.position[1],
                  v->camera.target[2] - v->camera.position[2]};
    float len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (len < 1e-9f) len = 1;
    v->yaw = atan2f(d[2], d[0]);
    v->pitch = asinf(fmaxf(-1.0f, fminf(1.0f, d[1] / len)));
}

/* The camera combo's items for the current scene: the start view, auto framing, the glTF cameras
 * (at most VIEW_MAX_CAMS listed). */
static void camera_list(viewer *v, const char *start_label)
{
    const pg_scene *sc = v->app.scene;
    int n = 0;
    snprintf(v->cam_items[n++], sizeof v->cam_items[0], "%s", start_label);
    snprintf(v->cam_items[n++], sizeof v->cam_items[0], "auto framing");
    for (uint32_t k = 0; sc && k < sc->n_cameras && k < VIEW_MAX_CAMS; k++)
        snprintf(v->cam_items[n++], sizeof v->cam_items[0], "%u %s (node %s)%s", k, sc->cameras[k].name,
                 sc->cameras[k].node_name, sc->cameras[k].type == PG_CAMERA_ORTHOGRAPHIC ? " [orthographic]" : "");
    for (int i = 0; i < n; i++) v->cam_ptrs[i] = v->cam_items[i];
    v->n_cam_items = n;
    v->cam_choice = 0;
}

/* Applies combo item `choice` (0 start view, 1 auto framing, 2.. the glTF cameras). */
static void camera_choose(viewer *v, int choice)
{
    const pg_scene *sc = v->app.scene;
    float aspect = v->win.extent.height ? (float)v->win.extent.width / (float)v->win.extent.height : 16.0f / 9;
    pg_camera cam = v->home;
    if (choice == 1) {
        float r = 0, d = 0;
        cam = pg_camera_frame_object(sc, aspect, &r, &d);
        printf("view: camera: auto framing (bounds radius %.3g, distance %.3g)\n", r, d);
    } else if (choice >= 2) {
        pg_error err = {0};
        if (pg_camera_from_scene(sc, (uint32_t)(choice - 2), aspect, &cam, &err)) {
            snprintf(v->error, sizeof v->error, "%s", err.msg);
            return;
        }
        printf("view: camera: glTF camera %d '%s'\n", choice - 2, sc->cameras[choice - 2].name);
    }
    v->cam_choice = choice;
    v->camera = cam;
    camera_angles(v);
}

static void camera_update(viewer *v, float dt)
{
    float fwd[3] = {cosf(v->pitch) * cosf(v->yaw), sinf(v->pitch), cosf(v->pitch) * sinf(v->yaw)};
    float right[3] = {-sinf(v->yaw), 0, cosf(v->yaw)};
    GLFWwindow *w = v->window;
    if (!pg_ui_want_keyboard()) {
        float s = v->move_speed * dt * (glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ? 4.0f : 1.0f);
        float mv[3] = {0, 0, 0};
        if (glfwGetKey(w, GLFW_KEY_W) == GLFW_PRESS)
            for (int k = 0; k < 3; k++) mv[k] += fwd[k] * s;
        if (glfwGetKey(w, GLFW_KEY_S) == GLFW_PRESS)
            for (int k = 0; k < 3; k++) mv[k] -= fwd[k] * s;
        if (glfwGetKey(w, GLFW_KEY_D) == GLFW_PRESS)
            for (int k = 0; k < 3; k++) mv[k] += right[k] * s;
        if (glfwGetKey(w, GLFW_KEY_A) == GLFW_PRESS)
            for (int k = 0; k < 3; k++) mv[k] -= right[k] * s;
        if (glfwGetKey(w, GLFW_KEY_E) == GLFW_PRESS) mv[1] += s;
        if (glfwGetKey(w, GLFW_KEY_Q) == GLFW_PRESS) mv[1] -= s;
        for (int k = 0; k < 3; k++) v->camera.position[k] += mv[k];
    }
    double x, y;
    glfwGetCursorPos(w, &x, &y);
    bool rmb = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    if (rmb && (v->looking || !pg_ui_want_mouse())) {
        if (v->looking) {
            v->yaw += (float)(x - v->last_x) * 0.004f;
            v->pitch -= (float)(y - v->last_y) * 0.004f;
            v->pitch = fmaxf(-1.55f, fminf(1.55f, v->pitch));
        }
        v->looking = true;
    } else {
        v->looking = false;
    }
    v->last_x = x;
    v->last_y = y;
    fwd[0] = cosf(v->pitch) * cosf(v->yaw);
    fwd[1] = sinf(v->pitch);
    fwd[2] = cosf(v->pitch) * sinf(v->yaw);
    for (int k = 0; k < 3; k++) v->camera.target[k] = v->camera.position[k] + fwd[k];
}

/* ---------------------------------------------------------------- UI */

static void param_widget(viewer *v, const pg_param *p)
{
    char val[PG_NAME_MAX];
    bool changed = false;
    switch (p->type) {
    case PG_PARAM_ENUM: {
        int cur = 0;
        const char *items[PG_MAX_ENUM_VALUES];
        for (uint32_t i = 0; i < p->n_values; i++) {
            items[i] = p->values[i];
            if (!strcmp(p->values[i], p->enum_value)) cur = (int)i;
        }
        if (pg_ui_combo(p->name, &cur, items, (int)p->n_values)) {
            snprintf(val, sizeof val, "%s", p->values[cur]);
            changed = true;
        }
        break;
    }
    case PG_PARAM_INT: {
        int x = (int)p->number;
        double lo = isfinite(p->min) ? p->min : 0, hi = isfinite(p->max) ? p->max : 4096;
        if (hi - lo <= 4096) changed = pg_ui_slider_int(p->name, &x, (int)lo, (int)hi, false);
        else changed = pg_ui_input_int(p->name, &x);
        if (changed) {
            if (x < lo) x = (int)lo;
            if (x > hi) x = (int)hi;
            snprintf(val, sizeof val, "%d", x);
        }
        break;
    }
    case PG_PARAM_FLOAT: {
        float x = (float)p->number;
        double lo = isfinite(p->min) ? p->min : 0, hi = isfinite(p->max) ? p->max : 100;
        bool log = lo > 0 && hi / lo > 100;
        if (hi > 1e4 && lo <= 0) hi = 100; /* a usable slider range; the JSON range still applies */
        if ((changed = pg_ui_slider_float(p->name, &x, (float)lo, (float)hi, "%.4g", log || hi > 1000)))
            snprintf(val, sizeof val, "%.9g", x);
        break;
    }
    case PG_PARAM_BOOL: {
        bool b = p->boolean;
        if ((changed = pg_ui_checkbox(p->name, &b))) snprintf(val, sizeof val, "%s", b ? "true" : "false");
        break;
    }
    }
    if (p->description[0]) pg_ui_tooltip(p->description);
    if (changed) {
        set_override(v, p->name, val);
        v->reload = true;
    }
}

static uint32_t block_color(int block)
{
    static const uint32_t c[] = {0x4e79a7ff, 0xf28e2bff, 0xe15759ff, 0x76b7b2ff, 0x59a14fff,
                                 0xedc948ff, 0xb07aa1ff, 0xff9da7ff, 0x9c755fff, 0xbab0acff};
    return c[(block < 0 ? 0 : block) % 10];
}

static void memory_timeline(const pg_graph_plan *p)
{
    int rows = 0;
    for (uint32_t r = 0; r < p->n_resources; r++)
        if (!p->resources[r].culled && p->resources[r].lifetime == PG_LIFETIME_TRANSIENT) rows++;
    if (!rows || !p->n_order) return;
    float w = pg_ui_avail_width(), label = 110, row_h = 16;
    float col_w = (w - label) / (float)(p->n_order + 1);
    pg_ui_canvas_begin(w, row_h * (float)(rows + 1) + 4);
    for (uint32_t k = 0; k <= p->n_order; k++) {
        char t[8];
        snprintf(t, sizeof t, "%u", k);
        pg_ui_canvas_text(label + col_w * (float)k + 2, 0, 0xaaaaaaff, k < p->n_order ? t : "end");
    }
    int row = 0;
    for (uint32_t r = 0; r < p->n_resources; r++) {
        const pg_plan_resource *pr = &p->resources[r];
        if (pr->culled || pr->lifetime != PG_LIFETIME_TRANSIENT) continue;
        float y = row_h * (float)(row + 1);
        char t[PG_NAME_MAX + 8];
        snprintf(t, sizeof t, "%.12s #%d", pr->name, pr->block);
        pg_ui_canvas_text(0, y, 0xddddddff, t);
        float x0 = label + col_w * (float)pr->first_pass, x1 = label + col_w * (float)(pr->last_pass + 1);
        pg_ui_canvas_rect(x0, y + 2, x1 - 2, y + row_h - 2, block_color(pr->block), true);
        row++;
    }
    pg_ui_canvas_end();
}

static void build_ui(viewer *v)
{
    pg_ui_new_frame();
    if (pg_ui_begin("passgraph", 10, 10, 390, (float)v->win.extent.height - 20)) {
        if (pg_ui_combo("pipeline", &v->requested, v->name_ptrs, v->n_pipelines)) v->reload = true;
        if (v->error[0]) {
            pg_ui_text_colored(0xff5050ff, "error (the last good graph keeps running):");
            pg_ui_text_wrapped(v->error);
        }
        const pg_pipeline *pl = v->session ? v->session->pipeline : NULL;
        if (pl && pl->description[0]) pg_ui_text_wrapped(pl->description);
        if (pg_ui_header("Scene and lights", true)) {
            pg_ui_text("scene: %s", v->app.scene_path);
            /* what the loader could not draw as the file asks (scene.h: warnings) */
            for (uint32_t k = 0; v->app.scene && k < v->app.scene->n_warnings; k++) {
                pg_ui_text_colored(0xffc040ff, "warning:");
                pg_ui_text_wrapped(v->app.scene->warnings[k]);
            }
            if (pg_ui_input_text("open glTF", v->scene_input, sizeof v->scene_input) && v->scene_input[0]) {
                pg_scene *sc = NULL;
                pg_scene_gpu *sg = NULL;
                pg_error err = {0};
                if (pg_scene_load(v->scene_input, &sc, &err) || pg_scene_gpu_create(v->app.gpu, sc, &sg, &err)) {
                    snprintf(v->error, sizeof v->error, "%s", err.msg);
                    pg_scene_free(sc);
                } else {
                    pg_scene_print_warnings(sc, "passgraph view: ", stderr);
                    vkDeviceWaitIdle(v->app.gpu->device);
                    pg_session_destroy(v->session);
                    pg_session_destroy(v->naive);
                    v->session = v->naive = NULL;
                    pg_scene_gpu_destroy(v->app.gpu, v->app.scene_gpu);
                    pg_scene_free(v->app.scene);
                    v->app.scene = sc;
                    v->app.scene_gpu = sg;
                    pg_strlcpy(v->app.scene_path, v->scene_input, sizeof v->app.scene_path);
                    pg_light_setup ls;
                    char cw[256], lw[256];
                    pg_error verr = {0};
                    float aspect = v->win.extent.height ? (float)v->win.extent.width / (float)v->win.extent.height
                                                        : 16.0f / 9;
                    if (pg_app_default_view(sc, NULL, aspect, (uint32_t)v->light_count, (uint32_t)v->seed, &v->home,
                                            &ls, cw, sizeof cw, lw, sizeof lw, &verr))
                        snprintf(v->error, sizeof v->error, "%s", verr.msg);
                    printf("view: %s\nview: %s\n", cw, lw);
                    v->camera = v->home;
                    camera_angles(v);
                    camera_list(v, "start view");
                    v->app.lights = ls;
                    v->radius = ls.radius;
                    v->intensity = ls.intensity;
                    v->ambient = ls.ambient;
                    v->reload = true;
                }
            }
            pg_ui_slider_int("lights", &v->light_count, 0, 1000000, true);
            pg_ui_slider_float("radius", &v->radius, 0.01f, 100.0f, "%.3f", true);
            pg_ui_slider_float("intensity", &v->intensity, 0.001f, 100.0f, "%.3f", true);
            pg_ui_slider_float("ambient", &v->ambient, 0.0f, 1.0f, "%.3f", false);
            pg_ui_slider_float("motion speed", &v->speed, 0.0f, 10.0f, "%.2f", false);
            pg_ui_input_int("seed", &v->seed);
            pg_ui_checkbox("pause", &v->paused);
            pg_ui_same_line();
            pg_ui_text("time %.2f s", v->time);
            pg_ui_slider_float("fly speed", &v->move_speed, 0.01f, 1000.0f, "%.2f", true);
            int cam_cur = v->cam_choice;
            if (pg_ui_combo("camera", &cam_cur, v->cam_ptrs, v->n_cam_items) && cam_cur != v->cam_choice)
                camera_choose(v, cam_cur);
            if (pg_ui_button("reset view")) {
                v->camera = v->home;
                v->cam_choice = 0;
                camera_angles(v);
            }
            pg_ui_same_line();
            if (pg_ui_button("screenshot")) {
                v->want_shot = true;
                snprintf(v->shot_file, sizeof v->shot_file, "passgraph-%ld.png", (long)time(NULL));
            }
            pg_ui_same_line();
            if (pg_ui_button("RenderDoc capture")) v->want_rdoc = true;
            pg_ui_text("WASD/QE fly (shift: faster), right mouse: look, C: RenderDoc capture");
            if (v->rdoc_status[0]) pg_ui_text("%s", v->rdoc_status);
        }
        colour_ui(v);
        if (pl && pg_ui_header("Pipeline parameters", true)) {
            for (uint32_t i = 0; i < pl->n_params; i++) param_widget(v, &pl->params[i]);
            if (pg_ui_checkbox("difference to the reference (heatmap)", &v->diff)) v->hist_n = 0;
            if (v->diff)
                pg_ui_text("linear RMSE %.4g, colour scale 0..%.4g", v->diff_rmse, v->diff_scale);
        }
    }
    pg_ui_end();
    float right_w = 420, right_x = (float)v->win.extent.width - right_w - 10;
    if (right_x < 410) right_x = 410;
    if (pg_ui_begin("graph", right_x, 10, right_w, (float)v->win.extent.height - 20)) {
        if (v->session && pg_ui_header("GPU timings", true)) {
            const pg_frame_stats *st = &v->stats;
            pg_ui_text("frame %.2f ms CPU, %.3f ms GPU (%s)", v->cpu_frame_ms, st->gpu_total_ms,
                       v->app.gpu->props.deviceName);
            if (st->n_counters) {
                pg_ui_text_colored(st->overflow_clusters ? 0xffa040ff : 0xa0ffa0ff,
                                   "light overflow: %llu clusters, %llu light refs dropped",
                                   (unsigned long long)st->overflow_clusters,
                                   (unsigned long long)st->overflow_dropped);
                uint64_t list_bytes = 0, refs = 0;
                for (uint32_t k = 0; k < st->n_counters; k++) {
                    if (!strcmp(st->counters[k].name, "list_bytes")) list_bytes += st->counters[k].value;
                    if (!strcmp(st->counters[k].name, "total_refs")) refs += st->counters[k].value;
                }
                if (list_bytes)
                    pg_ui_text("light lists: %llu refs in %.2f MiB; grew %u time%s%s%s", (unsigned long long)refs,
                               list_bytes / 1048576.0, v->growths, v->growths == 1 ? "" : "s",
                               v->last_growth[0] ? ", last: " : "", v->last_growth);
            }
            for (uint32_t k = 0; k < st->n_notes; k++) pg_ui_text_colored(0xffa040ff, "%s", st->notes[k]);
            static const char *const cols[] = {"pass", "ms", "share"};
            if (pg_ui_table_begin("timings", 3)) {
                pg_ui_table_header(cols, 3);
                for (uint32_t p = 0; p < st->n_passes; p++) {
                    pg_ui_table_next_row();
                    pg_ui_table_cell("%s%s", st->pass_names[p], /* the queue it ran on, when two */
                                     st->n_batches > 1 ? (st->pass_queue[p] == PG_QUEUE_COMPUTE ? " [compute]" : " [graphics]") : "");
                    pg_ui_table_cell("%.3f", st->pass_ms[p]);
                    pg_ui_table_cell("%.0f%%", st->gpu_total_ms > 0 ? 100 * st->pass_ms[p] / st->gpu_total_ms : 0);
                }
                pg_ui_table_end();
            }
            int n = v->hist_n < HIST ? v->hist_n : HIST;
            int off = v->hist_n < HIST ? 0 : v->hist_pos;
            float mx = 0;
            for (int i = 0; i < n; i++) mx = fmaxf(mx, v->hist_total[i]);
            char overlay[64];
            snprintf(overlay, sizeof overlay, "GPU total %.2f ms", st->gpu_total_ms);
            pg_ui_plot_lines("##total", v->hist_total, n, off, overlay, 0, mx * 1.1f + 1e-3f, pg_ui_avail_width(), 50);
            for (uint32_t p = 0; p < st->n_passes && p < PG_MAX_PASSES; p++) {
                float pm = 0;
                for (int i = 0; i < n; i++) pm = fmaxf(pm, v->hist_pass[p][i]);
                snprintf(overlay, sizeof overlay, "%s %.3f ms", st->pass_names[p], st->pass_ms[p]);
                pg_ui_push_id((int)p);
                pg_ui_plot_lines("##pass", v->hist_pass[p], n, off, overlay, 0, pm * 1.1f + 1e-3f, pg_ui_avail_width(), 28);
                pg_ui_pop_id();
            }
        }
        if (v->session && v->session->plan && pg_ui_header("Memory", true)) {
            const pg_graph_plan *p = v->session->plan;
            pg_runtime_stats rs = pg_runtime_get_stats(v->session->runtime);
            pg_ui_text("transient: %.2f MiB -> %.2f MiB aliased (plan)", p->transient_bytes_unaliased / 1048576.0,
                       p->transient_bytes_aliased / 1048576.0);
            pg_ui_text("device memory: %.2f MiB -> %.2f MiB", rs.memory_bytes_unaliased / 1048576.0,
                       rs.memory_bytes_transient / 1048576.0);
            pg_ui_text("passes run %u, culled %u; resources rebuilt %u times", p->n_order, p->n_passes - p->n_order,
                       rs.resource_creations);
            memory_timeline(p);
        }
        if (v->session && v->session->plan && pg_ui_header("Left out and culled", false)) {
            const pg_graph_plan *p = v->session->plan;
            for (uint32_t i = 0; i < p->n_explain; i++) pg_ui_text_wrapped(p->explain[i]);
        }
    }
    pg_ui_end();
}

/* ---------------------------------------------------------------- difference view */

static pg_result update_diff(viewer *v, pg_error *err)
{
    uint32_t w, h, rw, rh;
    pg_format fa, fb;
    const void *a = pg_runtime_output(v->session->runtime, 1, &w, &h, &fa);
    const void *b = v->naive ? pg_runtime_output(v->naive->runtime, 1, &rw, &rh, &fb) : NULL;
    if (!a || !b || w != rw || h != rh)
        return pg_fail(err, PG_ERR_INVALID_ARG, "difference view needs both pipelines to declare an hdr_output");
    size_t px = (size_t)w * h;
    if (!v->diff_image.image || v->diff_image.width != w || v->diff_image.height != h) {
        vkDeviceWaitIdle(v->app.gpu->device);
        pg_image_destroy(v->app.gpu, &v->diff_image);
        pg_buffer_destroy(v->app.gpu, &v->diff_staging);
        free(v->diff_rgba);
        free(v->hdr_a);
        free(v->hdr_b);
        v->diff_rgba = malloc(px * 4);
        v->hdr_a = malloc(px * 16);
        v->hdr_b = malloc(px * 16);
        if (!v->diff_rgba || !v->hdr_a || !v->hdr_b) return pg_fail(err, PG_ERR_OOM, "out of memory");
        pg_result r;
        if ((r = pg_image_create(v->app.gpu, VK_FORMAT_R8G8B8A8_SRGB, w, h, 1,
                                 VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                                 "view.diff",
                                 &v->diff_image, err)))
            return r;
        if ((r = pg_buffer_create(v->app.gpu, px * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true, "view.diff.staging",
                                  &v->diff_staging, err)))
            return r;
    }
    pg_result r;
    if ((r = pg_hdr_to_float(a, fa, w, h, v->hdr_a, err)) || (r = pg_hdr_to_float(b, fb, w, h, v->hdr_b, err))) return r;
    v->diff_scale = pg_error_quantile(v->hdr_a, v->hdr_b, w, h, 0.99);
    pg_error_heatmap(v->hdr_a, v->hdr_b, w, h, v->diff_scale, v->diff_rgba);
    double se = 0;
    for (size_t i = 0; i < px * 4; i++)
        if (i % 4 != 3) se += (double)(v->hdr_a[i] - v->hdr_b[i]) * (v->hdr_a[i] - v->hdr_b[i]);
    v->diff_rmse = sqrt(se / (double)(px * 3));
    memcpy(v->diff_staging.mapped, v->diff_rgba, px * 4);
    return PG_OK;
}

/* ---------------------------------------------------------------- one frame */

static bool srgb_format(VkFormat f)
{
    return f == VK_FORMAT_R8G8B8A8_SRGB || f == VK_FORMAT_B8G8R8A8_SRGB || f == VK_FORMAT_A8B8G8R8_SRGB_PACK32;
}

/* The image to blit into the swapchain. The graph's 8-bit output holds display-encoded bytes
 * whether it is rgba8 (the OCIO display pass encoded them) or rgba8_srgb (encoded on write); a
 * blit between a UNORM and an sRGB format would decode or encode them once more, so when the
 * output's kind differs from the swapchain's the bytes are first copied (vkCmdCopyImage: no
 * conversion) into an image of the swapchain's kind. */
static pg_result present_source(viewer *v, VkCommandBuffer cmd, const pg_phys_resource *out, VkImage *src,
                                pg_error *err)
{
    *src = out->image;
    VkFormat other;
    if (out->format == VK_FORMAT_R8G8B8A8_UNORM) other = VK_FORMAT_R8G8B8A8_SRGB;
    else if (out->format == VK_FORMAT_R8G8B8A8_SRGB) other = VK_FORMAT_R8G8B8A8_UNORM;
    else return PG_OK; /* float outputs: the blit converts values, which is right for them */
    if (srgb_format(out->format) == srgb_format(v->win.format)) return PG_OK;
    pg_image *pc = &v->present_copy;
    if (!pc->image || pc->format != other || pc->width != out->width || pc->height != out->height) {
        vkDeviceWaitIdle(v->app.gpu->device);
        pg_image_destroy(v->app.gpu, pc);
        pg_result r = pg_image_create(v->app.gpu, other, out->width, out->height, 1,
                                      VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                          VK_IMAGE_USAGE_SAMPLED_BIT, /* pg_image_create makes a view */
                                      "view.present_copy", pc, err);
        if (r) return r;
    }
    VkImageMemoryBarrier2 b = pg_image_barrier(pc->image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT, 0,
                                               VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                               VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    pg_cmd_barriers(cmd, 1, &b, 0, NULL);
    VkImageCopy c = {.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                     .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                     .extent = {out->width, out->height, 1}};
    vkCmdCopyImage(cmd, out->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, pc->image,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &c);
    b = pg_image_barrier(pc->image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                         VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                         VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    pg_cmd_barriers(cmd, 1, &b, 0, NULL);
    *src = pc->image;
    return PG_OK;
}

static pg_result draw_frame(viewer *v, bool capture, pg_error *err)
{
    pg_gpu *gpu = v->app.gpu;
    pg_view_window *w = &v->win;
    double t0 = now_s();
    pg_frame_info fi = pg_app_frame(&v->app);
    fi.camera = v->camera;
    fi.lights.count = (uint32_t)v->light_count;
    fi.lights.radius = v->radius;
    fi.lights.intensity = v->intensity;
    fi.lights.ambient = v->ambient;
    fi.lights.speed = v->speed;
    fi.lights.seed = (uint32_t)v->seed;
    fi.time = v->time;
    fi.width = w->extent.width;
    fi.height = w->extent.height;
    pg_result r = pg_session_render(v->session, &fi, v->diff, &v->stats, err);
    if (r) return r;
    for (uint32_t k = 0; k < v->stats.n_grown; k++) {
        v->growths++;
        snprintf(v->last_growth, sizeof v->last_growth, "%s grew %.2f -> %.2f MiB at %d lights", v->stats.grown[k].resource,
                 v->stats.grown[k].old_bytes / 1048576.0, v->stats.grown[k].new_bytes / 1048576.0, v->light_count);
        printf("view: %s\n", v->last_growth);
    }
    if (v->stats.overflow_dropped && v->stats.n_notes) printf("view: %s\n", v->stats.notes[0]);
    bool show_diff = false;
    if (v->diff) {
        if (!v->naive) {
            char naive[PG_PATH_MAX];
            pg_data_path(naive, sizeof naive, "pipelines/reference.json"); /* exact, fast at any count */
            if ((r = open_session(v, naive, false, &v->naive, err))) return r;
        }
        pg_frame_stats ns;
        if ((r = pg_session_render(v->naive, &fi, true, &ns, err))) return r;
        /* the diff staging is written by the host: no viewer frame may still read it */
        PG_VK_TRY(err, vkWaitForFences(gpu->device, PG_VIEW_FRAMES, w->fence, VK_TRUE, UINT64_MAX));
        if ((r = update_diff(v, err))) return r;
        show_diff = true;
    }
    /* statistics history */
    v->hist_total[v->hist_pos] = (float)v->stats.gpu_total_ms;
    for (uint32_t p = 0; p < v->stats.n_passes && p < PG_MAX_PASSES; p++) v->hist_pass[p][v->hist_pos] = (float)v->stats.pass_ms[p];
    v->hist_pos = (v->hist_pos + 1) % HIST;
    v->hist_n++;

    /* this slot's previous frame (two frames ago) must be done with its command buffer and semaphore */
    const uint32_t fs = w->slot;
    PG_VK_TRY(err, vkWaitForFences(gpu->device, 1, &w->fence[fs], VK_TRUE, UINT64_MAX));
    uint32_t index;
    VkResult vr = vkAcquireNextImageKHR(gpu->device, w->swapchain, UINT64_MAX, w->image_ready[fs], VK_NULL_HANDLE, &index);
    if (vr == VK_ERROR_OUT_OF_DATE_KHR) { /* the semaphore was not signalled: rebuild, next frame */
        bool minimised;
        return pg_view_window_resize(w, &minimised, err);
    }
    if (vr != VK_SUCCESS && vr != VK_SUBOPTIMAL_KHR)
        return pg_fail(err, PG_ERR_VULKAN, "vkAcquireNextImageKHR failed: %s", pg_vk_result_name(vr));

    build_ui(v);

    VkCommandBuffer cmd = w->cmd[fs];
    PG_VK_TRY(err, vkResetCommandBuffer(cmd, 0));
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                   .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    PG_VK_TRY(err, vkBeginCommandBuffer(cmd, &bi));
    VkImage src = VK_NULL_HANDLE;
    uint32_t sw = 0, sh = 0;
    if (show_diff) {
        VkImageMemoryBarrier2 b = pg_image_barrier(v->diff_image.image, VK_IMAGE_ASPECT_COLOR_BIT,
                                                   VK_PIPELINE_STAGE_2_BLIT_BIT, 0, VK_PIPELINE_STAGE_2_COPY_BIT,
                                                   VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                                                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        pg_cmd_barriers(cmd, 1, &b, 0, NULL);
        VkBufferImageCopy c = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                               .imageExtent = {v->diff_image.width, v->diff_image.height, 1}};
        vkCmdCopyBufferToImage(cmd, v->diff_staging.buffer, v->diff_image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &c);
        b = pg_image_barrier(v->diff_image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                             VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                             VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        pg_cmd_barriers(cmd, 1, &b, 0, NULL);
        src = v->diff_image.image;
        sw = v->diff_image.width;
        sh = v->diff_image.height;
    } else {
        const pg_phys_resource *out = pg_runtime_output_image(v->session->runtime, 0);
        if ((r = present_source(v, cmd, out, &src, err))) return r;
        sw = out->width;
        sh = out->height;
    }
    /* the acquire semaphore is waited at the blit stage; the transition chains after it */
    VkImageMemoryBarrier2 to_dst = pg_image_barrier(w->images[index], VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT,
                                                    0, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                                    VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    pg_cmd_barriers(cmd, 1, &to_dst, 0, NULL);
    VkImageBlit blit = {
        .srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
        .srcOffsets = {{0, 0, 0}, {(int32_t)sw, (int32_t)sh, 1}},
        .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
        .dstOffsets = {{0, 0, 0}, {(int32_t)w->extent.width, (int32_t)w->extent.height, 1}},
    };
    vkCmdBlitImage(cmd, src, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, w->images[index], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                   &blit, VK_FILTER_NEAREST);
    bool shot = capture && w->usage_transfer_src;
    VkRenderPassBeginInfo rp = {
        .sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO,
        .renderPass = shot ? w->pass_capture : w->pass_present,
        .framebuffer = w->framebuffers[index],
        .renderArea = {{0, 0}, w->extent},
    };
    vkCmdBeginRenderPass(cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
    pg_ui_render(cmd);
    vkCmdEndRenderPass(cmd);
    if (shot) {
        VkDeviceSize bytes = (VkDeviceSize)w->extent.width * w->extent.height * 4;
        if (v->shot.size < bytes) {
            pg_buffer_destroy(gpu, &v->shot);
            if ((r = pg_buffer_create(gpu, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, "view.screenshot", &v->shot, err)))
                return r;
        }
        VkBufferImageCopy c = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                               .imageExtent = {w->extent.width, w->extent.height, 1}};
        vkCmdCopyImageToBuffer(cmd, w->images[index], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, v->shot.buffer, 1, &c);
        VkImageMemoryBarrier2 to_present = pg_image_barrier(
            w->images[index], VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, 0, VK_PIPELINE_STAGE_2_NONE, 0,
            VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
        VkBufferMemoryBarrier2 host = pg_buffer_barrier(v->shot.buffer, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                                  VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        pg_cmd_barriers(cmd, 1, &to_present, 1, &host);
    }
    PG_VK_TRY(err, vkEndCommandBuffer(cmd));
    VkSemaphoreSubmitInfo wait = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO,
                                  .semaphore = w->image_ready[fs],
                                  .stageMask = VK_PIPELINE_STAGE_2_BLIT_BIT};
    VkSemaphoreSubmitInfo signal = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO,
                                    .semaphore = w->render_done[index],
                                    .stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT};
    VkCommandBufferSubmitInfo cbi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = cmd};
    VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2,
                        .waitSemaphoreInfoCount = 1,
                        .pWaitSemaphoreInfos = &wait,
                        .commandBufferInfoCount = 1,
                        .pCommandBufferInfos = &cbi,
                        .signalSemaphoreInfoCount = 1,
                        .pSignalSemaphoreInfos = &signal};
    PG_VK_TRY(err, vkResetFences(gpu->device, 1, &w->fence[fs]));
    PG_VK_TRY(err, vkQueueSubmit2(gpu->queue, 1, &si, w->fence[fs]));
    w->slot = (fs + 1) % PG_VIEW_FRAMES;
    VkPresentInfoKHR pi = {.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR,
                           .waitSemaphoreCount = 1,
                           .pWaitSemaphores = &w->render_done[index],
                           .swapchainCount = 1,
                           .pSwapchains = &w->swapchain,
                           .pImageIndices = &index};
    vr = vkQueuePresentKHR(gpu->queue, &pi);
    if (shot) { /* the screenshot is read after its own frame */
        PG_VK_TRY(err, vkWaitForFences(gpu->device, 1, &w->fence[fs], VK_TRUE, UINT64_MAX));
        /* swapchain pixels -> RGBA for the PNG */
        uint32_t n = w->extent.width * w->extent.height;
        uint8_t *px = malloc((size_t)n * 4);
        if (px) {
            memcpy(px, v->shot.mapped, (size_t)n * 4);
            if (w->format == VK_FORMAT_B8G8R8A8_SRGB || w->format == VK_FORMAT_B8G8R8A8_UNORM)
                for (uint32_t i = 0; i < n; i++) {
                    uint8_t t = px[i * 4];
                    px[i * 4] = px[i * 4 + 2];
                    px[i * 4 + 2] = t;
                }
            for (uint32_t i = 0; i < n; i++) px[i * 4 + 3] = 255;
            r = pg_write_image(v->shot_file, px, w->extent.width, w->extent.height, err);
            free(px);
            if (r) return r;
            printf("view: screenshot %s (%ux%u)\n", v->shot_file, w->extent.width, w->extent.height);
        }
    } else if (capture) {
        fprintf(stderr, "passgraph view: this surface cannot be read back; screenshot skipped\n");
    }
    if (vr == VK_ERROR_OUT_OF_DATE_KHR || vr == VK_SUBOPTIMAL_KHR) {
        bool minimised;
        if ((r = pg_view_window_resize(w, &minimised, err))) return r;
    } else if (vr != VK_SUCCESS) {
        return pg_fail(err, PG_ERR_VULKAN, "vkQueuePresentKHR failed: %s", pg_vk_result_name(vr));
    }
    v->cpu_frame_ms = (now_s() - t0) * 1e3;
    if (v->n_frame_ms < 512) v->frame_ms[v->n_frame_ms++] = v->cpu_frame_ms;
    return PG_OK;
}

/* ---------------------------------------------------------------- command */

static bool present_ok(VkInstance instance, VkPhysicalDevice phys, uint32_t family, void *user)
{
    (void)user;
    return glfwGetPhysicalDevicePresentationSupport(instance, phys, family) == GLFW_TRUE;
}

/* Scripted actions (--at FRAME:ACTION) for tests and demos. */
static pg_result run_action(viewer *v, const view_action *a, pg_error *err)
{
    printf("view: frame %u: %s %s\n", a->frame, a->what, a->arg);
    if (!strcmp(a->what, "resize")) {
        unsigned w = 0, h = 0;
        if (sscanf(a->arg, "%ux%u", &w, &h) != 2 || !w || !h || w > 16384 || h > 16384)
            return pg_fail(err, PG_ERR_INVALID_ARG, "--at %u:resize=%s: expected WxH", a->frame, a->arg);
        glfwSetWindowSize(v->window, (int)w, (int)h);
    } else if (!strcmp(a->what, "iconify")) {
        glfwIconifyWindow(v->window);
    } else if (!strcmp(a->what, "restore")) {
        glfwRestoreWindow(v->window);
    } else if (!strcmp(a->what, "copy")) { /* simulate an edit on disk: copy SRC over DST */
        char src[PG_PATH_MAX * 2];
        pg_strlcpy(src, a->arg, sizeof src);
        char *colon = strchr(src, ':');
        if (!colon) return pg_fail(err, PG_ERR_INVALID_ARG, "--at %u:copy=%s: expected SRC:DST", a->frame, a->arg);
        *colon = 0;
        char *text = NULL;
        size_t len = 0;
        pg_result r = pg_read_file(src, &text, &len, err);
        if (r) return r;
        FILE *f = fopen(colon + 1, "wb");
        if (!f) {
            free(text);
            return pg_fail(err, PG_ERR_IO, "%s: cannot write", colon + 1);
        }
        fwrite(text, 1, len, f);
        fclose(f);
        free(text);
        v->last_watch = 0; /* look at the disk on this frame */
    } else if (!strcmp(a->what, "set")) {
        char kv[PG_PATH_MAX];
        pg_strlcpy(kv, a->arg, sizeof kv);
        char *eq = strchr(kv, '=');
        if (!eq) return pg_fail(err, PG_ERR_INVALID_ARG, "--at %u:set=%s: expected KEY=VALUE", a->frame, a->arg);
        *eq = 0;
        set_override(v, kv, eq + 1);
        v->reload = true;
    } else if (!strcmp(a->what, "pipeline")) {
        for (int i = 0; i < v->n_pipelines; i++)
            if (!strcmp(v->names[i], a->arg)) v->requested = i;
        v->reload = true;
    } else if (!strcmp(a->what, "display") || !strcmp(a->what, "ocioview")) {
        pg_result r = !strcmp(a->what, "display") ? colour_choose(v, a->arg, NULL, err)
                                                  : colour_choose(v, NULL, a->arg, err);
        if (r) return pg_error_prefix(err, "--at %u:%s=%s", a->frame, a->what, a->arg);
    } else if (!strcmp(a->what, "diff")) {
        v->diff = !strcmp(a->arg, "on");
    } else if (!strcmp(a->what, "lights")) {
        v->light_count = atoi(a->arg);
    } else if (!strcmp(a->what, "camera")) {
        if (!strcmp(a->arg, "auto")) {
            camera_choose(v, 1);
        } else {
            uint32_t k = 0;
            pg_result r = pg_scene_find_camera(v->app.scene, a->arg, &k, err);
            if (r) return pg_error_prefix(err, "--at %u:camera", a->frame);
            v->error[0] = 0;
            camera_choose(v, (int)k + 2);
            if (v->error[0]) return pg_fail(err, PG_ERR_INVALID_ARG, "--at %u:camera=%s: %s", a->frame, a->arg, v->error);
        }
    } else if (!strcmp(a->what, "screenshot")) {
        v->want_shot = true;
        pg_strlcpy(v->shot_file, a->arg, sizeof v->shot_file);
    } else if (!strcmp(a->what, "capture")) {
        v->want_rdoc = true;
        pg_strlcpy(v->rdoc_file, a->arg, sizeof v->rdoc_file);
    } else {
        return pg_fail(err, PG_ERR_INVALID_ARG, "--at %u:%s: unknown action (resize, iconify, restore, copy, set, pipeline, display, ocioview, diff, lights, camera, screenshot, capture)",
                       a->frame, a->what);
    }
    return PG_OK;
}

/* RenderDoc capture of one viewer frame: found on first use; without it the status line (and
 * stderr) says why and the viewer goes on. */
static bool rdoc_ready(viewer *v)
{
    if (!v->rdoc) {
        char why[512];
        v->rdoc = pg_rdoc_open(why, sizeof why);
        if (!v->rdoc) {
            snprintf(v->rdoc_status, sizeof v->rdoc_status, "RenderDoc capture: %s", why);
            fprintf(stderr, "passgraph view: %s\n", v->rdoc_status);
            return false;
        }
    }
    return true;
}

static void rdoc_finish(viewer *v)
{
    char why[600], path[PG_PATH_MAX];
    if (!pg_rdoc_end(v->rdoc, v->rdoc_file[0] ? v->rdoc_file : NULL, why, sizeof why)) {
        snprintf(v->rdoc_status, sizeof v->rdoc_status, "RenderDoc capture failed: %s", why);
        fprintf(stderr, "passgraph view: %s\n", v->rdoc_status);
        return;
    }
    if (v->rdoc_file[0]) pg_strlcpy(path, v->rdoc_file, sizeof path);
    else pg_rdoc_captures(v->rdoc, path, sizeof path);
    snprintf(v->rdoc_status, sizeof v->rdoc_status, "RenderDoc capture %s", path);
    printf("view: %s\n", v->rdoc_status);
}

static const char *const view_help =
    "usage: passgraph view [options]\n"
    "Opens a window on the scene lit by the lights, rendered by a pipeline that can be switched,\n"
    "tuned and edited live: every JSON file in pipelines/ (and --pipelines DIR) is listed; editing a\n"
    "pipeline or shader on disk reloads it (a broken file shows its error and the last good graph\n"
    "keeps running). Controls: light count, radius, intensity, seed, time, every pipeline parameter\n"
    "(debug views included), OpenColorIO display, view and exposure, difference to the reference, camera\n"
    "fly (WASD/QE, right mouse to look).\n"
    "Scripted mode for tests and demos: --frames N [--screenshot FILE.png] [--cycle-pipelines].\n\n"
    "options:\n";

int pg_cmd_view(int argc, char **argv)
{
    pg_cli_common opt;
    pg_cli_defaults(&opt);
    opt.width = 1280;
    opt.height = 720;
    pg_error err = {0};
    viewer *v = calloc(1, sizeof *v);
    if (!v) return 1;
    v->cycle_every = 20;
    v->frames_in_flight = 2;
    for (int i = 0; i < argc; i++) {
        bool used;
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            printf("%s%s"
                   "  --frames-in-flight N 2 (default) or 1: frames the displayed graph keeps in flight\n"
                   "  --size WxH           initial window size (default 1280x720)\n"
                   "  --pipelines DIR      also list the pipelines in DIR\n"
                   "  --screenshot FILE    write the window (scene + UI) to FILE (.png, .jpg) at the last frame\n"
                   "  --cycle-pipelines    switch to the next pipeline every --cycle-every frames\n"
                   "  --cycle-every K      frames between switches (default 20)\n"
                   "  --random-params      with --cycle-pipelines: random shading, HDR format, cluster\n"
                   "                       capacity and depth slices, G-buffer packing, light count\n"
                   "  --at FRAME:ACTION    scripted action at a frame (repeatable): resize=WxH, iconify,\n"
                   "                       restore, copy=SRC:DST (an edit on disk), set=KEY=VALUE,\n"
                   "                       pipeline=FILE.json, display=NAME, ocioview=NAME (OCIO),\n"
                   "                       diff=on|off, lights=N, screenshot=FILE.png,\n"
                   "                       capture[=FILE.rdc] (RenderDoc, as the C key),\n"
                   "                       camera=auto|N|NAME (as the camera combo)\n"
                   "  (--frames N          exit after N frames; 0 or absent: run until closed)\n",
                   view_help, pg_cli_common_help);
            free(v);
            return 0;
        }
        if (!strcmp(argv[i], "--pipelines") && i + 1 < argc) {
            pg_strlcpy(v->extra_dir, argv[++i], sizeof v->extra_dir);
            continue;
        }
        if (!strcmp(argv[i], "--screenshot") && i + 1 < argc) {
            v->screenshot_path = argv[++i];
            if (pg_image_path_check(v->screenshot_path, false, &err)) {
                fprintf(stderr, "passgraph view: --screenshot %s\n", err.msg);
                free(v);
                return 2;
            }
            continue;
        }
        if (!strcmp(argv[i], "--at") && i + 1 < argc) {
            const char *spec = argv[++i];
            view_action *a = &v->actions[v->n_actions];
            char what[64] = {0};
            int used_chars = 0;
            if (v->n_actions >= MAX_ACTIONS || sscanf(spec, "%u:%15[a-z]%n", &a->frame, what, &used_chars) < 2) {
                fprintf(stderr, "passgraph view: --at %s: expected FRAME:ACTION[=ARG]\n", spec);
                free(v);
                return 2;
            }
            pg_strlcpy(a->what, what, sizeof a->what);
            const char *rest = spec + used_chars;
            pg_strlcpy(a->arg, *rest == '=' ? rest + 1 : "", sizeof a->arg);
            if (!strcmp(a->what, "screenshot") && pg_image_path_check(a->arg, false, &err)) {
                fprintf(stderr, "passgraph view: --at %s: %s\n", spec, err.msg);
                free(v);
                return 2;
            }
            v->n_actions++;
            continue;
        }
        if (!strcmp(argv[i], "--random-params")) {
            v->random_params = true;
            continue;
        }
        if (!strcmp(argv[i], "--cycle-pipelines")) {
            v->cycle = true;
            continue;
        }
        if (!strcmp(argv[i], "--frames-in-flight") && i + 1 < argc) {
            long k = strtol(argv[++i], NULL, 10);
            if (k < 1 || k > PG_MAX_FRAMES_IN_FLIGHT) {
                fprintf(stderr, "passgraph view: --frames-in-flight %s: expected 1 or 2\n", argv[i]);
                free(v);
                return 2;
            }
            v->frames_in_flight = (uint32_t)k;
            continue;
        }
        if (!strcmp(argv[i], "--cycle-every") && i + 1 < argc) {
            long k = strtol(argv[++i], NULL, 10);
            if (k < 1 || k > 100000) {
                fprintf(stderr, "passgraph view: --cycle-every %s: expected 1..100000\n", argv[i]);
                free(v);
                return 2;
            }
            v->cycle_every = (uint32_t)k;
            continue;
        }
        bool frames_given = !strcmp(argv[i], "--frames");
        if (pg_cli_parse_common(&opt, argc, argv, &i, &used, &err)) {
            fprintf(stderr, "passgraph view: %s\n", err.msg);
            free(v);
            return 2;
        }
        if (!used) {
            fprintf(stderr, "passgraph view: unknown option '%s' (see passgraph view --help)\n", argv[i]);
            free(v);
            return 2;
        }
        if (frames_given) v->frames_limit = opt.frames;
    }
    if (!glfwInit()) {
        fprintf(stderr, "passgraph view: cannot open a window (no display? try xvfb-run)\n");
        free(v);
        return 1;
    }
    int rc = 1;
    if (!glfwVulkanSupported()) {
        fprintf(stderr, "passgraph view: GLFW finds no Vulkan loader\n");
        goto out_glfw;
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    v->window = glfwCreateWindow((int)opt.width, (int)opt.height, "passgraph", NULL, NULL);
    if (!v->window) {
        fprintf(stderr, "passgraph view: cannot create a window\n");
        goto out_glfw;
    }
    uint32_t n_ext = 0;
    const char **exts = glfwGetRequiredInstanceExtensions(&n_ext);
    /* the device must be able to present to this window */
    pg_gpu_desc win_bits = {
        .instance_extensions = exts,
        .n_instance_extensions = n_ext,
        .swapchain = true,
        .present_ok = present_ok,
    };
    if (pg_app_open_ex(&v->app, &opt, true, &win_bits, &err)) {
        fprintf(stderr, "passgraph view: %s\n", err.msg);
        goto out_window;
    }
    if (pg_view_window_create(&v->win, v->app.gpu, v->window, &err)) goto fail;
    bool minimised = false;
    if (pg_view_window_resize(&v->win, &minimised, &err)) goto fail;
    pg_ui_init_info ui = {
        .window = v->window,
        .instance = v->app.gpu->instance,
        .phys = v->app.gpu->phys,
        .device = v->app.gpu->device,
        .queue_family = v->app.gpu->queue_family,
        .queue = v->app.gpu->queue,
        .render_pass = v->win.pass_present,
        .image_count = v->win.n_images,
        .pipeline_cache = v->app.gpu->pipeline_cache,
    };
    if (!pg_ui_init(&ui, err.msg, sizeof err.msg)) goto fail;
    v->ui_ready = true;
    {
        VkCommandBuffer cmd;
        if (pg_gpu_begin_once(v->app.gpu, &cmd, &err)) goto fail;
        pg_ui_upload_fonts(cmd);
        if (pg_gpu_end_once(v->app.gpu, cmd, &err)) goto fail;
        pg_ui_upload_fonts_done();
    }
    /* initial state */
    v->light_count = (int)v->app.lights.count;
    v->radius = v->app.lights.radius;
    v->intensity = v->app.lights.intensity;
    v->ambient = v->app.lights.ambient;
    v->speed = v->app.lights.speed;
    v->seed = (int)v->app.lights.seed;
    v->time = opt.time;
    v->camera = v->home = v->app.camera;
    camera_angles(v);
    printf("view: %s\nview: %s\n", v->app.camera_why, v->app.lights_why);
    camera_list(v, "start view");
    float ext[3] = {v->app.scene->bounds_max[0] - v->app.scene->bounds_min[0],
                    v->app.scene->bounds_max[1] - v->app.scene->bounds_min[1],
                    v->app.scene->bounds_max[2] - v->app.scene->bounds_min[2]};
    v->move_speed = fmaxf(0.1f, 0.15f * sqrtf(ext[0] * ext[0] + ext[1] * ext[1] + ext[2] * ext[2]));
    for (uint32_t i = 0; i < opt.n_sets; i++) set_override(v, opt.sets[i].key, opt.sets[i].value);
    colour_init(v);
    scan_pipelines(v, v->app.pipeline_path);
    v->requested = v->current;
    reload(v);
    if (!v->session) goto fail_msg;
    v->watch_sig = watch_signature(v);
    v->last_watch = now_s();
    double last = now_s();
    uint32_t frame = 0;
    while (!glfwWindowShouldClose(v->window)) {
        glfwPollEvents();
        for (int k = 0; k < v->n_actions; k++)
            if (v->actions[k].frame == frame && run_action(v, &v->actions[k], &err)) goto fail;
        int fw, fh;
        glfwGetFramebufferSize(v->window, &fw, &fh);
        if (fw == 0 || fh == 0) { /* minimised: nothing to draw into; scripted runs still count */
            glfwWaitEventsTimeout(0.05);
            if (v->frames_limit) {
                printf("view: frame %u: minimised, not drawing\n", frame);
                if (++frame >= v->frames_limit) break;
            }
            continue;
        }
        if ((uint32_t)fw != v->win.extent.width || (uint32_t)fh != v->win.extent.height) {
            if (pg_view_window_resize(&v->win, &minimised, &err)) goto fail;
            pg_ui_set_min_image_count(v->win.min_images);
            if (minimised) continue;
        }
        double t = now_s();
        float dt = (float)(t - last);
        last = t;
        /* scripted runs advance a fixed 1/30 s a frame so they are reproducible */
        if (!v->paused) v->time += v->frames_limit ? 1.0f / 30.0f : dt;
        if (t - v->last_watch > 0.5) {
            v->last_watch = t;
            double sig = watch_signature(v);
            if (sig != v->watch_sig) {
                v->watch_sig = sig;
                printf("view: change on disk, reloading %s\n", v->paths[v->current]);
                char cur[PG_PATH_MAX];
                pg_strlcpy(cur, v->paths[v->current], sizeof cur);
                scan_pipelines(v, cur);
                v->requested = v->current;
                pg_session_destroy(v->naive);
                v->naive = NULL;
                v->reload = true;
            }
        }
        if (v->cycle && frame > 0 && frame % v->cycle_every == 0 && v->n_pipelines > 1) {
            /* continue after the last one asked for even if it did not load (e.g. a --set value it
             * does not declare), so one pipeline that fails does not stop the cycle there */
            int from = v->current;
            for (int i = 0; i < v->n_pipelines && v->cycle_tried[0]; i++)
                if (!strcmp(v->paths[i], v->cycle_tried)) from = i;
            v->requested = (from + 1) % v->n_pipelines;
            pg_strlcpy(v->cycle_tried, v->paths[v->requested], sizeof v->cycle_tried);
            v->reload = true;
            if (v->random_params) { /* long-run soak: random values for the common parameters */
                static const char *const sh[] = {"lambert", "blinn_phong"}, *const hf[] = {"rgba16f", "rgba32f"},
                                         *const ml[] = {"0", "32", "512"}, *const gz[] = {"8", "24", "32"},
                                         *const gb[] = {"float", "oct16", "packed"};
                uint32_t r = frame * 2654435761u;
                set_override(v, "shading", sh[(r >> 3) % 2]);
                set_override(v, "hdr_format", hf[(r >> 7) % 2]);
                set_override(v, "max_lights", ml[(r >> 11) % 3]);
                set_override(v, "grid_z", gz[(r >> 15) % 3]);
                set_override(v, "gbuffer", gb[(r >> 19) % 3]);
                v->light_count = (int)((r >> 23) % 500);
            }
            printf("view: frame %u: switching to %s\n", frame, v->names[v->requested]);
        }
        double t_load = now_s();
        uint32_t loads_before = v->reloads;
        if (v->reload) reload(v);
        camera_update(v, dt);
        bool last_frame = v->frames_limit && frame + 1 >= v->frames_limit;
        bool capture = v->want_shot || (last_frame && v->screenshot_path);
        if (last_frame && v->screenshot_path) pg_strlcpy(v->shot_file, v->screenshot_path, sizeof v->shot_file);
        bool key_c = !pg_ui_want_keyboard() && glfwGetKey(v->window, GLFW_KEY_C) == GLFW_PRESS;
        if (key_c && !v->key_c_down) v->want_rdoc = true;
        v->key_c_down = key_c;
        bool rdoc_now = v->want_rdoc && rdoc_ready(v);
        if (rdoc_now) pg_rdoc_begin(v->rdoc);
        if (draw_frame(v, capture, &err)) goto fail;
        if (rdoc_now) rdoc_finish(v);
        v->want_rdoc = false;
        v->rdoc_file[0] = 0;
        if (v->reloads != loads_before) /* the switch as the user waits for it */
            printf("view: frame %u: %s ready in %.1f ms (load, compile, first frame)\n", frame, v->names[v->current],
                   (now_s() - t_load) * 1e3);
        v->want_shot = false;
        frame++;
        if (frame == 100) {
            v->rss100 = pg_process_rss();
            v->mem100 = v->app.gpu->live_memory_objects;
        }
        if (v->frames_limit && frame >= v->frames_limit) break;
    }
    printf("view: %u frames, %u pipeline loads, %u swapchain builds, last GPU %.3f ms\n", frame, v->reloads,
           v->win.recreations, v->stats.gpu_total_ms);
    if (v->n_frame_ms) { /* median host time of draw_frame (render + UI + blit + present) */
        pg_sample_stats fs;
        pg_error fe = {0};
        if (!pg_sample_stats_compute(v->frame_ms, v->n_frame_ms, &fs, &fe))
            printf("view: host frame time median %.3f ms over %u frames, %u frame(s) in flight\n", fs.median,
                   v->n_frame_ms, v->frames_in_flight);
    }
    if (frame > 100)
        printf("view: RSS frame 100 %.1f MiB, end %.1f MiB; VkDeviceMemory objects frame 100 %lld, end %lld\n",
               v->rss100 / 1048576.0, pg_process_rss() / 1048576.0, (long long)v->mem100,
               (long long)v->app.gpu->live_memory_objects);
    rc = 0;
    if (v->app.gpu->validation && v->app.gpu->validation_messages) {
        fprintf(stderr, "passgraph view: %u validation message(s)\n", v->app.gpu->validation_messages);
        rc = 1;
    }
    goto done;
fail:
    fprintf(stderr, "passgraph view: %s\n", err.msg);
    goto done;
fail_msg:
    fprintf(stderr, "passgraph view: cannot start: %s\n", v->error);
done:
    if (v->app.gpu) vkDeviceWaitIdle(v->app.gpu->device);
    pg_session_destroy(v->session);
    pg_session_destroy(v->naive);
    if (v->app.gpu) {
        pg_image_destroy(v->app.gpu, &v->diff_image);
        pg_image_destroy(v->app.gpu, &v->present_copy);
        pg_buffer_destroy(v->app.gpu, &v->diff_staging);
        pg_buffer_destroy(v->app.gpu, &v->shot);
    }
    pg_ocio_close(v->ocio);
    free(v->rdoc);
    free(v->diff_rgba);
    free(v->hdr_a);
    free(v->hdr_b);
    if (v->ui_ready) pg_ui_shutdown();
    pg_view_window_destroy(&v->win);
    pg_app_close(&v->app);
out_window:
    glfwDestroyWindow(v->window);
out_glfw:
    glfwTerminate();
    free(v);
    return rc;
}
