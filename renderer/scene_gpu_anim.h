/* scene_gpu_anim.h - a scene's animation data uploaded for the geometry_animate pass
 * (shaders/animate_geometry.comp): device-local storage buffers written once, plus the pose buffer
 * the pass refreshes every frame with vkCmdUpdateBuffer.
 *   local:  pg_vertex per scene vertex (mesh space for a moving primitive; the world for a static one)
 *   info:   per vertex uvec4 (prim or 0xFFFFFFFF, joint slots 0|1<<16, 2|3<<16, 0) + vec4 weights;
 *           a scene whose skins use 8 joints a vertex (pg_scene_anim.influences) adds uvec4 (4|5<<16,
 *           6|7<<16, 0, 0) + vec4 weights 4-7 (info_stride 64 instead of 32; the shader is compiled
 *           with PG_ANIM_INFLUENCES8)
 *   prims:  per moving primitive uvec4 (node, skinned, targets, target base), uvec4 (first vertex,
 *           vertices, weight base, 0)
 *   deltas: pg_anim_delta per (target, vertex) of each morphing primitive
 *   pose:   mat4 per node (world), mat4 per joint slot (world x inverse bind), float per morph weight
 * Created by pg_scene_gpu_create for a scene with features.has_animation; it keeps a pointer to the
 * scene's pg_scene_anim (the scene must outlive its upload, as every tool's does). */
#ifndef PG_SCENE_GPU_ANIM_H
#define PG_SCENE_GPU_ANIM_H

#include "animation.h"
#include "vk_context.h"

/* The pose of the frame being recorded: evaluated once for each new (animation, time), so the passes
 * of one frame that need it (geometry_animate, light_animate) share one evaluation, into arrays
 * allocated once with the upload. */
typedef struct pg_scene_gpu_anim_now {
    pg_anim_pose pose;
    int animation;
    double time;
    bool valid;
    uint64_t evaluations; /* poses evaluated so far (tests: one a frame) */
} pg_scene_gpu_anim_now;

/* What sorting a moving primitive by its posed bounds needs: the centre of its mesh-space bounds and,
 * for a skinned one, its dominant joints (the largest summed weights over its vertices, normalised):
 * the posed centre is sum w_j (world(joint_j) x inverseBind_j) x centre, or its node's world matrix
 * x centre for a rigid one. Morph targets move the mesh-space centre first: + sum_t w_t x shift_t,
 * shift_t the move of the bounds' centre with target t at weight 1 (exact at each target, linear
 * between: a sort key). */
typedef struct pg_anim_prim_centre {
    float local[3];
    uint32_t morph_base; /* its targets' shifts: pg_scene_gpu_anim.morph_shift[morph_base + t] */
    uint32_t n_joints;  /* 0: rigid */
    uint16_t slot[4];
    float weight[4];
    bool wound_mirrored; /* the winding its uploaded indices hold (pg_anim_prim.wound_mirrored at upload:
                          * a CPU pose before it may have rewound them) */
} pg_anim_prim_centre;

typedef struct pg_scene_gpu_anim {
    pg_buffer local, info, prims, deltas, pose;
    uint32_t n_vertices;
    uint32_t joint_base, weight_base, pose_floats; /* float offsets in the pose, its size */
    uint32_t info_stride;      /* bytes a vertex of info: 32, or 64 with 8 joints a vertex */
    const pg_scene_anim *anim;
    /* the file lights on nodes that animation moves (the node or an ancestor has a TRS channel):
     * their indices in the light table and their records as loaded; light_animate rewrites them
     * each frame (pg_scene_gpu_anim_update_lights) */
    uint32_t n_moving_lights;
    uint32_t *moving_light;
    pg_scene_light *moving_rest;
    /* the materials KHR_animation_pointer animates: their indices in the material table and their
     * values as loaded; the frame prologue rewrites them each frame
     * (pg_scene_gpu_anim_update_materials) */
    uint32_t n_moving_materials;
    uint32_t *moving_material;
    pg_material *moving_mat_rest;
    pg_scene_gpu_anim_now *now;
    pg_anim_prim_centre *centres; /* per moving primitive (anim->n_prims) */
    float (*morph_shift)[3];       /* per morph target of each moving primitive (pg_anim_prim_centre) */
} pg_scene_gpu_anim;

pg_result pg_scene_gpu_anim_create(pg_gpu *gpu, const pg_scene *scene, pg_scene_gpu_anim **out, pg_error *err);
void pg_scene_gpu_anim_destroy(pg_gpu *gpu, pg_scene_gpu_anim *ga);
/* Records into cmd the file-light table's moving lights at (animation, time), placed by their
 * nodes' world matrices, with the barriers around the writes (after earlier compute reads, before
 * the next). Nothing when no light moves. */
void pg_scene_gpu_anim_update_lights(const pg_scene_gpu_anim *ga, VkBuffer table, int animation, double time,
                                     VkCommandBuffer cmd);
/* Records into cmd the material table's animated materials at (animation, time)
 * (pg_anim_material_props), after a barrier from every earlier read; the caller orders them before
 * this frame's reads (the runtime's frame prologue: pg_runtime_set_frame_prologue). False, nothing
 * recorded, when no material is animated. */
bool pg_scene_gpu_anim_update_materials(const pg_scene_gpu_anim *ga, VkBuffer table, int animation, double time,
                                        VkCommandBuffer cmd);
/* The pose at (animation, time): ga->now's, evaluated only when (animation, time) differs from the
 * last call's. */
const pg_anim_pose *pg_scene_gpu_anim_pose(const pg_scene_gpu_anim *ga, int animation, double time);
/* The anim primitive whose vertices start at scene vertex `first_vertex` (a draw's vertex_offset), or
 * -1 when that primitive does not move. */
int32_t pg_scene_gpu_anim_prim_at(const pg_scene_gpu_anim *ga, int32_t first_vertex);
/* Whether moving primitive `prim` (a pg_draw.anim_prim; < 0: false) faces the other way at
 * (animation, time) than its uploaded indices are wound: the pose mirrors it
 * (pg_anim_prim_mirrored) and its indices were not wound for a mirror, or the reverse. Its draws
 * swap their front face. */
bool pg_scene_gpu_anim_flipped(const pg_scene_gpu_anim *ga, int32_t prim, int animation, double time);
/* The world centre of moving primitive `prim` under `pose` (pg_anim_prim_centre). */
void pg_scene_gpu_anim_centre(const pg_scene_gpu_anim *ga, uint32_t prim, const pg_anim_pose *pose, float out[3]);
/* The pose at (animation, time) packed as the pose buffer holds it (ga->pose_floats floats). */
void pg_scene_gpu_anim_pack_pose(const pg_scene_gpu_anim *ga, int animation, double time, float *out);

#endif
