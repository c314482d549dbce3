#include "app.h"

#include <stdio.h>
#include <string.h>

#include "pass_list.h"
#include "shader.h"

pg_result pg_app_default_view(const pg_scene *scene, const char *camera_spec, float aspect, uint32_t count,
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
        if (!want_auto && scene && scene->n_cameras > 0) {
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
        snprintf(lw, sizeof lw, "lights: interior box (bounds shrunk by 2%%), radius %.3g, intensity %.3g", ls.radius,
                 ls.intensity);
    } else {
        ls = pg_light_setup_object(scene, count, seed);
        snprintf(lw, sizeof lw,
                 "lights: object box (bounds grown by 0.6 x radius per side), radius %.3g, intensity %.3g, ambient %.3g",
                 ls.radius, ls.intensity, ls.ambient);
    }
    *camera = cam;
    *lights = ls;
    if (camera_why && camera_why_size) pg_strlcpy(camera_why, cw, camera_why_size);
    if (lights_why && lights_why_size) pg_strlcpy(lights_why, lw, lights_why_size);
    return PG_OK;
}

pg_result pg_app_open(pg_app *app, const pg_cli_common *opt, bool with_gpu, pg_error *err)
{
    return pg_app_open_ex(app, opt, with_gpu, NULL, err);
}

pg_result pg_app_open_ex(pg_app *app, const pg_cli_common *opt, bool with_gpu, const pg_gpu_desc *window_bits,
                         pg_error *err)
{
    memset(app, 0, sizeof *app);
    app->opt = *opt;
    pg_register_builtin_passes(&app->registry);
    pg_result r;
    if (opt->pipeline) pg_strlcpy(app->pipeline_path, opt->pipeline, sizeof app->pipeline_path);
    else pg_data_path(app->pipeline_path, sizeof app->pipeline_path, "pipelines/naive.json");
    if (opt->scenario) {
        if ((r = pg_scenario_load(opt->scenario, &app->scenario, err))) return r;
        app->has_scenario = true;
    }
    const char *scene = opt->scene ? opt->scene : "default";
    if (app->has_scenario && app->scenario.scene[0] && (!opt->scene || !strcmp(opt->scene, "default")))
        scene = app->scenario.scene;
    pg_strlcpy(app->scene_path, scene, sizeof app->scene_path);
    if ((r = pg_scene_load(scene, &app->scene, err))) return r;
    pg_scene_print_warnings(app->scene, "passgraph: ", stderr); /* once per loaded scene */
    if (with_gpu) {
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
        if ((r = pg_gpu_create(&gd, &app->gpu, err))) goto fail;
        if ((r = pg_scene_gpu_create(app->gpu, app->scene, &app->scene_gpu, err))) goto fail;
    }
    if ((r = pg_app_default_view(app->scene, opt->camera, (float)opt->width / (float)opt->height, opt->lights,
                                 opt->seed, &app->camera, &app->lights, app->camera_why, sizeof app->camera_why,
                                 app->lights_why, sizeof app->lights_why, err)))
        goto fail;
    if (app->has_scenario) {
        bool cam_from_scenario = app->scenario.has_camera && !opt->camera;
        /* a scenario that places its own lights (an interior set-up such as cis565) gets no object
         * ambient unless it asks for one */
        if ((app->scenario.has_light_box || app->scenario.has_radius || app->scenario.has_intensity) &&
            !app->scenario.has_ambient)
            app->lights.ambient = 0;
        pg_scenario_apply(&app->scenario, &app->lights, cam_from_scenario ? &app->camera : NULL);
        if (cam_from_scenario)
            snprintf(app->camera_why, sizeof app->camera_why, "camera: scenario %s (its camera fields over the default)",
                     app->scenario.path);
        if (app->scenario.has_light_box || app->scenario.has_radius || app->scenario.has_intensity)
            snprintf(app->lights_why, sizeof app->lights_why, "lights: scenario %s: box (%g,%g,%g)..(%g,%g,%g), radius %g, intensity %g",
                     app->scenario.path, app->lights.box_min[0], app->lights.box_min[1], app->lights.box_min[2],
                     app->lights.box_max[0], app->lights.box_max[1], app->lights.box_max[2], app->lights.radius,
                     app->lights.intensity);
    }
    if (opt->has_lights || !(app->has_scenario && app->scenario.has_light_count)) app->lights.count = opt->lights;
    if (opt->has_radius) app->lights.radius = opt->radius;
    if (opt->has_intensity) app->lights.intensity = opt->intensity;
    if (opt->has_ambient) app->lights.ambient = opt->ambient;
    app->object_lights = strcmp(app->scene->path, "default") != 0 && !opt->has_intensity &&
                         !(app->has_scenario && app->scenario.has_intensity);
    if (app->object_lights && app->lights.count != opt->lights) /* a scenario's light count */
        app->lights.intensity = pg_light_setup_object(app->scene, app->lights.count, opt->seed).intensity;
    if (opt->has_radius || opt->has_intensity)
        snprintf(app->lights_why + strlen(app->lights_why), sizeof app->lights_why - strlen(app->lights_why),
                 "; %s%s%s from the command line", opt->has_radius ? "radius" : "",
                 opt->has_radius && opt->has_intensity ? " and " : "", opt->has_intensity ? "intensity" : "");
    if (opt->has_ambient || (app->has_scenario && app->scenario.has_ambient))
        snprintf(app->lights_why + strlen(app->lights_why), sizeof app->lights_why - strlen(app->lights_why),
                 "; ambient %g from %s", app->lights.ambient, opt->has_ambient ? "--ambient" : "the scenario");
    app->lights.seed = opt->seed;
    return PG_OK;
fail:
    pg_app_close(app);
    return r;
}

void pg_app_close(pg_app *app)
{
    if (app->scene_gpu) pg_scene_gpu_destroy(app->gpu, app->scene_gpu);
    pg_scene_free(app->scene);
    pg_gpu_destroy(app->gpu);
    app->scene_gpu = NULL;
    app->scene = NULL;
    app->gpu = NULL;
}

pg_frame_info pg_app_frame(const pg_app *app)
{
    pg_frame_info fi = {
        .camera = app->camera,
        .lights = app->lights,
        .time = app->opt.time,
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
