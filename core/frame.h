/* frame.h - per-frame inputs shared by every pass: camera, lights set-up, time, output size.
 * pg_frame_uniforms is the std140 layout of `FrameUniforms` in shaders/common.glsl (set 0,
 * binding 0 of every pass); keep the two in sync. */
#ifndef PG_FRAME_H
#define PG_FRAME_H

#include "pg_common.h"
#include "scenario.h"
#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Smallest light-to-surface distance used by the attenuation (world units): the 1/d^2 term is
 * evaluated as 1/max(d^2, PG_LIGHT_MIN_DISTANCE^2), so one light contributes at most
 * intensity / PG_LIGHT_MIN_DISTANCE^2 = intensity * 1e4. */
#define PG_LIGHT_MIN_DISTANCE 0.01f
/* Largest value a shading pass writes to the HDR target (below half-float max 65504). */
#define PG_HDR_MAX 65000.0f

typedef struct pg_frame_uniforms {
    float view[16], proj[16], view_proj[16], inv_view[16], inv_proj[16];
    float camera_pos[4];    /* xyz, w = time (s) */
    float light_box_min[4]; /* xyz, w = radius */
    float light_box_max[4]; /* xyz, w = intensity */
    float light_params[4];  /* saturation, speed, motion (0 noise, 1 static), min distance */
    uint32_t counts[4];     /* light count, seed, width, height */
    float clip[4];          /* near, far, ambient (pg_light_setup.ambient), 1 = orthographic */
} pg_frame_uniforms;

typedef struct pg_frame_info {
    pg_camera camera;
    pg_light_setup lights;  /* count and seed included */
    float time;
    uint32_t width, height;
} pg_frame_info;

void pg_frame_uniforms_fill(const pg_frame_info *info, pg_frame_uniforms *u);

#ifdef __cplusplus
}
#endif
#endif
