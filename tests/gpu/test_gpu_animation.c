/* test_gpu_animation.c - animation as a graph pass (geometry_animate, shaders/animate_geometry.comp)
 * on the Vulkan device with the validation layer and synchronization validation on (zero
 * messages), 160x90.
 *  1. For each generated file of tests/corpus/gltf/animation (rigid TRS with STEP and CUBICSPLINE,
 *     a two-joint skin, 8 joints a vertex (skinned8.gltf), two morph targets) at two times, and for the pipelines naive, forward_plus,
 *     deferred (G-buffer), visibility and reference: the scene uploaded in its rest pose and
 *     deformed on the GPU at the frame's time renders like its static twin, the same file posed on
 *     the CPU (scene/animation.c pg_anim_deform) and uploaded without animation: at most
 *     ANIM_EDGE_PIXELS of the pixels differ by more than 1e-3 of the peak (rasterisation of edges
 *     whose vertices differ in the last float bits), none by more than that elsewhere; a file whose
 *     geometry does not move (lights, cameras, materials animated) not one pixel. The same
 *     scene rendered with --animation none must differ from the twin (the test fails if the pass
 *     does nothing).
 *     lamp.gltf (a point light on an orbiting node, no moving geometry) likewise: light_animate
 *     rewrites the light's record for the frame's time (the geometry pass is culled). lantern.gltf
 *     (a light and a box on one orbiting node): both passes run, and the frame evaluates the pose
 *     once (pg_scene_gpu_anim_now.evaluations), not once a pass. glass.gltf (two BLEND boxes, the
 *     moving one in front of the still one at t = 1, behind it at rest): the transparent pass sorts
 *     by the posed bounds, as the CPU-posed twin does. shimmer.gltf (materials animated by
 *     KHR_animation_pointer: base colour, metallic, roughness, emissive, emissive strength, a texture
 *     transform, an alpha cutoff, a normal scale, an occlusion strength): the frame prologue rewrites their records before any pass reads
 *     them, and every pipeline renders the CPU-posed materials' image.
 *     mirror.gltf (scales through -1, against the winding the indices were loaded with), also with
 *     visibility.json at raster=compute, and uploaded after a CPU pose that rewound its indices.
 *  2. A scene without animation: geometry_animate culled with its reason, the geometry buffer not
 *     allocated, every drawing pass on the static vertex buffer. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "animation.h"
#include "gpu_harness.h"
#include "pass_list.h"
#include "render_session.h"
#include "scene_gpu_anim.h"
#include "test_util.h"

#define W 160
#define H 90
#define ANIM_EDGE_PIXELS 0.004 /* share of the pixels that may differ at triangle edges */

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;

static bool upload(pg_scene *s, pg_scene_gpu **sg, const char *what)
{
    pg_error err = {0};
    if (pg_scene_gpu_create(g_gpu, s, sg, &err)) {
        CHECK_MSG(0, "%s: upload: %s", what, err.msg);
        return false;
    }
    return true;
}

/* pixels whose HDR RGB differ by more than tol */
static uint32_t differing(const pg_th_frame *a, const pg_th_frame *b, double tol)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < a->w * a->h; i++)
        for (int c = 0; c < 3; c++)
            if (fabs((double)a->hdr[i * 4 + c] - b->hdr[i * 4 + c]) > tol) {
                n++;
                break;
            }
    return n;
}

/* compute_raster: also visibility.json with raster=compute (the compute rasterizer's culling);
 * posed_at >= 0: the live scene is posed on the CPU at that time before its upload, as the tools
 * do to frame the posed bounds (rewinding the indices of primitives the pose mirrors) */
static void twin_with(const char *file, double t, bool compute_raster, double posed_at)
{
    char path[PG_PATH_MAX], label[PG_PATH_MAX + 64];
    snprintf(path, sizeof path, "%s/corpus/gltf/animation/%s", PG_TEST_DIR, file);
    snprintf(label, sizeof label, posed_at >= 0 ? "%s t=%g (uploaded posed at %g)" : "%s t=%g", file, t, posed_at);
    pg_scene *live = NULL, *still = NULL;
    pg_scene_gpu *live_g = NULL, *still_g = NULL;
    pg_error err = {0};
    if (pg_scene_load(path, &live, &err) || pg_scene_load(path, &still, &err)) {
        CHECK_MSG(0, "%s: %s", label, err.msg);
        goto out;
    }
    if (posed_at >= 0) CHECK(pg_scene_pose(live, PG_ANIM_FIRST, posed_at, &err) == PG_OK);
    /* the twin: posed on the CPU, then static */
    CHECK(pg_scene_pose(still, PG_ANIM_FIRST, t, &err) == PG_OK);
    pg_scene_anim_free(still->anim);
    still->anim = NULL;
    pg_scene_finalize(still);
    CHECK(!still->features.has_animation && live->anim);
    if (!upload(live, &live_g, label) || !upload(still, &still_g, label)) goto out;
    pg_frame_info fi = {
        .camera = {.position = {0.3f, 2.2f, 4.0f}, .target = {0, 1, -0.5f}, .up = {0, 1, 0}, .fov_y_deg = 45,
                   .near_z = 0.1f, .far_z = 100},
        .lights = pg_light_setup_default(live, 64, 7),
        .time = (float)t,
        .animation = PG_ANIM_FIRST,
        .width = W,
        .height = H,
    };
    fi.lights.count = 64;
    if (live->n_lights) fi.lights.count = fi.lights.file_count = live->n_lights; /* the file's lights alone */
    static const char *const pipes[] = {"pipelines/naive.json", "pipelines/forward_plus.json",
                                        "pipelines/deferred.json", "pipelines/visibility.json",
                                        "pipelines/reference.json", "pipelines/visibility.json"};
    static const pg_param_override compute = {"raster", "compute"};
    const size_t n_pipes = sizeof pipes / sizeof pipes[0] - (compute_raster ? 0 : 1);
    for (size_t p = 0; p < n_pipes; p++) {
        pg_th_frame a, b, rest;
        const uint64_t evals = live_g->anim ? live_g->anim->now->evaluations : 0;
        const uint32_t n_sets = p == 5 ? 1 : 0; /* the last: raster=compute */
        bool ok_a = pg_th_render(g_gpu, &g_reg, live_g, pipes[p], &compute, n_sets, &fi, 1, false, &a);
        if (ok_a && live_g->anim) { /* one frame at a new time: one evaluation, however many passes need it */
            const uint64_t n = live_g->anim->now->evaluations - evals;
            CHECK_MSG(n == 1, "%s %s: the pose was evaluated %llu times for one frame", label, pipes[p],
                      (unsigned long long)n);
        }
        bool ok_b = pg_th_render(g_gpu, &g_reg, still_g, pipes[p], &compute, n_sets, &fi, 1, false, &b);
        pg_frame_info fr = fi;
        fr.animation = PG_ANIM_NONE;
        bool ok_r = pg_th_render(g_gpu, &g_reg, live_g, pipes[p], &compute, n_sets, &fr, 1, false, &rest);
        CHECK_MSG(ok_a && ok_b && ok_r, "%s %s: render failed", label, pipes[p]);
        if (ok_a && ok_b && ok_r) {
            double peak = 0;
            pg_th_max_abs(&a, &b, &peak);
            const uint32_t n = differing(&a, &b, 1e-3 * peak), n_rest = differing(&rest, &b, 1e-3 * peak);
            printf("%s %s%s: %u of %u pixels differ from the CPU-posed twin; the rest pose: %u\n", label, pipes[p],
                   n_sets ? " raster=compute" : "", n, W * H, n_rest);
            CHECK_MSG(n <= (uint32_t)(ANIM_EDGE_PIXELS * W * H), "%s %s: %u pixels differ", label, pipes[p], n);
            /* no moving geometry (lights, cameras, materials only): no edge to round, nothing may differ */
            CHECK_MSG(live->features.has_animation || n == 0, "%s %s: %u pixels differ with still geometry", label,
                      pipes[p], n);
            CHECK_MSG(n_rest > 10 * (n + 1), "%s %s: the rest pose differs in only %u pixels", label, pipes[p],
                      n_rest);
            CHECK_MSG(!live->features.has_animation || strstr(a.order, "animate_geometry") != NULL, "%s: not run: %s",
                      pipes[p], a.order);
            CHECK_MSG(!strstr(b.order, "animate_geometry"), "%s: run for a static scene: %s", pipes[p], b.order);
        }
        if (ok_a) pg_th_release(&a);
        if (ok_b) pg_th_release(&b);
        if (ok_r) pg_th_release(&rest);
    }
out:
    if (live_g) pg_scene_gpu_destroy(g_gpu, live_g);
    if (still_g) pg_scene_gpu_destroy(g_gpu, still_g);
    pg_scene_free(live);
    pg_scene_free(still);
}

static void twin(const char *file, double t) { twin_with(file, t, false, -1); }

static void culled(void)
{
    char path[PG_PATH_MAX];
    snprintf(path, sizeof path, "%s/corpus/gltf/pbr/spheres.gltf", PG_TEST_DIR);
    pg_scene *s = NULL;
    pg_scene_gpu *sg = NULL;
    pg_error err = {0};
    if (pg_scene_load(path, &s, &err) || !upload(s, &sg, "spheres")) {
        CHECK_MSG(0, "spheres: %s", err.msg);
        pg_scene_free(s);
        return;
    }
    static const char *const pipes[] = {"pipelines/naive.json", "pipelines/visibility.json"};
    for (size_t p = 0; p < 2; p++) {
        char pp[PG_PATH_MAX];
        pg_data_path(pp, sizeof pp, pipes[p]);
        pg_session_desc sd = {.pipeline_path = pp, .registry = &g_reg};
        pg_session *ss = NULL;
        if (!pg_session_create(g_gpu, sg, &sd, &ss, &err) && !pg_session_compile(ss, 0, W, H, &err)) {
            bool seen = false;
            for (uint32_t i = 0; i < ss->plan->n_passes; i++)
                if (!strcmp(ss->plan->passes[i].name, "animate_geometry")) {
                    seen = true;
                    printf("%s: animate_geometry culled: %s\n", pipes[p], ss->plan->passes[i].cull_reason);
                    CHECK_MSG(ss->plan->passes[i].culled && strstr(ss->plan->passes[i].cull_reason, "no animation"),
                              "animate_geometry: culled %d (%s)", ss->plan->passes[i].culled,
                              ss->plan->passes[i].cull_reason);
                }
            CHECK_MSG(seen, "%s: no animate_geometry pass", pipes[p]);
            for (uint32_t i = 0; i < ss->plan->n_resources; i++)
                if (!strcmp(ss->plan->resources[i].name, "geometry"))
                    CHECK_MSG(ss->plan->resources[i].culled, "the geometry buffer is allocated without animation");
        } else {
            CHECK_MSG(0, "compile: %s", err.msg);
        }
        pg_session_destroy(ss);
    }
    pg_scene_gpu_destroy(g_gpu, sg);
    pg_scene_free(s);
}

int main(void)
{
    if (getenv("PG_TEST_NO_GPU")) return pg_test_skip("test_gpu_animation", "PG_TEST_NO_GPU is set");
    pg_register_builtin_passes(&g_reg);
    pg_gpu_desc gd = {.validation = true, .device_index = -1, .quiet = true};
    pg_error err = {0};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_gpu_animation: %s\n", err.msg);
        return 1;
    }
    twin("rigid.gltf", 0.5);
    twin("rigid.gltf", 2.5);
    twin("skinned.gltf", 0.5);
    twin("skinned.gltf", 1.0);
    twin("skinned8.gltf", 1.0); /* 8 joints a vertex: the larger info record, PG_ANIM_INFLUENCES8 */
    twin("morph.gltf", 1.0);
    twin("lamp.gltf", 1.0); /* a light on an animated node: light_animate places it each frame */
    twin("lamp.gltf", 2.0);
    twin("lantern.gltf", 1.0); /* geometry and a light on one node: both passes, one pose a frame */
    twin("beacon.gltf", 1.0);  /* a spot light's colour, intensity, range and cones (KHR_animation_pointer) */
    twin("beacon.gltf", 3.0);
    /* materials (KHR_animation_pointer): base colour, metallic, roughness, emissive and its strength,
     * a texture transform, an alpha cutoff, a normal scale and an occlusion strength, rewritten by
     * the frame prologue */
    twin("shimmer.gltf", 1.0);
    twin("shimmer.gltf", 3.0);
    twin("glass.gltf", 1.0);   /* two BLEND boxes whose back-to-front order the animation swaps */
    twin("glass_morph.gltf", 1.0); /* likewise by a morph target: the sort key follows the weights */
    twin("../instancing/grove_moving.gltf", 1.0); /* EXT_mesh_gpu_instancing on a turning node */
    /* scales through -1: boxes and double-sided panels mirrored against the winding of their rest
     * pose, drawn with the front face swapped (hardware), culled the other way (raster=compute) and
     * lit on the side the camera sees (gl_FrontFacing; visibility_surface.glsl's facing) */
    twin_with("mirror.gltf", 1.5, true, -1);
    twin_with("mirror.gltf", 1.5, true, 1.5); /* the indices uploaded rewound: drawn as wound */
    twin_with("mirror.gltf", 0.5, true, 1.5); /* ... and flipped back by the GPU's pose */
    culled();
    printf("validation messages: %u\n", g_gpu->validation_messages);
    CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_gpu_animation");
}
