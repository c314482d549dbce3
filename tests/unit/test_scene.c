/* test_scene.c - the CPU scene: default scene, textures and mips, camera math, Sponza (when the
 * shared asset is present; set PG_TEST_NO_SPONZA=1 to skip it, e.g. under valgrind), scenarios,
 * and the glTF robustness corpus (tests/corpus/gltf/MANIFEST). No GPU. */
#include "scenario.h"
#include "scene.h"
#include "test_util.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#ifndef PG_TEST_DIR
#define PG_TEST_DIR "tests"
#endif
#ifndef PG_SHARED_DIR
#define PG_SHARED_DIR "../shared"
#endif

static bool near_f(float a, float b, float eps) { return fabsf(a - b) <= eps; }

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

static float len3(const float *v) { return sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }
static float dot3(const float *a, const float *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void cross3(const float *a, const float *b, float *o)
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

/* ---- shared structural checks ---------------------------------------------------------------- */

typedef struct geo_stats {
    uint32_t bad_index, bad_normal, bad_tangent, tangents, tris, wound_ok, wound_bad, degenerate;
} geo_stats;

static geo_stats scene_geometry_stats(const pg_scene *s)
{
    geo_stats g;
    memset(&g, 0, sizeof g);
    for (uint32_t i = 0; i < s->n_vertices; i++) {
        const pg_vertex *v = &s->vertices[i];
        if (fabsf(len3(v->normal) - 1.0f) > 1e-3f) g.bad_normal++;
        if (v->tangent[0] != 0 || v->tangent[1] != 0 || v->tangent[2] != 0 || v->tangent[3] != 0) {
            g.tangents++;
            if (fabsf(len3(v->tangent) - 1.0f) > 1e-3f || fabsf(dot3(v->tangent, v->normal)) > 1e-3f ||
                fabsf(fabsf(v->tangent[3]) - 1.0f) > 0)
                g.bad_tangent++;
        }
    }
    for (uint32_t p = 0; p < s->n_primitives; p++) {
        const pg_primitive *pr = &s->primitives[p];
        if ((uint64_t)pr->first_index + pr->index_count > s->n_indices || pr->index_count % 3) {
            g.bad_index++;
            continue;
        }
        for (uint32_t t = 0; t < pr->index_count; t += 3) {
            const pg_vertex *v[3];
            bool ok = true;
            for (int k = 0; k < 3; k++) {
                int64_t vi = (int64_t)s->indices[pr->first_index + t + k] + pr->vertex_offset;
                if (vi < 0 || vi >= (int64_t)s->n_vertices) {
                    ok = false;
                    break;
                }
                v[k] = &s->vertices[vi];
            }
            if (!ok) {
                g.bad_index++;
                continue;
            }
            g.tris++;
            float e1[3], e2[3], fn[3], vn[3];
            for (int k = 0; k < 3; k++) {
                e1[k] = v[1]->position[k] - v[0]->position[k];
                e2[k] = v[2]->position[k] - v[0]->position[k];
                vn[k] = v[0]->normal[k] + v[1]->normal[k] + v[2]->normal[k];
            }
            cross3(e1, e2, fn);
            if (len3(fn) < 1e-12f) {
                g.degenerate++;
                continue;
            }
            if (dot3(fn, vn) > 0) g.wound_ok++;
            else g.wound_bad++;
        }
    }
    return g;
}

static void check_texture_chain(const pg_texture *t)
{
    uint32_t w = t->mips[0].width, h = t->mips[0].height, m = w > h ? w : h, n = 1;
    while (m > 1) {
        m >>= 1;
        n++;
    }
    CHECK_MSG(t->n_mips == n, "texture %s: %u mips, expected %u", t->name, t->n_mips, n);
    CHECK_MSG(t->mips[t->n_mips - 1].width == 1 && t->mips[t->n_mips - 1].height == 1,
              "texture %s: last mip not 1x1", t->name);
    size_t off = 0;
    bool ok = true;
    for (uint32_t i = 0; i < t->n_mips; i++) {
        uint32_t ew = w >> i ? w >> i : 1, eh = h >> i ? h >> i : 1;
        if (t->mips[i].width != ew || t->mips[i].height != eh) ok = false;
        if (t->mips[i].rgba != t->data + off) ok = false;
        off += (size_t)ew * eh * 4;
    }
    CHECK_MSG(ok && off == t->data_size, "texture %s: mip layout", t->name);
}

/* ---- default scene --------------------------------------------------------------------------- */

static void test_default_scene(void)
{
    pg_scene *s = NULL, *s2 = NULL;
    pg_error err = {0};
    double t0 = now_s();
    CHECK(pg_scene_create_default(&s, &err) == PG_OK);
    double t1 = now_s();
    if (!s) {
        fprintf(stderr, "default scene: %s\n", err.msg);
        return;
    }
    printf("default scene: %u triangles, %u vertices, %u materials, %u textures, %.3f s\n",
           s->n_indices / 3, s->n_vertices, s->n_materials, s->n_textures, t1 - t0);
    CHECK(strcmp(s->name, "default") == 0);
    CHECK(s->n_indices / 3 >= 30000 && s->n_indices / 3 <= 80000);
    CHECK(s->n_materials >= 5);
    CHECK(s->features.has_textures && s->features.has_normal_maps && s->features.has_alpha_mask);
    CHECK(near_f(s->bounds_min[1], 0.0f, 1e-4f));
    CHECK(s->bounds_max[0] - s->bounds_min[0] > 25 && s->bounds_max[0] - s->bounds_min[0] < 40);
    CHECK(s->bounds_max[1] > 8 && s->bounds_max[1] < 20);
    CHECK(fabsf(s->bounds_min[0] + s->bounds_max[0]) < 1 && fabsf(s->bounds_min[2] + s->bounds_max[2]) < 1);

    geo_stats g = scene_geometry_stats(s);
    CHECK_MSG(g.bad_index == 0, "%u bad indices", g.bad_index);
    CHECK_MSG(g.bad_normal == 0, "%u non-unit normals", g.bad_normal);
    CHECK_MSG(g.tangents > 0 && g.bad_tangent == 0, "%u tangents, %u bad", g.tangents, g.bad_tangent);
    CHECK_MSG(g.wound_bad == 0, "%u triangles wound against their normals", g.wound_bad);
    CHECK(g.tris == s->n_indices / 3);

    bool mask = false, mask_ds = false, normal_tex_linear = true, plain = false;
    uint32_t with_nm = 0;
    for (uint32_t i = 0; i < s->n_materials; i++) {
        const pg_material *m = &s->materials[i];
        if (m->alpha_mode == PG_ALPHA_MASK) {
            mask = true;
            mask_ds = m->double_sided && near_f(m->alpha_cutoff, 0.5f, 1e-6f);
        }
        if (m->base_color_tex < 0) plain = true;
        if (m->normal_tex >= 0) {
            with_nm++;
            CHECK(m->normal_tex < (int)s->n_textures);
            if (s->textures[m->normal_tex].srgb) normal_tex_linear = false;
        }
        if (m->base_color_tex >= 0) {
            CHECK(m->base_color_tex < (int)s->n_textures);
            CHECK(s->textures[m->base_color_tex].srgb);
        }
    }
    CHECK(mask && mask_ds);
    CHECK(plain);
    CHECK(with_nm >= 1 && normal_tex_linear);
    for (uint32_t i = 0; i < s->n_textures; i++) check_texture_chain(&s->textures[i]);
    /* each primitive uses a valid material and has bounds inside the scene's */
    for (uint32_t p = 0; p < s->n_primitives; p++) {
        const pg_primitive *pr = &s->primitives[p];
        CHECK(pr->material < s->n_materials);
        for (int k = 0; k < 3; k++)
            CHECK(pr->bounds_min[k] >= s->bounds_min[k] && pr->bounds_max[k] <= s->bounds_max[k]);
    }

    /* deterministic: a second generation gives identical bytes */
    CHECK(pg_scene_load("default", &s2, &err) == PG_OK);
    if (s2) {
        bool same = s2->n_vertices == s->n_vertices && s2->n_indices == s->n_indices &&
                    s2->n_textures == s->n_textures && s2->n_materials == s->n_materials &&
                    s2->n_primitives == s->n_primitives;
        if (same) {
            same = memcmp(s->vertices, s2->vertices, sizeof(pg_vertex) * s->n_vertices) == 0 &&
                   memcmp(s->indices, s2->indices, sizeof(uint32_t) * s->n_indices) == 0 &&
                   memcmp(s->materials, s2->materials, sizeof(pg_material) * s->n_materials) == 0 &&
                   memcmp(s->primitives, s2->primitives, sizeof(pg_primitive) * s->n_primitives) == 0;
            for (uint32_t i = 0; same && i < s->n_textures; i++)
                same = s->textures[i].data_size == s2->textures[i].data_size &&
                       memcmp(s->textures[i].data, s2->textures[i].data, s->textures[i].data_size) == 0;
        }
        CHECK_MSG(same, "two default scenes differ");
        pg_scene_free(s2);
    }

    /* the default camera stands inside the room and looks along +X */
    pg_camera cam = pg_camera_default_for_scene(s, 16.0f / 9.0f);
    for (int k = 0; k < 3; k++)
        CHECK(cam.position[k] > s->bounds_min[k] && cam.position[k] < s->bounds_max[k]);
    CHECK(cam.target[0] > cam.position[0] && near_f(cam.target[1], cam.position[1], 1e-4f) &&
          near_f(cam.target[2], cam.position[2], 1e-4f));
    CHECK(near_f(cam.fov_y_deg, 60.0f, 0) && near_f(cam.aspect, 16.0f / 9.0f, 1e-6f));
    float sz[3] = {s->bounds_max[0] - s->bounds_min[0], s->bounds_max[1] - s->bounds_min[1],
                   s->bounds_max[2] - s->bounds_min[2]};
    float diag = len3(sz);
    CHECK(near_f(cam.near_z, fmaxf(0.01f, 0.001f * diag), 1e-5f));
    CHECK(near_f(cam.far_z, 2.0f * diag, 1e-3f));

    /* light defaults from the bounds */
    pg_light_setup L = pg_light_setup_default(s, 1000, 7);
    CHECK(L.count == 1000 && L.seed == 7 && L.motion == PG_MOTION_NOISE);
    CHECK(near_f(L.radius, 0.12f * sz[0], 1e-3f));
    CHECK(near_f(L.intensity, 1.0f, 0) && near_f(L.saturation, 0.8f, 1e-6f) && near_f(L.speed, 1.0f, 0));
    for (int k = 0; k < 3; k++)
        CHECK(L.box_min[k] > s->bounds_min[k] && L.box_max[k] < s->bounds_max[k] &&
              L.box_min[k] < L.box_max[k]);
    pg_scene_free(s);
}

/* ---- textures -------------------------------------------------------------------------------- */

static void test_textures(void)
{
    pg_texture t;
    pg_error err = {0};
    uint8_t px[5 * 3 * 4];
    for (size_t i = 0; i < sizeof px; i++) px[i] = (uint8_t)(i % 4 == 3 ? 255 : 100);
    CHECK(pg_texture_init(&t, "odd", px, 5, 3, true, &err) == PG_OK);
    CHECK(t.n_mips == 3 && t.mips[1].width == 2 && t.mips[1].height == 1 && t.mips[2].width == 1);
    check_texture_chain(&t);
    /* a constant image stays constant (sRGB round trip is exact) */
    bool constant = true;
    for (uint32_t m = 0; m < t.n_mips; m++)
        for (uint32_t i = 0; i < t.mips[m].width * t.mips[m].height * 4; i++)
            if (t.mips[m].rgba[i] != (i % 4 == 3 ? 255 : 100)) constant = false;
    CHECK(constant);
    pg_texture_release(&t);
    CHECK(t.data == NULL && t.n_mips == 0);

    /* 2x2 black/white: sRGB averages in linear space (-> 188), linear averages bytes (-> 128) */
    uint8_t bw[16] = {0, 0, 0, 255, 255, 255, 255, 255, 255, 255, 255, 255, 0, 0, 0, 0};
    CHECK(pg_texture_init(&t, "bw_srgb", bw, 2, 2, true, &err) == PG_OK);
    CHECK_MSG(t.mips[1].rgba[0] == 188 && t.mips[1].rgba[3] == 191, "srgb mip %u a %u",
              t.mips[1].rgba[0], t.mips[1].rgba[3]);
    pg_texture_release(&t);
    CHECK(pg_texture_init(&t, "bw_linear", bw, 2, 2, false, &err) == PG_OK);
    CHECK_MSG(t.mips[1].rgba[0] == 128, "linear mip %u", t.mips[1].rgba[0]);
    pg_texture_release(&t);
    /* 3x1 -> 1x1 box: every source texel weighs 1/3 */
    uint8_t row[12] = {0, 30, 90, 255, 30, 60, 90, 255, 60, 90, 90, 255};
    CHECK(pg_texture_init(&t, "row", row, 3, 1, false, &err) == PG_OK);
    CHECK(t.n_mips == 2 && t.mips[1].rgba[0] == 30 && t.mips[1].rgba[1] == 60 && t.mips[1].rgba[2] == 90);
    pg_texture_release(&t);
    /* 1 x 7 column: only the height halves */
    uint8_t col[28];
    memset(col, 77, sizeof col);
    CHECK(pg_texture_init(&t, "col", col, 1, 7, false, &err) == PG_OK);
    CHECK(t.n_mips == 3 && t.mips[1].width == 1 && t.mips[1].height == 3 && t.mips[2].height == 1);
    pg_texture_release(&t);
    /* invalid sizes */
    CHECK(pg_texture_init(&t, "zero", px, 0, 3, false, &err) == PG_ERR_INVALID_ARG);
    CHECK(pg_texture_init(&t, "null", NULL, 2, 2, false, &err) == PG_ERR_INVALID_ARG);
}

/* ---- camera math ----------------------------------------------------------------------------- */

static void xform(const float m[16], const float p[4], float o[4])
{
    for (int r = 0; r < 4; r++) {
        o[r] = 0;
        for (int k = 0; k < 4; k++) o[r] += m[k * 4 + r] * p[k];
    }
}

static bool is_identity(const float m[16], float eps)
{
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++)
            if (fabsf(m[c * 4 + r] - (c == r ? 1.0f : 0.0f)) > eps) return false;
    return true;
}

static void test_camera(void)
{
    pg_camera cam = {.position = {1, 2, 3}, .target = {11, 2, 3}, .up = {0, 1, 0},
                     .fov_y_deg = 60, .near_z = 0.5f, .far_z = 100, .aspect = 2.0f};
    float V[16], P[16], VP[16], I[16], M[16];
    pg_camera_view(&cam, V);
    pg_camera_proj(&cam, P);
    float o[4];
    float eye[4] = {1, 2, 3, 1};
    xform(V, eye, o);
    CHECK(near_f(o[0], 0, 1e-5f) && near_f(o[1], 0, 1e-5f) && near_f(o[2], 0, 1e-5f));
    float tgt[4] = {11, 2, 3, 1};
    xform(V, tgt, o);
    CHECK(near_f(o[0], 0, 1e-5f) && near_f(o[1], 0, 1e-5f) && near_f(o[2], -10, 1e-4f));
    float above[4] = {6, 3, 3, 1}; /* world up -> view +Y */
    xform(V, above, o);
    CHECK(o[1] > 0.99f && near_f(o[0], 0, 1e-5f));
    float right[4] = {6, 2, 4, 1}; /* looking +X with +Y up, +Z is to the right */
    xform(V, right, o);
    CHECK(o[0] > 0.99f);

    /* projection: near -> depth 0, far -> depth 1, above -> top (y_ndc < 0), right -> x_ndc > 0 */
    pg_mat4_mul(P, V, VP);
    float pn[4] = {1.5f, 2, 3, 1}, pf[4] = {101, 2, 3, 1}, pu[4] = {11, 4, 3, 1}, pr[4] = {11, 2, 5, 1};
    xform(VP, pn, o);
    CHECK(near_f(o[2] / o[3], 0.0f, 1e-5f) && near_f(o[3], 0.5f, 1e-5f));
    xform(VP, pf, o);
    CHECK(near_f(o[2] / o[3], 1.0f, 1e-5f));
    xform(VP, pu, o);
    CHECK(o[1] / o[3] < 0);
    xform(VP, pr, o);
    CHECK(o[0] / o[3] > 0);
    /* fov: a point at the top edge of the frustum maps to y_ndc = -1; aspect scales x */
    float h = 10.0f * tanf(30.0f * 3.14159265f / 180.0f);
    float top[4] = {11, 2 + h, 3, 1}, side[4] = {11, 2, 3 + 2 * h, 1};
    xform(VP, top, o);
    CHECK(near_f(o[1] / o[3], -1.0f, 1e-4f));
    xform(VP, side, o);
    CHECK(near_f(o[0] / o[3], 1.0f, 1e-4f));

    /* inverses */
    CHECK(pg_mat4_invert(V, I));
    pg_mat4_mul(I, V, M);
    CHECK(is_identity(M, 1e-5f));
    CHECK(pg_mat4_invert(P, I));
    pg_mat4_mul(I, P, M);
    CHECK(is_identity(M, 1e-4f));
    CHECK(pg_mat4_invert(VP, I));
    pg_mat4_mul(VP, I, M);
    CHECK(is_identity(M, 1e-4f));
    float G[16] = {2, 1, 0, 0.5f, -1, 3, 2, 0, 0.25f, 0, 1, 4, 1, 2, 3, 1};
    CHECK(pg_mat4_invert(G, I));
    pg_mat4_mul(I, G, M);
    CHECK(is_identity(M, 1e-5f));
    float S[16] = {1, 2, 3, 4, 2, 4, 6, 8, 0, 1, 0, 1, 5, 5, 5, 5}; /* column 1 = 2 * column 0 */
    float keep[16];
    memcpy(keep, I, sizeof keep);
    CHECK(!pg_mat4_invert(S, I));
    CHECK(memcmp(keep, I, sizeof keep) == 0);
    float Z[16] = {0};
    CHECK(!pg_mat4_invert(Z, I));
    /* regression: a camera ~1e5 from the origin has a view matrix with det 1 but a huge
     * translation; it must invert (the far-geometry deferred variants rebuild positions with it) */
    pg_camera farcam = {.position = {1.0e5f, 2, 1.0e5f}, .target = {1.0e5f + 10, 2, 1.0e5f}, .up = {0, 1, 0},
                        .fov_y_deg = 60, .near_z = 0.1f, .far_z = 100, .aspect = 16.0f / 9};
    float FV[16], FI[16];
    pg_camera_view(&farcam, FV);
    CHECK(pg_mat4_invert(FV, FI));
    float fp[4] = {1.0e5f + 5, 3, 1.0e5f - 1, 1}, fv4[4], back[4];
    xform(FV, fp, fv4);
    xform(FI, fv4, back);
    CHECK(fabsf(back[0] - fp[0]) < 0.05f && fabsf(back[1] - fp[1]) < 0.05f && fabsf(back[2] - fp[2]) < 0.05f);
    /* mul may alias its output */
    float A[16];
    memcpy(A, G, sizeof A);
    pg_mat4_invert(G, I);
    pg_mat4_mul(A, I, A);
    CHECK(is_identity(A, 1e-5f));

    /* up parallel to the view direction still gives a valid (invertible) view */
    pg_camera down = {.position = {0, 10, 0}, .target = {0, 0, 0}, .up = {0, 1, 0},
                      .fov_y_deg = 60, .near_z = 0.1f, .far_z = 100, .aspect = 1};
    pg_camera_view(&down, V);
    CHECK(pg_mat4_invert(V, I));
    float orig[4] = {0, 0, 0, 1};
    xform(V, orig, o);
    CHECK(near_f(o[2], -10, 1e-4f));

    /* a camera for an empty scene is still usable */
    pg_camera c0 = pg_camera_default_for_scene(NULL, 1.0f);
    CHECK(c0.near_z > 0 && c0.far_z > c0.near_z && c0.target[0] > c0.position[0]);
}

/* ---- Sponza ---------------------------------------------------------------------------------- */

static void test_sponza(void)
{
    const char *skip = getenv("PG_TEST_NO_SPONZA");
    if (skip && skip[0] && strcmp(skip, "0") != 0) {
        printf("sponza: skipped (PG_TEST_NO_SPONZA set)\n");
        return;
    }
    const char *path = PG_SHARED_DIR "/assets/dabrovic-sponza/sponza.gltf";
    if (access(path, R_OK) != 0) {
        printf("sponza: skipped (%s not present)\n", path);
        return;
    }
    pg_scene *s = NULL;
    pg_error err = {0};
    double t0 = now_s();
    pg_result r = pg_scene_load(path, &s, &err);
    double t1 = now_s();
    CHECK_MSG(r == PG_OK, "%s", err.msg);
    if (!s) return;
    printf("sponza: %u triangles, %u vertices, %u materials, %u textures, loaded in %.3f s\n",
           s->n_indices / 3, s->n_vertices, s->n_materials, s->n_textures, t1 - t0);
    CHECK(t1 - t0 < 5.0);
    CHECK(strcmp(s->name, "sponza") == 0);
    CHECK(s->n_indices / 3 == 66454);
    CHECK(s->n_vertices == 62611);
    CHECK(s->n_primitives == 37);
    CHECK(s->n_materials == 14);
    CHECK(s->n_textures == 17);
    uint32_t nm = 0;
    for (uint32_t i = 0; i < s->n_materials; i++) nm += s->materials[i].normal_tex >= 0;
    CHECK(nm == 6);
    CHECK(s->features.has_textures && s->features.has_normal_maps && !s->features.has_alpha_mask);
    const float bmin[3] = {-17.4028f, -0.9067f, -7.7985f}, bmax[3] = {17.4172f, 15.6533f, 7.8015f};
    for (int k = 0; k < 3; k++)
        CHECK(near_f(s->bounds_min[k], bmin[k], 1e-3f) && near_f(s->bounds_max[k], bmax[k], 1e-3f));
    geo_stats g = scene_geometry_stats(s);
    CHECK(g.bad_index == 0);
    CHECK_MSG(g.bad_normal == 0, "%u non-unit normals", g.bad_normal);
    CHECK_MSG(g.bad_tangent == 0, "%u bad tangents", g.bad_tangent);
    /* the asset itself: 66218 of 66453 triangles have vertex normals on their CCW side */
    CHECK_MSG(g.wound_ok >= 0.995 * (g.wound_ok + g.wound_bad), "winding agrees on %u of %u",
              g.wound_ok, g.wound_ok + g.wound_bad);
    for (uint32_t i = 0; i < s->n_textures; i++) check_texture_chain(&s->textures[i]);
    /* every primitive of a normal-mapped material carries tangents */
    uint32_t missing_t = 0;
    for (uint32_t p = 0; p < s->n_primitives; p++) {
        const pg_primitive *pr = &s->primitives[p];
        if (s->materials[pr->material].normal_tex < 0) continue;
        for (uint32_t i = 0; i < pr->index_count; i++) {
            const pg_vertex *v = &s->vertices[s->indices[pr->first_index + i] + pr->vertex_offset];
            if (fabsf(fabsf(v->tangent[3]) - 1) > 0) missing_t++;
        }
    }
    CHECK_MSG(missing_t == 0, "%u normal-mapped vertices without tangents", missing_t);

    /* pg_mesh_compute_tangents agrees with the file's tangents (same glTF convention) */
    uint32_t n_cmp = 0, w_same = 0, dir_same = 0;
    for (uint32_t p = 0; p < s->n_primitives; p++) {
        const pg_primitive *pr = &s->primitives[p];
        if (s->materials[pr->material].normal_tex < 0) continue;
        uint32_t vmax = 0;
        for (uint32_t i = 0; i < pr->index_count; i++)
            if (s->indices[pr->first_index + i] + 1 > vmax) vmax = s->indices[pr->first_index + i] + 1;
        pg_vertex *copy = malloc(sizeof(pg_vertex) * vmax);
        if (!copy) continue;
        memcpy(copy, s->vertices + pr->vertex_offset, sizeof(pg_vertex) * vmax);
        pg_mesh_compute_tangents(copy, vmax, s->indices + pr->first_index, pr->index_count);
        for (uint32_t i = 0; i < vmax; i++) {
            const pg_vertex *f = &s->vertices[pr->vertex_offset + i];
            n_cmp++;
            w_same += copy[i].tangent[3] == f->tangent[3];
            dir_same += dot3(copy[i].tangent, f->tangent) > 0.9f;
        }
        free(copy);
    }
    printf("sponza: recomputed tangents: handedness agrees on %.1f%%, direction on %.1f%% of %u\n",
           100.0 * w_same / (n_cmp ? n_cmp : 1), 100.0 * dir_same / (n_cmp ? n_cmp : 1), n_cmp);
    CHECK(n_cmp > 0 && w_same >= 0.95 * n_cmp && dir_same >= 0.9 * n_cmp);

    pg_camera cam = pg_camera_default_for_scene(s, 1.0f);
    CHECK(cam.position[0] > s->bounds_min[0] && cam.position[0] < s->bounds_max[0]);
    pg_scene_free(s);
}

/* ---- scenarios ------------------------------------------------------------------------------- */

static char g_tmpdir[256];

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    if (!f) return;
    fputs(text, f);
    fclose(f);
}

typedef struct bad_scenario {
    const char *json;
    pg_result code;
    const char *substring;
} bad_scenario;

static void test_scenarios(void)
{
    pg_scenario sc;
    pg_error err = {0};
    const char *path = PG_TEST_DIR "/../assets/scenarios/cis565.json";
    pg_result r = pg_scenario_load(path, &sc, &err);
    CHECK_MSG(r == PG_OK, "%s", err.msg);
    if (r == PG_OK) {
        CHECK(strcmp(sc.name, "cis565") == 0);
        CHECK(sc.has_camera && sc.has_cam_position && sc.has_cam_target && sc.has_cam_up &&
              sc.has_cam_fov && sc.has_cam_near && sc.has_cam_far);
        CHECK(sc.camera.position[0] == -7 && sc.camera.position[1] == 2 && sc.camera.position[2] == 0);
        CHECK(sc.camera.target[0] > sc.camera.position[0] && sc.camera.target[1] == 2 &&
              sc.camera.target[2] == 0);
        CHECK(sc.camera.fov_y_deg == 45 && near_f(sc.camera.near_z, 0.1f, 1e-7f) && sc.camera.far_z == 1000);
        CHECK(sc.has_light_count && sc.lights.count == 500);
        CHECK(sc.has_light_box && sc.lights.box_min[0] == -10 && sc.lights.box_min[1] == 0 &&
              sc.lights.box_min[2] == -5 && sc.lights.box_max[0] == 10 && sc.lights.box_max[1] == 8 &&
              sc.lights.box_max[2] == 5);
        CHECK(sc.has_radius && sc.lights.radius == 2.0f);
        CHECK(sc.has_intensity && near_f(sc.lights.intensity, 0.1f, 1e-7f));
        CHECK(sc.has_saturation && near_f(sc.lights.saturation, 0.8f, 1e-7f));
        CHECK(sc.has_motion && sc.lights.motion == PG_MOTION_NOISE);
        CHECK(sc.has_speed && sc.lights.speed == 1.0f);
        CHECK(!sc.has_seed);
        CHECK(strcmp(sc.shading, "lambert") == 0);
        CHECK(sc.scene[0] == 0);

        /* apply: present fields replace, the seed (absent) is kept; --lights applied after wins */
        pg_light_setup L = pg_light_setup_default(NULL, 64, 99);
        pg_camera cam = pg_camera_default_for_scene(NULL, 1.5f);
        pg_scenario_apply(&sc, &L, &cam);
        CHECK(L.count == 500 && L.seed == 99 && L.radius == 2.0f && L.box_max[1] == 8);
        CHECK(cam.position[0] == -7 && cam.fov_y_deg == 45 && cam.far_z == 1000 && cam.aspect == 1.5f);
        pg_scenario_apply(&sc, NULL, NULL);
    }

    /* a scenario with only some fields */
    snprintf(g_tmpdir, sizeof g_tmpdir, "/tmp/pg_test_scene_XXXXXX");
    if (!mkdtemp(g_tmpdir)) {
        CHECK_MSG(0, "mkdtemp failed");
        return;
    }
    char p[512];
    snprintf(p, sizeof p, "%s/partial.json", g_tmpdir);
    write_text(p, "{\"scene\": \"models/x.gltf\", \"lights\": {\"radius\": 0.5, \"seed\": 12, \"ambient\": 0.25},"
                  " \"camera\": {\"near\": 5}}");
    r = pg_scenario_load(p, &sc, &err);
    CHECK_MSG(r == PG_OK, "%s", err.msg);
    if (r == PG_OK) {
        char want[512];
        snprintf(want, sizeof want, "%s/models/x.gltf", g_tmpdir);
        CHECK(strcmp(sc.scene, want) == 0);
        CHECK(strcmp(sc.name, "partial") == 0);
        pg_light_setup L = pg_light_setup_default(NULL, 64, 1);
        pg_light_setup L0 = L;
        pg_camera cam = {.position = {1, 1, 1}, .target = {2, 1, 1}, .up = {0, 1, 0},
                         .fov_y_deg = 50, .near_z = 0.1f, .far_z = 2, .aspect = 1};
        pg_scenario_apply(&sc, &L, &cam);
        CHECK(L0.ambient == 0 && L.ambient == 0.25f && sc.has_ambient);
        CHECK(L.radius == 0.5f && L.seed == 12 && L.count == 64 && L.intensity == L0.intensity &&
              memcmp(L.box_min, L0.box_min, sizeof L.box_min) == 0);
        CHECK(cam.near_z == 5 && cam.far_z > cam.near_z && cam.fov_y_deg == 50 && cam.position[0] == 1);
    }
    unlink(p);
    snprintf(p, sizeof p, "%s/default_scene.json", g_tmpdir);
    write_text(p, "{\"scene\": \"default\"}");
    CHECK(pg_scenario_load(p, &sc, &err) == PG_OK && strcmp(sc.scene, "default") == 0);
    unlink(p);

    static const bad_scenario bad[] = {
        {"{\"lights\": {\"radius\": -1}}", PG_ERR_SCHEMA, "lights.radius: expected a number in [0, 1e30]"},
        {"{\"lights\": {\"radius\": \"big\"}}", PG_ERR_SCHEMA, "lights.radius: expected a number in [0, 1e30]"},
        {"{\"lights\": {\"raduis\": 2}}", PG_ERR_SCHEMA, "lights.raduis: unknown key"},
        {"{\"camrea\": {}}", PG_ERR_SCHEMA, "camrea: unknown key"},
        {"{\"camera\": {\"fov\": 45}}", PG_ERR_SCHEMA, "camera.fov: unknown key"},
        {"{\"lights\": {\"box_min\": [0, 0, 0], \"box_max\": [1, -1, 1]}}", PG_ERR_SCHEMA,
         "lights.box_min: must be <= lights.box_max in every component (y: 0 > -1)"},
        {"{\"lights\": {\"box_min\": [0, 0, 0]}}", PG_ERR_SCHEMA, "lights.box_max: required together"},
        {"{\"lights\": {\"box_min\": [0, 0], \"box_max\": [1, 1, 1]}}", PG_ERR_SCHEMA,
         "lights.box_min: expected an array of 3 numbers in [-1e30, 1e30]"},
        {"{\"camera\": {\"fov_y\": 0}}", PG_ERR_SCHEMA, "camera.fov_y: expected a number of degrees in (0, 180)"},
        {"{\"camera\": {\"fov_y\": 180}}", PG_ERR_SCHEMA, "camera.fov_y"},
        {"{\"camera\": {\"near\": 0}}", PG_ERR_SCHEMA, "camera.near: expected a finite number > 0"},
        {"{\"camera\": {\"near\": 10, \"far\": 10}}", PG_ERR_SCHEMA, "camera.far: must be greater than camera.near"},
        {"{\"camera\": {\"position\": [1, 2, 3], \"target\": [1, 2, 3]}}", PG_ERR_SCHEMA,
         "camera.target: must differ from camera.position"},
        {"{\"camera\": {\"position\": [0, 0, 0], \"target\": [0, 5, 0], \"up\": [0, 1, 0]}}",
         PG_ERR_SCHEMA, "camera.up: must not be parallel"},
        {"{\"camera\": {\"up\": [0, 0, 0]}}", PG_ERR_SCHEMA, "camera.up: must not be the zero vector"},
        {"{\"lights\": {\"count\": 1.5}}", PG_ERR_SCHEMA, "lights.count: expected an integer"},
        {"{\"lights\": {\"count\": -3}}", PG_ERR_SCHEMA, "lights.count: expected an integer"},
        {"{\"lights\": {\"count\": 100000000}}", PG_ERR_SCHEMA, "lights.count: expected an integer in 0..16777216"},
        {"{\"lights\": {\"saturation\": 1.5}}", PG_ERR_SCHEMA, "lights.saturation: expected a number in [0, 1]"},
        {"{\"lights\": {\"motion\": \"wobble\"}}", PG_ERR_SCHEMA, "lights.motion: expected \"noise\" or \"static\""},
        {"{\"lights\": {\"speed\": -1}}", PG_ERR_SCHEMA, "lights.speed"},
        {"{\"lights\": {\"seed\": -1}}", PG_ERR_SCHEMA, "lights.seed"},
        {"{\"lights\": {\"ambient\": -0.1}}", PG_ERR_SCHEMA, "lights.ambient: expected a number in [0, 1000]"},
        {"{\"shading\": \"phong\"}", PG_ERR_SCHEMA, "shading: expected \"lambert\", \"blinn_phong\" or \"pbr\""},
        {"{\"name\": 3}", PG_ERR_SCHEMA, "name: expected a string"},
        {"{\"lights\": {\"radius\": 1, \"radius\": 2}}", PG_ERR_SCHEMA, "lights.radius: duplicate key"},
        {"[1, 2]", PG_ERR_SCHEMA, "expected a JSON object"},
        {"{\"lights\": [1]}", PG_ERR_SCHEMA, "lights: expected an object"},
        {"{\"lights\": {\"radius\": 2,}}", PG_ERR_PARSE, "JSON syntax error"},
        /* values that pass in double and not as the float they are stored in: they were replaced
         * silently (fov 180 -> 60, near 0 -> 0.01) or gave a black image */
        {"{\"camera\": {\"fov_y\": 179.9999999}}", PG_ERR_SCHEMA, "camera.fov_y: expected a number of degrees in (0, 180) (179.9999999 is 180 as a 32-bit float)"},
        {"{\"camera\": {\"fov_y\": 1e-40}}", PG_ERR_SCHEMA, "below the smallest normal 32-bit float"},
        {"{\"camera\": {\"near\": 1e-50}}", PG_ERR_SCHEMA, "camera.near: expected a finite number > 0 (1e-50 is 0 as a 32-bit float)"},
        {"{\"camera\": {\"position\": [0, 2, 0], \"target\": [1e-30, 2, 0]}}", PG_ERR_SCHEMA, "camera.target: must differ from camera.position (by at least 1e-15)"},
        {"{\"camera\": {\"up\": [0, 1e-30, 0]}}", PG_ERR_SCHEMA, "camera.up: must not be the zero vector"},
        /* 32 lights of 3e38 summed to infinity in RIS (black pixels) */
        {"{\"lights\": {\"intensity\": 3e38}}", PG_ERR_SCHEMA, "lights.intensity: expected a number in [0, 1e30]"},
        /* a box of +-3e38 generated inf positions; a radius of 3e38 made a file range past the spec's */
        {"{\"lights\": {\"box_min\": [-3e38, 0, 0], \"box_max\": [3e38, 1, 1]}}", PG_ERR_SCHEMA,
         "lights.box_min: expected an array of 3 numbers in [-1e30, 1e30]"},
        {"{\"lights\": {\"radius\": 3e38}}", PG_ERR_SCHEMA, "lights.radius: expected a number in [0, 1e30]"},
        {"{\n  \"name\": \"x\"\n  \"shading\": \"lambert\"\n}", PG_ERR_PARSE, ":3:"},
        {"", PG_ERR_PARSE, "empty file"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        snprintf(p, sizeof p, "%s/bad%zu.json", g_tmpdir, i);
        write_text(p, bad[i].json);
        memset(&err, 0, sizeof err);
        r = pg_scenario_load(p, &sc, &err);
        CHECK_MSG(r == bad[i].code && strstr(err.msg, bad[i].substring) && strstr(err.msg, p),
                  "bad scenario %zu: got %s '%s', want %s '%s'", i, pg_result_name(r), err.msg,
                  pg_result_name(bad[i].code), bad[i].substring);
        unlink(p);
    }
    { /* nesting past the parser's limit is named; brackets inside a string are not nesting */
        static char deep[2 * 1100 + 64];
        for (int depth = 1000; depth <= 1001; depth++) {
            int n = snprintf(deep, sizeof deep, "{\"name\": \"[[[\", \"x\": ");
            for (int i = 1; i < depth; i++) deep[n++] = '[';
            for (int i = 1; i < depth; i++) deep[n++] = ']';
            snprintf(deep + n, sizeof deep - (size_t)n, "}");
            snprintf(p, sizeof p, "%s/deep.json", g_tmpdir);
            write_text(p, deep);
            memset(&err, 0, sizeof err);
            r = pg_scenario_load(p, &sc, &err);
            bool note = strstr(err.msg, "nested deeper than 1000 levels") != NULL;
            CHECK_MSG(r == PG_ERR_PARSE || r == PG_ERR_SCHEMA, "depth %d: %s", depth, err.msg);
            CHECK_MSG(note == (depth > 1000), "depth %d: %s", depth, err.msg);
            unlink(p);
        }
    }
    snprintf(p, sizeof p, "%s/missing.json", g_tmpdir);
    CHECK(pg_scenario_load(p, &sc, &err) == PG_ERR_IO);
    rmdir(g_tmpdir);
}

/* ---- glTF corpus ----------------------------------------------------------------------------- */

static pg_result code_from_name(const char *n)
{
    for (int r = 0; r < PG_ERR_COUNT; r++)
        if (strcmp(pg_result_name((pg_result)r), n) == 0) return (pg_result)r;
    return PG_ERR_COUNT;
}

static pg_scene *load_corpus(const char *name)
{
    char p[512];
    snprintf(p, sizeof p, "%s/corpus/gltf/%s", PG_TEST_DIR, name);
    pg_scene *s = NULL;
    pg_error err = {0};
    if (pg_scene_load_gltf(p, &s, &err) != PG_OK) {
        CHECK_MSG(0, "%s: %s", name, err.msg);
        return NULL;
    }
    return s;
}

static void test_corpus_valid_details(void)
{
    pg_scene *s;
    if ((s = load_corpus("ok_minimal.gltf"))) {
        CHECK(s->n_indices == 3 && s->n_vertices == 3 && s->n_materials == 1);
        CHECK(strcmp(s->materials[0].name, "default") == 0 && s->materials[0].base_color[0] == 1);
        CHECK(near_f(s->vertices[0].normal[2], 1.0f, 1e-6f)); /* computed from the winding */
        CHECK(strcmp(s->name, "ok_minimal") == 0);
        pg_scene_free(s);
    }
    if ((s = load_corpus("ok_minimal.glb"))) {
        CHECK(s->n_indices == 3);
        pg_scene_free(s);
    }
    if ((s = load_corpus("ok_external_bin.gltf"))) {
        CHECK(s->n_indices == 3);
        pg_scene_free(s);
    }
    if ((s = load_corpus("ok_strip.gltf"))) { /* no NORMAL: flat, each triangle its own vertices */
        CHECK(s->n_indices == 6 && s->n_vertices == 6);
        geo_stats g = scene_geometry_stats(s);
        CHECK(g.wound_bad == 0 && g.wound_ok == 2);
        pg_scene_free(s);
    }
    if ((s = load_corpus("ok_mirrored.gltf"))) {
        geo_stats g = scene_geometry_stats(s);
        CHECK(g.wound_ok == 1 && g.wound_bad == 0);
        CHECK(near_f(s->vertices[1].position[0], -1.0f, 1e-6f));
        CHECK(near_f(s->vertices[0].normal[2], 1.0f, 1e-6f));
        pg_scene_free(s);
    }
    if ((s = load_corpus("ok_mirrored_tangent.gltf"))) {
        const pg_vertex *v = &s->vertices[0];
        CHECK(near_f(v->tangent[0], -1, 1e-6f) && v->tangent[3] == 1.0f);
        pg_vertex copy[3];
        memcpy(copy, s->vertices, sizeof copy);
        pg_mesh_compute_tangents(copy, 3, s->indices, 3);
        CHECK(near_f(copy[0].tangent[0], v->tangent[0], 1e-5f) && copy[0].tangent[3] == v->tangent[3]);
        pg_scene_free(s);
    }
    /* without NORMAL: flat normals, outward, also on a mirrored node an animation moves (they were
     * smooth, and inward there); a normal map's tangents from the set it reads; TANGENT ignored
     * without NORMAL (glTF 2.0 3.7.2.1) */
    static const char *const flat_files[] = {"ok_flat_normals.gltf", "ok_flat_normals_mirrored_animated.gltf"};
    for (int f = 0; f < 2; f++) {
        if (!(s = load_corpus(flat_files[f]))) continue;
        int bad = 0;
        CHECK_MSG(s->n_indices == 36 && s->n_vertices == 36, "%s: %u vertices", flat_files[f], s->n_vertices);
        for (uint32_t t = 0; t + 2 < s->n_indices && s->n_vertices == 36; t += 3) {
            const pg_vertex *v0 = &s->vertices[s->indices[t]], *v1 = &s->vertices[s->indices[t + 1]],
                            *v2 = &s->vertices[s->indices[t + 2]];
            float e1[3], e2[3], fn[3], c[3];
            for (int k = 0; k < 3; k++) {
                e1[k] = v1->position[k] - v0->position[k];
                e2[k] = v2->position[k] - v0->position[k];
                c[k] = (v0->position[k] + v1->position[k] + v2->position[k]) / 3 -
                       0.5f * (s->bounds_min[k] + s->bounds_max[k]);
            }
            fn[0] = e1[1] * e2[2] - e1[2] * e2[1], fn[1] = e1[2] * e2[0] - e1[0] * e2[2], fn[2] = e1[0] * e2[1] - e1[1] * e2[0];
            float fl = sqrtf(fn[0] * fn[0] + fn[1] * fn[1] + fn[2] * fn[2]);
            for (int j = 0; j < 3; j++) {
                const float *n = s->vertices[s->indices[t + j]].normal;
                bool flat = true;
                for (int k = 0; k < 3; k++) flat = flat && fabsf(n[k] - fn[k] / fl) < 1e-5f;
                bad += !flat || n[0] * c[0] + n[1] * c[1] + n[2] * c[2] <= 0;
            }
        }
        CHECK_MSG(bad == 0, "%s: %d vertices without the outward face normal", flat_files[f], bad);
        pg_scene_free(s);
    }
    if ((s = load_corpus("ok_normal_map_texcoord1.gltf"))) { /* TEXCOORD_1 = (1 - u, v): -X */
        for (uint32_t i = 0; i < s->n_vertices; i++)
            CHECK_MSG(near_f(s->vertices[i].tangent[0], -1, 1e-5f), "vertex %u: tangent x %g", i,
                      s->vertices[i].tangent[0]);
        pg_scene_free(s);
    }
    if ((s = load_corpus("ok_normal_map_transform.gltf"))) {
        /* tangents from the coordinates the normal map is sampled with: the material's transform of
         * the normal slot applied to the uv, as the shaders do */
        const pg_material *m = &s->materials[s->primitives[0].material];
        CHECK(m->has_uv_transform[PG_TEXSLOT_NORMAL]);
        pg_vertex t[4];
        memcpy(t, s->vertices, sizeof t);
        const float *x = m->uv_transform[PG_TEXSLOT_NORMAL];
        for (int i = 0; i < 4; i++) {
            const float u = t[i].uv[0], v = t[i].uv[1];
            t[i].uv[0] = x[0] * u + x[1] * v + x[2];
            t[i].uv[1] = x[3] * u + x[4] * v + x[5];
        }
        pg_mesh_compute_tangents(t, 4, s->indices, 6);
        for (uint32_t i = 0; i < 4 && s->n_vertices == 4; i++) {
            const float *g = s->vertices[i].tangent;
            CHECK_MSG(near_f(g[0], t[i].tangent[0], 1e-5f) && near_f(g[1], t[i].tangent[1], 1e-5f) &&
                          near_f(g[2], t[i].tangent[2], 1e-5f) && g[3] == t[i].tangent[3] && fabsf(g[0]) < 1e-5f,
                      "vertex %u: tangent (%g, %g, %g, %g), want (%g, %g, %g, %g)", i, g[0], g[1], g[2], g[3],
                      t[i].tangent[0], t[i].tangent[1], t[i].tangent[2], t[i].tangent[3]);
        }
        pg_scene_free(s);
    }
    if ((s = load_corpus("ok_tangent_without_normals.gltf"))) { /* the file's (-1, 0, 0) ignored: +X */
        for (uint32_t i = 0; i < s->n_vertices; i++)
            CHECK_MSG(near_f(s->vertices[i].tangent[0], 1, 1e-5f) && near_f(s->vertices[i].normal[2], 1, 1e-5f),
                      "vertex %u: tangent x %g, normal z %g", i, s->vertices[i].tangent[0], s->vertices[i].normal[2]);
        pg_scene_free(s);
    }
    if ((s = load_corpus("ok_trs_hierarchy.gltf"))) {
        CHECK(near_f(s->bounds_min[0], 9, 1e-5f) && near_f(s->bounds_max[0], 10, 1e-5f));
        CHECK(near_f(s->bounds_min[1], 0, 1e-5f) && near_f(s->bounds_max[1], 1, 1e-5f));
        /* vertex 1 (1,0,0): rotated 90 deg about Z -> (0,1,0), translated -> (10,1,0) */
        CHECK(near_f(s->vertices[1].position[0], 10, 1e-5f) && near_f(s->vertices[1].position[1], 1, 1e-5f));
        CHECK(near_f(s->primitives[0].bounds_min[0], 9, 1e-5f));
        pg_scene_free(s);
    }
    if ((s = load_corpus("ok_interleaved_u8.gltf"))) {
        CHECK(s->n_indices == 3 && near_f(s->vertices[2].normal[2], 1, 0) &&
              near_f(s->vertices[2].position[1], 1, 0));
        pg_scene_free(s);
    }
    if ((s = load_corpus("ok_textured.gltf"))) {
        CHECK(s->n_textures == 2 && s->n_materials == 1);
        const pg_material *m = &s->materials[0];
        CHECK(m->base_color_tex >= 0 && m->normal_tex >= 0 && m->base_color_tex != m->normal_tex);
        if (m->base_color_tex >= 0 && m->normal_tex >= 0) {
            CHECK(s->textures[m->base_color_tex].srgb && !s->textures[m->normal_tex].srgb);
            CHECK(s->textures[m->base_color_tex].mips[0].width == 2 &&
                  s->textures[m->base_color_tex].n_mips == 2);
            CHECK(s->textures[m->base_color_tex].mips[0].rgba[0] == 255 &&
                  s->textures[m->base_color_tex].mips[0].rgba[1] == 0);
        }
        CHECK(m->alpha_mode == PG_ALPHA_MASK && near_f(m->alpha_cutoff, 0.3f, 1e-6f) && m->double_sided);
        CHECK(near_f(m->normal_scale, 0.5f, 1e-6f));
        CHECK(s->features.has_textures && s->features.has_normal_maps && s->features.has_alpha_mask);
        /* tangents computed from UVs: T = +X (u grows along x), bitangent = -Y (v grows along y,
         * glTF v points down the image), N = +Z -> w = -1 */
        const pg_vertex *v = &s->vertices[0];
        CHECK(near_f(v->tangent[0], 1, 1e-5f) && near_f(v->tangent[1], 0, 1e-5f) && v->tangent[3] == -1);
        geo_stats g = scene_geometry_stats(s);
        CHECK(g.bad_tangent == 0 && g.tangents == 3);
        pg_scene_free(s);
    }
    if ((s = load_corpus("ok_points_skipped.gltf"))) {
        CHECK(s->n_primitives == 1 && s->n_indices == 3);
        pg_scene_free(s);
    }
}

/* scene->warnings must be exactly the WARNINGS lines of `file` (each "PATH: LINE"), in order. */
static bool check_corpus_warnings(const char *file, const char *path, const pg_scene *s)
{
    char wpath[512];
    snprintf(wpath, sizeof wpath, "%s/corpus/gltf/WARNINGS", PG_TEST_DIR);
    FILE *f = fopen(wpath, "r");
    CHECK_MSG(f != NULL, "cannot open %s", wpath);
    if (!f) return false;
    char line[1024];
    uint32_t k = 0;
    bool ok = true;
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\r\n")] = 0;
        char *tab = strchr(line, '\t');
        if (!tab) continue;
        *tab = 0;
        if (strcmp(line, file) != 0) continue;
        char want[1400];
        snprintf(want, sizeof want, "%s: %s", path, tab + 1);
        bool same = k < s->n_warnings && !strcmp(s->warnings[k], want);
        CHECK_MSG(same, "%s: warning %u is '%s', want '%s'", file, k, k < s->n_warnings ? s->warnings[k] : "(none)",
                  want);
        ok = ok && same;
        k++;
    }
    fclose(f);
    CHECK_MSG(s->n_warnings == k, "%s: %u warnings, WARNINGS lists %u (first: %s)", file, s->n_warnings, k,
              s->n_warnings ? s->warnings[0] : "-");
    return ok && s->n_warnings == k;
}

/* Sparse substitution, the exact lines of the new-user mistakes, ownership of the warnings. */
static void test_corpus_features(void)
{
    pg_scene *s;
    if ((s = load_corpus("ok_sparse.gltf"))) {
        /* vertex 2 moved from (0,1,0) to (0,2,0) by the sparse values; 0 and 1 kept */
        CHECK(s->n_vertices == 3 && s->vertices[2].position[1] == 2.0f && s->vertices[1].position[0] == 1.0f &&
              s->vertices[0].position[1] == 0.0f);
        CHECK(s->bounds_max[1] == 2.0f);
        CHECK(s->n_warnings == 0 && s->warnings == NULL);
        pg_scene_free(s);
    }
    if ((s = load_corpus("ok_sparse_no_view.gltf"))) {
        CHECK(s->n_vertices == 3 && s->vertices[1].position[0] == 1.0f && s->vertices[2].position[1] == 3.0f);
        pg_scene_free(s);
    }
    if ((s = load_corpus("ok_skins.gltf"))) {
        char want[600];
        snprintf(want, sizeof want, "%s/corpus/gltf/ok_skins.gltf: 1 primitive(s) of skinned nodes without JOINTS_0/WEIGHTS_0: drawn by their node's transform, unskinned", PG_TEST_DIR);
        CHECK(s->n_warnings == 1 && !strcmp(s->warnings[0], want));
        /* the tools' printer: one "PREFIXwarning: LINE" per warning */
        char *buf = NULL;
        size_t len = 0;
        FILE *mf = open_memstream(&buf, &len);
        CHECK(mf != NULL);
        if (mf) {
            pg_scene_print_warnings(s, "passgraph: ", mf);
            fclose(mf);
            char line[700];
            snprintf(line, sizeof line, "passgraph: warning: %s\n", want);
            CHECK(buf && !strcmp(buf, line));
            free(buf);
        }
        pg_scene_free(s);
    }
    if ((s = load_corpus("ok_alpha_blend.gltf"))) {
        CHECK(s->n_materials >= 1 && s->materials[0].alpha_mode == PG_ALPHA_BLEND);
        pg_scene_free(s);
    }
    pg_error err = {0};
    pg_scene *bad = (pg_scene *)1;
    /* a directory: said so, with what was expected */
    CHECK(pg_scene_load_gltf(PG_TEST_DIR "/corpus/gltf", &bad, &err) == PG_ERR_IO && bad == NULL);
    CHECK_MSG(!strcmp(err.msg, "scene '" PG_TEST_DIR "/corpus/gltf': is a directory, not a regular file"),
              "%s", err.msg);
    CHECK(pg_scene_load(PG_TEST_DIR "/corpus/gltf/", &bad, &err) == PG_ERR_IO);
    CHECK(strstr(err.msg, "': is a directory, not a regular file") != NULL);
    CHECK(pg_scene_load_gltf(PG_TEST_DIR "/corpus/gltf/cube.obj", &bad, &err) == PG_ERR_PARSE);
    CHECK_MSG(!strcmp(err.msg, PG_TEST_DIR "/corpus/gltf/cube.obj: not a glTF 2.0 file (passgraph reads .gltf and "
                               ".glb only)"),
              "%s", err.msg);
    CHECK(pg_scene_load_gltf(PG_TEST_DIR "/corpus/gltf/version_1.gltf", &bad, &err) == PG_ERR_GLTF);
    CHECK_MSG(!strcmp(err.msg, PG_TEST_DIR "/corpus/gltf/version_1.gltf: asset.version: '1.0': glTF 1.0 is not "
                               "supported, only 2.0"),
              "%s", err.msg);
    /* the implemented required extension (EXT_meshopt_compression) is not named */
    CHECK(pg_scene_load_gltf(PG_TEST_DIR "/corpus/gltf/required_made_up.gltf", &bad, &err) == PG_ERR_GLTF);
    CHECK_MSG(!strcmp(err.msg, PG_TEST_DIR "/corpus/gltf/required_made_up.gltf: extensionsRequired: "
                               "'EXT_made_up' is not supported (passgraph implements only these glTF extensions: "
                               "EXT_mesh_gpu_instancing, EXT_meshopt_compression, EXT_texture_webp, "
                               "KHR_draco_mesh_compression, KHR_lights_punctual, "
                               "KHR_materials_emissive_strength, KHR_materials_unlit, KHR_materials_variants, "
                               "KHR_mesh_quantization, KHR_texture_transform, PASSGRAPH_lights_table)"),
              "%s", err.msg);
    /* a scenario path that is a directory */
    pg_scenario sc;
    CHECK(pg_scenario_load(PG_TEST_DIR "/corpus", &sc, &err) == PG_ERR_IO);
    CHECK_MSG(!strcmp(err.msg, "scenario '" PG_TEST_DIR "/corpus': is a directory, not a regular file"), "%s", err.msg);
    /* the default scene has no warnings */
    if (pg_scene_create_default(&s, &err) == PG_OK) {
        CHECK(s->n_warnings == 0 && s->warnings == NULL);
        CHECK(pg_scene_add_warning(s, "x: one", &err) == PG_OK && pg_scene_add_warning(s, "x: two", &err) == PG_OK);
        CHECK(s->n_warnings == 2 && !strcmp(s->warnings[1], "x: two"));
        pg_scene_free(s);
    }
}

static bool rgb_eq(const float *v, float r, float g, float b) { return v[0] == r && v[1] == g && v[2] == b; }

/* emissive = emissiveFactor x KHR_materials_emissive_strength (default 1); the extension is
 * implemented: no warning when used, accepted when required. The refused values (negative,
 * non-finite, past the float range) are MANIFEST lines (gen_corpus.py). */
static void test_emissive_loader(void)
{
    pg_error err = {0};
    static const char *const files[] = {"emissive.gltf", "emissive_required.gltf", "plain.gltf"};
    for (int f = 0; f < 3; f++) {
        char path[PG_PATH_MAX];
        snprintf(path, sizeof path, "%s/corpus/gltf/emissive/%s", PG_TEST_DIR, files[f]);
        pg_scene *s = NULL;
        CHECK_MSG(pg_scene_load_gltf(path, &s, &err) == PG_OK, "%s: %s", files[f], err.msg);
        if (!s) continue;
        bool emits = f < 2;
        CHECK_MSG(s->n_materials == 4 && s->n_warnings == 0, "%s: %u materials, %u warnings", files[f], s->n_materials,
                  s->n_warnings);
        if (s->n_materials == 4) {
            CHECK_MSG(!strcmp(s->materials[0].name, "glow") && !strcmp(s->materials[1].name, "lamp"), "%s", files[f]);
            CHECK_MSG(emits ? rgb_eq(s->materials[0].emissive, 1.0f, 0.5f, 0.25f)
                            : rgb_eq(s->materials[0].emissive, 0, 0, 0),
                      "%s: glow emissive %g %g %g", files[f], s->materials[0].emissive[0], s->materials[0].emissive[1],
                      s->materials[0].emissive[2]);
            /* (0.25, 0.5, 1) x emissiveStrength 4 */
            CHECK_MSG(emits ? rgb_eq(s->materials[1].emissive, 1.0f, 2.0f, 4.0f)
                            : rgb_eq(s->materials[1].emissive, 0, 0, 0),
                      "%s: lamp emissive %g %g %g", files[f], s->materials[1].emissive[0], s->materials[1].emissive[1],
                      s->materials[1].emissive[2]);
            CHECK(rgb_eq(s->materials[2].emissive, 0, 0, 0) && rgb_eq(s->materials[3].emissive, 0, 0, 0));
        }
        CHECK_MSG(s->features.has_emissive == emits, "%s: has_emissive %d", files[f], s->features.has_emissive);
        pg_scene_free(s);
    }
    pg_scene *s;
    if ((s = load_corpus("ok_emissive.gltf"))) { /* (1, 0.5, 0) x 5; the textured material emits nothing */
        CHECK(s->n_materials >= 2 && rgb_eq(s->materials[0].emissive, 5.0f, 2.5f, 0.0f) &&
              rgb_eq(s->materials[1].emissive, 0, 0, 0));
        pg_scene_free(s);
    }
    if ((s = load_corpus("ok_required_emissive_strength.gltf"))) { /* (0.5, 0.25, 1) x 2, required */
        CHECK(s->n_materials >= 1 && rgb_eq(s->materials[0].emissive, 1.0f, 0.5f, 2.0f) && s->n_warnings == 0);
        pg_scene_free(s);
    }
}

/* ---- glTF surface features (tests/corpus/gltf/features/gen_features.py) ----------------------- */

static pg_scene *load_feature(const char *name)
{
    char p[600];
    snprintf(p, sizeof p, "%s/corpus/gltf/features/%s", PG_TEST_DIR, name);
    pg_scene *s = NULL;
    pg_error err = {0};
    if (pg_scene_load_gltf(p, &s, &err) != PG_OK) {
        CHECK_MSG(0, "%s: %s", name, err.msg);
        return NULL;
    }
    return s;
}

static bool same_sampler(const pg_sampler_state *a, pg_wrap s, pg_wrap t, bool mag_nearest, bool min_nearest,
                         pg_mip_mode mip)
{
    return a->wrap_s == s && a->wrap_t == t && a->mag_nearest == mag_nearest && a->min_nearest == min_nearest &&
           a->mip == mip;
}

static void test_gltf_features(void)
{
    /* COLOR_0: four sub-quads of 4 vertices, colours (gen_features.py SUB_COLORS) decoded exactly */
    static const float sub[4][4] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {0.25f, 0.5f, 1, 0.5f}};
    static const float u8[4][4] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {64 / 255.0f, 128 / 255.0f, 1, 128 / 255.0f}};
    static const float u16[4][4] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1},
                                    {16384 / 65535.0f, 32768 / 65535.0f, 1, 32768 / 65535.0f}};
    const struct {
        const char *file;
        const float (*want)[4];
        bool vec3;
        uint32_t n_vertices;
    } vc[] = {{"vcolor_float3.gltf", sub, true, 16}, {"vcolor_unorm8.gltf", u8, false, 20},
              {"vcolor_unorm16.gltf", u16, false, 16}};
    for (size_t f = 0; f < 3; f++) {
        pg_scene *s = load_feature(vc[f].file);
        if (!s) continue;
        CHECK_MSG(s->colors != NULL && s->features.has_vertex_colors && s->n_vertices == vc[f].n_vertices,
                  "%s: colors %p, %u vertices", vc[f].file, (void *)s->colors, s->n_vertices);
        CHECK(s->n_warnings == 0 && s->uv1 == NULL && !s->features.has_uv1 && !s->features.has_uv_transform);
        for (uint32_t v = 0; s->colors && v < s->n_vertices; v++) {
            const float *want = v < 16 ? vc[f].want[v / 4] : (const float[4]){1, 1, 1, 1}; /* no COLOR_0: white */
            for (int k = 0; k < 4; k++) {
                float w = (k == 3 && vc[f].vec3) ? 1.0f : want[k]; /* VEC3: alpha 1 */
                CHECK_MSG(near_f(s->colors[v][k], w, 1e-7f), "%s: vertex %u colour[%d] %g, want %g", vc[f].file, v, k,
                          s->colors[v][k], w);
            }
        }
        pg_scene_free(s);
    }
    pg_scene *s;
    pg_error err = {0};
    pg_scene *bad = NULL;
    const struct {
        const char *file, *msg;
    } errs[] = {
        {"bad_color_vec2.gltf", "accessors[2]: COLOR_0 must be VEC3 or VEC4, FLOAT or normalized "
                                "UNSIGNED_BYTE/UNSIGNED_SHORT (got VEC2 FLOAT)"},
        {"bad_color_not_normalized.gltf", "accessors[2]: COLOR_0 must be VEC3 or VEC4, FLOAT or normalized "
                                          "UNSIGNED_BYTE/UNSIGNED_SHORT (got VEC4 UNSIGNED_BYTE)"},
        {"bad_xform_offset.gltf", "materials[0].pbrMetallicRoughness.baseColorTexture.extensions."
                                  "KHR_texture_transform.offset: expected 2 finite numbers"},
        {"bad_xform_rotation.gltf", "materials[0].pbrMetallicRoughness.baseColorTexture.extensions."
                                    "KHR_texture_transform.rotation: expected a finite number (radians)"},
    };
    for (size_t i = 0; i < sizeof errs / sizeof errs[0]; i++) {
        char p[600];
        snprintf(p, sizeof p, "%s/corpus/gltf/features/%s", PG_TEST_DIR, errs[i].file);
        pg_result r = pg_scene_load_gltf(p, &bad, &err);
        CHECK_MSG(r == PG_ERR_GLTF && bad == NULL && strstr(err.msg, errs[i].msg), "%s: %s", errs[i].file, err.msg);
        pg_scene_free(bad);
        bad = NULL;
    }

    /* TEXCOORD_1: read by the base texture (texCoord 1) -> uv1 exactly; read by none -> no stream */
    if ((s = load_feature("texcoord1.gltf"))) {
        CHECK(s->uv1 != NULL && s->features.has_uv1 && s->materials[0].tex_coord[PG_TEXSLOT_BASE] == 1);
        static const float uv1[4][2] = {{0.55f, 0.1f}, {0.95f, 0.1f}, {0.55f, 0.9f}, {0.95f, 0.9f}};
        for (int v = 0; s->uv1 && v < 4; v++)
            CHECK(near_f(s->uv1[v][0], uv1[v][0], 1e-7f) && near_f(s->uv1[v][1], uv1[v][1], 1e-7f) &&
                  near_f(s->vertices[v].uv[0], uv1[v][0] - 0.5f, 1e-6f));
        CHECK(s->colors == NULL && !s->features.has_vertex_colors && s->n_warnings == 0);
        pg_scene_free(s);
    }
    if ((s = load_feature("uv1_unused.gltf"))) {
        CHECK(s->uv1 == NULL && !s->features.has_uv1 && s->materials[0].tex_coord[PG_TEXSLOT_BASE] == 0);
        pg_scene_free(s);
    }
    if ((s = load_feature("uv1_missing.gltf"))) { /* primitives 0 and 2 lack TEXCOORD_1: their TEXCOORD_0 */
        CHECK(s->uv1 != NULL && s->n_vertices == 12 && s->features.has_uv1);
        for (uint32_t v = 0; s->uv1 && v < 12; v++) {
            const float *want = v >= 4 && v < 8 ? (const float[2]){0.55f + 0.4f * (v % 2), v < 6 ? 0.1f : 0.9f}
                                                : s->vertices[v].uv;
            CHECK_MSG(near_f(s->uv1[v][0], want[0], 1e-6f) && near_f(s->uv1[v][1], want[1], 1e-6f),
                      "uv1_missing: vertex %u uv1 %g %g, want %g %g", v, s->uv1[v][0], s->uv1[v][1], want[0], want[1]);
        }
        CHECK(near_f(s->vertices[0].uv[0], 0.1f, 1e-6f) && near_f(s->vertices[11].uv[1], 0.9f, 1e-6f));
        CHECK_MSG(s->n_warnings == 1 && strstr(s->warnings[0], "uv1_missing.gltf: TEXCOORD_1 missing in 2 primitives "
                                                              "whose material reads it (texCoord 1): TEXCOORD_0 used"),
                  "%s", s->n_warnings ? s->warnings[0] : "no warning");
        pg_scene_free(s);
    }
    if ((s = load_feature("texcoord0.gltf"))) {
        CHECK(s->uv1 == NULL && !s->features.has_uv1);
        pg_scene_free(s);
    }

    /* every slot: texCoord, transforms (M = T * R * S, row-major 2x3), the emissive texture */
    if ((s = load_feature("slots.gltf"))) {
        CHECK(s->n_materials == 2 && s->uv1 != NULL && s->features.has_uv1 && s->features.has_uv_transform);
        const pg_material *m = &s->materials[0];
        CHECK(m->base_color_tex >= 0 && m->normal_tex >= 0 && m->emissive_tex >= 0);
        if (m->emissive_tex >= 0 && m->normal_tex >= 0) {
            CHECK(s->textures[m->emissive_tex].srgb && !s->textures[m->normal_tex].srgb);
            CHECK(m->emissive_tex == m->base_color_tex); /* same image, sRGB, default sampler */
        }
        CHECK(m->tex_coord[PG_TEXSLOT_BASE] == 0 && m->tex_coord[PG_TEXSLOT_NORMAL] == 1 &&
              m->tex_coord[PG_TEXSLOT_EMISSIVE] == 1); /* emissive: the transform's texCoord overrides */
        CHECK(!m->has_uv_transform[PG_TEXSLOT_BASE] && m->has_uv_transform[PG_TEXSLOT_NORMAL] &&
              m->has_uv_transform[PG_TEXSLOT_EMISSIVE]);
        const float id[6] = {1, 0, 0, 0, 1, 0};
        const float nrm[6] = {2, 0, 0.25f, 0, 3, -0.5f}; /* offset (0.25, -0.5), scale (2, 3) */
        const float c = cosf(0.5f), sn = sinf(0.5f);
        const float emi[6] = {c, sn, 0, -sn, c, 0};       /* rotation 0.5 rad */
        for (int k = 0; k < 6; k++) {
            CHECK_MSG(m->uv_transform[PG_TEXSLOT_BASE][k] == id[k], "base transform[%d]", k);
            CHECK_MSG(near_f(m->uv_transform[PG_TEXSLOT_NORMAL][k], nrm[k], 1e-6f), "normal transform[%d] %g", k,
                      m->uv_transform[PG_TEXSLOT_NORMAL][k]);
            CHECK_MSG(near_f(m->uv_transform[PG_TEXSLOT_EMISSIVE][k], emi[k], 1e-6f), "emissive transform[%d] %g", k,
                      m->uv_transform[PG_TEXSLOT_EMISSIVE][k]);
        }
        /* texCoord 2: warned, read with TEXCOORD_0 */
        CHECK(s->materials[1].tex_coord[PG_TEXSLOT_BASE] == 0);
        bool warned = false;
        for (uint32_t i = 0; i < s->n_warnings; i++)
            warned = warned || strstr(s->warnings[i], "textures of 1 material (materials[1] 'far') ask for a texCoord "
                                                      "other than 0 or 1: read with TEXCOORD_0");
        CHECK(warned);
        pg_scene_free(s);
    }
    if ((s = load_feature("xform_rotation.gltf"))) {
        const float *x = s->materials[0].uv_transform[PG_TEXSLOT_BASE];
        /* 90 degrees counter-clockwise: (u, v) -> (v, -u) */
        CHECK(near_f(x[0], 0, 1e-6f) && near_f(x[1], 1, 1e-6f) && near_f(x[3], -1, 1e-6f) && near_f(x[4], 0, 1e-6f));
        CHECK(s->features.has_uv_transform && s->n_warnings == 0);
        pg_scene_free(s);
    }
    if ((s = load_feature("xform_texcoord.gltf"))) { /* extensionsRequired: KHR_texture_transform accepted */
        CHECK(s->n_warnings == 0 && s->materials[0].tex_coord[PG_TEXSLOT_BASE] == 1 && s->uv1 != NULL);
        pg_scene_free(s);
    }

    /* samplers: every minFilter value, wrap modes, one pg_texture per (image, sRGB, state) */
    if ((s = load_feature("samplers.gltf"))) {
        CHECK_MSG(s->n_textures == 7 && s->n_warnings == 0, "%u textures, %u warnings", s->n_textures, s->n_warnings);
        const pg_sampler_state *st[9];
        for (int i = 0; i < 9; i++) {
            int t = s->materials[i].base_color_tex;
            st[i] = t >= 0 && (uint32_t)t < s->n_textures ? &s->textures[t].sampler : NULL;
            CHECK_MSG(st[i] != NULL, "material %d: texture %d", i, t);
            if (!st[i]) return pg_scene_free(s);
        }
        CHECK(same_sampler(st[0], PG_WRAP_CLAMP, PG_WRAP_MIRROR, true, true, PG_MIP_NONE));     /* NEAREST */
        CHECK(same_sampler(st[1], PG_WRAP_MIRROR, PG_WRAP_CLAMP, false, false, PG_MIP_NONE));   /* LINEAR */
        CHECK(same_sampler(st[2], PG_WRAP_REPEAT, PG_WRAP_REPEAT, false, true, PG_MIP_NEAREST));/* N_MIPMAP_N */
        CHECK(same_sampler(st[3], PG_WRAP_REPEAT, PG_WRAP_REPEAT, false, false, PG_MIP_NEAREST));/* L_MIPMAP_N */
        CHECK(same_sampler(st[4], PG_WRAP_REPEAT, PG_WRAP_REPEAT, false, true, PG_MIP_LINEAR)); /* N_MIPMAP_L */
        CHECK(same_sampler(st[5], PG_WRAP_REPEAT, PG_WRAP_REPEAT, false, false, PG_MIP_LINEAR));/* L_MIPMAP_L */
        CHECK(same_sampler(st[6], PG_WRAP_CLAMP, PG_WRAP_REPEAT, false, false, PG_MIP_LINEAR));
        CHECK(s->materials[6].base_color_tex == s->materials[7].base_color_tex); /* same state: one texture */
        CHECK(same_sampler(st[8], PG_WRAP_REPEAT, PG_WRAP_REPEAT, false, false, PG_MIP_LINEAR)); /* none: default */
        CHECK(s->materials[8].base_color_tex == s->materials[5].base_color_tex);
        pg_scene_free(s);
    }
    /* the corpus file with COLOR_0 + TEXCOORD_1 + texCoord 1 now draws them */
    if ((s = load_corpus("ok_color_texcoord1.gltf"))) {
        CHECK(s->colors && s->uv1 && s->features.has_vertex_colors && s->features.has_uv1);
        if (s->colors) CHECK(s->colors[1][0] == 1 && s->colors[1][1] == 0 && s->colors[1][3] == 1); /* (1,0,0) VEC3 */
        pg_scene_free(s);
    }
}

static void test_corpus(void)
{
    char mpath[512];
    snprintf(mpath, sizeof mpath, "%s/corpus/gltf/MANIFEST", PG_TEST_DIR);
    FILE *f = fopen(mpath, "r");
    CHECK_MSG(f != NULL, "cannot open %s", mpath);
    if (!f) return;
    char line[1024];
    int n_err = 0, n_ok = 0, n_fail = 0;
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\r\n")] = 0;
        char *p = line;
        while (*p == ' ' || *p == '\t') p++;
        if (!*p || *p == '#') continue;
        char file[256], code[64];
        int used = 0;
        if (sscanf(p, "%255s %63s %n", file, code, &used) < 2) {
            CHECK_MSG(0, "bad MANIFEST line: %s", line);
            continue;
        }
        const char *sub = p + used;
        pg_result want = code_from_name(code);
        CHECK_MSG(want != PG_ERR_COUNT, "MANIFEST: unknown code %s", code);
        char path[600];
        snprintf(path, sizeof path, "%s/corpus/gltf/%s", PG_TEST_DIR, file);
        pg_scene *s = NULL;
        pg_error err = {0};
        pg_result r = pg_scene_load_gltf(path, &s, &err);
        bool ok;
        if (want == PG_OK) {
            ok = r == PG_OK && s != NULL && s->n_indices > 0;
            if (ok) ok = check_corpus_warnings(file, path, s);
            n_ok++;
        } else {
            ok = r == want && s == NULL && strstr(err.msg, sub) != NULL && strstr(err.msg, file) != NULL;
            n_err++;
        }
        if (!ok) n_fail++;
        CHECK_MSG(ok, "%s: got %s '%s', want %s '%s'", file, pg_result_name(r), r ? err.msg : "",
                  code, sub);
        pg_scene_free(s);
    }
    fclose(f);
    printf("glTF corpus: %d error cases, %d valid files, %d mismatches\n", n_err, n_ok, n_fail);
    CHECK(n_err >= 30);
    test_corpus_valid_details();
    test_corpus_features();
    test_emissive_loader();
    test_gltf_features();
}

/* ---- compressed and quantized geometry (tests/corpus/gltf/compressed) ------------------------- */

typedef struct twin_err {
    double pos, nrm, tan, uv;
    bool same_indices, tan_w;
} twin_err;

/* Largest differences between primitive `p` of `s` and the one primitive of `twin`; the
 * indices (relative to each primitive's vertex_offset) must be equal, triangle by triangle; with
 * `rotated`, each triangle's three indices may be rotated (EXT_meshopt_compression TRIANGLES mode
 * keeps the triangle order and winding, not the first vertex). */
static twin_err twin_diff(const pg_scene *twin, const pg_scene *s, uint32_t p, bool rotated)
{
    twin_err e = {0, 0, 0, 0, false, false};
    const pg_primitive *a = &twin->primitives[0], *b = &s->primitives[p];
    if (a->index_count != b->index_count || a->index_count % 3) return e;
    e.same_indices = e.tan_w = true;
    const uint32_t *ia = twin->indices + a->first_index, *ib = s->indices + b->first_index;
    for (uint32_t t = 0; t < a->index_count; t += 3) {
        int rot = -1;
        for (int r = 0; r < (rotated ? 3 : 1) && rot < 0; r++)
            if (ia[t] == ib[t + r] && ia[t + 1] == ib[t + (r + 1) % 3] && ia[t + 2] == ib[t + (r + 2) % 3]) rot = r;
        e.same_indices = e.same_indices && rot >= 0;
    }
    for (uint32_t i = 0; i < a->index_count; i++) {
        const pg_vertex *va = &twin->vertices[a->vertex_offset + (int32_t)ia[i]];
        const pg_vertex *vb = &s->vertices[b->vertex_offset + (int32_t)ia[i]];
        for (int k = 0; k < 3; k++) {
            e.pos = fmax(e.pos, fabs((double)va->position[k] - vb->position[k]));
            e.nrm = fmax(e.nrm, fabs((double)va->normal[k] - vb->normal[k]));
            e.tan = fmax(e.tan, fabs((double)va->tangent[k] - vb->tangent[k]));
        }
        for (int k = 0; k < 2; k++) e.uv = fmax(e.uv, fabs((double)va->uv[k] - vb->uv[k]));
        e.tan_w = e.tan_w && va->tangent[3] == vb->tangent[3];
    }
    return e;
}

/* Like twin_diff, for a primitive whose points and triangles may be renumbered (Draco): each
 * triangle of `s` is matched to the twin triangle with the nearest centroid, its corners by the
 * rotation (winding kept) with the nearest positions; every twin triangle must be matched once. */
static twin_err twin_match(const pg_scene *twin, const pg_scene *s, uint32_t p)
{
    twin_err e = {0, 0, 0, 0, false, false};
    const pg_primitive *a = &twin->primitives[0], *b = &s->primitives[p];
    if (a->index_count != b->index_count || a->index_count % 3) return e;
    const uint32_t nt = a->index_count / 3;
    const uint32_t *ia = twin->indices + a->first_index, *ib = s->indices + b->first_index;
    const pg_vertex *va = twin->vertices + a->vertex_offset, *vb = s->vertices + b->vertex_offset;
    char *used = calloc(nt, 1);
    if (!used) return e;
    e.same_indices = e.tan_w = true;
    for (uint32_t t = 0; t < nt; t++) {
        float cb[3] = {0, 0, 0};
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < 3; j++) cb[j] += vb[ib[3 * t + k]].position[j] / 3;
        uint32_t best = 0;
        double bd = 1e30;
        for (uint32_t u = 0; u < nt; u++) {
            double d = 0;
            for (int j = 0; j < 3; j++) {
                float ca = (va[ia[3 * u]].position[j] + va[ia[3 * u + 1]].position[j] + va[ia[3 * u + 2]].position[j]) / 3;
                d += (ca - cb[j]) * (ca - cb[j]);
            }
            if (d < bd) bd = d, best = u;
        }
        if (used[best]) e.same_indices = false;
        used[best] = 1;
        int rot = 0;
        double rd = 1e30;
        for (int r = 0; r < 3; r++) {
            double d = 0;
            for (int k = 0; k < 3; k++)
                for (int j = 0; j < 3; j++)
                    d = fmax(d, fabs((double)va[ia[3 * best + k]].position[j] - vb[ib[3 * t + (k + r) % 3]].position[j]));
            if (d < rd) rd = d, rot = r;
        }
        for (int k = 0; k < 3; k++) {
            const pg_vertex *x = &va[ia[3 * best + k]], *y = &vb[ib[3 * t + (k + rot) % 3]];
            for (int j = 0; j < 3; j++) {
                e.pos = fmax(e.pos, fabs((double)x->position[j] - y->position[j]));
                e.nrm = fmax(e.nrm, fabs((double)x->normal[j] - y->normal[j]));
                e.tan = fmax(e.tan, fabs((double)x->tangent[j] - y->tangent[j]));
            }
            for (int j = 0; j < 2; j++) e.uv = fmax(e.uv, fabs((double)x->uv[j] - y->uv[j]));
            e.tan_w = e.tan_w && x->tangent[3] == y->tangent[3];
        }
    }
    free(used);
    return e;
}

static void test_compressed_twins(void)
{
    pg_scene *twin = load_corpus("compressed/twin.gltf");
    if (!twin) return;
    CHECK(twin->n_primitives == 1 && twin->n_vertices == 81 && twin->n_indices == 384);
    /* KHR_mesh_quantization: within half a quantization step (gen_compressed.py QUANT_STEPS:
     * position, normal/tangent component, texcoord) plus float rounding; normals and tangents are
     * renormalized after dequantization, which can move a component by up to one step. */
    static const struct {
        const char *file;
        double pos_step, nrm_step, uv_step;
    } q[] = {
        {"compressed/q_u16.gltf", 2.0 / 65535, 1.0 / 127, 1.0 / 65535},
        {"compressed/q_s16n.gltf", 1.0 / 32767, 1.0 / 32767, 1.0 / 32767},
        {"compressed/q_i8.gltf", 1.0 / 127, 1.0 / 127, 1.0 / 127},
        {"compressed/q_u8n.gltf", 2.0 / 255, 1.0 / 127, 1.0 / 255},
        {"compressed/q_s16.gltf", 2.0 / 65534, 1.0 / 32767, -8}, /* texcoords: integers, 8x the twin's */
    };
    for (size_t i = 0; i < sizeof q / sizeof q[0]; i++) {
        pg_scene *s = load_corpus(q[i].file);
        if (!s) continue;
        CHECK(s->n_primitives == 1 && s->n_vertices == twin->n_vertices);
        if (q[i].uv_step < 0 && s->n_vertices == twin->n_vertices) {
            /* not normalized SHORT texcoords are their integer values */
            bool exact = true;
            for (uint32_t v = 0; v < s->n_vertices; v++)
                for (int k = 0; k < 2; k++) exact = exact && s->vertices[v].uv[k] == 8 * twin->vertices[v].uv[k];
            CHECK_MSG(exact, "%s: texcoords are not 8x the twin's", q[i].file);
            for (uint32_t v = 0; v < s->n_vertices; v++)
                for (int k = 0; k < 2; k++) s->vertices[v].uv[k] /= 8;
        }
        twin_err e = twin_diff(twin, s, 0, false);
        printf("%s: max |d| position %.3g, normal %.3g, tangent %.3g, texcoord %.3g\n", q[i].file, e.pos, e.nrm,
               e.tan, e.uv);
        CHECK_MSG(e.same_indices && e.tan_w, "%s: indices or tangent handedness differ from the twin", q[i].file);
        CHECK_MSG(e.pos <= 0.5 * q[i].pos_step + 1e-6, "%s: position off by %g (step %g)", q[i].file, e.pos,
                  q[i].pos_step);
        CHECK_MSG(e.nrm <= q[i].nrm_step + 1e-6 && e.tan <= q[i].nrm_step + 1e-6,
                  "%s: normal/tangent off by %g/%g (step %g)", q[i].file, e.nrm, e.tan, q[i].nrm_step);
        CHECK_MSG(e.uv <= 0.5 * fabs(q[i].uv_step) * (q[i].uv_step > 0) + 1e-7, "%s: texcoord off by %g (step %g)", q[i].file, e.uv,
                  q[i].uv_step);
        CHECK(s->n_warnings == 0);
        pg_scene_free(s);
    }
    /* EXT_meshopt_compression (tests/gen_meshopt.c): POSITION (filter NONE) and both index
     * streams (TRIANGLES, INDICES) decode exactly; NORMAL went through the 16-bit octahedral
     * filter, TANGENT through the 16-bit quaternion filter (both normalized SHORT, renormalized:
     * within 2e-4), TEXCOORD_0 through the exponential
     * filter with a 24-bit mantissa shared by u and v (within 1e-6 for |uv| <= 1). */
    const char *mo[] = {"compressed/meshopt.gltf", "compressed/meshopt.glb"};
    for (size_t i = 0; i < 2; i++) {
        pg_scene *s = load_corpus(mo[i]);
        if (!s) continue;
        CHECK_MSG(s->n_primitives == 2 && s->n_vertices == 2 * twin->n_vertices, "%s: %u primitives", mo[i],
                  s->n_primitives);
        for (uint32_t p = 0; p < s->n_primitives && p < 2; p++) {
            twin_err e = twin_diff(twin, s, p, p == 0);
            printf("%s primitive %u: max |d| position %.3g, normal %.3g, tangent %.3g, texcoord %.3g\n", mo[i], p,
                   e.pos, e.nrm, e.tan, e.uv);
            CHECK_MSG(e.same_indices && e.tan_w && e.pos == 0, "%s primitive %u: indices/positions differ", mo[i], p);
            CHECK_MSG(e.nrm <= 2e-4 && e.tan <= 2e-4 && e.uv <= 1e-6, "%s primitive %u: normal %g tangent %g uv %g",
                      mo[i], p, e.nrm, e.tan, e.uv);
        }
        CHECK(s->n_warnings == 0);
        pg_scene_free(s);
    }
    /* KHR_draco_mesh_compression (tests/gen_draco.cpp): draco.gltf is unquantized (every value
     * exact); draco_q.gltf quantizes POSITION to 14 bits over the 2.0 extent (half step 6.1e-5),
     * TEXCOORD_0 to 12 bits over 1.0 (half step 1.22e-4), NORMAL (octahedral) and the generic
     * TANGENT attribute to 12 bits (within 2e-3 after renormalization). */
    static const struct {
        const char *file;
        double pos, nrm, uv;
    } dr[] = {{"compressed/draco.gltf", 0, 0, 0},
              {"compressed/draco_q.gltf", 0.5 * 2.0 / 16383 + 1e-6, 2e-3, 0.5 / 4095 + 1e-6},
              /* draco.gltf not required, its accessors with an all-zero fallback (not read) */
              {"compressed/draco_fallback.gltf", 0, 0, 0}};
    for (size_t i = 0; i < sizeof dr / sizeof dr[0]; i++) {
        pg_scene *s = load_corpus(dr[i].file);
        if (!s) continue;
        CHECK(s->n_primitives == 1);
        twin_err e = twin_match(twin, s, 0);
        printf("%s: max |d| position %.3g, normal %.3g, tangent %.3g, texcoord %.3g\n", dr[i].file, e.pos, e.nrm, e.tan,
               e.uv);
        CHECK_MSG(e.same_indices && e.tan_w, "%s: triangles or tangent handedness differ from the twin", dr[i].file);
        CHECK_MSG(e.pos <= dr[i].pos && e.nrm <= dr[i].nrm && e.tan <= dr[i].nrm && e.uv <= dr[i].uv,
                  "%s: position %g normal %g tangent %g uv %g", dr[i].file, e.pos, e.nrm, e.tan, e.uv);
        CHECK(s->n_warnings == 0);
        pg_scene_free(s);
    }
    pg_scene_free(twin);
}

/* ---- object framing, object lights, glTF cameras (tests/corpus/gltf/objects) ------------------ */

static pg_scene *load_object(const char *file)
{
    char path[PG_PATH_MAX];
    snprintf(path, sizeof path, "%s/corpus/gltf/objects/%s", PG_TEST_DIR, file);
    pg_scene *s = NULL;
    pg_error err = {0};
    if (pg_scene_load_gltf(path, &s, &err)) CHECK_MSG(0, "%s: %s", file, err.msg);
    return s;
}

/* Projects every vertex; *inside: all in front of near, behind far and in the image. *fill: the
 * larger of the vertices' screen box width over the image width and height over the image height
 * (1 = the object touches two opposite edges); *size: the box's larger side in pixels over the
 * image's shorter side; *off: the box centre's largest NDC offset from the image centre. */
static void projected_fill(const pg_scene *s, const pg_camera *cam, float w, float h, bool *inside, double *fill,
                           double *size, double *off)
{
    float V[16], P[16], VP[16];
    pg_camera_view(cam, V);
    pg_camera_proj(cam, P);
    pg_mat4_mul(P, V, VP);
    double x0 = 1e30, y0 = 1e30, x1 = -1e30, y1 = -1e30;
    *inside = true;
    for (uint32_t i = 0; i < s->n_vertices; i++) {
        float p[4] = {s->vertices[i].position[0], s->vertices[i].position[1], s->vertices[i].position[2], 1}, o[4];
        xform(VP, p, o);
        if (!(o[3] > 0)) {
            *inside = false;
            continue;
        }
        double x = o[0] / o[3], y = o[1] / o[3], z = o[2] / o[3];
        if (x < -1 || x > 1 || y < -1 || y > 1 || z < 0 || z > 1) *inside = false;
        x0 = fmin(x0, x), x1 = fmax(x1, x), y0 = fmin(y0, y), y1 = fmax(y1, y);
    }
    *fill = fmax(0.5 * (x1 - x0), 0.5 * (y1 - y0));
    *size = fmax(0.5 * (x1 - x0) * w, 0.5 * (y1 - y0) * h) / fmin(w, h);
    *off = fmax(fabs(0.5 * (x0 + x1)), fabs(0.5 * (y0 + y1)));
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void test_object_framing(void)
{
    /* every camera-less object of the corpus; the last five are flat (seen from the front) */
    const char *files[] = {"cube.gltf",   "sphere.gltf",     "rod.gltf",    "tiny.gltf",
                           "huge.gltf",   "tall.gltf",       "quad.gltf",   "panels.gltf",
                           "panel_back.gltf", "wall_x.gltf", "panel_tilted.gltf"};
    /* the camera's direction from the centre for the flat ones: quad faces +Y, panels +Z,
     * panel_back -Z, wall_x -X, panel_tilted (0, sin 30, -cos 30): no axis is thin along it */
    const float flat_dir[5][3] = {{0, 1, 0}, {0, 0, 1}, {0, 0, -1}, {-1, 0, 0}, {0, 0.5f, -0.8660254f}};
    const size_t n_files = sizeof files / sizeof files[0], first_flat = 6;
    const float aspects[] = {16.0f / 9, 1.0f, 9.0f / 16, 4.0f};
    double sizes[16];
    size_t n_sizes = 0;
    float cube_intensity = 0, cube_r = 0;
    for (size_t i = 0; i < n_files; i++) {
        pg_scene *s = load_object(files[i]);
        if (!s) continue;
        CHECK(s->n_cameras == 0 && s->cameras == NULL);
        for (size_t a = 0; a < sizeof aspects / sizeof aspects[0]; a++) {
            float r = 0, d = 0;
            pg_camera cam = pg_camera_frame_object(s, aspects[a], &r, &d);
            bool inside;
            double fill, size, off;
            projected_fill(s, &cam, 160.0f * aspects[a], 160.0f, &inside, &fill, &size, &off);
            CHECK_MSG(inside, "%s aspect %.2f: vertices not all in view", files[i], aspects[a]);
            /* fitted into 90% of the tighter half-angle, centred */
            CHECK_MSG(fill >= 0.85 && fill <= 0.901, "%s aspect %.2f: fill %.3f", files[i], aspects[a], fill);
            CHECK_MSG(off <= 0.01, "%s aspect %.2f: off-centre by %.3f", files[i], aspects[a], off);
            if (a == 0 && n_sizes < 16) sizes[n_sizes++] = size;
            /* near/far hug the vertices: depth precision follows the object's size */
            CHECK_MSG(cam.near_z > 0 && cam.far_z > cam.near_z && cam.far_z / cam.near_z < 20.0f,
                      "%s: near %g far %g d %g", files[i], cam.near_z, cam.far_z, d);
            float c[3], v[3];
            for (int k = 0; k < 3; k++) {
                c[k] = cam.target[k];
                v[k] = cam.position[k] - c[k];
            }
            float vl = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            if (i < first_flat) { /* 3/4 view: from above and in front (+Y, +Z), to the side (+X) */
                CHECK(v[1] > 0 && v[2] > 0 && v[0] > 0);
            } else { /* from the front: along the face's normal */
                const float *fd = flat_dir[i - first_flat];
                CHECK_MSG((v[0] * fd[0] + v[1] * fd[1] + v[2] * fd[2]) > 0.9999f * vl, "%s: seen from (%g,%g,%g)",
                          files[i], v[0] / vl, v[1] / vl, v[2] / vl);
            }
        }
        float r = 0;
        pg_camera_frame_object(s, 1.0f, &r, NULL);
        pg_light_setup L = pg_light_setup_object(s, 256, 3);
        for (int k = 0; k < 3; k++) /* the box surrounds the bounds */
            CHECK(L.box_min[k] < s->bounds_min[k] - 0.5f * r && L.box_max[k] > s->bounds_max[k] + 0.5f * r);
        CHECK(fabsf(L.radius - 1.5f * r) <= 1e-5f * r);
        CHECK(L.ambient == PG_OBJECT_AMBIENT);
        if (!strcmp(files[i], "cube.gltf")) {
            cube_intensity = L.intensity;
            cube_r = r;
            CHECK(fabsf(L.intensity - PG_OBJECT_LIGHT_K * r * r) < 1e-6f);
            /* the total stays when the count changes */
            pg_light_setup L4 = pg_light_setup_object(s, 1024, 3);
            CHECK(fabsf(L4.intensity * 4 - L.intensity) < 1e-6f);
        }
        if (!strcmp(files[i], "huge.gltf") && cube_r > 0) /* intensity ~ r^2 */
            CHECK_MSG(fabs(L.intensity / cube_intensity / ((r / cube_r) * (r / cube_r)) - 1) < 1e-3,
                      "huge: intensity %g", L.intensity);
        pg_scene_free(s);
    }
    /* docs/scenes.md: at 16:9 the median object's screen box spans at least 0.8 of the image's
     * shorter side (the smallest at least 0.5) */
    CHECK(n_sizes == n_files);
    if (n_sizes == n_files) {
        qsort(sizes, n_sizes, sizeof sizes[0], cmp_double);
        CHECK_MSG(sizes[0] >= 0.5 && sizes[n_sizes / 2] >= 0.8, "sizes: smallest %.2f, median %.2f", sizes[0],
                  sizes[n_sizes / 2]);
    }
    /* empty / NULL scene: the unit box, still valid */
    pg_camera c0 = pg_camera_frame_object(NULL, 0.0f, NULL, NULL);
    CHECK(c0.aspect == 1.0f && c0.near_z > 0 && c0.far_z > c0.near_z);
}

/* --gltf-scene: the file's default scene, another one by index, an index out of range (an error
 * naming the count and the names), the atrium refusing it, and the line the tools print. */
static void test_gltf_scene_choice(void)
{
    char path[PG_PATH_MAX], line[PG_PATH_MAX + 160];
    snprintf(path, sizeof path, "%s/corpus/gltf/objects/two_scenes.gltf", PG_TEST_DIR);
    pg_error err = {0};
    pg_scene *s = NULL;
    CHECK_MSG(pg_scene_load(path, &s, &err) == PG_OK, "%s", err.msg);
    if (s) {
        CHECK(s->n_gltf_scenes == 2 && s->gltf_scene == 0 && !s->gltf_scene_chosen);
        CHECK(!strcmp(s->gltf_scene_name, "small"));
        CHECK(fabsf(s->bounds_max[0] - 0.5f) < 1e-6f);
        CHECK(pg_scene_choice_line(s, line, sizeof line) && strstr(line, "has 2 scenes; drawing scene 0 'small' (the "
                                                                        "file's default); --gltf-scene N"));
        pg_scene_free(s);
    }
    pg_scene_load_opts o = {.gltf_scene = 1};
    s = NULL;
    CHECK_MSG(pg_scene_load_ex(path, &o, &s, &err) == PG_OK, "%s", err.msg);
    if (s) {
        CHECK(s->gltf_scene == 1 && s->gltf_scene_chosen && !strcmp(s->gltf_scene_name, "big"));
        CHECK_MSG(fabsf(s->bounds_max[0] - 11.5f) < 1e-5f && fabsf(s->bounds_min[0] - 8.5f) < 1e-5f, "big: x %g..%g",
                  s->bounds_min[0], s->bounds_max[0]);
        CHECK(pg_scene_choice_line(s, line, sizeof line) && strstr(line, "drawing scene 1 'big' (--gltf-scene)"));
        pg_scene_free(s);
    }
    o.gltf_scene = 2;
    s = NULL;
    CHECK(pg_scene_load_ex(path, &o, &s, &err) == PG_ERR_INVALID_ARG && s == NULL);
    CHECK_MSG(strstr(err.msg, "two_scenes.gltf: --gltf-scene 2: out of range (the file has 2 scenes: 0 'small', 1 "
                              "'big')"),
              "%s", err.msg);
    CHECK(pg_scene_load_ex("default", &o, &s, &err) == PG_ERR_INVALID_ARG && strstr(err.msg, "--gltf-scene 2"));
    /* a one-scene file says nothing */
    snprintf(path, sizeof path, "%s/corpus/gltf/objects/cube.gltf", PG_TEST_DIR);
    s = NULL;
    CHECK(pg_scene_load(path, &s, &err) == PG_OK);
    if (s) {
        CHECK(s->n_gltf_scenes == 1 && s->gltf_scene == 0 && !pg_scene_choice_line(s, line, sizeof line) && !line[0]);
        pg_scene_free(s);
    }
}

static pg_scene *load_lights(const char *file)
{
    char path[PG_PATH_MAX];
    snprintf(path, sizeof path, "%s/corpus/gltf/lights/%s", PG_TEST_DIR, file);
    pg_scene *s = NULL;
    pg_error err = {0};
    if (pg_scene_load_gltf(path, &s, &err)) CHECK_MSG(0, "%s: %s", file, err.msg);
    return s;
}

static bool near3(const float *v, float x, float y, float z, float tol)
{
    return fabsf(v[0] - x) <= tol && fabsf(v[1] - y) <= tol && fabsf(v[2] - z) <= tol;
}

/* KHR_lights_punctual: types, colours, intensities, ranges, cones, placement through the node
 * hierarchy (tests/corpus/gltf/lights/gen_lights.py); the bad cases are MANIFEST lines. */
static void test_file_lights(void)
{
    pg_scene *s = load_lights("rgb_points.gltf");
    if (s) {
        CHECK(s->n_lights == 3);
        if (s->n_lights == 3) {
            const pg_scene_light *L = s->lights;
            CHECK(L[0].type == PG_LIGHT_POINT && !strcmp(L[0].name, "red") && L[0].gltf_light == 0);
            CHECK(near3(L[0].position, -3, 2, 0, 1e-6f) && near3(L[1].position, 0, 2, 0, 1e-6f) &&
                  near3(L[2].position, 3, 2, 0, 1e-6f));
            CHECK(near3(L[0].color, 1, 0, 0, 0) && near3(L[1].color, 0, 1, 0, 0) && near3(L[2].color, 0, 0, 1, 0));
            CHECK(L[0].range == 4.0f && L[1].range == 0.0f && L[2].intensity == 5.0f);
        }
        pg_scene_free(s);
    }
    s = load_lights("spot.gltf");
    if (s) {
        CHECK(s->n_lights == 1);
        if (s->n_lights == 1) {
            const pg_scene_light *L = s->lights;
            CHECK(L->type == PG_LIGHT_SPOT && fabsf(L->inner_cone - 0.3f) < 1e-7f && fabsf(L->outer_cone - 0.5f) < 1e-7f);
            CHECK(near3(L->position, 0, 3, 0, 1e-6f) && near3(L->direction, 0, -1, 0, 1e-6f));
            CHECK(near3(L->color, 1, 1, 1, 0) && L->intensity == 20.0f); /* default colour white */
        }
        pg_scene_free(s);
    }
    s = load_lights("sun.gltf");
    if (s) {
        CHECK(s->n_lights == 1);
        if (s->n_lights == 1) { /* -Z turned -60 degrees about X: down and towards -Z */
            CHECK(s->lights[0].type == PG_LIGHT_DIRECTIONAL && s->lights[0].range == 0.0f);
            CHECK_MSG(near3(s->lights[0].direction, 0, -0.8660254f, -0.5f, 1e-6f), "sun direction %g %g %g",
                      s->lights[0].direction[0], s->lights[0].direction[1], s->lights[0].direction[2]);
        }
        pg_scene_free(s);
    }
    s = load_lights("mixed.gltf");
    if (s) {
        CHECK(s->n_lights == 3 && s->lights[0].type == PG_LIGHT_POINT && s->lights[1].type == PG_LIGHT_SPOT &&
              s->lights[2].type == PG_LIGHT_DIRECTIONAL);
        pg_scene_free(s);
    }
    /* PASSGRAPH_lights_table: two records */
    pg_error err = {0};
    s = NULL;
    CHECK(pg_scene_load_gltf(PG_TEST_DIR "/corpus/gltf/ok_lights_table.gltf", &s, &err) == PG_OK);
    if (s) {
        CHECK(s->n_lights == 2);
        if (s->n_lights == 2) {
            const pg_scene_light *L = s->lights;
            CHECK(L[0].type == PG_LIGHT_POINT && near3(L[0].position, 0, 1, 0, 0) && L[0].range == 2.0f &&
                  near3(L[0].color, 1, 0.5f, 0.25f, 0) && L[0].intensity == 3.0f && L[0].gltf_node == -1);
            CHECK(near3(L[1].position, 1, 2, 3, 0) && L[1].range == 0.0f && near3(L[1].color, 0, 1, 0, 0));
        }
        pg_scene_free(s);
    }
    s = load_object("cube.gltf"); /* no extension: no lights */
    if (s) {
        CHECK(s->n_lights == 0 && s->lights == NULL);
        pg_scene_free(s);
    }
}

/* 1,000,000 lights in a PASSGRAPH_lights_table load (the time is printed: a benchmark, not a
 * bound; docs/scenes.md) with every record intact */
static void test_million_table_lights(void)
{
    char dir[] = "/tmp/pg_table_XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK_MSG(0, "mkdtemp failed");
        return;
    }
    const uint32_t n = 1000000;
    char bin[64], gltf[64];
    snprintf(bin, sizeof bin, "%s/t.bin", dir);
    snprintf(gltf, sizeof gltf, "%s/t.gltf", dir);
    FILE *f = fopen(bin, "wb");
    CHECK(f != NULL);
    if (!f) return;
    /* a triangle (3 positions, 3 indices as uint32) then the table */
    const float tri[9] = {0, 0, 0, 1, 0, 0, 0, 0, 1};
    const uint32_t idx[3] = {0, 1, 2};
    fwrite(tri, sizeof tri, 1, f);
    fwrite(idx, sizeof idx, 1, f);
    for (uint32_t i = 0; i < n; i++) {
        float r[8] = {(float)(i % 1000), (float)(i / 1000), 1.0f, 0.5f, 1.0f, 0.5f, 0.25f, (float)i};
        fwrite(r, sizeof r, 1, f);
    }
    fclose(f);
    f = fopen(gltf, "w");
    CHECK(f != NULL);
    if (!f) return;
    fprintf(f,
            "{\"asset\": {\"version\": \"2.0\"}, \"extensionsUsed\": [\"PASSGRAPH_lights_table\"],\n"
            " \"extensions\": {\"PASSGRAPH_lights_table\": {\"bufferView\": 2, \"count\": %u}},\n"
            " \"scene\": 0, \"scenes\": [{\"nodes\": [0]}], \"nodes\": [{\"mesh\": 0}],\n"
            " \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0}, \"indices\": 1}]}],\n"
            " \"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": 3, \"type\": \"VEC3\",\n"
            "   \"min\": [0, 0, 0], \"max\": [1, 0, 1]},\n"
            "  {\"bufferView\": 1, \"componentType\": 5125, \"count\": 3, \"type\": \"SCALAR\"}],\n"
            " \"bufferViews\": [{\"buffer\": 0, \"byteLength\": 36}, {\"buffer\": 0, \"byteOffset\": 36, "
            "\"byteLength\": 12},\n"
            "   {\"buffer\": 0, \"byteOffset\": 48, \"byteLength\": %u}],\n"
            " \"buffers\": [{\"uri\": \"t.bin\", \"byteLength\": %u}]}\n",
            n, n * 32u, 48u + n * 32u);
    fclose(f);
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    pg_scene *s = NULL;
    pg_error err = {0};
    pg_result r = pg_scene_load_gltf(gltf, &s, &err);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    double sec = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    CHECK_MSG(r == PG_OK, "%s", err.msg);
    if (s) {
        printf("1,000,000 table lights loaded in %.3f s\n", sec);
        CHECK(s->n_lights == n);
        if (s->n_lights == n) {
            const pg_scene_light *L = &s->lights[123456];
            CHECK(near3(L->position, 456, 123, 1, 0) && L->intensity == 123456.0f && L->range == 0.5f);
        }
        pg_scene_free(s);
    }
    remove(bin);
    remove(gltf);
    rmdir(dir);
}

static void test_gltf_cameras(void)
{
    pg_error err = {0};
    pg_scene *s = load_object("camera.gltf");
    if (s) {
        CHECK(s->n_cameras == 1);
        if (s->n_cameras == 1) {
            const pg_scene_camera *c = &s->cameras[0];
            CHECK(!strcmp(c->name, "front") && !strcmp(c->node_name, "front_node"));
            CHECK(c->type == PG_CAMERA_PERSPECTIVE && c->gltf_camera == 0 && c->gltf_node == 1);
            CHECK(fabsf(c->yfov_rad - 0.6f) < 1e-6f && fabsf(c->znear - 0.1f) < 1e-7f && fabsf(c->zfar - 100) < 1e-4f);
            CHECK(fabsf(c->aspect_ratio - 1.5f) < 1e-6f);
            CHECK(fabsf(c->position[0] - 0.5f) < 1e-6f && fabsf(c->position[1] - 0.8f) < 1e-6f &&
                  fabsf(c->position[2] - 3.0f) < 1e-6f);
            /* looks at the origin (gen_objects.py), up has no component along forward */
            float l = sqrtf(0.25f + 0.64f + 9.0f);
            CHECK(fabsf(c->forward[0] + 0.5f / l) < 1e-5f && fabsf(c->forward[1] + 0.8f / l) < 1e-5f &&
                  fabsf(c->forward[2] + 3.0f / l) < 1e-5f);
            CHECK(fabsf(c->up[0] * c->forward[0] + c->up[1] * c->forward[1] + c->up[2] * c->forward[2]) < 1e-5f &&
                  c->up[1] > 0.9f);
            pg_camera cam;
            CHECK(pg_camera_from_scene(s, 0, 2.0f, &cam, &err) == PG_OK);
            CHECK(fabsf(cam.fov_y_deg - 0.6f * 180.0f / 3.14159265f) < 1e-3f && cam.aspect == 2.0f);
            CHECK(cam.near_z == c->znear && cam.far_z == c->zfar);
            /* the origin projects to the image centre */
            float V[16], P[16], VP[16], o4[4], org[4] = {0, 0, 0, 1};
            pg_camera_view(&cam, V);
            pg_camera_proj(&cam, P);
            pg_mat4_mul(P, V, VP);
            xform(VP, org, o4);
            CHECK(o4[3] > 0 && fabsf(o4[0] / o4[3]) < 1e-4f && fabsf(o4[1] / o4[3]) < 1e-4f);
        }
        uint32_t idx = 9;
        CHECK(pg_scene_find_camera(s, "0", &idx, &err) == PG_OK && idx == 0);
        CHECK(pg_scene_find_camera(s, "front", &idx, &err) == PG_OK && idx == 0);
        CHECK(pg_scene_find_camera(s, "front_node", &idx, &err) == PG_OK && idx == 0);
        CHECK(pg_scene_find_camera(s, "1", &idx, &err) == PG_ERR_INVALID_ARG);
        CHECK_MSG(strstr(err.msg, "--camera 1: no such camera") && strstr(err.msg, "0 'front' (node 'front_node')") &&
                      strstr(err.msg, "or auto"),
                  "%s", err.msg);
        pg_scene_free(s);
    }
    s = load_object("two_cameras.gltf");
    if (s) {
        CHECK(s->n_cameras == 2);
        if (s->n_cameras == 2) {
            CHECK(!strcmp(s->cameras[0].name, "side") && s->cameras[0].zfar == 0);
            CHECK(!strcmp(s->cameras[1].name, "top") && s->cameras[1].type == PG_CAMERA_ORTHOGRAPHIC);
            CHECK(s->cameras[1].xmag == 1.0f && s->cameras[1].ymag == 1.0f && s->cameras[1].zfar == 10.0f);
            CHECK(s->cameras[1].forward[1] < -0.999f); /* rotated -90 deg about X: looks down */
            pg_camera cam;
            CHECK(pg_camera_from_scene(s, 0, 1.0f, &cam, &err) == PG_OK);
            /* infinite zfar: twice the farthest bounds corner from (4,0,0) = 2*|(4.5,.5,.5)|, or 1000 near */
            float want = fmaxf(2.0f * sqrtf(4.5f * 4.5f + 0.5f), 1000.0f * 0.05f);
            CHECK_MSG(fabsf(cam.far_z - want) < 1e-3f * want, "far %g want %g", cam.far_z, want);
            CHECK(cam.ortho_height == 0);
            /* orthographic: full height 2 ymag, near/far kept; the projection maps y = +-ymag to the
             * image edges, x = +-ymag * aspect, z_ndc linear from near to far, w = 1 */
            CHECK(pg_camera_from_scene(s, 1, 2.0f, &cam, &err) == PG_OK);
            CHECK(cam.ortho_height == 2.0f && cam.near_z == 0.1f && cam.far_z == 10.0f && cam.aspect == 2.0f);
            float P[16];
            pg_camera_proj(&cam, P);
            CHECK(fabsf(P[0] - 0.5f) < 1e-7f && fabsf(P[5] + 1.0f) < 1e-7f && P[11] == 0 && P[15] == 1.0f);
            CHECK(fabsf(P[10] * -0.1f + P[14]) < 1e-7f && fabsf(P[10] * -10.0f + P[14] - 1.0f) < 1e-6f);
            CHECK(pg_camera_from_scene(s, 2, 1.0f, &cam, &err) == PG_ERR_INVALID_ARG);
        }
        uint32_t idx = 9;
        CHECK(pg_scene_find_camera(s, "top", &idx, &err) == PG_OK && idx == 1);
        CHECK(pg_scene_find_camera(s, "side_node", &idx, &err) == PG_OK && idx == 0);
        CHECK(pg_scene_find_camera(s, "1", &idx, &err) == PG_OK && idx == 1);
        CHECK(pg_scene_find_camera(s, "nope", &idx, &err) == PG_ERR_INVALID_ARG);
        CHECK_MSG(strstr(err.msg, "0 'side' (node 'side_node')") && strstr(err.msg, "1 'top' (node 'top_node', orthographic)"),
                  "%s", err.msg);
        pg_scene_free(s);
    }
    /* a negative xmag/ymag (the specification: should not be) drew a 45-degree perspective view */
    if ((s = load_corpus("ok_camera_ortho_negative.gltf"))) {
        pg_camera cam;
        CHECK(s->n_cameras == 1 && s->cameras[0].type == PG_CAMERA_ORTHOGRAPHIC && s->cameras[0].ymag == 2.0f);
        CHECK(pg_camera_from_scene(s, 0, 1.0f, &cam, &err) == PG_OK && cam.ortho_height == 4.0f);
        pg_scene_free(s);
    }
    s = load_object("cube.gltf");
    if (s) {
        uint32_t idx;
        CHECK(pg_scene_find_camera(s, "0", &idx, &err) == PG_ERR_INVALID_ARG);
        CHECK_MSG(strstr(err.msg, "has no cameras; use --camera auto"), "%s", err.msg);
        pg_scene_free(s);
    }
    /* the atrium has no cameras; its interior camera is unchanged (docs and tests depend on it) */
    pg_scene *d = NULL;
    if (pg_scene_create_default(&d, &err) == PG_OK) {
        CHECK(d->n_cameras == 0 && d->cameras == NULL);
        pg_scene_free(d);
    }
}

/* Bad camera objects in a file: errors name the glTF object. */
static void test_gltf_camera_errors(void)
{
    const char *tmpl =
        "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0,1]}],"
        "\"nodes\":[{\"mesh\":0},{\"camera\":0}],\"cameras\":[%s],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],"
        "\"buffers\":[{\"byteLength\":36,\"uri\":\"data:application/octet-stream;base64,"
        "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA\"}]}";
    struct {
        const char *cam, *want;
    } cases[] = {
        {"{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.7,\"znear\":0.1}}", NULL},
        {"{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.7,\"znear\":0.1,\"zfar\":0.05}}",
         "cameras[0].perspective.zfar"},
        {"{\"type\":\"perspective\",\"perspective\":{\"yfov\":4.0,\"znear\":0.1}}", "cameras[0].perspective.yfov"},
    };
    char path[PG_PATH_MAX];
    snprintf(path, sizeof path, "/tmp/pg_test_scene_cam_%d.gltf", (int)getpid());
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char text[2048];
        snprintf(text, sizeof text, tmpl, cases[i].cam);
        write_text(path, text);
        pg_scene *s = NULL;
        pg_error err = {0};
        pg_result r = pg_scene_load_gltf(path, &s, &err);
        if (!cases[i].want) {
            CHECK_MSG(r == PG_OK && s && s->n_cameras == 1 && !strcmp(s->cameras[0].name, "cameras[0]") &&
                          !strcmp(s->cameras[0].node_name, "nodes[1]"),
                      "case %zu: %s", i, err.msg);
        } else {
            CHECK_MSG(r != PG_OK && strstr(err.msg, cases[i].want), "case %zu: %d %s", i, r, err.msg);
        }
        pg_scene_free(s);
    }
    unlink(path);
}

static void test_api_edges(void)
{
    pg_scene *s = (pg_scene *)1;
    pg_error err = {0};
    CHECK(pg_scene_load(NULL, &s, &err) == PG_ERR_INVALID_ARG && s == NULL);
    CHECK(pg_scene_load("", &s, &err) == PG_ERR_INVALID_ARG);
    CHECK(pg_scene_load_gltf(PG_TEST_DIR "/corpus/gltf/nothing_here.gltf", &s, &err) == PG_ERR_IO);
    CHECK(strstr(err.msg, "nothing_here.gltf") != NULL);
    pg_scene_free(NULL);
    pg_texture_release(NULL);
}

int main(void)
{
    test_textures();
    test_camera();
    test_default_scene();
    test_scenarios();
    test_corpus();
    test_compressed_twins();
    test_api_edges();
    test_object_framing();
    test_gltf_cameras();
    test_gltf_scene_choice();
    test_file_lights();
    test_million_table_lights();
    test_gltf_camera_errors();
    test_sponza();
    return pg_test_finish("test_scene");
}
