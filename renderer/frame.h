/* frame.h - per-frame inputs shared by every pass: camera, lights set-up, time, output size.
 * pg_frame_uniforms is the std140 layout of `FrameUniforms` in shaders/common.glsl (set 0,
 * binding 0 of every pass); keep the two in sync. */
#ifndef PG_FRAME_H
#define PG_FRAME_H

#include <assert.h>
#include <string.h>

#include "pg_common.h"
#include "scenario.h"
#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

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
    uint32_t noise[4];      /* sample index, seed (pg_frame_info.sample, lights.seed), 0, 0 */
    float light_keep_min[4]; /* pg_light_setup.keep_min, w = 1 when keep_out */
    float light_keep_max[4]; /* pg_light_setup.keep_max, w = 0 */
    uint32_t light_src[4];   /* x: lights from the scene file (pg_light_setup.file_count), y: the
                                played glTF animation (pg_frame_info.animation as int32), 0, 0 */
    float environment[4];    /* intensity, rotation about +Y (radians), 0, 0 (pg_light_setup.env_*) */
} pg_frame_uniforms;

typedef struct pg_frame_info {
    pg_camera camera;
    pg_light_setup lights;  /* count and seed included */
    float time;
    int32_t animation;      /* the glTF animation played at `time` (scene/animation.h: an index,
                               PG_ANIM_ALL, PG_ANIM_NONE; 0 = the first, the default) */
    uint32_t width, height;
    /* the random stream of stochastic passes (hash of pixel, sample, seed): frames with one
     * sample index and seed give one image; accumulation and temporal measures step it */
    uint32_t sample;
} pg_frame_info;

void pg_frame_uniforms_fill(const pg_frame_info *info, pg_frame_uniforms *u);

/* The glTF animation a frame block plays (light_src.y; its time is camera_pos.w). */
static inline int32_t pg_frame_animation(const pg_frame_uniforms *u)
{
    int32_t animation;
    memcpy(&animation, &u->light_src[1], sizeof animation);
    return animation;
}

/* The frame block a pass's record() was given (pg_pass_record_ctx.frame), seen as the built-in
 * passes' pg_frame_uniforms: the runtime does not know its layout, so a block of another size
 * (a runtime created for another frame layout) is a contract break caught here. */
#define PG_FRAME_OF(ctx) \
    (assert((ctx)->frame_size == sizeof(pg_frame_uniforms)), (const pg_frame_uniforms *)(ctx)->frame)

#ifdef __cplusplus
}
#endif
#endif
