/* scene_pose.c - a loaded scene posed on the CPU at a time (animation.h pg_scene_pose): its own
 * file so that the scene (scene.c) and the animation (animation.c) do not depend on each other. */
#include "animation.h"
#include "node_place.h"

#include <string.h>

bool pg_scene_pose_camera(pg_scene *scene, uint32_t index, const pg_anim_pose *pose)
{
    const pg_scene_anim *a = scene->anim;
    if (!a || index >= scene->n_cameras) return false;
    pg_scene_camera *C = &scene->cameras[index];
    if (C->gltf_node < 0 || (uint32_t)C->gltf_node >= a->n_nodes) return false;
    double m[16];
    pg_mat4_widen(pose->node_world + (size_t)C->gltf_node * 16, m);
    pg_anim_camera_props(a, pose, C); /* KHR_animation_pointer: yfov, aspect, xmag, ymag, znear, zfar */
    return pg_place_camera(m, C); /* singular at this time: keeps the last placement */
}

pg_result pg_scene_pose(pg_scene *scene, int animation, double time, pg_error *err)
{
    pg_scene_anim *a = scene ? scene->anim : NULL;
    if (!a) return PG_OK;
    pg_anim_pose pose;
    pg_result r = pg_anim_pose_alloc(a, &pose, err);
    if (r) return r;
    pg_anim_pose_eval(a, animation, time, &pose);
    pg_anim_deform(a, &pose, scene->vertices);
    for (uint32_t i = 0; i < scene->n_lights; i++) { /* a light on a node moves with it */
        pg_scene_light *L = &scene->lights[i];
        if (L->gltf_node < 0 || (uint32_t)L->gltf_node >= a->n_nodes) continue;
        double m[16];
        pg_mat4_widen(pose.node_world + (size_t)L->gltf_node * 16, m);
        pg_place_light(m, L);
        pg_anim_light_props(a, &pose, L); /* KHR_animation_pointer: colour, intensity, range, cones */
    }
    for (uint32_t i = 0; i < scene->n_cameras; i++) pg_scene_pose_camera(scene, i, &pose); /* placed at `time` */
    for (uint32_t m = 0; m < scene->n_materials && m < a->n_materials; m++) /* the file's materials come first */
        pg_anim_material_props(a, &pose, (int)m, &scene->materials[m]);
    pg_anim_pose_release(&pose);
    const bool env = scene->features.has_environment;
    const uint8_t shading = scene->features.auto_shading;
    pg_scene_finalize(scene);
    scene->features.has_environment = env;
    scene->features.auto_shading = shading;
    return PG_OK;
}
