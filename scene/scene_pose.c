/* scene_pose.c - a loaded scene posed on the CPU at a time (animation.h pg_scene_pose): its own
 * file so that the scene (scene.c) and the animation (animation.c) do not depend on each other. */
#include "animation.h"

#include <math.h>
#include <string.h>

pg_result pg_scene_pose(pg_scene *scene, int animation, double time, pg_error *err)
{
    pg_scene_anim *a = scene ? scene->anim : NULL;
    if (!a) return PG_OK;
    pg_anim_pose pose;
    pg_result r = pg_anim_pose_alloc(a, &pose, err);
    if (r) return r;
    pg_anim_pose_eval(a, animation, time, &pose);
    pg_anim_deform(a, &pose, scene->vertices);
    for (uint32_t i = 0; i < scene->n_lights; i++) {
        pg_scene_light *L = &scene->lights[i];
        if (L->gltf_node < 0 || (uint32_t)L->gltf_node >= a->n_nodes) continue;
        const float *m = pose.node_world + (size_t)L->gltf_node * 16;
        const float d[3] = {-m[8], -m[9], -m[10]};
        const float dl = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (int k = 0; k < 3; k++) {
            L->position[k] = m[12 + k];
            if (dl > 1e-30f) L->direction[k] = d[k] / dl;
        }
    }
    for (uint32_t i = 0; i < scene->n_cameras; i++) { /* a camera on an animated node: placed at `time` */
        pg_scene_camera *C = &scene->cameras[i];
        if (C->gltf_node < 0 || (uint32_t)C->gltf_node >= a->n_nodes) continue;
        const float *m = pose.node_world + (size_t)C->gltf_node * 16;
        float f[3] = {-m[8], -m[9], -m[10]}, u[3] = {m[4], m[5], m[6]};
        const float fl = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
        if (!(fl > 1e-30f)) continue; /* singular at this time: keep the last placement */
        for (int k = 0; k < 3; k++) f[k] /= fl;
        const float fu = f[0] * u[0] + f[1] * u[1] + f[2] * u[2];
        for (int k = 0; k < 3; k++) u[k] -= fu * f[k];
        const float ul = sqrtf(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        if (!(ul > 1e-12f)) continue;
        for (int k = 0; k < 3; k++) {
            C->position[k] = m[12 + k];
            C->forward[k] = f[k];
            C->up[k] = u[k] / ul;
        }
    }
    pg_anim_pose_release(&pose);
    const bool env = scene->features.has_environment;
    const uint8_t shading = scene->features.auto_shading;
    pg_scene_finalize(scene);
    scene->features.has_environment = env;
    scene->features.auto_shading = shading;
    return PG_OK;
}
