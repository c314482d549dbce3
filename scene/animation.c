/* animation.c - glTF animation on the CPU (animation.h): channel sampling, node hierarchy, joint
 * matrices, the deformed vertices, and the scene posed at a time. */
#include "animation.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void pg_scene_anim_free(pg_scene_anim *a)
{
    if (!a) return;
    for (uint32_t i = 0; i < a->n_skins; i++) {
        free(a->skins[i].joints);
        free(a->skins[i].inverse_bind);
    }
    for (uint32_t i = 0; i < a->n_animations; i++) {
        for (uint32_t c = 0; c < a->animations[i].n_channels; c++) {
            free(a->animations[i].channels[c].times);
            free(a->animations[i].channels[c].values);
        }
        free(a->animations[i].channels);
    }
    free(a->nodes);
    free(a->skins);
    free(a->animations);
    free(a->prims);
    free(a->rest_weights);
    free(a->local);
    free(a->vertex_prim);
    free(a->joints);
    free(a->weights);
    free(a->deltas);
    free(a->light_animated);
    free(a->light_rest);
    free(a->camera_animated);
    free(a->camera_rest);
    free(a->material_animated);
    free(a->material_rest);
    free(a);
}

pg_result pg_anim_pose_alloc(const pg_scene_anim *a, pg_anim_pose *out, pg_error *err)
{
    memset(out, 0, sizeof *out);
    out->node_world = calloc((size_t)a->n_nodes * 16 + 16, sizeof(float));
    out->joints = calloc((size_t)a->n_joint_slots * 16 + 16, sizeof(float));
    out->weights = calloc((size_t)a->n_weights + 1, sizeof(float));
    out->lights = calloc((size_t)a->n_lights + 1, sizeof *out->lights);
    out->cameras = calloc((size_t)a->n_cameras + 1, sizeof *out->cameras);
    out->materials = calloc((a->n_animated_materials ? (size_t)a->n_materials : 0) + 1, sizeof *out->materials);
    const size_t nn = (size_t)a->n_nodes + 1;
    out->work.t = malloc(sizeof *out->work.t * nn);
    out->work.r = malloc(sizeof *out->work.r * nn);
    out->work.s = malloc(sizeof *out->work.s * nn);
    out->work.local = malloc(sizeof(float) * 16 * nn);
    out->work.stack = malloc(sizeof(uint32_t) * nn);
    out->work.done = malloc(nn);
    if (!out->node_world || !out->joints || !out->weights || !out->lights || !out->cameras || !out->materials ||
        !out->work.t ||
        !out->work.r || !out->work.s || !out->work.local || !out->work.stack || !out->work.done) {
        pg_anim_pose_release(out);
        return pg_fail(err, PG_ERR_OOM, "animation pose: out of memory");
    }
    return PG_OK;
}

void pg_anim_pose_release(pg_anim_pose *p)
{
    free(p->node_world);
    free(p->joints);
    free(p->weights);
    free(p->lights);
    free(p->cameras);
    free(p->materials);
    free(p->work.t);
    free(p->work.r);
    free(p->work.s);
    free(p->work.local);
    free(p->work.stack);
    free(p->work.done);
    memset(p, 0, sizeof *p);
}

/* ---- sampling ---- */

static void quat_normalize(float q[4])
{
    const double l = sqrt((double)q[0] * q[0] + (double)q[1] * q[1] + (double)q[2] * q[2] + (double)q[3] * q[3]);
    if (!(l > 1e-30)) {
        q[0] = q[1] = q[2] = 0;
        q[3] = 1;
        return;
    }
    for (int k = 0; k < 4; k++) q[k] = (float)(q[k] / l);
}

/* spherical linear interpolation along the shorter arc */
static void quat_slerp(const float *a, const float *b, double t, float out[4])
{
    double d = 0;
    for (int k = 0; k < 4; k++) d += (double)a[k] * b[k];
    const double s = d < 0 ? -1.0 : 1.0;
    d = fabs(d);
    double wa, wb;
    if (d > 0.9995) { /* nearly parallel: linear, normalised below */
        wa = 1 - t;
        wb = t;
    } else {
        const double th = acos(d), sn = sin(th);
        wa = sin((1 - t) * th) / sn;
        wb = sin(t * th) / sn;
    }
    for (int k = 0; k < 4; k++) out[k] = (float)(wa * a[k] + wb * s * b[k]);
    quat_normalize(out);
}

/* The channel's value at time t into out[width]. */
static void channel_sample(const pg_anim_channel *ch, double t, float *out)
{
    const uint32_t w = ch->width, n = ch->n_keys;
    const bool cubic = ch->interp == PG_INTERP_CUBICSPLINE;
    const uint32_t stride = cubic ? 3 * w : w, voff = cubic ? w : 0; /* the value within a key */
    if (n == 1 || t <= ch->times[0]) {
        memcpy(out, ch->values + voff, w * sizeof(float));
        return;
    }
    if (t >= ch->times[n - 1]) {
        memcpy(out, ch->values + (size_t)(n - 1) * stride + voff, w * sizeof(float));
        return;
    }
    uint32_t lo = 0, hi = n - 1; /* times[lo] <= t < times[hi] */
    while (hi - lo > 1) {
        const uint32_t mid = lo + (hi - lo) / 2;
        if (ch->times[mid] <= t) lo = mid;
        else hi = mid;
    }
    const double t0 = ch->times[lo], t1 = ch->times[hi], dt = t1 - t0;
    const double u = dt > 0 ? (t - t0) / dt : 0;
    const float *k0 = ch->values + (size_t)lo * stride, *k1 = ch->values + (size_t)hi * stride;
    if (ch->interp == PG_INTERP_STEP) {
        memcpy(out, k0, w * sizeof(float));
        return;
    }
    if (!cubic) {
        if (ch->path == PG_ANIM_ROTATION) {
            quat_slerp(k0, k1, u, out);
            return;
        }
        for (uint32_t k = 0; k < w; k++) out[k] = (float)((1 - u) * k0[k] + u * k1[k]);
        return;
    }
    /* Hermite: v0 = k0[w..2w), b0 = k0[2w..3w) (out-tangent), a1 = k1[0..w) (in-tangent), v1 */
    const double u2 = u * u, u3 = u2 * u;
    const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
    for (uint32_t k = 0; k < w; k++)
        out[k] = (float)(h00 * k0[w + k] + h10 * dt * k0[2 * w + k] + h01 * k1[w + k] + h11 * dt * k1[k]);
    if (ch->path == PG_ANIM_ROTATION) quat_normalize(out);
}

/* ---- matrices (column-major, m[c*4 + r]) ---- */

static void trs_matrix(const float t[3], const float q[4], const float s[3], float m[16])
{
    const double x = q[0], y = q[1], z = q[2], w = q[3];
    const double R[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),
                         2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                         2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y)};
    for (int c = 0; c < 3; c++) {
        for (int r = 0; r < 3; r++) m[c * 4 + r] = (float)(R[c * 3 + r] * s[c]);
        m[c * 4 + 3] = 0;
    }
    m[12] = t[0];
    m[13] = t[1];
    m[14] = t[2];
    m[15] = 1;
}

double pg_anim_local_time(const pg_scene_anim *a, int animation, double time)
{
    double end = 0;
    if (animation == PG_ANIM_ALL) {
        for (uint32_t i = 0; i < a->n_animations; i++)
            if (a->animations[i].end > end) end = a->animations[i].end;
    } else if (animation >= 0 && (uint32_t)animation < a->n_animations) {
        end = a->animations[animation].end;
    }
    if (!(end > 0) || !isfinite(time)) return 0;
    double t = fmod(time, end) + 0.0; /* + 0.0: -0 (a negative whole number of loops) becomes 0 */
    if (t < 0) t += end;
    if (time > 0 && t == 0) t = end; /* t = end plays the last key, not the first */
    return t;
}

/* offset of a light channel's value in a pose's light properties, -1 for a node channel */
static int light_prop_offset(pg_anim_path p)
{
    switch (p) {
    case PG_ANIM_LIGHT_COLOR: return 0;
    case PG_ANIM_LIGHT_INTENSITY: return 3;
    case PG_ANIM_LIGHT_RANGE: return 4;
    case PG_ANIM_SPOT_INNER: return 5;
    case PG_ANIM_SPOT_OUTER: return 6;
    default: return -1;
    }
}

/* apply one animation's channels at t to the local TRS arrays and the pose's weights, light
 * properties and camera projections */
static void apply_animation(const pg_scene_anim *a, const pg_animation *an, double t, float (*T)[3], float (*R)[4],
                            float (*S)[3], const pg_anim_pose *pose)
{
    float v[4];
    for (uint32_t c = 0; c < an->n_channels; c++) {
        const pg_anim_channel *ch = &an->channels[c];
        const int lo = light_prop_offset(ch->path);
        if (lo >= 0) { /* the loader made width 3 for the colour, 1 for the rest */
            if (ch->node < a->n_lights && ch->width == (lo == 0 ? 3u : 1u)) {
                channel_sample(ch, t, v);
                memcpy(&pose->lights[ch->node][lo], v, ch->width * sizeof(float));
            }
            continue;
        }
        uint32_t mw = 0;
        const int mo = pg_anim_material_offset(ch->path, &mw);
        if (mo >= 0) { /* the loader made the width pg_anim_material_offset's */
            if (ch->node < a->n_materials && a->n_animated_materials && ch->width == mw) {
                channel_sample(ch, t, v);
                memcpy(&pose->materials[ch->node][mo], v, mw * sizeof(float));
            }
            continue;
        }
        if (ch->path >= PG_ANIM_CAM_YFOV && ch->path <= PG_ANIM_CAM_ZFAR) { /* width 1 */
            if (ch->node < a->n_cameras && ch->width == 1) {
                channel_sample(ch, t, v);
                pose->cameras[ch->node][ch->path - PG_ANIM_CAM_YFOV] = v[0];
            }
            continue;
        }
        if (ch->node >= a->n_nodes) continue;
        if (ch->path == PG_ANIM_WEIGHTS) { /* the loader made width the node's weight count */
            const pg_anim_node *nd = &a->nodes[ch->node];
            if (ch->width == nd->n_weights && nd->n_weights) channel_sample(ch, t, pose->weights + nd->weight_base);
            continue;
        }
        if (ch->width > 4) continue;
        channel_sample(ch, t, v);
        if (ch->path == PG_ANIM_TRANSLATION) memcpy(T[ch->node], v, 3 * sizeof(float));
        else if (ch->path == PG_ANIM_ROTATION) memcpy(R[ch->node], v, 4 * sizeof(float));
        else memcpy(S[ch->node], v, 3 * sizeof(float));
    }
}

/* world matrices of every node, parents before children (stack: n_nodes scratch entries, done:
 * n_nodes flags; the loader refused cycles and gave each node at most one parent) */
static void node_worlds(const pg_scene_anim *a, const float *local, float *world, uint32_t *stack, uint8_t *done)
{
    memset(done, 0, a->n_nodes);
    for (uint32_t i = 0; i < a->n_nodes; i++) {
        uint32_t n = 0, cur = i;
        while (!done[cur] && n < a->n_nodes) { /* the unresolved ancestors, nearest first */
            stack[n++] = cur;
            const int32_t p = a->nodes[cur].parent;
            if (p < 0) break;
            cur = (uint32_t)p;
        }
        while (n > 0) {
            const uint32_t k = stack[--n];
            const int32_t p = a->nodes[k].parent;
            if (p < 0 || !done[p]) memcpy(world + (size_t)k * 16, local + (size_t)k * 16, 16 * sizeof(float));
            else pg_mat4_mul(world + (size_t)p * 16, local + (size_t)k * 16, world + (size_t)k * 16);
            done[k] = 1;
        }
    }
}

void pg_anim_pose_eval(const pg_scene_anim *a, int animation, double time, pg_anim_pose *pose)
{
    const uint32_t nn = a->n_nodes;
    float(*T)[3] = pose->work.t, (*R)[4] = pose->work.r, (*S)[3] = pose->work.s;
    float *local = pose->work.local;
    for (uint32_t i = 0; i < nn; i++) {
        memcpy(T[i], a->nodes[i].translation, sizeof T[i]);
        memcpy(R[i], a->nodes[i].rotation, sizeof R[i]);
        memcpy(S[i], a->nodes[i].scale, sizeof S[i]);
    }
    if (a->n_weights) memcpy(pose->weights, a->rest_weights, a->n_weights * sizeof(float));
    if (a->n_lights) memcpy(pose->lights, a->light_rest, a->n_lights * sizeof *pose->lights);
    if (a->n_cameras) memcpy(pose->cameras, a->camera_rest, a->n_cameras * sizeof *pose->cameras);
    for (uint32_t m = 0; a->n_animated_materials && m < a->n_materials; m++)
        if (a->material_animated[m]) memcpy(pose->materials[m], a->material_rest[m], sizeof *pose->materials);
    const double t = pg_anim_local_time(a, animation, time);
    if (animation == PG_ANIM_ALL) {
        for (uint32_t k = 0; k < a->n_animations; k++) apply_animation(a, &a->animations[k], t, T, R, S, pose);
    } else if (animation >= 0 && (uint32_t)animation < a->n_animations) {
        apply_animation(a, &a->animations[animation], t, T, R, S, pose);
    }
    for (uint32_t i = 0; i < nn; i++) {
        if (a->nodes[i].has_matrix) memcpy(local + (size_t)i * 16, a->nodes[i].matrix, 16 * sizeof(float));
        else trs_matrix(T[i], R[i], S[i], local + (size_t)i * 16);
    }
    node_worlds(a, local, pose->node_world, pose->work.stack, pose->work.done);
    for (uint32_t s = 0; s < a->n_skins; s++) {
        const pg_anim_skin *sk = &a->skins[s];
        for (uint32_t j = 0; j < sk->n_joints; j++) {
            float *out = pose->joints + (size_t)(sk->slot_base + j) * 16;
            const uint32_t node = sk->joints[j];
            if (node < nn) pg_mat4_mul(pose->node_world + (size_t)node * 16, sk->inverse_bind[j], out);
            else memcpy(out, sk->inverse_bind[j], 16 * sizeof(float));
        }
    }
}

/* ---- light properties (KHR_animation_pointer) ---- */

bool pg_anim_light_animated(const pg_scene_anim *a, int gltf_light)
{
    return a && gltf_light >= 0 && (uint32_t)gltf_light < a->n_lights && a->light_animated[gltf_light];
}

static float clampf_(float x, float lo, float hi)
{
    return x >= lo ? (x <= hi ? x : hi) : lo; /* NaN -> lo */
}

bool pg_anim_light_props(const pg_scene_anim *a, const pg_anim_pose *pose, pg_scene_light *L)
{
    if (!pg_anim_light_animated(a, L->gltf_light)) return false;
    const float *p = pose->lights[L->gltf_light];
    for (int k = 0; k < 3; k++) L->color[k] = clampf_(p[k], 0.0f, 3.4e38f);
    L->intensity = clampf_(p[3], 0.0f, 1e30f);
    if (L->type != PG_LIGHT_DIRECTIONAL) /* a range that reaches 0 stays a tiny one, not "none given" */
        L->range = a->light_rest[L->gltf_light][4] > 0 || p[4] != a->light_rest[L->gltf_light][4]
                       ? clampf_(p[4], 1e-6f, 1e30f)
                       : 0.0f;
    if (L->type == PG_LIGHT_SPOT) {
        const float outer = clampf_(p[6], 1e-6f, 1.5707963f);
        L->outer_cone = outer;
        L->inner_cone = fminf(clampf_(p[5], 0.0f, outer), outer * (1.0f - 1e-6f));
    }
    return true;
}

bool pg_anim_camera_animated(const pg_scene_anim *a, int gltf_camera)
{
    return a && gltf_camera >= 0 && (uint32_t)gltf_camera < a->n_cameras && a->camera_animated[gltf_camera];
}

/* ---- material properties (KHR_animation_pointer) ---- */

int pg_anim_material_offset(pg_anim_path p, uint32_t *width)
{
    static const struct { int8_t offset, width; } fixed[] = {
        {0, 4}, {4, 1}, {5, 1}, {6, 3}, {9, 1}, {10, 1}, {11, 1}, {12, 1}}; /* PG_ANIM_MAT_BASE_COLOR .. _OCCLUSION_STRENGTH */
    *width = 0;
    if (p < PG_ANIM_MAT_BASE_COLOR || p > PG_ANIM_MAT_LAST) return -1;
    if (p < PG_ANIM_MAT_UV) {
        *width = (uint32_t)fixed[p - PG_ANIM_MAT_BASE_COLOR].width;
        return fixed[p - PG_ANIM_MAT_BASE_COLOR].offset;
    }
    const int slot = (p - PG_ANIM_MAT_UV) / 3, k = (p - PG_ANIM_MAT_UV) % 3; /* offset, rotation, scale */
    *width = k == 1 ? 1u : 2u;
    return PG_ANIM_MAT_UV_BASE + 5 * slot + (k == 0 ? 0 : k == 1 ? 2 : 3);
}

bool pg_anim_material_animated(const pg_scene_anim *a, int gltf_material)
{
    return a && gltf_material >= 0 && (uint32_t)gltf_material < a->n_materials && a->material_animated[gltf_material];
}

static bool mat_bit(uint32_t bits, pg_anim_path p)
{
    return (bits >> (p - PG_ANIM_MAT_BASE_COLOR)) & 1u;
}

/* finite and >= 0 (NaN -> 0) */
static float nonneg_(float x)
{
    return clampf_(x, 0.0f, 3.4e38f);
}

bool pg_anim_material_props(const pg_scene_anim *a, const pg_anim_pose *pose, int gltf_material, pg_material *M)
{
    if (!pg_anim_material_animated(a, gltf_material)) return false;
    const uint32_t bits = a->material_animated[gltf_material];
    const float *p = pose->materials[gltf_material];
    if (mat_bit(bits, PG_ANIM_MAT_BASE_COLOR))
        for (int k = 0; k < 4; k++) M->base_color[k] = clampf_(p[k], 0.0f, 1.0f);
    if (mat_bit(bits, PG_ANIM_MAT_METALLIC) || mat_bit(bits, PG_ANIM_MAT_ROUGHNESS)) {
        M->metallic = clampf_(p[4], 0.0f, 1.0f);
        M->roughness = clampf_(p[5], 0.0f, 1.0f);
        pg_material_specular_from(M->metallic, M->roughness, &M->specular, &M->shininess);
    }
    if (mat_bit(bits, PG_ANIM_MAT_EMISSIVE) || mat_bit(bits, PG_ANIM_MAT_EMISSIVE_STRENGTH))
        for (int k = 0; k < 3; k++) M->emissive[k] = (float)fmin((double)nonneg_(p[6 + k]) * nonneg_(p[9]), 3.4e38);
    if (mat_bit(bits, PG_ANIM_MAT_ALPHA_CUTOFF)) M->alpha_cutoff = nonneg_(p[10]);
    if (mat_bit(bits, PG_ANIM_MAT_NORMAL_SCALE)) M->normal_scale = clampf_(p[11], -3.4e38f, 3.4e38f);
    if (mat_bit(bits, PG_ANIM_MAT_OCCLUSION_STRENGTH)) M->occlusion_strength = clampf_(p[12], 0.0f, 1.0f);
    for (int sl = 0; sl < PG_TEXSLOT_COUNT; sl++) {
        const pg_anim_path first = (pg_anim_path)(PG_ANIM_MAT_UV + 3 * sl);
        if (!mat_bit(bits, first) && !mat_bit(bits, first + 1) && !mat_bit(bits, first + 2)) continue;
        const float *u = p + PG_ANIM_MAT_UV_BASE + 5 * sl;
        const double off[2] = {clampf_(u[0], -1e30f, 1e30f), clampf_(u[1], -1e30f, 1e30f)};
        const double sc[2] = {clampf_(u[3], -1e30f, 1e30f), clampf_(u[4], -1e30f, 1e30f)};
        pg_material_uv_transform(off, clampf_(u[2], -1e30f, 1e30f), sc, M->uv_transform[sl]);
        M->has_uv_transform[sl] = true;
    }
    return true;
}

/* x kept at least `lo` away from 0, its sign kept (NaN -> lo) */
static float away_from_0(float x, float lo)
{
    return x <= -lo ? fmaxf(x, -3.4e38f) : x >= lo ? fminf(x, 3.4e38f) : lo;
}

bool pg_anim_camera_props(const pg_scene_anim *a, const pg_anim_pose *pose, pg_scene_camera *C)
{
    if (!pg_anim_camera_animated(a, C->gltf_camera)) return false;
    const float *p = pose->cameras[C->gltf_camera];
    if (C->type == PG_CAMERA_PERSPECTIVE) {
        C->yfov_rad = clampf_(p[0], 1e-4f, 3.1415f);
        C->aspect_ratio = clampf_(p[1], 0.0f, 1e6f);
        C->znear = clampf_(p[4], 1e-6f, 1e30f);
    } else {
        C->xmag = away_from_0(fabsf(p[2]), 1e-6f); /* the magnitude, as the loader takes a static one */
        C->ymag = away_from_0(fabsf(p[3]), 1e-6f);
        C->znear = clampf_(p[4], 0.0f, 1e30f);
    }
    const bool infinite = C->type == PG_CAMERA_PERSPECTIVE && p[5] == 0;
    C->zfar = infinite ? 0.0f : fmaxf(clampf_(p[5], 0.0f, 3.4e38f), C->znear * (1.0f + 1e-3f) + 1e-6f);
    return true;
}

/* ---- deformation ---- */

static void xform_vertex(const float m[16], const float p[3], const float nrm[3], const float tan[4],
                         pg_vertex *o)
{
    for (int r = 0; r < 3; r++) o->position[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
    const float a00 = m[0], a01 = m[4], a02 = m[8], a10 = m[1], a11 = m[5], a12 = m[9], a20 = m[2], a21 = m[6],
                a22 = m[10];
    const float cof[9] = {a11 * a22 - a12 * a21, a12 * a20 - a10 * a22, a10 * a21 - a11 * a20,
                          a02 * a21 - a01 * a22, a00 * a22 - a02 * a20, a01 * a20 - a00 * a21,
                          a01 * a12 - a02 * a11, a02 * a10 - a00 * a12, a00 * a11 - a01 * a10};
    const float det = a00 * cof[0] + a01 * cof[1] + a02 * cof[2];
    const float sg = det < 0 ? -1.0f : 1.0f;
    float n[3], t[3];
    for (int r = 0; r < 3; r++) {
        n[r] = sg * (cof[r * 3 + 0] * nrm[0] + cof[r * 3 + 1] * nrm[1] + cof[r * 3 + 2] * nrm[2]);
        t[r] = m[r] * tan[0] + m[4 + r] * tan[1] + m[8 + r] * tan[2];
    }
    const float nl = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const float tl = sqrtf(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    for (int r = 0; r < 3; r++) {
        o->normal[r] = nl > 1e-30f ? n[r] / nl : (r == 1 ? 1.0f : 0.0f);
        o->tangent[r] = tl > 1e-30f ? t[r] / tl : 0.0f;
    }
    o->tangent[3] = tan[3] * sg;
}

void pg_anim_deform(const pg_scene_anim *a, const pg_anim_pose *pose, pg_vertex *out)
{
    for (uint32_t v = 0; v < a->n_vertices; v++) {
        const pg_vertex *L = &a->local[v];
        const uint32_t pi = a->vertex_prim[v];
        if (pi == PG_ANIM_STATIC || pi >= a->n_prims) {
            out[v] = *L;
            continue;
        }
        const pg_anim_prim *pr = &a->prims[pi];
        float p[3], n[3], t[4];
        memcpy(p, L->position, sizeof p);
        memcpy(n, L->normal, sizeof n);
        memcpy(t, L->tangent, sizeof t);
        const uint32_t i = v - pr->first_vertex;
        for (uint32_t k = 0; k < pr->n_targets; k++) {
            const float w = pose->weights[pr->weight_base + k];
            if (w == 0.0f) continue;
            const pg_anim_delta *d = &a->deltas[pr->target_base + k * pr->n_vertices + i];
            for (int r = 0; r < 3; r++) {
                p[r] += w * d->position[r];
                n[r] += w * d->normal[r];
                t[r] += w * d->tangent[r];
            }
        }
        float m[16];
        if (pr->skin >= 0 && a->joints) {
            memset(m, 0, sizeof m);
            for (int k = 0; k < PG_ANIM_MAX_INFLUENCES; k++) {
                const float w = a->weights[v][k];
                if (w == 0.0f) continue;
                const float *J = pose->joints + (size_t)a->joints[v][k] * 16;
                for (int e = 0; e < 16; e++) m[e] += w * J[e];
            }
        } else {
            memcpy(m, pose->node_world + (size_t)pr->node * 16, sizeof m);
        }
        out[v] = *L;
        xform_vertex(m, p, n, t, &out[v]);
    }
}

bool pg_anim_prim_mirrored(const pg_scene_anim *a, const pg_anim_pose *pose, uint32_t prim)
{
    if (!a || prim >= a->n_prims || a->prims[prim].skin >= 0 || a->prims[prim].node >= a->n_nodes) return false;
    const float *m = pose->node_world + (size_t)a->prims[prim].node * 16;
    const double det = (double)m[0] * ((double)m[5] * m[10] - (double)m[9] * m[6]) -
                       (double)m[4] * ((double)m[1] * m[10] - (double)m[9] * m[2]) +
                       (double)m[8] * ((double)m[1] * m[6] - (double)m[5] * m[2]);
    return det < 0;
}

/* ---- choosing, describing, posing a scene ---- */

pg_result pg_anim_find(const pg_scene_anim *a, const char *spec, int *out, pg_error *err)
{
    if (!strcmp(spec, "none")) return *out = PG_ANIM_NONE, PG_OK;
    if (!strcmp(spec, "all")) return *out = PG_ANIM_ALL, PG_OK;
    const uint32_t n = a ? a->n_animations : 0;
    char *end = NULL;
    const long k = strtol(spec, &end, 10);
    if (end && end != spec && *end == 0 && k >= 0 && (unsigned long)k < n) return *out = (int)k, PG_OK;
    for (uint32_t i = 0; i < n; i++)
        if (!strcmp(a->animations[i].name, spec)) return *out = (int)i, PG_OK;
    char list[512] = "";
    size_t len = 0;
    for (uint32_t i = 0; i < n && len + 64 < sizeof list; i++)
        len += (size_t)snprintf(list + len, sizeof list - len, "%s%u '%s'", i ? ", " : "", i, a->animations[i].name);
    if (!n)
        return pg_fail(err, PG_ERR_INVALID_ARG, "--animation %s: the scene has no animations; use none", spec);
    return pg_fail(err, PG_ERR_INVALID_ARG, "--animation %s: no such animation; available: %s%s, all or none", spec,
                   list, n > 8 ? ", ..." : "");
}

bool pg_anim_describe(const pg_scene *scene, int animation, double time, char *buf, size_t size)
{
    const pg_scene_anim *a = scene ? scene->anim : NULL;
    if (!a || !size) {
        if (size) buf[0] = 0;
        return false;
    }
    uint32_t targets = 0;
    for (uint32_t i = 0; i < a->n_prims; i++) targets += a->prims[i].n_targets;
    char what[160];
    if (animation >= 0 && (uint32_t)animation < a->n_animations)
        snprintf(what, sizeof what, "animation %d '%s' of %u (%.3g s loop) at t = %.3g s", animation,
                 a->animations[animation].name, a->n_animations, (double)a->animations[animation].end,
                 pg_anim_local_time(a, animation, time));
    else if (animation == PG_ANIM_ALL && a->n_animations)
        snprintf(what, sizeof what, "all %u animations at t = %.3g s", a->n_animations,
                 pg_anim_local_time(a, animation, time));
    else
        snprintf(what, sizeof what, "the rest pose (%s)", a->n_animations ? "--animation none" : "no animations");
    int n = snprintf(buf, size, "%s; %u skin%s (%u joints), %u morph target%s on %u deformed primitive%s", what,
                     a->n_skins, a->n_skins == 1 ? "" : "s", a->n_joint_slots, targets, targets == 1 ? "" : "s",
                     a->n_prims, a->n_prims == 1 ? "" : "s");
    if (a->n_animated_materials && n > 0 && (size_t)n < size)
        snprintf(buf + n, size - (size_t)n, "; %u material%s animated (KHR_animation_pointer)", a->n_animated_materials,
                 a->n_animated_materials == 1 ? "" : "s");
    return true;
}
