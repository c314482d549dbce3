/* cmd_view.c - `passgraph view`: a window to fly through a scene lit by many lights, switch and
 * tune pipelines live (hot reload of pipeline JSON and shaders), and see per-pass GPU timings,
 * overflow, memory and its aliasing timeline, and debug views.
 *
 * Frame: the graph renders offscreen (its own submit + fence); then one command buffer blits the
 * graph's display image (or the difference-to-naive heatmap) into the swapchain image, draws the
 * UI over it in a render pass, optionally copies the result for a screenshot, and presents. */
#include "pg_file.h"
#include "view.h"

/* ---------------------------------------------------------------- command */

static bool present_ok(VkInstance instance, VkPhysicalDevice phys, uint32_t family, void *user)
{
    (void)user;
    return glfwGetPhysicalDevicePresentationSupport(instance, phys, family) == GLFW_TRUE;
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

static void print_view_help(void)
{
    printf("%s%s"
           "  --frames-in-flight N 2 (default) or 1: frames the displayed graph keeps in flight\n"
           "  --size WxH           (here) the initial window size (default 1280x720)\n"
           "  --pipelines DIR      also list the pipelines in DIR\n"
           "  --screenshot FILE    write the window (scene + UI) to FILE (.png, .jpg) at the last frame\n"
           "  --cycle-pipelines    switch to the next pipeline every --cycle-every frames\n"
           "  --cycle-every K      frames between switches (default 20)\n"
           "  --random-params      with --cycle-pipelines: random shading, HDR format, cluster\n"
           "                       capacity and depth slices, G-buffer packing, light count\n"
           "  --at FRAME:ACTION    scripted action at a frame (repeatable): resize=WxH, iconify,\n"
           "                       restore, copy=SRC:DST (an edit on disk), set=KEY=VALUE,\n"
           "                       pipeline=FILE.json, display=NAME, ocioview=NAME (OCIO),\n"
           "                       diff=on|off|flip, lights=N, screenshot=FILE.png,\n"
           "                       capture[=FILE.rdc] (RenderDoc, as the C key),\n"
           "                       camera=auto|N|NAME (as the camera combo), gltf_scene=N,\n"
           "                       variant=N|NAME|default, env_intensity=X, env_rotation=DEG\n"
           "  --frames N           (here) exit after N frames; 0 or absent: run until closed\n",
           view_help, pg_cli_common_help);
}

/* --at FRAME:ACTION[=ARG] appended to v->actions; false (said on stderr) when malformed */
static bool parse_at(viewer *v, const char *spec, pg_error *err)
{
    view_action *a = &v->actions[v->n_actions];
    char what[64] = {0};
    int used_chars = 0;
    if (v->n_actions >= MAX_ACTIONS) {
        fprintf(stderr, "passgraph view: --at %s: more than %d --at actions\n", spec, MAX_ACTIONS);
        return false;
    }
    if (sscanf(spec, "%u:%15[a-z_]%n", &a->frame, what, &used_chars) < 2) {
        fprintf(stderr, "passgraph view: --at %s: expected FRAME:ACTION[=ARG]\n", spec);
        return false;
    }
    pg_strlcpy(a->what, what, sizeof a->what);
    const char *rest = spec + used_chars;
    pg_strlcpy(a->arg, *rest == '=' ? rest + 1 : "", sizeof a->arg);
    if (!strcmp(a->what, "screenshot") &&
        (pg_image_path_check(a->arg, false, err) || pg_file_check_writable(a->arg, "screenshot", err))) {
        fprintf(stderr, "passgraph view: --at %s: %s\n", spec, err->msg);
        return false;
    }
    v->n_actions++;
    return true;
}

/* a whole-number option value in lo..hi; false (said on stderr as "OPTION VALUE: expected
 * WANT") otherwise */
static bool parse_count(const char *option, const char *value, long lo, long hi, const char *want,
                        uint32_t *out)
{
    char *end = NULL;
    long k = strtol(value, &end, 10);
    if (end == value || *end || k < lo || k > hi) { /* "2x" was 2 */
        fprintf(stderr, "passgraph view: %s %s: expected %s\n", option, value, want);
        return false;
    }
    *out = (uint32_t)k;
    return true;
}

/* the view options, then the common ones (pg_cli_parse_common); -1 to go on, else the exit
 * code (0 after --help, 2 after a message on stderr) */
static int parse_view_options(viewer *v, pg_cli_common *opt, int argc, char **argv)
{
    pg_error err = {0};
    for (int i = 0; i < argc; i++) {
        bool used;
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            print_view_help();
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
                return 2;
            }
            if (pg_file_check_writable(v->screenshot_path, "--screenshot", &err)) { /* before any frame */
                fprintf(stderr, "passgraph view: %s\n", err.msg);
                return 2;
            }
            continue;
        }
        if (!strcmp(argv[i], "--at") && i + 1 < argc) {
            if (!parse_at(v, argv[++i], &err)) return 2;
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
            if (!parse_count("--frames-in-flight", argv[++i], 1, PG_MAX_FRAMES_IN_FLIGHT, "1 or 2",
                             &v->frames_in_flight))
                return 2;
            continue;
        }
        if (!strcmp(argv[i], "--cycle-every") && i + 1 < argc) {
            if (!parse_count("--cycle-every", argv[++i], 1, 100000, "1..100000", &v->cycle_every))
                return 2;
            continue;
        }
        bool frames_given = !strcmp(argv[i], "--frames");
        if (pg_cli_parse_common(opt, argc, argv, &i, &used, &err)) {
            fprintf(stderr, "passgraph view: %s\n", err.msg);
            return 2;
        }
        if (!used) {
            fprintf(stderr, "passgraph view: unknown option '%s' (see passgraph view --help)\n", argv[i]);
            return 2;
        }
        if (frames_given) v->frames_limit = opt->frames;
    }
    return -1;
}

/* the window (no client API: Vulkan draws into it); false (said on stderr) when there is none */
static bool open_window(viewer *v, const pg_cli_common *opt)
{
    if (!glfwVulkanSupported()) {
        fprintf(stderr, "passgraph view: GLFW finds no Vulkan loader\n");
        return false;
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    v->window = glfwCreateWindow((int)opt->width, (int)opt->height, "passgraph", NULL, NULL);
    if (!v->window) {
        fprintf(stderr, "passgraph view: cannot create a window\n");
        return false;
    }
    return true;
}

/* the app (scene, lights, camera) on a GPU that can present to the window */
static pg_result open_app(viewer *v, const pg_cli_common *opt, pg_error *err)
{
    uint32_t n_ext = 0;
    const char **exts = glfwGetRequiredInstanceExtensions(&n_ext);
    pg_gpu_desc win_bits = {
        .instance_extensions = exts,
        .n_instance_extensions = n_ext,
        .swapchain = true,
        .present_ok = present_ok,
    };
    return pg_app_open_ex(&v->app, opt, true, &win_bits, err);
}

/* the swapchain and the UI (ImGui over the present render pass, its fonts uploaded) */
static bool open_window_ui(viewer *v, pg_error *err)
{
    if (pg_view_window_create(&v->win, v->app.gpu, v->window, err)) return false;
    bool minimised = false;
    if (pg_view_window_resize(&v->win, &minimised, err)) return false;
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
    if (!pg_ui_init(&ui, err->msg, sizeof err->msg)) return false;
    v->ui_ready = true;
    VkCommandBuffer cmd;
    if (pg_gpu_begin_once(v->app.gpu, &cmd, err)) return false;
    pg_ui_upload_fonts(cmd);
    if (pg_gpu_end_once(v->app.gpu, cmd, err)) return false;
    pg_ui_upload_fonts_done();
    return true;
}

/* the viewer's starting state (lights, camera, overrides, colour, pipelines) and the first
 * pipeline loaded; false when it did not load (v->error says why) */
static bool initial_state(viewer *v, const pg_cli_common *opt)
{
    v->light_count = (int)v->app.lights.count;
    v->failed_lights = -1;
    v->radius = v->app.lights.radius;
    v->intensity = v->app.lights.intensity;
    v->ambient = v->app.lights.ambient;
    v->env_intensity = v->app.lights.env_intensity;
    v->env_rotation_deg = v->app.lights.env_rotation * (float)(180.0 / 3.14159265358979);
    v->speed = v->app.lights.speed;
    v->seed = (int)v->app.lights.seed;
    v->time = opt->time;
    v->camera = v->home = v->app.camera;
    camera_angles(v);
    printf("view: %s\nview: %s\n", v->app.camera_why, v->app.lights_why);
    camera_list(v, "start view");
    const bool scenario_camera = v->app.has_scenario && v->app.scenario.has_camera && !v->app.opt.camera;
    v->cam_start_gltf = scenario_camera ? -1 : pg_scene_default_camera(v->app.scene, v->app.opt.camera);
    camera_follow_set(v, v->cam_start_gltf);
    float ext[3] = {v->app.scene->bounds_max[0] - v->app.scene->bounds_min[0],
                    v->app.scene->bounds_max[1] - v->app.scene->bounds_min[1],
                    v->app.scene->bounds_max[2] - v->app.scene->bounds_min[2]};
    v->move_speed = fmaxf(0.1f, 0.15f * sqrtf(ext[0] * ext[0] + ext[1] * ext[1] + ext[2] * ext[2]));
    for (uint32_t i = 0; i < opt->n_sets; i++) set_override(v, opt->sets[i].key, opt->sets[i].value);
    colour_init(v);
    scan_pipelines(v, v->app.pipeline_path);
    for (uint32_t i = 0; i < opt->n_sets; i++) /* a key no pipeline of the list knows is a typo */
        if (!declared_by_any(v, opt->sets[i].key)) {
            snprintf(v->error, sizeof v->error, "%s %s%s%s: no pipeline of the viewer declares a parameter '%s'",
                     opt->sets[i].value == opt->debug_view ? "--debug-view" : "--set",
                     opt->sets[i].value == opt->debug_view ? "" : opt->sets[i].key,
                     opt->sets[i].value == opt->debug_view ? "" : "=", opt->sets[i].value, opt->sets[i].key);
            v->bad_option = true;
            return false;
        }
    pg_error bad = {0}; /* a value a pipeline refuses, named by the option that gave it */
    if (check_set_values(v, opt, &bad)) {
        pg_strlcpy(v->error, bad.msg, sizeof v->error);
        v->bad_option = true;
        return false;
    }
    v->requested = v->current;
    reload(v);
    if (!v->session) return false;
    v->watch_sig = watch_signature(v);
    v->last_watch = pg_time_s();
    return true;
}

/* every 0.1 s: a change on disk (pipeline JSON or shader) rescans and reloads the current one */
static void watch_disk(viewer *v, double t)
{
    if (t - v->last_watch <= 0.1) return;
    v->last_watch = t;
    double sig = watch_signature(v);
    if (sig == v->watch_sig) return;
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

/* --cycle-pipelines: every cycle_every frames, the next pipeline (with --random-params, random
 * values for the common parameters too) */
static void cycle_pipelines(viewer *v, uint32_t frame)
{
    if (!(v->cycle && frame > 0 && frame % v->cycle_every == 0 && v->n_pipelines > 1)) return;
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

/* one drawn frame: a pending reload, the camera, draw_frame (with a screenshot at the last
 * scripted frame or when asked, and a RenderDoc capture on C); the reload's time said */
static bool draw_one(viewer *v, uint32_t frame, float dt, pg_error *err)
{
    double t_load = pg_time_s();
    uint32_t loads_before = v->reloads;
    if (!v->session && v->failed_lights >= 0 && v->light_count != v->failed_lights) { /* draw_frame dropped it */
        v->failed_lights = -1;
        v->reload = true;
    }
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
    if (capture) /* where the picture is taken from (view_test: a followed glTF camera) */
        printf("view: frame %u: camera at (%.5f, %.5f, %.5f), time %.5f s\n", frame, v->camera.position[0],
               v->camera.position[1], v->camera.position[2], v->time);
    if (draw_frame(v, capture, err)) return false;
    if (rdoc_now) rdoc_finish(v);
    v->want_rdoc = false;
    v->rdoc_file[0] = 0;
    if (v->reloads != loads_before && v->session) { /* the switch as the user waits for it (a graph whose
                                                     * first frame failed was dropped: no line) */
        const pg_runtime_stats st = pg_runtime_get_stats(v->session->runtime);
        printf("view: frame %u: %s ready in %.1f ms (load, compile, first frame; rebuilt: %s", frame,
               v->names[v->current], (pg_time_s() - t_load) * 1e3, pg_rebuild_kind_name(st.last_rebuild));
        if (st.last_rebuild == PG_REBUILD_PIPELINES)
            printf(", %u pass(es) created, %u kept", st.last_passes_created, st.last_passes_kept);
        printf(")\n");
    }
    v->want_shot = false;
    return true;
}

/* frames until the window closes or --frames is reached: scripted actions, minimised and resized
 * windows, time, disk changes, pipeline cycling, the frame; *frames counts them */
static bool frame_loop(viewer *v, uint32_t *frames, pg_error *err)
{
    double last = pg_time_s();
    uint32_t frame = 0;
    while (!glfwWindowShouldClose(v->window)) {
        glfwPollEvents();
        for (int k = 0; k < v->n_actions; k++)
            if (v->actions[k].frame == frame && run_action(v, &v->actions[k], err)) return false;
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
            bool minimised = false;
            if (pg_view_window_resize(&v->win, &minimised, err)) return false;
            pg_ui_set_min_image_count(v->win.min_images);
            if (minimised) continue;
        }
        double t = pg_time_s();
        float dt = (float)(t - last);
        last = t;
        /* scripted runs advance a fixed 1/30 s a frame so they are reproducible */
        if (!v->paused) v->time += v->frames_limit ? 1.0f / 30.0f : dt;
        watch_disk(v, t);
        cycle_pipelines(v, frame);
        if (!draw_one(v, frame, dt, err)) return false;
        frame++;
        if (frame == 100) {
            v->rss100 = pg_process_rss();
            v->mem100 = v->app.gpu->live_memory_objects;
        }
        if (v->frames_limit && frame >= v->frames_limit) break;
    }
    *frames = frame;
    return true;
}

/* the closing lines (frames, loads, host frame time, memory growth); 1 when validation spoke */
static int report(const viewer *v, uint32_t frame)
{
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
    if (v->app.gpu->validation && v->app.gpu->validation_messages) {
        fprintf(stderr, "passgraph view: %u validation message(s)\n", v->app.gpu->validation_messages);
        return 1;
    }
    return 0;
}

/* everything the viewer made on the app's GPU, the UI, the swapchain and the app */
static void close_viewer(viewer *v)
{
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
    free(v->flip_map);
    if (v->ui_ready) pg_ui_shutdown();
    pg_view_window_destroy(&v->win);
    pg_app_close(&v->app);
}

/* the viewer on an open app: UI, first pipeline, the frames, the report; the exit code */
static int run_viewer(viewer *v, const pg_cli_common *opt)
{
    pg_error err = {0};
    uint32_t frames = 0;
    if (!open_window_ui(v, &err)) goto fail;
    if (!initial_state(v, opt)) {
        fprintf(stderr, "passgraph view: cannot start: %s\n", v->error);
        return v->bad_option ? 2 : 1; /* a --set the pipelines refuse: a bad option, as in render */
    }
    if (!frame_loop(v, &frames, &err)) goto fail;
    return report(v, frames);
fail:
    fprintf(stderr, "passgraph view: %s\n", err.msg);
    return 1;
}

int pg_cmd_view(int argc, char **argv)
{
    pg_cli_common opt;
    pg_cli_defaults(&opt);
    opt.width = 1280;
    opt.height = 720;
    viewer *v = calloc(1, sizeof *v);
    if (!v) return 1;
    v->cycle_every = 20;
    v->frames_in_flight = 2;
    v->cam_follow = v->cam_start_gltf = -1;
    int rc = parse_view_options(v, &opt, argc, argv);
    if (rc >= 0) {
        free(v);
        return rc;
    }
    if (!glfwInit()) {
        fprintf(stderr, "passgraph view: cannot open a window (no display? try xvfb-run)\n");
        free(v);
        return 1;
    }
    rc = 1;
    if (open_window(v, &opt)) {
        pg_error err = {0};
        if (open_app(v, &opt, &err)) {
            fprintf(stderr, "passgraph view: %s\n", err.msg);
        } else {
            rc = run_viewer(v, &opt);
            close_viewer(v);
        }
        glfwDestroyWindow(v->window);
    }
    glfwTerminate();
    free(v);
    return rc;
}
