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

/* the triangles of each rigid moving primitive wound as the pose mirrors it (pg_anim_prim_mirrored) */
static void flip_windings(pg_scene *scene, const pg_anim_pose *pose)
{
    pg_scene_anim *a = scene->anim;
    for (uint32_t k = 0; k < a->n_prims; k++) {
        const uint32_t want = pg_anim_prim_mirrored(a, pose, k);
        if (a->prims[k].skin >= 0 || want == a->prims[k].wound_mirrored) continue;
        a->prims[k].wound_mirrored = want;
        for (uint32_t p = 0; p < scene->n_primitives; p++) {
            const pg_primitive *pr = &scene->primitives[p];
            if ((int64_t)pr->vertex_offset != (int64_t)a->prims[k].first_vertex) continue;
            uint32_t *t = scene->indices + pr->first_index;
            for (uint32_t i = 0; i + 2 < pr->index_count; i += 3) {
                const uint32_t swap = t[i + 1];
                t[i + 1] = t[i + 2];
                t[i + 2] = swap;
            }
        }
    }
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
    flip_windings(scene, &pose);
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
