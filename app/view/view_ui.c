/* view_ui.c - `passgraph view`: the ImGui panels (pipeline, parameters, lights, timings,
 * memory and its aliasing timeline). */
#include "view.h"

#include "environment.h"

/* ---------------------------------------------------------------- UI */

static void param_widget(viewer *v, const pg_param *p)
{
    char val[PG_NAME_MAX];
    bool changed = false;
    char now[PG_NAME_MAX];
    pg_param_format(p, now, sizeof now); /* an int with values: its combo's current item */
    switch (p->n_values ? PG_PARAM_ENUM : p->type) {
    case PG_PARAM_ENUM: {                /* and an int that takes only its listed values */
        int cur = 0;
        const char *items[PG_MAX_ENUM_VALUES];
        for (uint32_t i = 0; i < p->n_values; i++) {
            items[i] = p->values[i];
            if (!strcmp(p->values[i], now)) cur = (int)i;
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

/* The scene at `path` (load options o) replaces the app's: posed, its environment attached, on the
 * GPU; the sessions are dropped (reloaded at the next frame). On failure nothing changes. */
static pg_result replace_scene(viewer *v, const char *path, const pg_scene_load_opts *o, pg_error *err)
{
    pg_scene *sc = NULL;
    pg_scene_gpu *sg = NULL;
    pg_result r;
    if ((r = pg_scene_load_ex(path, o, &sc, err)) || (r = pg_app_pose_scene(&v->app, sc, err)) ||
        (r = pg_app_attach_environment(&v->app, sc, err)) || (r = pg_scene_gpu_create(v->app.gpu, sc, &sg, err))) {
        pg_scene_free(sc);
        return r;
    }
    pg_scene_print_warnings(sc, "passgraph view: ", stderr);
    vkDeviceWaitIdle(v->app.gpu->device);
    pg_session_destroy(v->session);
    pg_session_destroy(v->naive);
    v->session = v->naive = NULL;
    pg_scene_gpu_destroy(v->app.gpu, v->app.scene_gpu);
    pg_scene_free(v->app.scene);
    v->app.scene = sc;
    v->app.scene_gpu = sg;
    if (path != v->app.scene_path) pg_strlcpy(v->app.scene_path, path, sizeof v->app.scene_path);
    v->reload = true;
    return PG_OK;
}

pg_result variant_choose(viewer *v, const char *variant, pg_error *err)
{
    const pg_scene_load_opts o = {.gltf_scene = v->app.scene ? v->app.scene->gltf_scene : -1,
                                  .gltf_variant = variant};
    pg_result r = replace_scene(v, v->app.scene_path, &o, err);
    char line[PG_PATH_MAX + 800];
    if (!r && pg_scene_variant_line(v->app.scene, line, sizeof line)) printf("view: %s\n", line);
    return r;
}

/* "variant": the file's KHR_materials_variants (shown when it has any) */
static void variant_ui(viewer *v)
{
    const pg_scene *sc = v->app.scene;
    if (!sc || sc->n_gltf_variants == 0) return;
    int n = 1;
    snprintf(v->var_items[0], sizeof v->var_items[0], "default materials");
    for (uint32_t k = 0; k < sc->n_gltf_variants && n <= VIEW_MAX_VARIANTS; k++, n++)
        snprintf(v->var_items[n], sizeof v->var_items[0], "%u '%s'", k,
                 k < PG_SCENE_VARIANT_NAMES ? sc->gltf_variant_names[k] : "...");
    for (int i = 0; i < n; i++) v->var_ptrs[i] = v->var_items[i];
    int cur = sc->gltf_variant + 1;
    if (pg_ui_combo("variant", &cur, v->var_ptrs, n) && cur != sc->gltf_variant + 1) {
        char idx[16];
        snprintf(idx, sizeof idx, "%d", cur - 1);
        pg_error err = {0};
        if (variant_choose(v, cur > 0 ? idx : NULL, &err)) snprintf(v->error, sizeof v->error, "%s", err.msg);
    }
}

/* the new scene's default view and lights (after "open glTF" or another glTF scene) */
static void adopt_default_view(viewer *v)
{
    pg_scene *sc = v->app.scene;
    pg_light_setup ls;
    char cw[256], lw[256];
    pg_error verr = {0};
    float aspect = v->win.extent.height ? (float)v->win.extent.width / (float)v->win.extent.height
                                        : 16.0f / 9;
    if (pg_scene_default_view(sc, NULL, aspect, (uint32_t)v->light_count, (uint32_t)v->seed, &v->home,
                              &ls, cw, sizeof cw, lw, sizeof lw, &verr))
        snprintf(v->error, sizeof v->error, "%s", verr.msg);
    printf("view: %s\nview: %s\n", cw, lw);
    v->camera = v->home;
    camera_angles(v);
    camera_list(v, "start view");
    v->cam_start_gltf = pg_scene_default_camera(sc, NULL);
    camera_follow_set(v, v->cam_start_gltf);
    v->app.lights = ls;
    v->radius = ls.radius;
    v->intensity = ls.intensity;
    v->ambient = ls.ambient;
}

/* "open glTF": the scene in the input box replaces the app's (sessions dropped and reloaded), with
 * its default view and lights; an error goes to the error line */
static void open_scene(viewer *v)
{
    pg_error err = {0};
    if (replace_scene(v, v->scene_input, NULL, &err)) {
        snprintf(v->error, sizeof v->error, "%s", err.msg);
        return;
    }
    adopt_default_view(v);
}

pg_result gltf_scene_choose(viewer *v, int index, pg_error *err)
{
    char variant[16] = "";
    if (v->app.scene && v->app.scene->gltf_variant >= 0) snprintf(variant, sizeof variant, "%d", v->app.scene->gltf_variant);
    const pg_scene_load_opts o = {.gltf_scene = index, .gltf_variant = variant};
    pg_result r = replace_scene(v, v->app.scene_path, &o, err);
    if (r) return r;
    adopt_default_view(v);
    char line[PG_PATH_MAX + 160];
    if (pg_scene_choice_line(v->app.scene, line, sizeof line)) printf("view: %s\n", line);
    return PG_OK;
}

/* "glTF scene": the file's scenes (shown when it has several) */
static void gltf_scene_ui(viewer *v)
{
    const pg_scene *sc = v->app.scene;
    if (!sc || sc->n_gltf_scenes < 2 || sc->gltf_scene < 0) return;
    int n = 0;
    for (uint32_t k = 0; k < sc->n_gltf_scenes && n < VIEW_MAX_GLTF_SCENES; k++, n++) {
        snprintf(v->gscene_items[n], sizeof v->gscene_items[0], "%u '%s'", k,
                 k < PG_SCENE_GLTF_SCENE_NAMES ? sc->gltf_scene_names[k] : "...");
        v->gscene_ptrs[n] = v->gscene_items[n];
    }
    int cur = sc->gltf_scene;
    pg_error err = {0};
    if (pg_ui_combo("glTF scene", &cur, v->gscene_ptrs, n) && cur != sc->gltf_scene && gltf_scene_choose(v, cur, &err))
        snprintf(v->error, sizeof v->error, "%s", err.msg);
}

/* "Scene and lights": the scene (its warnings, another glTF), the light and time settings, the
 * camera, screenshot and RenderDoc buttons */
static void scene_and_lights_ui(viewer *v)
{
    pg_ui_text("scene: %s", v->app.scene_path);
    /* what the loader could not draw as the file asks (scene.h: warnings) */
    for (uint32_t k = 0; v->app.scene && k < v->app.scene->n_warnings; k++) {
        pg_ui_text_colored(0xffc040ff, "warning:");
        pg_ui_text_wrapped(v->app.scene->warnings[k]);
    }
    if (pg_ui_input_text("open glTF", v->scene_input, sizeof v->scene_input) && v->scene_input[0]) open_scene(v);
    gltf_scene_ui(v);
    variant_ui(v);
    pg_ui_slider_int("lights", &v->light_count, 0, 1000000, true);
    pg_ui_slider_float("radius", &v->radius, 0.01f, 100.0f, "%.3f", true);
    pg_ui_slider_float("intensity", &v->intensity, 0.001f, 100.0f, "%.3f", true);
    pg_ui_slider_float("ambient", &v->ambient, 0.0f, 1.0f, "%.3f", false);
    if (v->app.scene && v->app.scene->environment) { /* frame uniforms: no rebuild, no new filtering */
        pg_ui_text("environment: %s", v->app.scene->environment->source);
        pg_ui_slider_float("environment intensity", &v->env_intensity, 0.0f, 16.0f, "%.3f", false);
        pg_ui_slider_float("environment rotation", &v->env_rotation_deg, -180.0f, 180.0f, "%.1f deg", false);
    }
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
        camera_follow_set(v, v->cam_start_gltf);
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

/* the left window: pipeline choice and its error, scene and lights, colour, the parameters */
static void settings_window(viewer *v)
{
    if (!pg_ui_begin("passgraph", 10, 10, 390, (float)v->win.extent.height - 20)) return;
    if (pg_ui_combo("pipeline", &v->requested, v->name_ptrs, v->n_pipelines)) v->reload = true;
    if (v->error[0]) {
        pg_ui_text_colored(0xff5050ff, v->session ? "error (the last good graph keeps running):"
                                                  : "error (no graph until the pipeline loads again):");
        pg_ui_text_wrapped(v->error);
    }
    const pg_pipeline *pl = v->session ? v->session->pipeline : NULL;
    if (pl && pl->description[0]) pg_ui_text_wrapped(pl->description);
    if (pg_ui_header("Scene and lights", true)) scene_and_lights_ui(v);
    colour_ui(v);
    if (pl && pg_ui_header("Pipeline parameters", true)) {
        for (uint32_t i = 0; i < pl->n_params; i++) param_widget(v, &pl->params[i]);
        if (pg_ui_checkbox("difference to the reference (heatmap)", &v->diff)) v->hist_n = 0;
        if (v->diff) {
            if (pg_ui_checkbox("FLIP (perceptual, display images) instead", &v->diff_flip)) v->flip_said = false;
            if (v->diff_flip)
                pg_ui_text("LDR-FLIP mean %.4g, colour scale 0..1; %.0f ms CPU", v->flip_mean, v->flip_ms);
            else
                pg_ui_text("linear RMSE %.4g, colour scale 0..%.4g", v->diff_rmse, v->diff_scale);
        }
    }
}

/* the clustered passes' light overflow and light-list size */
static void counters_ui(const viewer *v, const pg_frame_stats *st)
{
    pg_ui_text_colored(pg_frame_counter_sum(st, "overflow_clusters") ? 0xffa040ff : 0xa0ffa0ff,
                       "light overflow: %llu clusters, %llu light refs dropped",
                       (unsigned long long)pg_frame_counter_sum(st, "overflow_clusters"),
                       (unsigned long long)pg_frame_counter_sum(st, "overflow_dropped"));
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

/* the pass table: time and share of the frame, and the queue each ran on when two */
static void timings_table(const pg_frame_stats *st)
{
    static const char *const cols[] = {"pass", "ms", "share"};
    if (!pg_ui_table_begin("timings", 3)) return;
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

/* the history plots: the GPU total, then each pass */
static void timing_plots(const viewer *v, const pg_frame_stats *st)
{
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

/* "GPU timings": frame times, counters, notes, the pass table and the history */
static void timings_ui(const viewer *v)
{
    const pg_frame_stats *st = &v->stats;
    pg_ui_text("frame %.2f ms CPU, %.3f ms GPU (%s)", v->cpu_frame_ms, st->gpu_total_ms,
               v->app.gpu->props.deviceName);
    if (st->n_counters) counters_ui(v, st);
    for (uint32_t k = 0; k < st->n_notes; k++) pg_ui_text_colored(0xffa040ff, "%s", st->notes[k]);
    timings_table(st);
    timing_plots(v, st);
}

/* "Memory": the plan's and the device's transient bytes, plan changes, the aliasing timeline */
static void memory_ui(const viewer *v)
{
    const pg_graph_plan *p = v->session->plan;
    pg_runtime_stats rs = pg_runtime_get_stats(v->session->runtime);
    pg_ui_text("transient: %.2f MiB -> %.2f MiB aliased (plan)", p->transient_bytes_unaliased / 1048576.0,
               p->transient_bytes_aliased / 1048576.0);
    pg_ui_text("device memory: %.2f MiB -> %.2f MiB", rs.memory_bytes_unaliased / 1048576.0,
               rs.memory_bytes_transient / 1048576.0);
    pg_ui_text("passes run %u, culled %u; resources rebuilt %u times", p->n_order, p->n_passes - p->n_order,
               rs.resource_creations);
    pg_ui_text("plan changes: memory %u, resources %u, pipelines %u, values %u; last: %s", rs.memory_rebuilds,
               rs.resource_rebuilds, rs.pipeline_rebuilds, rs.value_updates,
               pg_rebuild_kind_name(rs.last_rebuild));
    memory_timeline(p);
}

/* the right window: timings, memory, and what the plan left out */
static void graph_window(viewer *v)
{
    float right_w = 420, right_x = (float)v->win.extent.width - right_w - 10;
    if (right_x < 410) right_x = 410;
    if (!pg_ui_begin("graph", right_x, 10, right_w, (float)v->win.extent.height - 20)) return;
    if (v->session && pg_ui_header("GPU timings", true)) timings_ui(v);
    if (v->session && v->session->plan && pg_ui_header("Memory", true)) memory_ui(v);
    if (v->session && v->session->plan && pg_ui_header("Left out and culled", false)) {
        const pg_graph_plan *p = v->session->plan;
        for (uint32_t i = 0; i < p->n_explain; i++) pg_ui_text_wrapped(p->explain[i]);
    }
}

/* the viewer's UI for this frame: the settings window and the graph window */
void build_ui(viewer *v)
{
    pg_ui_new_frame();
    settings_window(v);
    pg_ui_end();
    graph_window(v);
    pg_ui_end();
}
