/* test_gpu_fif.c - two frames in flight render what one frame in flight renders, without a host
 * wait per frame, across a light-count change and a pipeline switch.
 *
 * One sequence of 13 frames (time 0.05 k) is rendered twice, with 1 and with 2 frames in flight:
 * deferred_oct16.json with 64 lights for frames 0-5, 96 lights for frames 6-8 (a new plan while
 * frame 5 may be in flight), then a pipeline switch to naive.json (the session destroyed and a new
 * one made while frame 8 may be in flight) for frames 9-12. Frames 2, 4, 7, 11 and 12 are read
 * back; their LDR and HDR bytes must be identical between the two runs. With 2 in flight the host
 * must wait for the frame it just submitted only on those read-back frames (sync_waits), and at
 * least once a frame must still be running when the next call returns (reports_valid false:
 * the host got ahead of the GPU). Validation with synchronization validation runs throughout:
 * zero messages. */
#include <stdlib.h>
#include <string.h>

#include "pass_list.h"
#include "shader.h"
#include "render_session.h"
#include "test_util.h"

#define W 160
#define H 90
#define NF 13

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;

static bool is_readback(uint32_t k) { return k == 2 || k == 4 || k == 7 || k == 11 || k == 12; }

typedef struct run {
    uint8_t *img[NF][2];
    size_t bytes[NF][2];
    uint32_t sync_waits, fence_waits, report_waits, ahead, frames;
} run;

static pg_session *open_session(const pg_scene_gpu *sg, const char *pipeline, uint32_t fif)
{
    char path[PG_PATH_MAX];
    pg_data_path(path, sizeof path, pipeline);
    pg_session_desc sd = {.pipeline_path = path, .registry = &g_reg};
    pg_session *s = NULL;
    pg_error err = {0};
    if (pg_session_create(g_gpu, sg, &sd, &s, &err) || pg_session_set_frames_in_flight(s, fif, &err)) {
        CHECK_MSG(0, "%s: %s", pipeline, err.msg);
        pg_session_destroy(s);
        return NULL;
    }
    return s;
}

static void add_counts(run *r, pg_session *s)
{
    pg_runtime_stats rs = pg_runtime_get_stats(s->runtime);
    r->sync_waits += rs.sync_waits;
    r->fence_waits += rs.fence_waits;
    r->report_waits += rs.report_waits;
    r->frames += (uint32_t)rs.frames_submitted;
}

static bool sequence(const pg_scene *scene, const pg_scene_gpu *sg, uint32_t fif, run *r)
{
    memset(r, 0, sizeof *r);
    pg_session *s = open_session(sg, "pipelines/deferred_oct16.json", fif);
    if (!s) return false;
    for (uint32_t k = 0; k < NF; k++) {
        if (k == 9) { /* pipeline switch with a frame in flight */
            add_counts(r, s);
            pg_session_destroy(s);
            if (!(s = open_session(sg, "pipelines/naive.json", fif))) return false;
        }
        pg_frame_info fi = {.camera = pg_camera_default_for_scene(scene, (float)W / H),
                            .lights = pg_light_setup_default(scene, k < 6 ? 64 : 96, 7),
                            .time = 0.05f * (float)k, .width = W, .height = H};
        pg_frame_stats st;
        pg_error err = {0};
        if (pg_session_render(s, &fi, is_readback(k), &st, &err)) {
            CHECK_MSG(0, "fif %u frame %u: %s", fif, k, err.msg);
            pg_session_destroy(s);
            return false;
        }
        CHECK_MSG(st.in_flight == fif && st.frame <= k, "frame %u: in_flight %u frame %llu", k, st.in_flight,
                  (unsigned long long)st.frame);
        if (!st.reports_valid) r->ahead++;
        if (!is_readback(k)) continue;
        for (int w = 0; w < 2; w++) {
            uint32_t iw = 0, ih = 0;
            pg_format fmt;
            const void *px = pg_runtime_output(s->runtime, w, &iw, &ih, &fmt);
            CHECK_MSG(px != NULL, "fif %u frame %u: no read-back output %d", fif, k, w);
            if (!px) continue;
            r->bytes[k][w] = (size_t)iw * ih * pg_format_get(fmt)->bytes_per_pixel;
            r->img[k][w] = malloc(r->bytes[k][w]);
            memcpy(r->img[k][w], px, r->bytes[k][w]);
        }
    }
    add_counts(r, s);
    pg_session_destroy(s);
    return true;
}

int main(void)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    if (getenv("PG_TEST_NO_GPU")) return pg_test_skip("test_gpu_fif", "PG_TEST_NO_GPU set");
    pg_register_builtin_passes(&g_reg);
    pg_test_queue_submit_validation(); /* hazards between frames in flight too */
    pg_gpu_desc gd = {.validation = true, .device_index = -1, .quiet = true};
    pg_error err = {0};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_gpu_fif: %s\n", err.msg);
        return 1;
    }
    CHECK_MSG(g_gpu->messenger != VK_NULL_HANDLE, "validation on but no messenger");
    pg_scene *scene = NULL;
    pg_scene_gpu *sg = NULL;
    if (pg_scene_create_default(&scene, &err) || pg_scene_gpu_create(g_gpu, scene, &sg, &err)) {
        fprintf(stderr, "test_gpu_fif: scene: %s\n", err.msg);
        return 1;
    }
    run a, b;
    bool ok = sequence(scene, sg, 1, &a) && sequence(scene, sg, 2, &b);
    if (ok) {
        uint32_t n_readback = 0, same = 0;
        for (uint32_t k = 0; k < NF; k++) {
            if (!is_readback(k)) continue;
            n_readback++;
            bool eq = true;
            for (int w = 0; w < 2; w++)
                eq = eq && a.img[k][w] && b.img[k][w] && a.bytes[k][w] == b.bytes[k][w] &&
                     !memcmp(a.img[k][w], b.img[k][w], a.bytes[k][w]);
            CHECK_MSG(eq, "frame %u: 2 in flight differs from 1 in flight", k);
            same += eq;
        }
        printf("1 in flight: %u frames, %u waits for the frame just submitted, %u fence waits\n", a.frames,
               a.sync_waits, a.fence_waits);
        printf("2 in flight: %u frames, %u waits for the frame just submitted (read-backs), %u waits on an "
               "earlier frame's fence, %u waits to read the pass reports, %u calls returned with a frame still "
               "running\n",
               b.frames, b.sync_waits, b.fence_waits, b.report_waits, b.ahead);
        printf("read-back frames identical: %u of %u\n", same, n_readback);
        CHECK_MSG(a.sync_waits == a.frames, "1 in flight must wait every frame (%u of %u)", a.sync_waits, a.frames);
        CHECK_MSG(b.sync_waits <= b.frames - (NF - n_readback),
                  "2 in flight waited for the frame just submitted %u times in %u frames (%u read-backs)",
                  b.sync_waits, b.frames, n_readback);
        CHECK_MSG(b.ahead >= 1, "2 in flight: the host never got ahead of the GPU");
    }
    CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
    for (uint32_t k = 0; k < NF; k++)
        for (int w = 0; w < 2; w++) {
            free(a.img[k][w]);
            free(b.img[k][w]);
        }
    pg_scene_gpu_destroy(g_gpu, sg);
    pg_scene_free(scene);
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_gpu_fif");
}
