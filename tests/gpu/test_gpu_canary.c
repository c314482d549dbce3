/* test_gpu_canary.c - proves that the validation the GPU tests rely on can fail.
 *
 * 1. Validation is required: with the Khronos layer hidden from the loader
 *    (VK_LOADER_LAYERS_DISABLE), pg_gpu_create with validation fails with a message naming the
 *    layer; with it, the counting messenger exists.
 * 2. The canary: shipped pipelines (naive.json, deferred_oct16.json) compiled on the default
 *    scene at 160x90 with 64 lights render with zero validation messages; then, one case per
 *    barrier kind, ONE barrier is removed from the compiled plan (pg_session_desc.test_edit_plan,
 *    after compile, before the runtime is built) and the frame must raise at least one
 *    synchronization-validation message (SYNC-HAZARD-*) counted by the messenger; a removed
 *    layout transition at least one message of any kind (layer 1.4.309 reports the aliased
 *    image's missing first-use transition as a layout mismatch at submit, 1.3.239 as a hazard).
 * 3. The frame-start barrier: with two frames in flight consecutive frames share the graph's
 *    resources and only the full barrier that begins each frame's commands orders them. This test
 *    turns on the layer's queue-submit synchronization validation (VK_LAYER_ENABLES +=
 *    VALIDATION_CHECK_ENABLE_SYNCHRONIZATION_VALIDATION_QUEUE_SUBMIT: hazards between command
 *    buffers of different submits; layer 1.3.239 leaves it off by default). 6 frames with 2 in
 *    flight (no read-back, so the host does not wait for the frame it just submitted) raise no
 *    message with the barrier on either pipeline, and on deferred_oct16.json (aliased G-buffer
 *    transients) at least one SYNC-HAZARD without it (pg_runtime_test_drop_frame_barrier).
 *    naive.json needs the barrier too: its light buffer and depth image are transients that the
 *    next frame writes (layer 1.4.309 with its shader-access checks reports both), but layer
 *    1.3.239 reports nothing there, so the count is printed, not required.
 * Every plan here is for one queue (pg_session_desc.async_off), as lavapipe runs them, also on a
 * GPU with a separate compute queue: there the barriers cut above cross queues and become
 * semaphore waits, and the layer's queue-submit checks (1.3.239) report layout transitions
 * ordered by a timeline semaphore as racing. */
#include <stdlib.h>
#include <string.h>

#include "pass_list.h"
#include "shader.h"
#include "render_session.h"
#include "test_util.h"

#define W 160
#define H 90

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;

typedef struct cut {
    const char *pass;     /* remove the barrier placed before this pass ... */
    const char *resource; /* ... on this resource */
    int want_image;       /* 1: must be an image barrier, 0: a buffer barrier */
    int want_layout;      /* 1: must change the layout, 0: must not, -1: either */
    const char *why;      /* substring of the barrier's reason ("RAW", "alias first use") */
    int removed;          /* barriers removed (set by cut_barrier) */
    char what[200];
    bool layout; /* the removed barrier changed a layout (set by cut_barrier) */
} cut;

static void cut_barrier(pg_graph_plan *plan, void *user)
{
    cut *c = user;
    for (uint32_t p = 0; p < plan->n_passes; p++) {
        pg_plan_pass *pass = &plan->passes[p];
        if (strcmp(pass->name, c->pass) != 0) continue;
        for (uint32_t i = 0; i < pass->n_barriers; i++) {
            pg_barrier *b = &pass->barriers[i];
            if (strcmp(plan->resources[b->resource].name, c->resource) != 0) continue;
            bool layout = b->is_image && b->old_layout != b->new_layout;
            if ((int)b->is_image != c->want_image || (c->want_layout >= 0 && (int)layout != c->want_layout) ||
                !strstr(b->why, c->why))
                continue;
            if (b->is_image)
                snprintf(c->what, sizeof c->what, "image barrier on '%s' before '%s' (%s, %s -> %s)", c->resource,
                         c->pass, b->why, pg_layout_name(b->old_layout), pg_layout_name(b->new_layout));
            else
                snprintf(c->what, sizeof c->what, "buffer barrier on '%s' before '%s' (%s)", c->resource, c->pass,
                         b->why);
            memmove(b, b + 1, (pass->n_barriers - i - 1) * sizeof *b);
            pass->n_barriers--;
            c->removed++;
            c->layout = layout;
            return;
        }
    }
}

/* Renders one frame of pipeline (with c: minus one barrier); returns the messages and the
 * SYNC-HAZARD messages it caused. */
static bool render(const pg_scene *scene, const pg_scene_gpu *sg, const char *pipeline, cut *c, uint32_t *messages,
                   uint32_t *hazards)
{
    char path[PG_PATH_MAX];
    pg_data_path(path, sizeof path, pipeline);
    pg_session_desc sd = {.pipeline_path = path, .registry = &g_reg, .async_off = true};
    if (c) {
        sd.test_edit_plan = cut_barrier;
        sd.test_edit_user = c;
    }
    pg_session *s = NULL;
    pg_error err = {0};
    if (pg_session_create(g_gpu, sg, &sd, &s, &err)) {
        CHECK_MSG(0, "%s: %s", pipeline, err.msg);
        return false;
    }
    pg_frame_info fi = {.camera = pg_camera_default_for_scene(scene, (float)W / H),
                        .lights = pg_light_setup_default(scene, 64, 7), .time = 0.5f, .width = W, .height = H};
    uint32_t m0 = g_gpu->validation_messages, h0 = g_gpu->sync_hazards;
    pg_frame_stats st;
    bool ok = !pg_session_render(s, &fi, true, &st, &err);
    CHECK_MSG(ok, "%s: render: %s", pipeline, err.msg);
    pg_session_destroy(s);
    *messages = g_gpu->validation_messages - m0;
    *hazards = g_gpu->sync_hazards - h0;
    return ok;
}

/* 6 frames with 2 in flight, no read-back; drop: without the frame-start barrier. */
static bool frames_in_flight(const pg_scene *scene, const pg_scene_gpu *sg, const char *pipeline, bool drop,
                             uint32_t *messages, uint32_t *hazards, uint32_t *overlapped)
{
    char path[PG_PATH_MAX];
    pg_data_path(path, sizeof path, pipeline);
    pg_session_desc sd = {.pipeline_path = path, .registry = &g_reg, .async_off = true};
    pg_session *s = NULL;
    pg_error err = {0};
    if (pg_session_create(g_gpu, sg, &sd, &s, &err) || pg_session_set_frames_in_flight(s, 2, &err)) {
        CHECK_MSG(0, "%s: %s", pipeline, err.msg);
        pg_session_destroy(s);
        return false;
    }
    pg_runtime_test_drop_frame_barrier(s->runtime, drop);
    uint32_t m0 = g_gpu->validation_messages, h0 = g_gpu->sync_hazards;
    bool ok = true;
    *overlapped = 0;
    for (uint32_t k = 0; k < 6 && ok; k++) {
        pg_frame_info fi = {.camera = pg_camera_default_for_scene(scene, (float)W / H),
                            .lights = pg_light_setup_default(scene, 64, 7), .time = 0.1f * (float)k, .width = W,
                            .height = H};
        pg_frame_stats st;
        ok = !pg_session_render(s, &fi, false, &st, &err);
        CHECK_MSG(ok, "%s: frame %u: %s", pipeline, k, err.msg);
        *overlapped += !st.reports_valid; /* returned with the frame still in flight */
    }
    if (ok) ok = !pg_runtime_wait_idle(s->runtime, &err);
    pg_session_destroy(s);
    *messages = g_gpu->validation_messages - m0;
    *hazards = g_gpu->sync_hazards - h0;
    return ok;
}

static void required(void)
{
    /* the loader reads VK_LOADER_LAYERS_DISABLE at every instance creation */
    const char *old = getenv("VK_LOADER_LAYERS_DISABLE");
    char *saved = old ? strdup(old) : NULL;
    setenv("VK_LOADER_LAYERS_DISABLE", "VK_LAYER_KHRONOS_validation", 1);
    pg_gpu_desc gd = {.validation = true, .device_index = -1, .quiet = true};
    pg_gpu *gpu = NULL;
    pg_error err = {0};
    pg_result r = pg_gpu_create(&gd, &gpu, &err);
    printf("required: without the layer: %s\n", r ? err.msg : "(created)");
    CHECK_MSG(r != PG_OK, "validation without the layer must fail, it did not");
    CHECK_MSG(r == PG_OK || strstr(err.msg, "VK_LAYER_KHRONOS_validation"), "message: %s", err.msg);
    if (!r) pg_gpu_destroy(gpu);
    if (saved) setenv("VK_LOADER_LAYERS_DISABLE", saved, 1);
    else unsetenv("VK_LOADER_LAYERS_DISABLE");
    free(saved);
}

int main(void)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    if (getenv("PG_TEST_NO_GPU")) return pg_test_skip("test_gpu_canary", "PG_TEST_NO_GPU set");
    pg_register_builtin_passes(&g_reg);
    pg_test_queue_submit_validation(); /* hazards across submits (two frames in flight) */
    required();
    pg_gpu_desc gd = {.validation = true, .device_index = -1, .quiet = true};
    pg_error err = {0};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_gpu_canary: %s\n", err.msg);
        return 1;
    }
    CHECK_MSG(g_gpu->messenger != VK_NULL_HANDLE, "validation on but no messenger");
    pg_scene *scene = NULL;
    pg_scene_gpu *sg = NULL;
    if (pg_scene_create_default(&scene, &err) || pg_scene_gpu_create(g_gpu, scene, &sg, &err)) {
        fprintf(stderr, "test_gpu_canary: scene: %s\n", err.msg);
        pg_scene_free(scene);
        pg_gpu_destroy(g_gpu);
        return 1;
    }

    const char *pipelines[] = {"pipelines/naive.json", "pipelines/deferred_oct16.json"};
    for (size_t i = 0; i < sizeof pipelines / sizeof pipelines[0]; i++) {
        uint32_t m = 0, h = 0;
        if (render(scene, sg, pipelines[i], NULL, &m, &h))
            printf("kept: %s: %u validation message(s), %u SYNC-HAZARD\n", pipelines[i], m, h);
        CHECK_MSG(m == 0, "%s with every barrier: %u validation message(s)", pipelines[i], m);
    }

    struct {
        const char *pipeline;
        cut c;
    } cases[] = {
        /* an image layout transition: colour attachment -> sampled (read after write) */
        {"pipelines/naive.json", {"display", "hdr", 1, 1, "RAW", 0, "", false}},
        /* a buffer write -> read: compute storage write -> fragment storage read */
        {"pipelines/naive.json", {"shade", "lights", 0, 0, "RAW", 0, "", false}},
        /* a buffer write -> read between two compute passes (cluster_lights, written by the last
         * dispatch of assign_lights; not cluster_counts: the pass's own compute -> compute
         * memory barriers between its steps already cover that one, and validation agrees) */
        {"pipelines/deferred_oct16.json", {"lighting_oct16", "cluster_lights", 0, 0, "RAW", 0, "", false}},
        /* a depth attachment -> sampled transition */
        {"pipelines/deferred_oct16.json", {"lighting_oct16", "depth", 1, 1, "RAW", 0, "", false}},
        /* the first use of an aliased image after the previous occupant (write after write) */
        {"pipelines/deferred_oct16.json", {"display", "ldr", 1, -1, "alias first use", 0, "", false}},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        cut *c = &cases[i].c;
        uint32_t m = 0, h = 0;
        bool ok = render(scene, sg, cases[i].pipeline, c, &m, &h);
        printf("removed: %s: %s: %u validation message(s), %u SYNC-HAZARD\n", cases[i].pipeline,
               c->removed ? c->what : "(no such barrier)", m, h);
        CHECK_MSG(c->removed == 1, "%s: barrier %s/%s (%s) not found in the plan", cases[i].pipeline, c->pass,
                  c->resource, c->why);
        if (c->layout)
            CHECK_MSG(!ok || m >= 1, "%s: removing the %s raised no validation message", cases[i].pipeline, c->what);
        else CHECK_MSG(!ok || h >= 1, "%s: removing the %s raised no SYNC-HAZARD message", cases[i].pipeline, c->what);
    }

    for (size_t i = 0; i < sizeof pipelines / sizeof pipelines[0]; i++) {
        for (int drop = 0; drop < 2; drop++) {
            uint32_t m = 0, h = 0, ov = 0;
            bool ok = frames_in_flight(scene, sg, pipelines[i], drop, &m, &h, &ov);
            printf("2 in flight, %s the frame-start barrier: %s: %u validation message(s), %u SYNC-HAZARD "
                   "(%u of 6 calls returned with the frame in flight)\n",
                   drop ? "without" : "with", pipelines[i], m, h, ov);
            CHECK_MSG(ov >= 1, "%s: the frames never overlapped (host never ahead)", pipelines[i]);
            if (!drop)
                CHECK_MSG(ok && m == 0, "%s: with the frame-start barrier: %u validation message(s)", pipelines[i], m);
            else if (strstr(pipelines[i], "deferred"))
                CHECK_MSG(!ok || h >= 1, "%s: without the frame-start barrier: no SYNC-HAZARD", pipelines[i]);
        }
    }

    pg_scene_gpu_destroy(g_gpu, sg);
    pg_scene_free(scene);
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_gpu_canary");
}
