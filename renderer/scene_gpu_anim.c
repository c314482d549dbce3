/* scene_gpu_anim.c - the animation buffers of an uploaded scene (scene_gpu_anim.h). */
#include "scene_gpu_anim.h"
#include "node_place.h"
#include "scene_gpu.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* data -> a new device-local storage buffer, through a staging buffer and one submit; made visible
 * to compute shader reads */
static pg_result upload(pg_gpu *gpu, const void *data, VkDeviceSize size, VkBufferUsageFlags usage, const char *name,
                        pg_buffer *out, pg_error *err)
{
    if (size == 0) size = 16; /* an unused binding still needs a buffer */
    /* concurrent over both queue families: geometry_animate may run on the compute queue */
    pg_result r = pg_buffer_create_ex(gpu, size,
                                      usage | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false,
                                      true, name, out, err);
    if (r || !data) return r;
    pg_buffer staging;
    if ((r = pg_buffer_create(gpu, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true, "scene.anim.staging", &staging, err)))
        return r;
    memcpy(staging.mapped, data, (size_t)size);
    VkCommandBuffer cmd;
    if (!(r = pg_gpu_begin_once(gpu, &cmd, err))) {
        VkBufferCopy c = {0, 0, size};
        vkCmdCopyBuffer(cmd, staging.buffer, out->buffer, 1, &c);
        VkBufferMemoryBarrier2 b = pg_buffer_barrier(out->buffer, VK_PIPELINE_STAGE_2_COPY_BIT,
                                                     VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                                     VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
        pg_cmd_barriers(cmd, 0, NULL, 1, &b);
        r = pg_gpu_end_once(gpu, cmd, err);
    }
    pg_buffer_destroy(gpu, &staging);
    return r;
}

/* per vertex: (prim, joints 0|1, joints 2|3, 0) and weights 0-3; with 8 influences also
 * (joints 4|5, joints 6|7, 0, 0) and weights 4-7 (ga->info_stride bytes a vertex) */
static void *vertex_info(const pg_scene_anim *a, uint32_t stride)
{
    const uint32_t words = stride / 4;
    uint32_t *info = calloc((size_t)a->n_vertices + 1, stride);
    if (!info) return NULL;
    for (uint32_t v = 0; v < a->n_vertices; v++) {
        uint32_t *w = info + (size_t)v * words;
        w[0] = a->vertex_prim[v];
        if (!a->joints) continue;
        const uint16_t *J = a->joints[v];
        w[1] = (uint32_t)J[0] | (uint32_t)J[1] << 16;
        w[2] = (uint32_t)J[2] | (uint32_t)J[3] << 16;
        memcpy(w + 4, a->weights[v], sizeof(float[4]));
        if (words == 16) {
            w[8] = (uint32_t)J[4] | (uint32_t)J[5] << 16;
            w[9] = (uint32_t)J[6] | (uint32_t)J[7] << 16;
            memcpy(w + 12, a->weights[v] + 4, sizeof(float[4]));
        }
    }
    return info;
}

static void *prim_table(const pg_scene_anim *a)
{
    uint32_t *t = calloc((size_t)a->n_prims + 1, 32);
    if (!t) return NULL;
    for (uint32_t i = 0; i < a->n_prims; i++) {
        const pg_anim_prim *p = &a->prims[i];
        uint32_t *w = t + (size_t)i * 8;
        w[0] = p->node;
        w[1] = p->skin >= 0 && a->joints ? 1u : 0u;
        w[2] = p->n_targets;
        w[3] = p->target_base;
        w[4] = p->first_vertex;
        w[5] = p->n_vertices;
        w[6] = p->weight_base;
    }
    return t;
}

/* per node: animation moves it (a TRS channel on it or an ancestor) */
static uint8_t *moving_nodes(const pg_scene_anim *a)
{
    uint8_t *m = calloc(a->n_nodes + 1, 1), *direct = calloc(a->n_nodes + 1, 1);
    if (!m || !direct) {
        free(m);
        free(direct);
        return NULL;
    }
    for (uint32_t i = 0; i < a->n_animations; i++)
        for (uint32_t c = 0; c < a->animations[i].n_channels; c++) {
            const pg_anim_channel *ch = &a->animations[i].channels[c];
            if (ch->path != PG_ANIM_WEIGHTS && ch->node < a->n_nodes) direct[ch->node] = 1;
        }
    for (uint32_t n = 0; n < a->n_nodes; n++) {
        uint32_t steps = 0;
        for (int32_t k = (int32_t)n; k >= 0 && steps <= a->n_nodes && !m[n]; k = a->nodes[k].parent, steps++)
            m[n] = direct[k];
    }
    free(direct);
    return m;
}

/* The centre of the bounds of primitive pr's mesh-space vertices, with morph target t at weight 1
 * (t < 0: none). */
static void prim_bounds_centre(const pg_scene_anim *a, const pg_anim_prim *pr, int t, float out[3])
{
    float mn[3] = {3.4e38f, 3.4e38f, 3.4e38f}, mx[3] = {-3.4e38f, -3.4e38f, -3.4e38f};
    for (uint32_t i = 0; i < pr->n_vertices && pr->first_vertex + i < a->n_vertices; i++) {
        const float *p = a->local[pr->first_vertex + i].position;
        const float *d = t >= 0 ? a->deltas[pr->target_base + (uint32_t)t * pr->n_vertices + i].position : NULL;
        for (int k = 0; k < 3; k++) {
            const float x = d ? p[k] + d[k] : p[k];
            mn[k] = fminf(mn[k], x);
            mx[k] = fmaxf(mx[k], x);
        }
    }
    for (int k = 0; k < 3; k++) out[k] = pr->n_vertices ? 0.5f * (mn[k] + mx[k]) : 0.0f;
}

/* per moving primitive: the centre of its mesh-space bounds, its morph targets' shifts of it and
 * its dominant joints */
static pg_result prim_centres(const pg_scene_anim *a, pg_scene_gpu_anim *ga, pg_error *err)
{
    uint64_t n_shift = 0;
    for (uint32_t p = 0; p < a->n_prims; p++) n_shift += a->prims[p].n_targets;
    ga->centres = calloc((size_t)a->n_prims + 1, sizeof *ga->centres);
    ga->morph_shift = calloc((size_t)n_shift + 1, sizeof *ga->morph_shift);
    float *sum = a->joints ? calloc((size_t)a->n_joint_slots + 1, sizeof(float)) : NULL;
    if (!ga->centres || !ga->morph_shift || (a->joints && !sum)) {
        free(sum);
        return pg_fail(err, PG_ERR_OOM, "out of memory");
    }
    uint32_t shift_at = 0;
    for (uint32_t p = 0; p < a->n_prims; p++) {
        const pg_anim_prim *pr = &a->prims[p];
        pg_anim_prim_centre *c = &ga->centres[p];
        c->wound_mirrored = pr->wound_mirrored != 0;
        prim_bounds_centre(a, pr, -1, c->local);
        c->morph_base = shift_at;
        for (uint32_t t = 0; t < pr->n_targets && a->deltas; t++, shift_at++) {
            prim_bounds_centre(a, pr, (int)t, ga->morph_shift[shift_at]);
            for (int k = 0; k < 3; k++) ga->morph_shift[shift_at][k] -= c->local[k];
        }
        if (pr->skin < 0 || !sum) continue;
        for (uint32_t v = pr->first_vertex; v < pr->first_vertex + pr->n_vertices && v < a->n_vertices; v++)
            for (int k = 0; k < PG_ANIM_MAX_INFLUENCES; k++) sum[a->joints[v][k]] += a->weights[v][k];
        for (uint32_t v = pr->first_vertex; v < pr->first_vertex + pr->n_vertices && v < a->n_vertices; v++)
            for (int k = 0; k < PG_ANIM_MAX_INFLUENCES; k++) { /* the 4 largest sums, then cleared */
                const uint16_t s = a->joints[v][k];
                float w = sum[s];
                sum[s] = 0;
                if (!(w > 0)) continue;
                const uint32_t n = c->n_joints;
                uint32_t at = n;
                while (at > 0 && c->weight[at - 1] < w) at--;
                if (at >= 4) continue;
                for (uint32_t q = n < 4 ? n : 3; q > at; q--) {
                    c->slot[q] = c->slot[q - 1];
                    c->weight[q] = c->weight[q - 1];
                }
                c->slot[at] = s;
                c->weight[at] = w;
                if (n < 4) c->n_joints++;
            }
        float total = 0;
        for (uint32_t j = 0; j < c->n_joints; j++) total += c->weight[j];
        for (uint32_t j = 0; j < c->n_joints; j++) c->weight[j] /= total;
    }
    free(sum);
    return PG_OK;
}

int32_t pg_scene_gpu_anim_prim_at(const pg_scene_gpu_anim *ga, int32_t first_vertex)
{
    const pg_scene_anim *a = ga ? ga->anim : NULL;
    for (uint32_t p = 0; a && ga->centres && p < a->n_prims; p++)
        if ((int64_t)a->prims[p].first_vertex == first_vertex) return (int32_t)p;
    return -1;
}

bool pg_scene_gpu_anim_flipped(const pg_scene_gpu_anim *ga, int32_t prim, int animation, double time)
{
    if (!ga || prim < 0 || !ga->centres) return false;
    const bool mirrored = pg_anim_prim_mirrored(ga->anim, pg_scene_gpu_anim_pose(ga, animation, time), (uint32_t)prim);
    return mirrored != ga->centres[prim].wound_mirrored;
}

void pg_scene_gpu_anim_centre(const pg_scene_gpu_anim *ga, uint32_t prim, const pg_anim_pose *pose, float out[3])
{
    const pg_anim_prim_centre *c = &ga->centres[prim];
    const pg_anim_prim *pr = &ga->anim->prims[prim];
    float lc[3] = {c->local[0], c->local[1], c->local[2]};
    for (uint32_t t = 0; t < pr->n_targets && ga->anim->deltas; t++) /* morphed before skinning or the node */
        for (int k = 0; k < 3; k++) lc[k] += pose->weights[pr->weight_base + t] * ga->morph_shift[c->morph_base + t][k];
    float m[16];
    if (c->n_joints) {
        memset(m, 0, sizeof m);
        for (uint32_t j = 0; j < c->n_joints; j++)
            for (int e = 0; e < 16; e++) m[e] += c->weight[j] * pose->joints[(size_t)c->slot[j] * 16 + e];
    } else {
        memcpy(m, pose->node_world + (size_t)ga->anim->prims[prim].node * 16, sizeof m);
    }
    for (int r = 0; r < 3; r++) out[r] = m[r] * lc[0] + m[4 + r] * lc[1] + m[8 + r] * lc[2] + m[12 + r];
}

/* a file light the frame's pose changes: on a moving node, or with animated properties */
static bool light_moves(const pg_scene_anim *a, const uint8_t *moving, const pg_scene_light *L)
{
    const int32_t n = L->gltf_node;
    return (n >= 0 && (uint32_t)n < a->n_nodes && moving[n]) || pg_anim_light_animated(a, L->gltf_light);
}

static pg_result find_moving_lights(const pg_scene *scene, pg_scene_gpu_anim *ga, pg_error *err)
{
    const pg_scene_anim *a = scene->anim;
    uint8_t *moving = moving_nodes(a);
    if (!moving) return pg_fail(err, PG_ERR_OOM, "out of memory");
    for (uint32_t i = 0; i < scene->n_lights; i++) ga->n_moving_lights += light_moves(a, moving, &scene->lights[i]);
    if (ga->n_moving_lights) {
        ga->moving_light = calloc(ga->n_moving_lights, sizeof *ga->moving_light);
        ga->moving_rest = calloc(ga->n_moving_lights, sizeof *ga->moving_rest);
        if (!ga->moving_light || !ga->moving_rest) {
            free(moving);
            return pg_fail(err, PG_ERR_OOM, "out of memory");
        }
        uint32_t k = 0;
        for (uint32_t i = 0; i < scene->n_lights; i++) {
            if (!light_moves(a, moving, &scene->lights[i])) continue;
            ga->moving_light[k] = i;
            ga->moving_rest[k++] = scene->lights[i];
        }
    }
    free(moving);
    return PG_OK;
}

static pg_result find_moving_materials(const pg_scene *scene, pg_scene_gpu_anim *ga, pg_error *err)
{
    const pg_scene_anim *a = scene->anim;
    for (uint32_t m = 0; m < scene->n_materials && m < a->n_materials; m++)
        ga->n_moving_materials += pg_anim_material_animated(a, (int)m);
    if (!ga->n_moving_materials) return PG_OK;
    ga->moving_material = calloc(ga->n_moving_materials, sizeof *ga->moving_material);
    ga->moving_mat_rest = calloc(ga->n_moving_materials, sizeof *ga->moving_mat_rest);
    if (!ga->moving_material || !ga->moving_mat_rest) return pg_fail(err, PG_ERR_OOM, "out of memory");
    uint32_t k = 0;
    for (uint32_t m = 0; m < scene->n_materials && m < a->n_materials; m++) {
        if (!pg_anim_material_animated(a, (int)m)) continue;
        ga->moving_material[k] = m;
        ga->moving_mat_rest[k++] = scene->materials[m];
    }
    return PG_OK;
}

/* a scene table's earlier reads (by `readers`) before the transfer writes that rewrite its records */
static void before_update(VkCommandBuffer cmd, VkBuffer table, VkPipelineStageFlags2 readers)
{
    VkBufferMemoryBarrier2 b = pg_buffer_barrier(table, readers, VK_ACCESS_2_SHADER_STORAGE_READ_BIT,
                                                 VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    pg_cmd_barriers(cmd, 0, NULL, 1, &b);
}

bool pg_scene_gpu_anim_update_materials(const pg_scene_gpu_anim *ga, VkBuffer table, int animation, double time,
                                        VkCommandBuffer cmd)
{
    if (!ga || !ga->n_moving_materials || !table) return false;
    const pg_anim_pose *pose = pg_scene_gpu_anim_pose(ga, animation, time);
    before_update(cmd, table, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT); /* every pass may read materials */
    for (uint32_t k = 0; k < ga->n_moving_materials; k++) {
        pg_material M = ga->moving_mat_rest[k];
        pg_anim_material_props(ga->anim, pose, (int)ga->moving_material[k], &M);
        pg_gpu_material rec;
        pg_gpu_material_from(&M, &rec);
        vkCmdUpdateBuffer(cmd, table, (VkDeviceSize)ga->moving_material[k] * sizeof rec, sizeof rec, &rec);
    }
    return true;
}

const pg_anim_pose *pg_scene_gpu_anim_pose(const pg_scene_gpu_anim *ga, int animation, double time)
{
    pg_scene_gpu_anim_now *now = ga->now;
    if (!now->valid || now->animation != animation || now->time != time) {
        pg_anim_pose_eval(ga->anim, animation, time, &now->pose);
        now->animation = animation;
        now->time = time;
        now->valid = true;
        now->evaluations++;
    }
    return &now->pose;
}

void pg_scene_gpu_anim_update_lights(const pg_scene_gpu_anim *ga, VkBuffer table, int animation, double time,
                                     VkCommandBuffer cmd)
{
    if (!ga || !ga->n_moving_lights || !table) return;
    const pg_anim_pose *pose = pg_scene_gpu_anim_pose(ga, animation, time);
    before_update(cmd, table, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT); /* light_animate's earlier reads */
    for (uint32_t k = 0; k < ga->n_moving_lights; k++) {
        pg_scene_light L = ga->moving_rest[k];
        double m[16];
        pg_mat4_widen(pose->node_world + (size_t)L.gltf_node * 16, m);
        pg_place_light(m, &L);
        pg_anim_light_props(ga->anim, pose, &L); /* KHR_animation_pointer: colour, intensity, range, cones */
        pg_gpu_file_light rec;
        pg_gpu_file_light_from(&L, &rec);
        vkCmdUpdateBuffer(cmd, table, (VkDeviceSize)ga->moving_light[k] * sizeof rec, sizeof rec, &rec);
    }
    VkBufferMemoryBarrier2 b = pg_buffer_barrier(table, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                                 VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                                 VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    pg_cmd_barriers(cmd, 0, NULL, 1, &b);
}

pg_result pg_scene_gpu_anim_create(pg_gpu *gpu, const pg_scene *scene, pg_scene_gpu_anim **out, pg_error *err)
{
    *out = NULL;
    const pg_scene_anim *a = scene->anim;
    if (!a) return PG_OK;
    if (a->n_vertices != scene->n_vertices)
        return pg_fail(err, PG_ERR_INVALID_ARG, "scene '%s': animation data for %u vertices, the scene has %u",
                       scene->name, a->n_vertices, scene->n_vertices);
    pg_scene_gpu_anim *ga = calloc(1, sizeof *ga);
    if (!ga) return pg_fail(err, PG_ERR_OOM, "out of memory");
    ga->anim = a;
    ga->n_vertices = a->n_vertices;
    ga->joint_base = a->n_nodes * 16;
    ga->weight_base = ga->joint_base + a->n_joint_slots * 16;
    ga->pose_floats = ga->weight_base + a->n_weights;
    const bool geometry = scene->features.has_animation; /* else only lights move: no vertex buffers */
    ga->info_stride = a->influences > 4 ? 64u : 32u;
    void *info = geometry ? vertex_info(a, ga->info_stride) : NULL, *prims = geometry ? prim_table(a) : NULL;
    pg_result r = PG_OK;
    if (geometry && (!info || !prims)) r = pg_fail(err, PG_ERR_OOM, "out of memory");
    if (!r && geometry) r = upload(gpu, a->local, (VkDeviceSize)a->n_vertices * sizeof(pg_vertex), 0, "scene.anim.local", &ga->local, err);
    if (!r && geometry)
        r = upload(gpu, info, (VkDeviceSize)a->n_vertices * ga->info_stride, 0, "scene.anim.info", &ga->info, err);
    if (!r && geometry) r = upload(gpu, prims, (VkDeviceSize)a->n_prims * 32, 0, "scene.anim.prims", &ga->prims, err);
    if (!r && geometry)
        r = upload(gpu, a->deltas, (VkDeviceSize)a->n_deltas * sizeof(pg_anim_delta), 0, "scene.anim.deltas",
                   &ga->deltas, err);
    if (!r && geometry)
        r = upload(gpu, NULL, ((VkDeviceSize)ga->pose_floats * 4 + 15) & ~(VkDeviceSize)15, 0, "scene.anim.pose",
                   &ga->pose, err);
    free(info);
    free(prims);
    if (!r) r = find_moving_lights(scene, ga, err);
    if (!r) r = find_moving_materials(scene, ga, err);
    if (!r && !(ga->now = calloc(1, sizeof *ga->now))) r = pg_fail(err, PG_ERR_OOM, "out of memory");
    if (!r) r = pg_anim_pose_alloc(a, &ga->now->pose, err);
    if (!r && geometry) r = prim_centres(a, ga, err);
    if (r) {
        pg_scene_gpu_anim_destroy(gpu, ga);
        return r;
    }
    *out = ga;
    return PG_OK;
}

void pg_scene_gpu_anim_destroy(pg_gpu *gpu, pg_scene_gpu_anim *ga)
{
    if (!ga) return;
    pg_buffer_destroy(gpu, &ga->local);
    pg_buffer_destroy(gpu, &ga->info);
    pg_buffer_destroy(gpu, &ga->prims);
    pg_buffer_destroy(gpu, &ga->deltas);
    pg_buffer_destroy(gpu, &ga->pose);
    free(ga->moving_light);
    free(ga->moving_rest);
    free(ga->moving_material);
    free(ga->moving_mat_rest);
    if (ga->now) pg_anim_pose_release(&ga->now->pose);
    free(ga->now);
    free(ga->centres);
    free(ga->morph_shift);
    free(ga);
}

void pg_scene_gpu_anim_pack_pose(const pg_scene_gpu_anim *ga, int animation, double time, float *out)
{
    const pg_scene_anim *a = ga->anim;
    const pg_anim_pose *pose = pg_scene_gpu_anim_pose(ga, animation, time);
    memcpy(out, pose->node_world, (size_t)a->n_nodes * 16 * sizeof(float));
    memcpy(out + ga->joint_base, pose->joints, (size_t)a->n_joint_slots * 16 * sizeof(float));
    if (a->n_weights) memcpy(out + ga->weight_base, pose->weights, (size_t)a->n_weights * sizeof(float));
}
