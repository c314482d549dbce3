/* test_gpu_async.c - the two-queue (async compute) path on a device with one queue (lavapipe):
 * pg_gpu_desc.emulate_compute_queue (the CLI's --async-compute emulate) maps the compute queue to
 * the graphics VkQueue, so the two-queue plan runs with its batches, one command buffer per batch
 * and timeline semaphores (one family: no ownership transfer), under the Khronos validation
 * layer with synchronization validation (any message fails).
 *
 * For every shipped pipeline (pipelines/ *.json; all six put light animation on the compute
 * queue), on the built-in atrium with 256 lights at 160x90: the emulated two-queue
 * render (1 frame in flight, and 2 frames in flight over 4 frames) must give byte-identical HDR
 * and display images to the single-queue render of a device created without a compute queue
 * (--async-compute off). Not vacuous: the emulated plans must run the light animation and cluster
 * assignment on the compute queue in their own batch (deferred and reference: at least three
 * batches, the G-buffer in a batch of its own that waits for nothing), the single-queue plans in
 * one batch; all 6 must qualify and the images must be lit. The same for shimmer.gltf (materials
 * animated by KHR_animation_pointer, t = 3): the frame prologue that rewrites them runs in the
 * two-queue plans and with 2 frames in flight without a hazard, and changes no image. The compute
 * queue's first batch of every frame starts with a full barrier, also with one frame in flight
 * (pg_runtime_stats.frame_barriers: one a frame, two a frame with 2 in flight, none on one queue):
 * on an H100, with a real second queue, the validation layer reported cluster_assign's own buffers
 * against the previous frame without it. */
#include <dirent.h>
#include <stdlib.h>
#include <string.h>

#include "pass_list.h"
#include "render_session.h"
#include "scene.h"
#include "shader.h"
#include "test_util.h"

#define W 160
#define H 90
#define LIGHTS 256

static pg_pass_registry g_reg;

typedef struct shot {
    uint8_t *ldr;
    void *hdr;
    size_t ldr_bytes, hdr_bytes;
    bool async;
    uint32_t n_batches;
    bool chain_on_compute, raster_free;
    uint32_t lit;
    uint64_t frames, frame_barriers; /* frames rendered; full barriers that began a queue's frame */
} shot;

static bool render(pg_gpu *gpu, const pg_scene_gpu *sg, const char *pipe, const pg_frame_info *fi, uint32_t fif,
                   shot *out)
{
    memset(out, 0, sizeof *out);
    char path[PG_PATH_MAX];
    pg_data_path(path, sizeof path, pipe);
    pg_session_desc sd = {.pipeline_path = path, .registry = &g_reg};
    pg_session *s = NULL;
    pg_error err = {0};
    pg_frame_stats st;
    bool ok = !pg_session_create(gpu, sg, &sd, &s, &err) && !pg_session_set_frames_in_flight(s, fif, &err);
    for (uint32_t k = 0; ok && k < 2 * fif; k++) ok = !pg_session_render(s, fi, k + 1 == 2 * fif, &st, &err);
    if (!ok) {
        fprintf(stderr, "%s: %s\n", pipe, err.msg);
        pg_session_destroy(s);
        return false;
    }
    const pg_graph_plan *p = s->plan;
    const pg_runtime_stats rs = pg_runtime_get_stats(s->runtime);
    out->frames = rs.frames_submitted;
    out->frame_barriers = rs.frame_barriers;
    out->async = p->async;
    out->n_batches = p->n_batches;
    out->chain_on_compute = true;
    out->raster_free = false;
    for (uint32_t o = 0; o < p->n_order; o++) {
        const pg_plan_pass *pp = &p->passes[p->order[o]];
        if (!strcmp(pp->name, "animate_lights") || !strcmp(pp->name, "assign_lights"))
            out->chain_on_compute &= pp->queue == PG_QUEUE_COMPUTE && st.pass_queue[o] == PG_QUEUE_COMPUTE;
        /* the first raster pass is in a batch that waits for nothing */
        if (pp->queue == PG_QUEUE_GRAPHICS && pp->batch >= 0 && p->batches[pp->batch].n_waits == 0 &&
            p->batches[pp->batch].prev_frame_wait < 0)
            out->raster_free = true;
    }
    CHECK(st.n_batches == p->n_batches);
    uint32_t w, h;
    pg_format f;
    const uint8_t *ldr = pg_runtime_output(s->runtime, 0, &w, &h, &f);
    const void *hdr = pg_runtime_output(s->runtime, 1, &w, &h, &f);
    if (ldr) {
        out->ldr_bytes = (size_t)W * H * 4;
        out->ldr = malloc(out->ldr_bytes);
        memcpy(out->ldr, ldr, out->ldr_bytes);
        for (size_t i = 0; i < out->ldr_bytes; i += 4) out->lit += ldr[i] + ldr[i + 1] + ldr[i + 2] > 0;
    }
    if (hdr) {
        out->hdr_bytes = (size_t)w * h * pg_format_get(f)->bytes_per_pixel;
        out->hdr = malloc(out->hdr_bytes);
        memcpy(out->hdr, hdr, out->hdr_bytes);
    }
    pg_session_destroy(s);
    return ldr != NULL;
}

static void release(shot *s)
{
    free(s->ldr);
    free(s->hdr);
}

static bool same(const shot *a, const shot *b)
{
    return a->ldr_bytes == b->ldr_bytes && !memcmp(a->ldr, b->ldr, a->ldr_bytes) && a->hdr_bytes == b->hdr_bytes &&
           (!a->hdr_bytes || !memcmp(a->hdr, b->hdr, a->hdr_bytes));
}

/* every shipped pipeline on scene `which` (the built-in atrium with LIGHTS generated lights, or a
 * glTF file with its own lights) at fi's time and size: the single-queue image, the emulated
 * two-queue one with 1 and with 2 frames in flight, identical */
static void every_pipeline(pg_gpu *one, pg_gpu *two, const char *which, const pg_frame_info *fi0)
{
    pg_error err = {0};
    pg_scene *scene = NULL;
    pg_scene_gpu *sg1 = NULL, *sg2 = NULL;
    if (pg_scene_load(which, &scene, &err) || pg_scene_gpu_create(one, scene, &sg1, &err) ||
        pg_scene_gpu_create(two, scene, &sg2, &err)) {
        CHECK_MSG(0, "%s: %s", which, err.msg);
        pg_scene_gpu_destroy(one, sg1);
        pg_scene_free(scene);
        return;
    }
    pg_frame_info fi = *fi0;
    fi.camera = pg_camera_default_for_scene(scene, (float)W / H);
    fi.lights = pg_light_setup_default(scene, LIGHTS, 7);
    fi.lights.count = LIGHTS;
    if (scene->n_lights) fi.lights.count = fi.lights.file_count = scene->n_lights; /* the file's lights alone */
    printf("%s:\n", which);
    char dir[PG_PATH_MAX];
    pg_data_path(dir, sizeof dir, "pipelines");
    DIR *dh = opendir(dir);
    CHECK_MSG(dh != NULL, "cannot open %s", dir);
    uint32_t qualified = 0, total = 0;
    for (struct dirent *e; dh && (e = readdir(dh));) {
        size_t n = strlen(e->d_name);
        if (n <= 5 || strcmp(e->d_name + n - 5, ".json")) continue;
        char pipe[PG_PATH_MAX];
        snprintf(pipe, sizeof pipe, "pipelines/%s", e->d_name);
        total++;
        shot a, b, c;
        bool ok = render(one, sg1, pipe, &fi, 1, &a) && render(two, sg2, pipe, &fi, 1, &b) &&
                  render(two, sg2, pipe, &fi, 2, &c);
        CHECK_MSG(ok, "%s: render failed", pipe);
        if (ok) {
            CHECK_MSG(!a.async && a.n_batches == 1, "%s: the single-queue plan has %u batches", pipe, a.n_batches);
            if (b.async) {
                qualified++;
                printf("%s: %u batches; animate/assign on compute: %s; a raster batch waits for nothing: %s; "
                       "images %s (1 in flight), %s (2 in flight); %u lit pixels\n",
                       pipe, b.n_batches, b.chain_on_compute ? "yes" : "NO", b.raster_free ? "yes" : "NO",
                       same(&a, &b) ? "identical" : "DIFFERENT", same(&a, &c) ? "identical" : "DIFFERENT", a.lit);
                CHECK_MSG(b.chain_on_compute && b.n_batches >= 2, "%s: plan", pipe);
                /* deferred and reference: the G-buffer does not read the clusters: it overlaps */
                if (strstr(pipe, "deferred") || strstr(pipe, "reference"))
                    CHECK_MSG(b.n_batches >= 3 && b.raster_free, "%s: the G-buffer batch waits", pipe);
                /* every frame's compute work starts after the previous frame's on that queue, also
                 * with one frame in flight (the host's fence wait orders it only through the graphics
                 * queue's semaphore wait, which the validation layer did not follow on an H100);
                 * with two, every queue's work */
                CHECK_MSG(a.frame_barriers == 0 && b.frame_barriers == b.frames && c.frame_barriers == 2 * c.frames,
                          "%s: frame-start barriers %llu, %llu, %llu for %llu, %llu, %llu frames (one queue, two, two "
                          "with 2 in flight)", pipe, (unsigned long long)a.frame_barriers,
                          (unsigned long long)b.frame_barriers, (unsigned long long)c.frame_barriers,
                          (unsigned long long)a.frames, (unsigned long long)b.frames, (unsigned long long)c.frames);
                CHECK_MSG(same(&a, &b), "%s: the emulated two-queue image differs from the single-queue one", pipe);
                CHECK_MSG(same(&a, &c), "%s: with 2 frames in flight the image differs", pipe);
                CHECK_MSG(a.lit > (uint32_t)(W * H / 4), "%s: the image is dark (%u lit pixels)", pipe, a.lit);
            } else {
                printf("%s: no pass on the compute queue (%s)\n", pipe, "no compute pass independent of raster work");
            }
        }
        release(&a);
        release(&b);
        release(&c);
    }
    if (dh) closedir(dh);
    CHECK_MSG(qualified >= 6 && qualified == total, "only %u of %u shipped pipelines use the compute queue", qualified, total);
    pg_scene_gpu_destroy(one, sg1);
    pg_scene_gpu_destroy(two, sg2);
    pg_scene_free(scene);
}

int main(void)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    if (getenv("PG_TEST_NO_GPU")) return pg_test_skip("test_gpu_async", "PG_TEST_NO_GPU set");
    pg_register_builtin_passes(&g_reg);
    pg_gpu *one = NULL, *two = NULL;
    pg_error err = {0};
    pg_gpu_desc d1 = {.validation = true, .device_index = -1, .quiet = true, .no_compute_queue = true};
    pg_gpu_desc d2 = {.validation = true, .device_index = -1, .quiet = true, .emulate_compute_queue = true};
    if (pg_gpu_create(&d1, &one, &err) || pg_gpu_create(&d2, &two, &err)) {
        fprintf(stderr, "test_gpu_async: %s\n", err.msg);
        return 1;
    }
    CHECK(!one->compute_queue && two->compute_queue == two->queue && two->compute_emulated);
    pg_frame_info fi = {.time = 0.5f, .width = W, .height = H};
    every_pipeline(one, two, "default", &fi);
    /* materials animated by KHR_animation_pointer: the frame prologue rewrites them in the first
     * graphics batch while, with 2 in flight, the previous frame's batches may still read them */
    char path[PG_PATH_MAX];
    snprintf(path, sizeof path, "%s/corpus/gltf/animation/shimmer.gltf", PG_TEST_DIR);
    fi.time = 3.0f;
    every_pipeline(one, two, path, &fi);
    printf("validation messages: %u (one queue) + %u (emulated two queues)\n", one->validation_messages,
           two->validation_messages);
    CHECK(one->validation_messages == 0 && two->validation_messages == 0);
    pg_gpu_destroy(one);
    pg_gpu_destroy(two);
    return pg_test_finish("test_gpu_async");
}
