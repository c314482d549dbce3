/* view_script.c - `passgraph view`: the scripted actions (--at FRAME:ACTION) of tests and
 * demos. */
#include "view.h"

/* --at FRAME:set=KEY=VALUE */
static pg_result script_set(viewer *v, const view_action *a, pg_error *err)
{
    char kv[PG_PATH_MAX];
    pg_strlcpy(kv, a->arg, sizeof kv);
    char *eq = strchr(kv, '=');
    if (!eq) return pg_fail(err, PG_ERR_INVALID_ARG, "--at %u:set=%s: expected KEY=VALUE", a->frame, a->arg);
    *eq = 0;
    if (!declared_by_any(v, kv))
        return pg_fail(err, PG_ERR_INVALID_ARG, "--at %u:set=%s: no pipeline of the viewer declares a parameter '%s'",
                       a->frame, a->arg, kv);
    /* a value no listed pipeline takes ends the run, as --set's does (it was kept, and every
     * later reload or switch failed with it) */
    if (refused_by_all(v, kv, eq + 1, err)) return pg_error_prefix(err, "--at %u:set=%s", a->frame, a->arg);
    /* one the pipeline being shown refuses (another takes it) is said and not kept: kept, it
     * failed every later reload, and every later set= with it */
    pg_error e = {0};
    if (refused_by(v, v->requested, kv, eq + 1, &e)) {
        snprintf(v->error, sizeof v->error, "--at %u:set=%s: %s (not applied)", a->frame, a->arg, e.msg);
        fprintf(stderr, "passgraph view: %s\n", v->error);
        return PG_OK;
    }
    set_override(v, kv, eq + 1);
    v->reload = true;
    return PG_OK;
}

/* Scripted actions (--at FRAME:ACTION) for tests and demos. */
pg_result run_action(viewer *v, const view_action *a, pg_error *err)
{
    printf("view: frame %u: %s %s\n", a->frame, a->what, a->arg);
    if (!strcmp(a->what, "resize")) {
        unsigned w = 0, h = 0;
        int used = 0;
        if (sscanf(a->arg, "%ux%u%n", &w, &h, &used) != 2 || a->arg[used] || !w || !h || w > 16384 || h > 16384)
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
        const bool wrote = fwrite(text, 1, len, f) == len;
        free(text);
        if (fclose(f) != 0 || !wrote) return pg_fail(err, PG_ERR_IO, "%s: cannot write (disk full?)", colon + 1);
        v->last_watch = 0; /* look at the disk on this frame */
    } else if (!strcmp(a->what, "set")) {
        pg_result r = script_set(v, a, err);
        if (r) return r;
    } else if (!strcmp(a->what, "pipeline")) {
        int k = 0;
        pg_result r = find_pipeline(v, a->arg, &k, err);
        if (r) return pg_error_prefix(err, "--at %u:pipeline", a->frame);
        v->requested = k;
        v->reload = true;
    } else if (!strcmp(a->what, "display") || !strcmp(a->what, "ocioview")) {
        pg_result r = !strcmp(a->what, "display") ? colour_choose(v, a->arg, NULL, err)
                                                  : colour_choose(v, NULL, a->arg, err);
        if (r) return pg_error_prefix(err, "--at %u:%s=%s", a->frame, a->what, a->arg);
    } else if (!strcmp(a->what, "diff")) {
        if (strcmp(a->arg, "on") && strcmp(a->arg, "off") && strcmp(a->arg, "flip"))
            return pg_fail(err, PG_ERR_INVALID_ARG, "--at %u:diff=%s: expected on, off or flip", a->frame, a->arg);
        v->diff = strcmp(a->arg, "off") != 0;
        v->diff_flip = !strcmp(a->arg, "flip");
        v->flip_said = false;
    } else if (!strcmp(a->what, "lights")) {
        uint64_t n = 0;
        char opt[48];
        snprintf(opt, sizeof opt, "--at %u:lights", a->frame);
        pg_result r = pg_cli_parse_u64(opt, a->arg, 0, PG_MAX_LIGHTS, &n, err);
        if (r) return r;
        v->light_count = (int)n;
    } else if (!strcmp(a->what, "env_intensity") || !strcmp(a->what, "env_rotation")) {
        /* the command line's ranges (--environment-intensity, --environment-rotation): 1e38 made
         * the picture black */
        char *end = NULL;
        const bool in = a->what[4] == 'i';
        const float x = strtof(a->arg, &end), lo = in ? 0.0f : -36000.0f, hi = in ? 1e6f : 36000.0f;
        if (!end || end == a->arg || *end || !(x >= lo && x <= hi))
            return pg_fail(err, PG_ERR_INVALID_ARG, "--at %u:%s=%s: expected a number in [%g, %g]%s", a->frame, a->what,
                           a->arg, (double)lo, (double)hi, in ? "" : " (degrees)");
        if (a->what[4] == 'i') v->env_intensity = x;
        else v->env_rotation_deg = x;
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
    } else if (!strcmp(a->what, "gltf_scene")) {
        char *end = NULL;
        long k = strtol(a->arg, &end, 10);
        if (!end || *end || k < 0 || k > 1000000)
            return pg_fail(err, PG_ERR_INVALID_ARG, "--at %u:gltf_scene=%s: expected a scene index", a->frame, a->arg);
        pg_result r = gltf_scene_choose(v, (int)k, err);
        if (r) return pg_error_prefix(err, "--at %u:gltf_scene", a->frame);
    } else if (!strcmp(a->what, "variant")) {
        if (!v->app.scene || v->app.scene->n_gltf_variants == 0) /* as an index or a name would be */
            return pg_fail(err, PG_ERR_INVALID_ARG, "--at %u:variant=%s: the scene has no material variants "
                           "(KHR_materials_variants)", a->frame, a->arg);
        pg_result r = variant_choose(v, strcmp(a->arg, "default") ? a->arg : NULL, err);
        if (r) return pg_error_prefix(err, "--at %u:variant", a->frame);
    } else if (!strcmp(a->what, "screenshot")) {
        v->want_shot = true;
        pg_strlcpy(v->shot_file, a->arg, sizeof v->shot_file);
    } else if (!strcmp(a->what, "capture")) {
        v->want_rdoc = true;
        pg_strlcpy(v->rdoc_file, a->arg, sizeof v->rdoc_file);
    } else {
        return pg_fail(err, PG_ERR_INVALID_ARG, "--at %u:%s: unknown action (resize, iconify, restore, copy, set, pipeline, display, ocioview, diff, lights, env_intensity, env_rotation, camera, gltf_scene, variant, screenshot, capture)",
                       a->frame, a->what);
    }
    return PG_OK;
}
