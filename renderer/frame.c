#include "frame.h"

#include <string.h>

void pg_frame_uniforms_fill(const pg_frame_info *info, pg_frame_uniforms *u)
{
    memset(u, 0, sizeof *u);
    pg_camera cam = info->camera;
    cam.aspect = info->height ? (float)info->width / (float)info->height : 1.0f;
    pg_camera_view(&cam, u->view);
    pg_camera_proj(&cam, u->proj);
    pg_mat4_mul(u->proj, u->view, u->view_proj);
    pg_mat4_invert(u->view, u->inv_view);
    pg_mat4_invert(u->proj, u->inv_proj);
    for (int i = 0; i < 3; i++) {
        u->camera_pos[i] = cam.position[i];
        u->light_box_min[i] = info->lights.box_min[i];
        u->light_box_max[i] = info->lights.box_max[i];
    }
    u->camera_pos[3] = info->time;
    u->light_box_min[3] = info->lights.radius;
    u->light_box_max[3] = info->lights.intensity;
    u->light_params[0] = info->lights.saturation;
    u->light_params[1] = info->lights.speed;
    u->light_params[2] = info->lights.motion == PG_MOTION_STATIC ? 1.0f : 0.0f;
    u->light_params[3] = PG_LIGHT_MIN_DISTANCE;
    u->counts[0] = info->lights.count;
    u->counts[1] = info->lights.seed;
    u->counts[2] = info->width;
    u->counts[3] = info->height;
    pg_camera_depth_planes(&cam, &u->clip[0], &u->clip[1]); /* the planes of u->proj */
    u->clip[2] = info->lights.ambient;
    u->clip[3] = cam.ortho_height > 0 ? 1.0f : 0.0f;
    u->noise[0] = info->sample;
    u->noise[1] = info->lights.seed;
    u->noise[2] = 0;
    u->noise[3] = 0;
    for (int i = 0; i < 3; i++) {
        u->light_keep_min[i] = info->lights.keep_min[i];
        u->light_keep_max[i] = info->lights.keep_max[i];
    }
    u->light_keep_min[3] = info->lights.keep_out ? 1.0f : 0.0f;
    u->environment[0] = info->lights.env_intensity;
    u->environment[1] = info->lights.env_rotation;
    u->light_src[0] = info->lights.file_count < info->lights.count ? info->lights.file_count : info->lights.count;
    memcpy(&u->light_src[1], &info->animation, sizeof info->animation);
}
