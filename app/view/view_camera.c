/* view_camera.c - `passgraph view`: the camera list (start view, auto framing, glTF cameras),
 * choosing one, and the fly camera (WASD/QE, right mouse to look). */
#include "view.h"

/* ---------------------------------------------------------------- camera */

void camera_angles(viewer *v)
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
void camera_list(viewer *v, const char *start_label)
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
void camera_choose(viewer *v, int choice)
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
    camera_follow_set(v, choice >= 2 ? choice - 2 : choice == 0 ? v->cam_start_gltf : -1);
}

/* Follows glTF camera `gltf_camera` (-1: none) when animation can move its node. */
void camera_follow_set(viewer *v, int gltf_camera)
{
    const pg_scene *sc = v->app.scene;
    v->cam_follow = -1;
    if (!sc || !sc->anim || gltf_camera < 0 || (uint32_t)gltf_camera >= sc->n_cameras ||
        sc->cameras[gltf_camera].gltf_node < 0)
        return;
    v->cam_follow = gltf_camera;
    printf("view: camera: glTF camera %d '%s' follows its node '%s' as the clock plays\n", gltf_camera,
           sc->cameras[gltf_camera].name, sc->cameras[gltf_camera].node_name);
}

/* The followed camera placed by its node at the clock's time. The pose is the uploaded scene's
 * (pg_scene_gpu_anim_pose): the frame's passes then find it evaluated already. */
static void camera_follow(viewer *v)
{
    pg_scene *sc = v->app.scene;
    const pg_scene_gpu_anim *ga = v->app.scene_gpu ? v->app.scene_gpu->anim : NULL;
    if (!ga) {
        v->cam_follow = -1;
        return;
    }
    pg_scene_pose_camera(sc, (uint32_t)v->cam_follow, pg_scene_gpu_anim_pose(ga, v->app.animation, v->time));
    float aspect = v->win.extent.height ? (float)v->win.extent.width / (float)v->win.extent.height : 16.0f / 9;
    pg_error err = {0};
    if (pg_camera_from_scene(sc, (uint32_t)v->cam_follow, aspect, &v->camera, &err)) {
        v->cam_follow = -1;
        return;
    }
    camera_angles(v);
}

void camera_update(viewer *v, float dt)
{
    if (v->cam_follow >= 0) camera_follow(v);
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
        if (mv[0] != 0 || mv[1] != 0 || mv[2] != 0) v->cam_follow = -1; /* flown away: no longer follows */
    }
    double x, y;
    glfwGetCursorPos(w, &x, &y);
    bool rmb = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    if (rmb && (v->looking || !pg_ui_want_mouse())) {
        if (v->looking) {
            if (x != v->last_x || y != v->last_y) v->cam_follow = -1;
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
