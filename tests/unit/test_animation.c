/* test_animation.c - glTF animation on the CPU (scene/animation.h, the loader's
 * scene/scene_gltf_anim.cpp) against poses worked out by hand for the generated files of
 * tests/corpus/gltf/animation (README there):
 *  - rigid.gltf: a box spinning about +Y (LINEAR quaternions), stepping in x (STEP), a child scaled
 *    by a CUBICSPLINE channel; a second animation moving it up (LINEAR);
 *  - skinned.gltf: a tube skinned to two joints, the elbow bent about +Z; the skinned mesh node's
 *    own translation (5, 0, 0) must be ignored;
 *  - skinned8.gltf: 8 joints a vertex (JOINTS_1/WEIGHTS_1): the top rings weigh 8 joints 1/8 each,
 *    4 of them rising by 2 (the rings rise by 1; by 0 if the second set were dropped);
 *  - morph.gltf: a cube with two morph targets (one a sparse accessor), mesh default weights
 *    [0.25, 0] and a LINEAR weights channel;
 *  - pointer.gltf: rigid.gltf's animations through KHR_animation_pointer: the same poses;
 *  - beacon.gltf: a spot light's colour, intensity, range and cones and a camera's yfov and zfar
 *    animated through KHR_animation_pointer;
 *  - shimmer.gltf: materials' base colour, metallic, roughness, emissive and its strength, a texture
 *    transform, an alpha cutoff, a normal scale and an occlusion strength animated through
 *    KHR_animation_pointer (and one ignored pointer);
 *  - mirror.gltf: boxes and double-sided panels whose animated scale mirrors them against the
 *    winding of their rest pose: rewound when posed.
 * Every position within 1e-5 of the hand value; the loop, the rest pose, --animation lookup, the
 * scene bounds following the pose, and files whose animation data is broken (refused naming the
 * object). */
#define _DEFAULT_SOURCE /* mkstemps */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "animation.h"
#include "scene.h"
#include "test_scene_file.h"
#include "test_util.h"

/* a file of tests/corpus/gltf/animation, loaded (NULL and a failed check when it does not load) */
static pg_scene *load_file(const char *rel) { return pg_test_load_gltf("animation", rel); }

/* likewise, a file whose geometry moves */
static pg_scene *load(const char *rel)
{
    pg_scene *s = load_file(rel);
    if (!s) return NULL;
    CHECK_MSG(s->anim && s->features.has_animation, "%s: no animation data", rel);
    return s;
}

/* the scene vertex of node `node`'s moving primitive, local index i */
static const float *vert(const pg_scene *s, uint32_t node, uint32_t i)
{
    for (uint32_t p = 0; p < s->anim->n_prims; p++)
        if (s->anim->prims[p].node == node) return s->vertices[s->anim->prims[p].first_vertex + i].position;
    CHECK_MSG(0, "no moving primitive on node %u", node);
    static const float zero[3] = {0, 0, 0};
    return zero;
}

static void expect(pg_scene *s, int anim, double t, uint32_t node, uint32_t i, double x, double y, double z,
                   const char *what)
{
    pg_error err = {0};
    CHECK(pg_scene_pose(s, anim, t, &err) == PG_OK);
    const float *p = vert(s, node, i);
    const double d = fmax(fabs(p[0] - x), fmax(fabs(p[1] - y), fabs(p[2] - z)));
    CHECK_MSG(d < 1e-5, "%s at t=%g: (%g, %g, %g), expected (%g, %g, %g)", what, t, p[0], p[1], p[2], x, y, z);
}

static void rigid(void)
{
    pg_scene *s = load("rigid.gltf");
    if (!s) return;
    CHECK(s->anim->n_animations == 2 && !strcmp(s->anim->animations[0].name, "spin"));
    CHECK(fabsf(s->anim->animations[0].end - 4.0f) < 1e-6f);
    const double r = sqrt(0.5);
    expect(s, 0, 0, 1, 10, 0.5, 1, 0.5, "spinner v10");
    expect(s, 0, 0.5, 1, 10, r, 1, 0, "spinner v10 (slerp 45 deg)");
    expect(s, 0, 1, 1, 10, 0.5, 1, -0.5, "spinner v10");
    expect(s, 0, 2, 1, 10, 1.5, 1, -0.5, "spinner v10 (STEP to x = 2)");
    expect(s, 0, 3, 1, 10, 1.5, 1, 0.5, "spinner v10");
    expect(s, 0, 7, 1, 10, 1.5, 1, 0.5, "spinner v10 (t = 7 loops to 3)");
    expect(s, 0, 0, 2, 10, 1.75, 0.75, 0.25, "satellite v10");
    expect(s, 0, 0.5, 2, 10, 1.452883, 0.777344, -1.060660, "satellite v10 (CUBICSPLINE scale)");
    expect(s, 0, 1, 2, 10, 0.34375, 0.84375, -1.84375, "satellite v10");
    expect(s, 0, 2, 2, 10, 0, 1, -0.5, "satellite v10");
    expect(s, 1, 0.5, 1, 10, 0.5, 1.75, 0.5, "spinner v10 under 'bounce'");
    expect(s, 1, 1, 1, 10, 0.5, 2.5, 0.5, "spinner v10 under 'bounce'");
    pg_error err = {0};
    CHECK(pg_scene_pose(s, 1, 1, &err) == PG_OK);
    CHECK_MSG(fabsf(s->bounds_max[1] - 2.5f) < 1e-5f, "bounds follow the pose: max y %g", s->bounds_max[1]);
    int a = -5;
    CHECK(pg_anim_find(s->anim, "bounce", &a, &err) == PG_OK && a == 1);
    CHECK(pg_anim_find(s->anim, "0", &a, &err) == PG_OK && a == 0);
    CHECK(pg_anim_find(s->anim, "all", &a, &err) == PG_OK && a == PG_ANIM_ALL);
    CHECK(pg_anim_find(s->anim, "none", &a, &err) == PG_OK && a == PG_ANIM_NONE);
    CHECK(pg_anim_find(s->anim, "walk", &a, &err) == PG_ERR_INVALID_ARG && strstr(err.msg, "0 'spin'") &&
          strstr(err.msg, "1 'bounce'"));
    CHECK(pg_anim_find(s->anim, "2", &a, &err) == PG_ERR_INVALID_ARG);
    expect(s, PG_ANIM_NONE, 3, 1, 10, 0.5, 1, 0.5, "spinner v10 in the rest pose");
    char line[256];
    CHECK(pg_anim_describe(s, 0, 5, line, sizeof line) && strstr(line, "'spin'") && strstr(line, "t = 1 s"));
    /* a whole number of loops: forward it plays the last key, backward the first (printed 0, not -0) */
    CHECK(pg_anim_local_time(s->anim, 0, 4.0) == 4.0 && pg_anim_local_time(s->anim, 0, -3.0) == 1.0);
    CHECK(pg_anim_describe(s, 0, -4, line, sizeof line) && strstr(line, "at t = 0 s") && !strstr(line, "-0"));
    pg_scene_free(s);
}

/* nonunit.gltf: rotation keys of length 0.5 are normalised at load: slerp turns by 30 deg at t = 0.25
 * (32.2 deg before), and the keys themselves are whole turns of the unit box */
static void nonunit(void)
{
    pg_scene *s = load("nonunit.gltf");
    if (!s) return;
    expect(s, 0, 0.25, 1, 10, 0.6830127, 1, 0.1830127, "spinner v10 (slerp 30 deg between halved keys)");
    expect(s, 0, 1, 1, 10, 0.5 * (cos(2.0943951) + sin(2.0943951)), 1, 0.5 * (cos(2.0943951) - sin(2.0943951)),
           "spinner v10 (the last key, 120 deg)");
    pg_scene_free(s);
}

/* pointer.gltf: rigid.gltf's animations with KHR_animation_pointer targets (/nodes/N/path): every
 * vertex of every moving primitive equal, bit for bit, at every time of both animations; its
 * channel on a material's KHR_materials_ior ior (not animated by passgraph) is ignored with one
 * warning naming the pointer */
static void pointer(void)
{
    pg_scene *p = load("pointer.gltf"), *r = load("rigid.gltf");
    if (p && r) {
        CHECK(p->anim->n_animations == 2 && p->anim->animations[0].n_channels == 3 &&
              p->anim->animations[1].n_channels == 1 && p->n_vertices == r->n_vertices);
        uint32_t differ = 0;
        for (int a = 0; a < 2; a++)
            for (double t = 0; t <= 4.0; t += 0.25) {
                pg_error err = {0};
                CHECK(pg_scene_pose(p, a, t, &err) == PG_OK && pg_scene_pose(r, a, t, &err) == PG_OK);
                for (uint32_t v = 0; v < p->n_vertices && p->n_vertices == r->n_vertices; v++)
                    differ += memcmp(p->vertices[v].position, r->vertices[v].position, sizeof(float[3])) != 0;
            }
        CHECK_MSG(differ == 0, "pointer.gltf: %u vertex poses differ from rigid.gltf's", differ);
        uint32_t lines = 0;
        for (uint32_t i = 0; i < p->n_warnings; i++)
            lines += strstr(p->warnings[i], "KHR_animation_pointer: 1 channel ignored "
                                            "(/materials/1/extensions/KHR_materials_ior/ior)") != NULL;
        CHECK_MSG(lines == 1 && p->n_warnings == 1, "pointer.gltf: %u warnings, %u naming the material pointer",
                  p->n_warnings, lines);
        printf("pointer.gltf: the same poses as rigid.gltf at 34 times; %s\n", p->n_warnings ? p->warnings[0] : "");
    }
    pg_scene_free(p);
    pg_scene_free(r);
}

/* beacon.gltf: a spot light's colour, intensity, range and cones animated by KHR_animation_pointer
 * (README there): the posed light against the hand values, the rest pose the file's */
static void light_expect(pg_scene *s, int anim, double t, const float want[7], const char *what)
{
    pg_error err = {0};
    CHECK(pg_scene_pose(s, anim, t, &err) == PG_OK);
    const pg_scene_light *L = &s->lights[0];
    const float got[7] = {L->color[0], L->color[1], L->color[2], L->intensity, L->range, L->inner_cone, L->outer_cone};
    float d = 0;
    for (int k = 0; k < 7; k++) d = fmaxf(d, fabsf(got[k] - want[k]));
    CHECK_MSG(d < 1e-5f, "%s at t=%g: colour (%g, %g, %g) intensity %g range %g cones %g %g", what, t, got[0], got[1],
              got[2], got[3], got[4], got[5], got[6]);
    CHECK_MSG(fabsf(L->position[1] - 3) < 1e-5f && fabsf(L->direction[1] + 1) < 1e-5f, "%s: the light moved", what);
}

static void beacon(void)
{
    pg_scene *s = load_file("beacon.gltf");
    if (!s) return;
    pg_error err = {0};
    CHECK(s->anim && !s->features.has_animation && s->n_lights == 1 && s->n_warnings == 0);
    CHECK(pg_anim_light_animated(s->anim, 0) && !pg_anim_light_animated(s->anim, 1) &&
          !pg_anim_light_animated(s->anim, -1));
    const float rest[7] = {1, 1, 1, 20, 8, 0.3f, 0.6f}, t1[7] = {1, 0.65f, 0.6f, 30, 8, 0.25f, 0.675f},
                t3[7] = {0.6f, 0.35f, 0.6f, 50, 4, 0.15f, 0.825f};
    light_expect(s, 0, 1, t1, "beacon");
    light_expect(s, 0, 3, t3, "beacon (range stepped to 4)");
    light_expect(s, PG_ANIM_NONE, 3, rest, "beacon in the rest pose");
    light_expect(s, 0, 5, t1, "beacon (t = 5 loops to 1)");
    /* the camera's projection: yfov 0.8 -> 0.4 and zfar 50 -> 30 over 4 s, znear and its place kept */
    CHECK(s->n_cameras == 1 && pg_anim_camera_animated(s->anim, 0) && !pg_anim_camera_animated(s->anim, 1));
    const double cams[][3] = {{1, 0.7, 45}, {3, 0.5, 35}, {-1, 0.8, 50}}; /* t (-1: rest pose), yfov, zfar */
    for (size_t i = 0; i < sizeof cams / sizeof cams[0]; i++) {
        CHECK(pg_scene_pose(s, cams[i][0] < 0 ? PG_ANIM_NONE : 0, fabs(cams[i][0]), &err) == PG_OK);
        const pg_scene_camera *C = &s->cameras[0];
        CHECK_MSG(fabs(C->yfov_rad - cams[i][1]) < 1e-6 && fabs(C->zfar - cams[i][2]) < 1e-4 &&
                      fabsf(C->znear - 0.1f) < 1e-7f && fabsf(C->position[2] - 6) < 1e-5f,
                  "eye at t=%g: yfov %g zfar %g znear %g", cams[i][0], C->yfov_rad, C->zfar, C->znear);
    }
    /* values an animation may reach (a CUBICSPLINE overshoot, hostile keys) are kept valid */
    pg_anim_pose pose;
    if (pg_anim_pose_alloc(s->anim, &pose, &err) == PG_OK) {
        pg_anim_pose_eval(s->anim, 0, 1, &pose);
        const float bad_light[PG_ANIM_LIGHT_PROPS] = {-1, NAN, 2, -5, 0, 0.9f, 0.4f};
        memcpy(pose.lights[0], bad_light, sizeof bad_light);
        pg_scene_light L = s->lights[0];
        CHECK(pg_anim_light_props(s->anim, &pose, &L));
        CHECK_MSG(L.color[0] == 0 && L.color[1] == 0 && L.color[2] == 2 && L.intensity == 0 && L.range > 0 &&
                      L.outer_cone == 0.4f && L.inner_cone < L.outer_cone && L.inner_cone >= 0,
                  "clamped light: colour (%g, %g, %g) intensity %g range %g cones %g %g", L.color[0], L.color[1],
                  L.color[2], L.intensity, L.range, L.inner_cone, L.outer_cone);
        const float bad_cam[PG_ANIM_CAMERA_PROPS] = {5, -1, 0, 0, -1, 0.5f};
        memcpy(pose.cameras[0], bad_cam, sizeof bad_cam);
        pg_scene_camera C = s->cameras[0];
        CHECK(pg_anim_camera_props(s->anim, &pose, &C));
        CHECK_MSG(C.yfov_rad > 0 && C.yfov_rad < 3.1416f && C.aspect_ratio == 0 && C.znear > 0 && C.zfar > C.znear,
                  "clamped camera: yfov %g aspect %g znear %g zfar %g", C.yfov_rad, C.aspect_ratio, C.znear, C.zfar);
        pg_anim_pose_release(&pose);
    }
    pg_scene_free(s);
}

/* shimmer.gltf: materials animated by KHR_animation_pointer (README there), posed on the CPU
 * against hand values; the rest pose the file's; hostile pose values kept valid */
static void material_expect(pg_scene *s, int anim, double t, const float want[15], const char *what)
{
    pg_error err = {0};
    CHECK(pg_scene_pose(s, anim, t, &err) == PG_OK);
    const pg_material *tint = &s->materials[1], *glow = &s->materials[2], *scroll = &s->materials[3],
                      *fade = &s->materials[4];
    const float *u = scroll->uv_transform[PG_TEXSLOT_BASE];
    const float got[15] = {tint->base_color[0], tint->base_color[2], tint->metallic, tint->roughness,
                           glow->emissive[0], glow->emissive[1], glow->emissive[2], u[0], u[1], u[2], u[3], u[4], u[5],
                           fade->alpha_cutoff, fade->base_color[3]};
    float d = 0;
    for (int k = 0; k < 15; k++) d = fmaxf(d, fabsf(got[k] - want[k]));
    CHECK_MSG(d < 1e-5f, "%s at t=%g: tint (%g .. %g) m %g r %g, glow (%g %g %g), uv (%g %g %g / %g %g %g), cutoff %g",
              what, t, got[0], got[1], got[2], got[3], got[4], got[5], got[6], got[7], got[8], got[9], got[10],
              got[11], got[12], got[13]);
    float sp, sh;
    pg_material_specular_from(tint->metallic, tint->roughness, &sp, &sh);
    CHECK_MSG(tint->specular == sp && tint->shininess == sh, "%s: Blinn-Phong terms not following", what);
    /* "bump": normal scale 1 -> 0.2 and occlusion strength 1 -> 0 over 4 s (LINEAR) */
    const double k = anim == PG_ANIM_NONE ? 0.0 : fmod(t, 4.0) / 4.0;
    const pg_material *bump = &s->materials[5];
    CHECK_MSG(fabs(bump->normal_scale - (1 - 0.8 * k)) < 1e-6 && fabs(bump->occlusion_strength - (1 - k)) < 1e-6,
              "%s at t=%g: bump normal scale %g, occlusion strength %g", what, t, bump->normal_scale,
              bump->occlusion_strength);
}

static void shimmer(void)
{
    pg_scene *s = load_file("shimmer.gltf");
    if (!s) return;
    pg_error err = {0};
    CHECK(s->anim && !s->features.has_animation && s->n_materials >= 6 && s->anim->n_animated_materials == 5);
    CHECK(!pg_anim_material_animated(s->anim, 0) && pg_anim_material_animated(s->anim, 1) &&
          pg_anim_material_animated(s->anim, 5) && !pg_anim_material_animated(s->anim, 6) &&
          !pg_anim_material_animated(s->anim, -1));
    /* the emissive term and the texture transform may be needed at another time: compiled in */
    CHECK(s->features.has_emissive && s->features.has_uv_transform);
    uint32_t lines = 0;
    for (uint32_t i = 0; i < s->n_warnings; i++)
        lines += strstr(s->warnings[i], "1 channel ignored (/materials/0/extensions/KHR_materials_ior/ior)") != NULL;
    CHECK_MSG(lines == 1 && s->n_warnings == 1, "shimmer.gltf: %u warnings, %u naming the ior pointer", s->n_warnings,
              lines);
    char line[512];
    CHECK(pg_anim_describe(s, 0, 1.0, line, sizeof line));
    CHECK_MSG(strstr(line, "animation 0 'shimmer' of 1 (4 s loop) at t = 1 s") &&
                  strstr(line, "; 5 materials animated (KHR_animation_pointer)"),
              "--explain's animation line: %s", line);
    /* t = 1: a quarter of the LINEAR keys over [0, 4]; metallic and rotation STEP at 2 */
    const float t1[15] = {0.625f, 0.275f, 0, 0.825f, 0.375f, 0.1875f, 0.0375f, 1.25f, 0, 0.375f, 0, 1, 0.125f,
                          0.375f, 0.6f};
    const float c = cosf(0.5f), sn = sinf(0.5f); /* t = 3: rotation 0.5, scale (1.75, 1), offset (1.125, 0.375) */
    const float t3[15] = {0.275f, 0.625f, 1, 0.475f, 0.75f * 2.5f, 0.375f * 2.5f, 0.075f * 2.5f, 1.75f * c, sn,
                          1.125f, -1.75f * sn, c, 0.375f, 0.725f, 0.6f};
    const float rest[15] = {0.8f, 0.1f, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.5f, 0.6f};
    material_expect(s, 0, 1, t1, "shimmer");
    material_expect(s, 0, 3, t3, "shimmer");
    material_expect(s, PG_ANIM_NONE, 3, rest, "shimmer in the rest pose");
    material_expect(s, 0, 5, t1, "shimmer (t = 5 loops to 1)");
    /* values an animation may reach (a CUBICSPLINE overshoot) are kept valid */
    pg_anim_pose pose;
    if (pg_anim_pose_alloc(s->anim, &pose, &err) == PG_OK) {
        pg_anim_pose_eval(s->anim, 0, 1, &pose);
        float *p = pose.materials[1];
        p[0] = -1, p[1] = NAN, p[2] = 2, p[3] = 7, p[4] = -3, p[5] = 9;
        pg_material M = s->materials[1];
        CHECK(pg_anim_material_props(s->anim, &pose, 1, &M));
        CHECK_MSG(M.base_color[0] == 0 && M.base_color[1] == 0 && M.base_color[2] == 1 && M.base_color[3] == 1 &&
                      M.metallic == 0 && M.roughness == 1,
                  "clamped material: (%g %g %g %g) m %g r %g", M.base_color[0], M.base_color[1], M.base_color[2],
                  M.base_color[3], M.metallic, M.roughness);
        p = pose.materials[2];
        p[6] = -1, p[7] = 3e38f, p[9] = 1e10f;
        M = s->materials[2];
        CHECK(pg_anim_material_props(s->anim, &pose, 2, &M));
        CHECK_MSG(M.emissive[0] == 0 && isfinite(M.emissive[1]) && M.emissive[1] > 0, "clamped emissive: %g %g",
                  M.emissive[0], M.emissive[1]);
        M = s->materials[0];
        CHECK(!pg_anim_material_props(s->anim, &pose, 0, &M)); /* not animated: left as it is */
        pg_anim_pose_release(&pose);
    }
    uint32_t w = 0;
    CHECK(pg_anim_material_offset(PG_ANIM_MAT_BASE_COLOR, &w) == 0 && w == 4);
    CHECK(pg_anim_material_offset(PG_ANIM_MAT_EMISSIVE, &w) == 6 && w == 3);
    CHECK(pg_anim_material_offset((pg_anim_path)(PG_ANIM_MAT_UV + 3 * PG_TEXSLOT_OCCLUSION + 2), &w) ==
              PG_ANIM_MAT_UV_BASE + 5 * PG_TEXSLOT_OCCLUSION + 3 && w == 2);
    CHECK(pg_anim_material_offset(PG_ANIM_CAM_ZFAR, &w) == -1 && w == 0);
    pg_scene_free(s);
}

static void skinned(void)
{
    pg_scene *s = load("skinned.gltf");
    if (!s) return;
    CHECK(s->anim->n_skins == 1 && s->anim->n_joint_slots == 2);
    expect(s, 0, 0, 3, 17, 0.2, 2, 0.2, "tube v17 (the mesh node's translation ignored)");
    expect(s, 0, 2, 3, 17, 0.2, 2, 0.2, "tube v17");
    expect(s, 0, 0.5, 3, 17, -0.565685, 1.848528, 0.2, "tube v17");
    expect(s, 0, 1, 3, 17, -1, 1.2, 0.2, "tube v17");
    expect(s, 0, 1, 3, 9, 0.1, 1.1, 0.2, "tube v9 (half root, half elbow)");
    expect(s, 0, 0.5, 3, 9, 0.170711, 1.070711, 0.2, "tube v9");
    expect(s, 0, 1, 3, 1, 0.2, 0, 0.2, "tube v1 (root only)");
    /* normals turn with the bend: the upper +Z side still faces +Z, the upper +X side faces +Y */
    CHECK(pg_scene_pose(s, 0, 1, &(pg_error){0}) == PG_OK);
    for (uint32_t p = 0; p < s->anim->n_prims; p++)
        if (s->anim->prims[p].node == 3) {
            const pg_vertex *v = &s->vertices[s->anim->prims[p].first_vertex + 18 + 17]; /* +X side, top ring */
            CHECK_MSG(fabsf(v->normal[1] - 1.0f) < 1e-4f, "bent +X side normal (%g, %g, %g)", v->normal[0],
                      v->normal[1], v->normal[2]);
        }
    pg_scene_free(s);
}

static void skinned8(void)
{
    pg_scene *s = load("skinned8.gltf");
    if (!s) return;
    CHECK_MSG(s->anim->influences == 8 && s->anim->n_joint_slots == 8, "influences %u, joint slots %u",
              s->anim->influences, s->anim->n_joint_slots);
    expect(s, 0, 0, 10, 9, 0.2, 1, 0.2, "top ring v9");
    expect(s, 0, 1, 10, 9, 0.2, 2, 0.2, "top ring v9 (joints 4-7 of JOINTS_1 up by 2)");
    expect(s, 0, 0.5, 10, 9, 0.2, 1.5, 0.2, "top ring v9");
    expect(s, 0, 1, 10, 7, 0.2, 1.75, 0.2, "the y = 0.75 ring");
    expect(s, 0, 1, 10, 5, 0.2, 0.5, 0.2, "below: joint 0 alone");
    pg_scene_free(s);
    pg_scene *four = load("skinned.gltf"); /* one joint set: the 4-joint layout */
    if (four) CHECK_MSG(four->anim->influences == 4, "skinned.gltf: influences %u", four->anim->influences);
    pg_scene_free(four);
}

static void morph(void)
{
    pg_scene *s = load("morph.gltf");
    if (!s) return;
    CHECK(s->anim->n_weights == 2);
    expect(s, PG_ANIM_NONE, 0, 1, 10, 0.5, 1.25, 0.5, "cube v10 at the mesh's default weights");
    expect(s, 0, 0, 1, 10, 0.5, 1, 0.5, "cube v10");
    expect(s, 0, 0.5, 1, 10, 0.625, 1.5, 0.5, "cube v10 (weights 0.5, 0.25)");
    expect(s, 0, 1, 1, 10, 0.75, 2.0, 0.5, "cube v10 (weights 1, 0.5)");
    expect(s, 0, 1, 1, 2, 0.75, 2.0, 0.5, "cube v2");
    expect(s, 0, 1, 1, 12, -0.5, 0, -0.5, "cube v12 (no delta)");
    pg_scene_free(s);
}

/* corpus file `file` with its first `from` replaced by `to`, loaded (*out: the scene, or NULL) */
static pg_result load_edited(const char *file, const char *from, const char *to, pg_scene **out, pg_error *err)
{
    char src[1024];
    snprintf(src, sizeof src, "%s/corpus/gltf/animation/%s", PG_TEST_DIR, file);
    *out = NULL;
    FILE *f = fopen(src, "rb");
    if (!f) return pg_fail(err, PG_ERR_IO, "cannot read %s", src);
    char *text = calloc(1, 1 << 20);
    size_t n = fread(text, 1, (1 << 20) - 1, f);
    fclose(f);
    text[n] = 0;
    char *at = strstr(text, from), *mod = calloc(1, n + strlen(to) + 1);
    pg_result r = PG_ERR_INVALID_ARG;
    if (!at) pg_fail(err, r, "'%s' not in %s", from, file);
    if (at && mod) {
        memcpy(mod, text, (size_t)(at - text));
        strcat(mod, to);
        strcat(mod, at + strlen(from));
        char path[] = "/tmp/pg_anim_XXXXXX.gltf";
        int fd = mkstemps(path, 5);
        FILE *o = fd >= 0 ? fdopen(fd, "wb") : NULL;
        if (o) {
            fputs(mod, o);
            fclose(o);
            r = pg_scene_load_gltf(path, out, err);
            remove(path);
        }
    }
    free(mod);
    free(text);
    return r;
}

/* broken animation data: a clear error naming the object, no crash */
static void refused_in(const char *file, size_t n_cases, const char *const (*cases)[3])
{
    for (size_t c = 0; c < n_cases; c++) {
        pg_scene *s = NULL;
        pg_error err = {0};
        pg_result r = load_edited(file, cases[c][0], cases[c][1], &s, &err);
        CHECK_MSG(r == PG_ERR_GLTF && strstr(err.msg, cases[c][2]), "%s case %zu: %d '%s'", file, c, r, err.msg);
        pg_scene_free(s);
    }
}

/* a target without "node" whose path is not "pointer" names no node (glTF leaves it to an
 * extension): the channel is ignored, not applied to node 0 (the placeholder pointer targets get
 * for tinygltf) */
static void nodeless_target(void)
{
    pg_scene *s = NULL;
    pg_error err = {0};
    CHECK(load_edited("rigid.gltf", "\"node\": 1,\n      \"path\": \"rotation\"", "\"path\": \"rotation\"", &s, &err) ==
          PG_OK);
    if (!s) return;
    CHECK_MSG(s->anim && s->anim->animations[0].n_channels == 2, "spin keeps %u channels",
              s->anim ? s->anim->animations[0].n_channels : 0);
    expect(s, 0, 1, 1, 10, 0.5, 1, 0.5, "spinner v10 without its rotation channel");
    pg_scene_free(s);
}

static void refused(void)
{
    static const char *const rigid_cases[][3] = {
        {"\"interpolation\": \"STEP\"", "\"interpolation\": \"BOUNCY\"", "interpolation: 'BOUNCY'"},
        {"\"node\": 1,", "\"node\": 99,", "target.node: 99 out of range"},
        /* refused after the channel's keys were allocated (a leak the glTF fuzzer found; the
         * sanitizer suite runs this test) */
        {"\"bufferView\": 7,\n   \"componentType\": 5126,\n   \"count\": 5,\n   \"type\": \"SCALAR\"",
         "\"bufferView\": 0,\n   \"componentType\": 5126,\n   \"count\": 5,\n   \"type\": \"SCALAR\"",
         "samplers[0].input: key 0: time -10 (expected finite, >= 0, not decreasing)"},
    };
    static const char *const skin_cases[][3] = {
        {"\"joints\": [\n    1,\n    2\n   ],", "\"joints\": [],", "skins[0].joints: empty"},
        {"\"joints\": [\n    1,\n    2\n   ],", "\"joints\": [1],", "joint 1 out of range (skins[0] has 1 joints)"},
    };
    static const char *const skin8_cases[][3] = {
        {"\"WEIGHTS_1\": 6", "\"TEXCOORD_5\": 6", "JOINTS_1 without WEIGHTS_1"},
        {"\"JOINTS_1\": 5,", "\"JOINTS_1\": 4,", "JOINTS_1 must be VEC4 UNSIGNED_BYTE or UNSIGNED_SHORT"},
    };
    static const char *const pointer_cases[][3] = {
        {"\"pointer\": \"/nodes/1/rotation\"", "\"pointer\": \"/nodes/99/rotation\"",
         "channels[0].target.extensions.KHR_animation_pointer.pointer: node 99 out of range"},
        {"\"pointer\": \"/nodes/1/rotation\"", "\"pointr\": \"/nodes/1/rotation\"",
         "channels[0].target: path 'pointer' without a KHR_animation_pointer extension giving a \"pointer\" string"},
        {"\"pointer\": \"/nodes/1/rotation\"", "\"pointer\": 7",
         "channels[0].target: path 'pointer' without a KHR_animation_pointer extension giving a \"pointer\" string"},
    };
    refused_in("rigid.gltf", 3, rigid_cases);
    refused_in("pointer.gltf", 3, pointer_cases);
    static const char *const beacon_cases[][3] = {
        {"lights/0/intensity\"", "lights/5/intensity\"",
         "channels[1].target.extensions.KHR_animation_pointer.pointer: light 5 out of range (1 lights)"},
        {"/cameras/0/perspective/yfov\"", "/cameras/2/perspective/yfov\"",
         "channels[5].target.extensions.KHR_animation_pointer.pointer: camera 2 out of range (1 cameras)"},
    };
    refused_in("beacon.gltf", 2, beacon_cases);
    static const char *const shimmer_cases[][3] = {
        {"\"/materials/1/pbrMetallicRoughness/baseColorFactor\"", "\"/materials/9/pbrMetallicRoughness/baseColorFactor\"",
         "channels[0].target.extensions.KHR_animation_pointer.pointer: material 9 out of range (6 materials)"},
        /* the base colour's keys as VEC3 (its only VEC4 accessor): the property is a VEC4 */
        {"\"type\": \"VEC4\"", "\"type\": \"VEC3\"",
         "must be VEC4 with 2 elements for 2 keys of '/materials/1/pbrMetallicRoughness/baseColorFactor' (got VEC3"},
    };
    refused_in("shimmer.gltf", 2, shimmer_cases);
    refused_in("skinned.gltf", 2, skin_cases);
    refused_in("skinned8.gltf", 2, skin8_cases);
}

/* triangles of the moving primitives of `s` (posed) whose winding disagrees with their vertex
 * normals: the face normal by the right-hand rule (counter-clockwise = front) against the normal
 * of their first corner; the box and panel meshes of mirror.gltf are flat, so every triangle must
 * agree */
static uint32_t wound_against_normals(const pg_scene *s)
{
    uint32_t bad = 0;
    for (uint32_t k = 0; k < s->anim->n_prims; k++)
        for (uint32_t p = 0; p < s->n_primitives; p++) {
            const pg_primitive *pr = &s->primitives[p];
            if ((int64_t)pr->vertex_offset != (int64_t)s->anim->prims[k].first_vertex) continue;
            for (uint32_t i = 0; i + 2 < pr->index_count; i += 3) {
                const pg_vertex *v[3];
                for (int c = 0; c < 3; c++) v[c] = &s->vertices[s->indices[pr->first_index + i + c] + pr->vertex_offset];
                double e1[3], e2[3];
                for (int c = 0; c < 3; c++) {
                    e1[c] = v[1]->position[c] - v[0]->position[c];
                    e2[c] = v[2]->position[c] - v[0]->position[c];
                }
                const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                                     e1[0] * e2[1] - e1[1] * e2[0]};
                bad += n[0] * v[0]->normal[0] + n[1] * v[0]->normal[1] + n[2] * v[0]->normal[2] <= 0;
            }
        }
    return bad;
}

/* mirror.gltf: "turn" is scaled to (-1, 1, 1) from t = 1, "back" is mirrored at rest and unmirrored
 * from t = 1; posed on the CPU, the triangles the pose mirrors against their loaded winding are
 * rewound, so every triangle keeps facing along its normals (before: from t = 1 every one of them
 * faced inward) */
static void mirror(void)
{
    pg_scene *s = load("mirror.gltf");
    if (!s) return;
    CHECK_MSG(s->anim->n_prims == 4, "%u moving primitives", s->anim->n_prims);
    pg_anim_pose pose;
    pg_error err = {0};
    if (pg_anim_pose_alloc(s->anim, &pose, &err)) {
        CHECK_MSG(0, "%s", err.msg);
        pg_scene_free(s);
        return;
    }
    static const double times[] = {0.0, 0.5, 1.0, 1.5, 2.5, 3.2};
    for (size_t i = 0; i < sizeof times / sizeof times[0]; i++) {
        const double t = times[i];
        const bool turned = pg_anim_local_time(s->anim, 0, t) >= 1.0;
        pg_anim_pose_eval(s->anim, 0, t, &pose);
        for (uint32_t k = 0; k < s->anim->n_prims; k++) { /* prims 0, 1: "turn" and its panel; 2, 3: "back" */
            const bool due = k < 2 ? turned : !turned;
            CHECK_MSG(pg_anim_prim_mirrored(s->anim, &pose, k) == due, "t=%g prim %u: mirrored %d", t, k, !due);
        }
        CHECK(pg_scene_pose(s, 0, t, &err) == PG_OK);
        for (uint32_t k = 0; k < s->anim->n_prims; k++)
            CHECK_MSG(s->anim->prims[k].wound_mirrored == (k < 2 ? turned : !turned), "t=%g prim %u: wound %u", t, k,
                      s->anim->prims[k].wound_mirrored);
        const uint32_t bad = wound_against_normals(s);
        CHECK_MSG(bad == 0, "t=%g: %u triangles wound against their normals", t, bad);
    }
    CHECK(pg_scene_pose(s, PG_ANIM_NONE, 0, &err) == PG_OK && wound_against_normals(s) == 0);
    pg_anim_pose_release(&pose);
    pg_scene_free(s);
}

int main(void)
{
    rigid();
    nonunit();
    pointer();
    beacon();
    shimmer();
    skinned();
    skinned8();
    morph();
    mirror();
    refused();
    nodeless_target();
    return pg_test_finish("test_animation");
}
