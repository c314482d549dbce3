#include "app.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>
#include <stdlib.h>

#include "animation.h"
#include "environment.h"
#include "exr.h"
#include "pass_list.h"
#include "shading_common.h"
#include "shader.h"

/* FILE.exr (OpenEXR, RGB(A) of any pixel type, image/exr.h) or else a Radiance HDR file. */
static pg_result load_environment_file(const char *path, pg_environment **out, pg_error *err)
{
    size_t n = strlen(path);
    if (n < 4 || strcasecmp(path + n - 4, ".exr")) return pg_environment_load(path, out, err);
    float *rgba = NULL;
    uint32_t w = 0, h = 0;
    pg_result r = pg_exr_read_rgba_within(path, PG_ENV_MAX_WIDTH, &rgba, &w, &h, err); /* before its pixels */
    if (!r) r = pg_environment_from_pixels(path, w, h, rgba, out, err);
    free(rgba);
    return r;
}

pg_result pg_app_attach_environment(pg_app *app, pg_scene *scene, pg_error *err)
{
    const char *e = app->opt.environment;
    const bool gltf = strcmp(scene->path, "default") != 0;
    pg_environment *env = NULL;
    pg_result r = PG_OK;
    if (e && !strcmp(e, "none")) {
        snprintf(app->env_why, sizeof app->env_why, "environment: none (--environment none)");
    } else if (e && strcmp(e, "default")) {
        if ((r = load_environment_file(e, &env, err))) return r;
        snprintf(app->env_why, sizeof app->env_why, "environment: %s, %ux%u, %u levels (--environment)", e,
                 env->width[0], env->height[0], env->n_levels);
    } else if (e || (gltf && scene->n_lights == 0 && !app->has_scenario)) {
        if ((r = pg_environment_default(PG_DEFAULT_SKY_LEVEL, &env, err))) return r;
        snprintf(app->env_why, sizeof app->env_why, "environment: the neutral default sky, mean radiance %g (%s)",
                 PG_DEFAULT_SKY_LEVEL, e ? "--environment default" : "a glTF file without lights");
    } else {
        snprintf(app->env_why, sizeof app->env_why, "environment: none (%s; --environment FILE.hdr adds one)",
                 !gltf ? "the generated atrium" : scene->n_lights ? "the file has its own lights" : "a scenario");
    }
    if (env && env->clamped)
        fprintf(stderr, "passgraph: %s: %llu texel components were negative, not finite or above %g: read as 0 or "
                        "%g\n", env->source, (unsigned long long)env->clamped, PG_ENV_MAX_VALUE, PG_ENV_MAX_VALUE);
    pg_scene_set_environment(scene, env);
    return PG_OK;
}

pg_result pg_app_open(pg_app *app, const pg_cli_common *opt, bool with_gpu, pg_error *err)
{
    return pg_app_open_ex(app, opt, with_gpu, NULL, err);
}

/* "lights: the file's 3 KHR_lights_punctual lights (2 point, 1 directional)..." */
static void describe_file_lights(const pg_scene *scene, uint32_t generated, char *buf, size_t size)
{
    uint32_t n[3] = {0, 0, 0};
    for (uint32_t i = 0; i < scene->n_lights; i++) n[scene->lights[i].type]++;
    snprintf(buf, size, "lights: the file's %u light%s (%u point, %u spot, %u directional)", scene->n_lights,
             scene->n_lights == 1 ? "" : "s", n[0], n[1], n[2]);
    if (generated)
        snprintf(buf + strlen(buf), size - strlen(buf), " + %u generated point lights (--lights or the scenario)",
                 generated);
}

pg_result pg_app_session_create(pg_app *app, const pg_session_desc *desc, pg_session **out, pg_error *err)
{
    *out = NULL;
    pg_result r = pg_plugins_load_listed(&app->registry, desc->pipeline_path, &app->plugins, err);
    if (!r) r = pg_session_create(app->gpu, app->scene_gpu, desc, out, err);
    return r;
}

void pg_app_note_unused_colour(const pg_app *app, const pg_graph_plan *plan, const char *tool)
{
    const pg_cli_common *o = &app->opt;
    if (!plan || (!o->ocio_config && !o->display && !o->ocio_view)) return;
    for (uint32_t i = 0; i < plan->n_passes; i++)
        if (!plan->passes[i].culled && plan->passes[i].type && !strcmp(plan->passes[i].type->name, "display_ocio"))
            return;
    char what[3 * PG_PATH_MAX + 64] = "";
    size_t l = 0;
    const char *names[3] = {"--ocio-config", "--display", "--ocio-view"}, *vals[3] = {o->ocio_config, o->display, o->ocio_view};
    for (int k = 0; k < 3; k++)
        if (vals[k] && l < sizeof what)
            l += (size_t)snprintf(what + l, sizeof what - l, "%s%s %s", l ? ", " : "", names[k], vals[k]);
    fprintf(stderr, "%s: warning: %s: no effect, the pipeline runs no display_ocio pass (its display_tonemap, e.g. "
            "tonemap=clamp, reinhard or aces, encodes sRGB itself)\n", tool, what);
}

pg_result pg_app_pose_scene(pg_app *app, pg_scene *scene, pg_error *err)
{
    app->animation = PG_ANIM_FIRST;
    if (app->opt.animation) {
        pg_result r = pg_anim_find(scene->anim, app->opt.animation, &app->animation, err);
        if (r) return r;
    }
    return pg_scene_pose(scene, app->animation, app->opt.time, err);
}

/* A scenario that moves the camera (position or target) without giving near and far: the planes the
 * default view fitted to the scene at its own distance would cut the scene off, so the missing ones
 * are fitted again around the scene's bounding sphere from the new position. */
static void fit_scenario_planes(const pg_scene *scene, const pg_scenario *sc, pg_camera *cam)
{
    if (!(sc->has_cam_position || sc->has_cam_target) || (sc->has_cam_near && sc->has_cam_far)) return;
    double r2 = 0, d2 = 0;
    for (int k = 0; k < 3; k++) {
        const double c = 0.5 * ((double)scene->bounds_min[k] + scene->bounds_max[k]);
        const double h = 0.5 * ((double)scene->bounds_max[k] - scene->bounds_min[k]);
        r2 += h * h;
        d2 += (cam->position[k] - c) * (cam->position[k] - c);
    }
    const double r = sqrt(r2), d = sqrt(d2), far = 1.05 * (d + r) + 1e-3;
    if (!sc->has_cam_far) cam->far_z = (float)far;
    if (!sc->has_cam_near) cam->near_z = (float)fmax(d - r > 0 ? 0.95 * (d - r) : 0.0, 1e-4 * cam->far_z);
    if (!(cam->far_z > cam->near_z)) cam->far_z = cam->near_z * 1000.0f;
}

/* The device (with a window's instance extensions and swapchain hooks when given) and the scene's
 * GPU copy. */
static pg_result open_gpu(pg_app *app, const pg_cli_common *opt, const pg_gpu_desc *window_bits, pg_error *err)
{
    pg_gpu_desc gd = {
        .validation = opt->validation,
        .device_index = opt->device_index,
        .device_match = opt->device_match,
        .quiet = opt->quiet,
        .no_compute_queue = opt->async_compute == PG_ASYNC_OFF,
        .emulate_compute_queue = opt->async_compute == PG_ASYNC_EMULATE,
    };
    if (window_bits) {
        gd.instance_extensions = window_bits->instance_extensions;
        gd.n_instance_extensions = window_bits->n_instance_extensions;
        gd.swapchain = window_bits->swapchain;
        gd.present_ok = window_bits->present_ok;
        gd.present_user = window_bits->present_user;
    }
    pg_result r = pg_gpu_create(&gd, &app->gpu, err);
    if (!r) r = pg_scene_gpu_create(app->gpu, app->scene, &app->scene_gpu, err);
    return r;
}

pg_result pg_app_open_ex(pg_app *app, const pg_cli_common *opt, bool with_gpu, const pg_gpu_desc *window_bits,
                         pg_error *err)
{
    memset(app, 0, sizeof *app);
    app->opt = *opt;
    pg_register_builtin_passes(&app->registry);
    pg_result r;
    if ((r = pg_plugins_load(&app->registry, opt->plugins, opt->n_plugins, &app->plugins, err))) {
        pg_plugins_close(&app->plugins);
        return r;
    }
    if (opt->pipeline) pg_strlcpy(app->pipeline_path, opt->pipeline, sizeof app->pipeline_path);
    else pg_data_path(app->pipeline_path, sizeof app->pipeline_path, "pipelines/naive.json");
    /* the pipeline's own plug-ins (for dump, which compiles without a session) */
    if ((r = pg_plugins_load_listed(&app->registry, app->pipeline_path, &app->plugins, err))) return r;
    if (opt->scenario) {
        if ((r = pg_scenario_load(opt->scenario, &app->scenario, err))) return r;
        app->has_scenario = true;
    }
    const char *scene = opt->scene ? opt->scene : "default";
    if (app->has_scenario && app->scenario.scene[0] && (!opt->scene || !strcmp(opt->scene, "default")))
        scene = app->scenario.scene;
    pg_strlcpy(app->scene_path, scene, sizeof app->scene_path);
    pg_scene_load_opts lo = {.gltf_scene = opt->gltf_scene, .gltf_variant = opt->variant};
    if ((r = pg_scene_load_ex(scene, &lo, &app->scene, err))) return r;
    if (app->has_scenario && pg_scenario_shading(&app->scenario) >= 0) /* what a pipeline's shading "auto" picks */
        app->scene->features.auto_shading = (uint8_t)pg_scenario_shading(&app->scenario); /* before the GPU copy */
    pg_scene_print_warnings(app->scene, "passgraph: ", stderr); /* once per loaded scene */
    if ((r = pg_app_pose_scene(app, app->scene, err))) goto fail;
    char choice[PG_PATH_MAX + 800];
    if (pg_scene_choice_line(app->scene, choice, sizeof choice) && !opt->quiet)
        fprintf(stderr, "passgraph: %s\n", choice);
    if (pg_scene_variant_line(app->scene, choice, sizeof choice) && !opt->quiet)
        fprintf(stderr, "passgraph: %s\n", choice);
    if ((r = pg_app_attach_environment(app, app->scene, err))) goto fail;
    if (with_gpu && (r = open_gpu(app, opt, window_bits, err))) goto fail;
    /* the count and seed the default set-up is made for: the command line's, else the scenario's
     * (the object rule's intensity follows the count) */
    const bool sc_count = app->has_scenario && app->scenario.has_light_count && !opt->has_lights;
    const bool sc_seed = app->has_scenario && app->scenario.has_seed && !opt->has_seed;
    const uint32_t seed = sc_seed ? app->scenario.lights.seed : opt->seed;
    if ((r = pg_scene_default_view(app->scene, opt->camera, (float)opt->width / (float)opt->height,
                                 sc_count ? app->scenario.lights.count : opt->lights, seed, &app->camera, &app->lights,
                                 app->camera_why, sizeof app->camera_why, app->lights_why, sizeof app->lights_why, err)))
        goto fail;
    if (sc_count || sc_seed)
        snprintf(app->lights_why + strlen(app->lights_why), sizeof app->lights_why - strlen(app->lights_why),
                 "; %s%s%s from scenario %s", sc_count ? "count" : "", sc_count && sc_seed ? " and " : "",
                 sc_seed ? "seed" : "", app->scenario.path);
    if (app->has_scenario) {
        bool cam_from_scenario = app->scenario.has_camera && !opt->camera;
        /* a scenario that places its own lights (an interior set-up such as cis565) gets no object
         * ambient unless it asks for one */
        if ((app->scenario.has_light_box || app->scenario.has_radius || app->scenario.has_intensity) &&
            !app->scenario.has_ambient)
            app->lights.ambient = 0;
        pg_scenario_apply(&app->scenario, &app->lights, cam_from_scenario ? &app->camera : NULL);
        if (cam_from_scenario) {
            fit_scenario_planes(app->scene, &app->scenario, &app->camera);
            pg_camera_raise_near(&app->camera, app->scene); /* a near plane too small for the depth buffer */
        }
        if (cam_from_scenario)
            snprintf(app->camera_why, sizeof app->camera_why, "camera: scenario %s (its camera fields over the default)",
                     app->scenario.path);
        if (app->scenario.has_light_box || app->scenario.has_radius || app->scenario.has_intensity)
            snprintf(app->lights_why, sizeof app->lights_why, "lights: generated point lights, scenario %s: box (%g,%g,%g)..(%g,%g,%g), radius %g, intensity %g",
                     app->scenario.path, app->lights.box_min[0], app->lights.box_min[1], app->lights.box_min[2],
                     app->lights.box_max[0], app->lights.box_max[1], app->lights.box_max[2], app->lights.radius,
                     app->lights.intensity);
    }
    if (opt->has_lights || !(app->has_scenario && app->scenario.has_light_count)) app->lights.count = opt->lights;
    if (app->scene->n_lights > 0) { /* the file's own lights, first; generated ones only when asked */
        uint32_t generated = opt->has_lights || (app->has_scenario && app->scenario.has_light_count) ? app->lights.count : 0;
        if ((uint64_t)app->scene->n_lights + generated > PG_MAX_LIGHTS) { /* each source is capped on its own */
            r = pg_fail(err, PG_ERR_LIMIT, "%s: the file's %u lights and %u generated ones: more than %u in all",
                        app->scene->path, app->scene->n_lights, generated, PG_MAX_LIGHTS);
            goto fail;
        }
        app->lights.file_count = app->scene->n_lights;
        app->lights.count = app->scene->n_lights + generated;
        describe_file_lights(app->scene, generated, app->lights_why, sizeof app->lights_why);
    }
    if (opt->has_radius) app->lights.radius = opt->radius;
    if (opt->has_intensity) app->lights.intensity = opt->intensity;
    if (app->scene->environment && !opt->has_ambient && !(app->has_scenario && app->scenario.has_ambient) &&
        app->lights.ambient != 0) { /* the environment lights what the lights miss */
        app->lights.ambient = 0;
        snprintf(app->lights_why + strlen(app->lights_why), sizeof app->lights_why - strlen(app->lights_why),
                 "; ambient 0 (the environment light instead)");
    }
    app->lights.env_intensity = opt->env_intensity;
    app->lights.env_rotation = opt->env_rotation_deg * (float)(3.14159265358979 / 180.0);
    if (opt->has_ambient) app->lights.ambient = opt->ambient;
    app->object_lights = strcmp(app->scene->path, "default") != 0 && !opt->has_intensity &&
                         !(app->has_scenario && app->scenario.has_intensity);

    if (opt->has_radius || opt->has_intensity) { /* the values that replace the set-up's, not just their names */
        char rv[48] = "", iv[48] = "";
        if (opt->has_radius) snprintf(rv, sizeof rv, "radius %g (--radius)", app->lights.radius);
        if (opt->has_intensity) snprintf(iv, sizeof iv, "intensity %g (--intensity)", app->lights.intensity);
        snprintf(app->lights_why + strlen(app->lights_why), sizeof app->lights_why - strlen(app->lights_why),
                 "; instead: %s%s%s", rv, rv[0] && iv[0] ? ", " : "", iv);
    }
    if (opt->has_ambient || (app->has_scenario && app->scenario.has_ambient))
        snprintf(app->lights_why + strlen(app->lights_why), sizeof app->lights_why - strlen(app->lights_why),
                 "; ambient %g from %s", app->lights.ambient, opt->has_ambient ? "--ambient" : "the scenario");
    app->lights.seed = seed;
    return PG_OK;
fail:
    pg_app_close(app);
    return r;
}

void pg_app_print_explain_lighting(const pg_app *app, const pg_session *s, const char *label, FILE *f)
{
    if (!label) {
        fprintf(f, "explain: %s\nexplain: %s\n", app->camera_why, app->lights_why);
        char choice[PG_PATH_MAX + 800];
        if (pg_scene_choice_line(app->scene, choice, sizeof choice)) fprintf(f, "explain: scene: %s\n", choice);
        if (pg_scene_variant_line(app->scene, choice, sizeof choice)) fprintf(f, "explain: scene: %s\n", choice);
        char anim[256];
        if (pg_anim_describe(app->scene, app->animation, app->opt.time, anim, sizeof anim))
            fprintf(f, "explain: animation: %s; --animation N|NAME|all|none, --time T\n", anim);
        fprintf(f, "explain: %s; intensity %g, rotation %g deg; ambient term %g (x albedo; pbr: x (c_diff + F0) x "
                   "occlusion)\n",
                app->env_why, app->lights.env_intensity, app->lights.env_rotation * 180.0 / 3.14159265358979,
                app->lights.ambient);
    }
    if (!s) return;
    const pg_param *sh = s->pipeline ? pg_pipeline_find_param(s->pipeline, "shading") : NULL;
    char v[64] = "";
    if (sh) pg_param_format(sh, v, sizeof v);
    char resolved[160] = ""; /* what "auto" picks for this scene, and why */
    if (sh && !strcmp(v, "auto")) {
        const int a = app->scene ? app->scene->features.auto_shading : PG_SHADING_LAMBERT;
        snprintf(resolved, sizeof resolved, " -> %s%s (%s)", pg_shading_models[a],
                 a == PG_SHADING_PBR ? " (the glTF metallic-roughness BRDF)" : "",
                 app->has_scenario && pg_scenario_shading(&app->scenario) >= 0 ? "the scenario's shading"
                 : a == PG_SHADING_PBR                                        ? "a glTF file's materials"
                                                                              : "a generated scene");
    }
    fprintf(f, "explain: shading%s%s: %s%s\n", label ? " of " : "", label ? label : "",
            sh ? v : "the pipeline has no `shading` parameter (its passes' own model)", resolved);
}

void pg_app_close(pg_app *app)
{
    if (app->scene_gpu) pg_scene_gpu_destroy(app->gpu, app->scene_gpu);
    pg_scene_free(app->scene);
    pg_gpu_destroy(app->gpu);
    app->scene_gpu = NULL;
    app->scene = NULL;
    app->gpu = NULL;
    pg_plugins_close(&app->plugins); /* after every session that used their pass types */
}

pg_frame_info pg_app_frame(const pg_app *app)
{
    pg_frame_info fi = {
        .camera = app->camera,
        .lights = app->lights,
        .time = app->opt.time,
        .animation = app->animation,
        .width = app->opt.width,
        .height = app->opt.height,
    };
    return fi;
}

pg_session_desc pg_app_session_desc(const pg_app *app)
{
    pg_session_desc sd = {
        .pipeline_path = app->pipeline_path,
        .overrides = app->opt.sets,
        .n_overrides = app->opt.n_sets,
        .registry = &app->registry,
        .disable_aliasing = app->opt.no_aliasing,
        .immediate = app->opt.immediate,
        .async_off = app->opt.async_compute == PG_ASYNC_OFF,
        .settings = app->opt.settings,
        .n_settings = app->opt.n_settings,
    };
    return sd;
}

uint64_t pg_app_check_exact(const char *cmd, const char *what, const pg_frame_stats *st, bool require_exact)
{
    uint64_t dropped = pg_frame_counter_sum(st, "overflow_dropped");
    if (!dropped) return 0;
    uint64_t cap = pg_frame_counter_sum(st, "dropped_cap");
    fprintf(stderr,
            "%s: %s: %s is not exact: %llu light references dropped (%llu by max_lights, %llu past the list "
            "budget: raise list_budget_mb, 0 = half the device-local heap)%s\n",
            cmd, require_exact ? "error" : "warning", what, (unsigned long long)dropped, (unsigned long long)cap,
            (unsigned long long)(dropped - cap), require_exact ? " (--require-exact)" : "");
    return dropped;
}
