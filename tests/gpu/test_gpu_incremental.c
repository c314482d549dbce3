/* test_gpu_incremental.c - a new plan re-creates only what it needs (the three parts of the plan
 * signature, core/runtime/graph_execute_plan.c), and the images stay right.
 *
 * One session (deferred.json, default scene, 96x64, 16 lights, 2 frames in flight) is reloaded in
 * place (pg_session_reload) with, in turn:
 *   1. exposure=0.5          a run-time option (display_ocio's runtime_options): nothing is
 *                            re-created (value_updates + 1, no pipeline or memory rebuild);
 *   2. + ambient=0.05        a run-time option of deferred_lighting: the same (it is a push
 *                            constant now, not a define);
 *   3. the same overrides    nothing at all (last_rebuild "none", no counter moves);
 *   4. + shading=blinn_phong a new shader variant: the pass instances only (pipeline_rebuilds + 1),
 *                            the resources are kept, and so are the instances of the passes the
 *                            variant does not touch (the light animation, the light assignment,
 *                            the display: last_passes_kept 3, the G-buffer and lighting created);
 *   5. 24 lights             a bigger light buffer: it and the other members of its memory block
 *                            are re-created (the block packed again) with the pass instances, the
 *                            rest kept (resource_rebuilds + 1);
 *   6. a 128x72 frame        new memory (memory_rebuilds + 1).
 * After 1, 2 and 4 every resource of the plan still has its VkImage / VkBuffer handle
 * (pg_runtime_resource_at); after 5 every one outside the light buffer's block. After every step the read-back display and HDR images are byte-identical
 * to a fresh runtime's (pg_th_render with the same overrides and size), and steps 1, 2 and 4 change
 * the image (so a value that was not applied would be seen). The validation layer with
 * synchronization validation runs throughout: zero messages. Also: the pass registry refuses a type
 * that lists run-time options without an update(). */
#include <stdlib.h>
#include <string.h>

#include "gpu_harness.h"
#include "pass_list.h"
#include "shader.h"
#include "render_session.h"
#include "test_util.h"

#define W 96
#define H 64
#define LIGHTS 16

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;
static const pg_scene *g_scene;
static const pg_scene_gpu *g_sg;

typedef struct handles {
    uint32_t n;
    VkImage image[PG_MAX_RESOURCES];
    VkBuffer buffer[PG_MAX_RESOURCES];
} handles;

static void get_handles(const pg_session *s, handles *h)
{
    h->n = s->plan->n_resources;
    for (uint32_t i = 0; i < h->n; i++) {
        const pg_phys_resource *r = pg_runtime_resource_at(s->runtime, (int)i);
        h->image[i] = r ? r->image : VK_NULL_HANDLE;
        h->buffer[i] = r ? r->buffer : VK_NULL_HANDLE;
    }
}

/* Live resources of a whose handles b still has; *live: live resources of a. */
static uint32_t same_handles(const handles *a, const handles *b, uint32_t *live)
{
    uint32_t kept = 0;
    *live = 0;
    if (a->n != b->n) return 0;
    for (uint32_t i = 0; i < a->n; i++) {
        if (!a->image[i] && !a->buffer[i]) continue; /* culled */
        (*live)++;
        kept += a->image[i] == b->image[i] && a->buffer[i] == b->buffer[i];
    }
    return kept;
}

static pg_frame_info frame_info(uint32_t w, uint32_t h, uint32_t lights)
{
    pg_frame_info fi = {.camera = pg_camera_default_for_scene(g_scene, (float)w / h),
                        .lights = pg_light_setup_default(g_scene, lights, 7), .time = 0.5f, .width = w, .height = h};
    return fi;
}

/* The session's read-back images: which 0 display, 1 HDR. */
typedef struct image2 {
    uint8_t *px[2];
    size_t bytes[2];
} image2;

static bool render(pg_session *s, uint32_t w, uint32_t h, uint32_t lights, image2 *out)
{
    pg_frame_info fi = frame_info(w, h, lights);
    pg_frame_stats st;
    pg_error err = {0};
    memset(out, 0, sizeof *out);
    if (pg_session_render(s, &fi, true, &st, &err)) {
        CHECK_MSG(0, "render: %s", err.msg);
        return false;
    }
    for (int k = 0; k < 2; k++) {
        uint32_t iw, ih;
        pg_format fmt;
        const void *px = pg_runtime_output(s->runtime, k, &iw, &ih, &fmt);
        CHECK_MSG(px && iw == w && ih == h, "no read-back output %d (%ux%u)", k, px ? iw : 0, px ? ih : 0);
        if (!px) return false;
        out->bytes[k] = (size_t)iw * ih * pg_format_get(fmt)->bytes_per_pixel;
        out->px[k] = malloc(out->bytes[k]);
        memcpy(out->px[k], px, out->bytes[k]);
    }
    return true;
}

static void release(image2 *im)
{
    free(im->px[0]);
    free(im->px[1]);
    memset(im, 0, sizeof *im);
}

static bool same_image(const image2 *a, const image2 *b)
{
    for (int k = 0; k < 2; k++)
        if (!a->px[k] || !b->px[k] || a->bytes[k] != b->bytes[k] || memcmp(a->px[k], b->px[k], a->bytes[k]))
            return false;
    return true;
}

/* A fresh runtime's images for the same overrides and size. */
static bool fresh(const pg_param_override *ov, uint32_t n, uint32_t w, uint32_t h, uint32_t lights, image2 *out)
{
    pg_frame_info fi = frame_info(w, h, lights);
    pg_th_frame f;
    memset(out, 0, sizeof *out);
    if (!pg_th_render(g_gpu, &g_reg, g_sg, "pipelines/deferred.json", ov, n, &fi, 1, false, &f)) {
        CHECK_MSG(0, "fresh render failed");
        return false;
    }
    out->bytes[0] = (size_t)f.w * f.h * 4;
    out->px[0] = malloc(out->bytes[0]);
    memcpy(out->px[0], f.ldr, out->bytes[0]);
    out->bytes[1] = f.hdr_raw_bytes;
    out->px[1] = malloc(out->bytes[1]);
    memcpy(out->px[1], f.hdr_raw, out->bytes[1]);
    pg_th_release(&f);
    return true;
}

typedef struct step {
    const char *what;
    pg_param_override ov[3];
    uint32_t n_ov;
    uint32_t w, h, lights;
    pg_rebuild_kind want;
    bool changes_image;
} step;

static pg_result fake_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    (void)in, (void)out, (void)err;
    return PG_OK;
}

static void registry_rule(void)
{
    static const char *const rt[] = {"gain", NULL};
    const pg_pass_type t = {.name = "fake_runtime", .declare = fake_declare, .runtime_options = rt};
    pg_pass_registry reg = {0};
    pg_error err = {0};
    pg_result r = pg_registry_add(&reg, &t, &err);
    printf("registry: a type with run-time options and no update(): %s\n", r ? err.msg : "(accepted)");
    CHECK_MSG(r == PG_ERR_INVALID_ARG && strstr(err.msg, "fake_runtime") && strstr(err.msg, "update()"),
              "pg_registry_add must refuse it: %s", err.msg);
}

/* A pass whose update() fails once, wrapped around the display pass's type by the session's plan
 * hook: a values-only reload then fails, and the runtime must go back to the plan it had. It kept
 * the new plan and pipeline, which the session frees: the next frame read freed memory (and a
 * plug-in's update() may refuse a value). */
static const pg_pass_type *g_orig_type;
static pg_pass_type g_wrap_type;
static bool g_fail_next_update;

static pg_result failing_update(void *self, const void *params, pg_error *err)
{
    if (g_fail_next_update) {
        g_fail_next_update = false;
        return pg_fail(err, PG_ERR_INVALID_ARG, "refused by the test");
    }
    return g_orig_type->update(self, params, err);
}

/* ... and whose create() fails once: a new size then fails the compile, and the session must
 * render at its old size again (it kept its plan while the runtime had none: "no plan set" on
 * every later frame, at the old size too) */
static bool g_fail_next_create;

static pg_result failing_create(void *self, const struct pg_pass_create_ctx *ctx, pg_error *err)
{
    if (g_fail_next_create) {
        g_fail_next_create = false;
        return pg_fail(err, PG_ERR_VULKAN, "create refused by the test");
    }
    return g_orig_type->create(self, ctx, err);
}

static void wrap_updates(pg_graph_plan *plan, void *user)
{
    (void)user;
    for (uint32_t i = 0; i < plan->n_passes; i++) {
        const pg_pass_type *t = plan->passes[i].type;
        if (!t || !t->update || (g_orig_type && t != g_orig_type && t != &g_wrap_type)) continue;
        g_orig_type = t == &g_wrap_type ? g_orig_type : t;
        g_wrap_type = *g_orig_type;
        g_wrap_type.update = failing_update;
        g_wrap_type.create = failing_create;
        plan->passes[i].type = &g_wrap_type;
    }
}

static void failed_update(const char *path)
{
    pg_session_desc sd = {.pipeline_path = path, .registry = &g_reg, .test_edit_plan = wrap_updates};
    pg_session *s = NULL;
    pg_error err = {0};
    image2 a = {0}, b = {0}, c = {0};
    if (pg_session_create(g_gpu, g_sg, &sd, &s, &err) || !render(s, W, H, LIGHTS, &a)) {
        CHECK_MSG(0, "failing update: session: %s", err.msg);
        pg_session_destroy(s);
        return;
    }
    const pg_param_override ov[] = {{"exposure", "0.5"}};
    g_fail_next_update = true;
    pg_result r = pg_session_reload(s, path, ov, 1, &err);
    printf("failing update: reload with exposure=0.5: %s\n", r ? err.msg : "(accepted)");
    CHECK_MSG(r != PG_OK && strstr(err.msg, "refused by the test"), "the reload must fail: %s", err.msg);
    CHECK(render(s, W, H, LIGHTS, &b) && same_image(&a, &b)); /* the old plan and values, no freed memory */
    CHECK_MSG(!pg_session_reload(s, path, ov, 1, &err), "reload again: %s", err.msg);
    CHECK(render(s, W, H, LIGHTS, &c) && !same_image(&a, &c)); /* now applied */
    g_fail_next_create = true;
    pg_frame_info big = frame_info(2 * W, 2 * H, LIGHTS);
    pg_frame_stats st;
    err = (pg_error){0};
    r = pg_session_render(s, &big, true, &st, &err);
    CHECK_MSG(r != PG_OK && strstr(err.msg, "create refused by the test"), "a size whose pass creation fails: %s",
              r ? err.msg : "(rendered)");
    image2 again = {0};
    CHECK_MSG(render(s, W, H, LIGHTS, &again) && same_image(&c, &again), "the old size after a failed one");
    release(&again);
    release(&a);
    release(&b);
    release(&c);
    pg_session_destroy(s);
}

int main(void)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    registry_rule();
    if (getenv("PG_TEST_NO_GPU")) return pg_test_skip("test_gpu_incremental", "PG_TEST_NO_GPU set");
    pg_register_builtin_passes(&g_reg);
    pg_test_queue_submit_validation(); /* hazards between frames in flight too */
    pg_gpu_desc gd = {.validation = true, .device_index = -1, .quiet = true};
    pg_error err = {0};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_gpu_incremental: %s\n", err.msg);
        return 1;
    }
    CHECK_MSG(g_gpu->messenger != VK_NULL_HANDLE, "validation on but no messenger");
    pg_scene *scene = NULL;
    pg_scene_gpu *sg = NULL;
    if (pg_scene_create_default(&scene, &err) || pg_scene_gpu_create(g_gpu, scene, &sg, &err)) {
        fprintf(stderr, "test_gpu_incremental: scene: %s\n", err.msg);
        return 1;
    }
    g_scene = scene;
    g_sg = sg;

    char path[PG_PATH_MAX];
    pg_data_path(path, sizeof path, "pipelines/deferred.json");
    pg_session_desc sd = {.pipeline_path = path, .registry = &g_reg};
    pg_session *s = NULL;
    if (pg_session_create(g_gpu, sg, &sd, &s, &err) || pg_session_set_frames_in_flight(s, 2, &err)) {
        fprintf(stderr, "test_gpu_incremental: session: %s\n", err.msg);
        return 1;
    }
    image2 prev = {0}, cur = {0}, ref = {0};
    handles h0, h;
    bool ok = render(s, W, H, LIGHTS, &prev);
    if (ok) {
        pg_runtime_stats rs = pg_runtime_get_stats(s->runtime);
        CHECK_MSG(rs.memory_rebuilds == 1 && rs.pipeline_rebuilds == 0 && rs.value_updates == 0 &&
                      rs.last_rebuild == PG_REBUILD_MEMORY,
                  "first plan: memory %u pipelines %u values %u last %s", rs.memory_rebuilds, rs.pipeline_rebuilds,
                  rs.value_updates, pg_rebuild_kind_name(rs.last_rebuild));
        ok = fresh(NULL, 0, W, H, LIGHTS, &ref);
        CHECK_MSG(ok && same_image(&prev, &ref), "first frame differs from a fresh runtime's");
        release(&ref);
        get_handles(s, &h0);
    }
#define OV3 {{"exposure", "0.5"}, {"ambient", "0.05"}, {"shading", "blinn_phong"}}, 3
    const step steps[] = {
        {"exposure=0.5 (run-time option)", {{"exposure", "0.5"}}, 1, W, H, LIGHTS, PG_REBUILD_VALUES, true},
        {"+ ambient=0.05 (run-time option)", {{"exposure", "0.5"}, {"ambient", "0.05"}}, 2, W, H, LIGHTS,
         PG_REBUILD_VALUES, true},
        {"the same overrides", {{"exposure", "0.5"}, {"ambient", "0.05"}}, 2, W, H, LIGHTS, PG_REBUILD_NONE, false},
        {"+ shading=blinn_phong (new variant)", OV3, W, H, LIGHTS, PG_REBUILD_PIPELINES, true},
        {"24 lights (a bigger light buffer)", OV3, W, H, 24, PG_REBUILD_RESOURCES, true},
        {"128x72 (new size)", OV3, 128, 72, 24, PG_REBUILD_MEMORY, true},
    };
    for (size_t k = 0; ok && k < sizeof steps / sizeof steps[0]; k++) {
        const step *st = &steps[k];
        pg_runtime_stats before = pg_runtime_get_stats(s->runtime);
        const bool reload = st->w == W && st->lights == LIGHTS;
        if (reload) {
            ok = !pg_session_reload(s, path, st->ov, st->n_ov, &err);
            CHECK_MSG(ok, "%s: reload: %s", st->what, err.msg);
        }
        if (ok) ok = render(s, st->w, st->h, st->lights, &cur);
        if (!ok) break;
        pg_runtime_stats rs = pg_runtime_get_stats(s->runtime);
        uint32_t dm = rs.memory_rebuilds - before.memory_rebuilds, dr = rs.resource_rebuilds - before.resource_rebuilds,
                 dp = rs.pipeline_rebuilds - before.pipeline_rebuilds, dv = rs.value_updates - before.value_updates;
        get_handles(s, &h);
        uint32_t live = 0, kept = same_handles(&h0, &h, &live);
        printf("%-38s -> %-9s (memory +%u, resources +%u, pipelines +%u, values +%u); handles kept: %u of %u\n",
               st->what, pg_rebuild_kind_name(rs.last_rebuild), dm, dr, dp, dv, kept, live);
        CHECK_MSG(rs.last_rebuild == st->want, "%s: rebuilt %s, want %s", st->what,
                  pg_rebuild_kind_name(rs.last_rebuild), pg_rebuild_kind_name(st->want));
        CHECK_MSG(dm == (st->want == PG_REBUILD_MEMORY) && dr == (st->want == PG_REBUILD_RESOURCES) &&
                      dp == (st->want == PG_REBUILD_PIPELINES) && dv == (st->want == PG_REBUILD_VALUES),
                  "%s: counters moved memory +%u resources +%u pipelines +%u values +%u", st->what, dm, dr, dp, dv);
        if (st->want == PG_REBUILD_RESOURCES) {
            /* the light buffer is new (and bigger), every resource outside its block kept its handle */
            int li = -1;
            for (uint32_t i = 0; i < s->plan->n_resources; i++)
                if (!strcmp(s->plan->resources[i].name, "lights")) li = (int)i;
            const pg_phys_resource *lr = li >= 0 ? pg_runtime_resource_at(s->runtime, li) : NULL;
            CHECK_MSG(lr && lr->size >= 24 * 32, "%s: light buffer %llu bytes", st->what,
                      lr ? (unsigned long long)lr->size : 0ull);
            const int lb = li >= 0 ? s->plan->resources[li].block : -1;
            const uint32_t redone = lb >= 0 ? s->plan->blocks[lb].n_members : 1;
            CHECK_MSG(kept < live && kept == live - redone,
                      "%s: %u of %u handles kept, want all but the %u of the light buffer's block", st->what, kept,
                      live, redone);
            h0 = h; /* the next step compares with these */
            /* the memory counters match a fresh runtime's for this plan */
            pg_session *f2 = NULL;
            image2 tmp;
            if (!pg_session_create(g_gpu, sg, &sd, &f2, &err) && !pg_session_reload(f2, path, st->ov, st->n_ov, &err) &&
                render(f2, st->w, st->h, st->lights, &tmp)) {
                pg_runtime_stats fs = pg_runtime_get_stats(f2->runtime);
                printf("  device memory: %llu / %llu B (transient / unaliased), fresh runtime %llu / %llu B\n",
                       (unsigned long long)rs.memory_bytes_transient, (unsigned long long)rs.memory_bytes_unaliased,
                       (unsigned long long)fs.memory_bytes_transient, (unsigned long long)fs.memory_bytes_unaliased);
                CHECK_MSG(fs.memory_bytes_transient == rs.memory_bytes_transient &&
                              fs.memory_bytes_unaliased == rs.memory_bytes_unaliased &&
                              fs.blocks_fallback == rs.blocks_fallback,
                          "%s: memory counters differ from a fresh runtime's", st->what);
                release(&tmp);
            } else {
                CHECK_MSG(0, "%s: fresh session: %s", st->what, err.msg);
            }
            pg_session_destroy(f2);
        } else if (st->want != PG_REBUILD_MEMORY) {
            if (st->want == PG_REBUILD_PIPELINES) {
                printf("  pass instances: %u created, %u kept of %u\n", rs.last_passes_created, rs.last_passes_kept,
                       s->plan->n_order);
                CHECK_MSG(rs.last_passes_kept == 3 && rs.last_passes_created + rs.last_passes_kept == s->plan->n_order,
                          "%s: %u pass instances created, %u kept of %u (want the 3 the variant does not touch kept)",
                          st->what, rs.last_passes_created, rs.last_passes_kept, s->plan->n_order);
            }
            CHECK_MSG(live > 0 && kept == live, "%s: %u of %u resources kept their VkImage/VkBuffer", st->what,
                      kept, live);
        }
        ok = fresh(st->ov, st->n_ov, st->w, st->h, st->lights, &ref);
        bool same = ok && same_image(&cur, &ref);
        CHECK_MSG(same, "%s: the image differs from a fresh runtime's", st->what);
        if (st->w == W) {
            bool changed = !same_image(&cur, &prev);
            CHECK_MSG(changed == st->changes_image, "%s: the image %s", st->what,
                      changed ? "changed (nothing should have)" : "did not change");
        }
        release(&ref);
        release(&prev);
        prev = cur;
        memset(&cur, 0, sizeof cur);
    }
    release(&prev);
    pg_session_destroy(s);
    failed_update(path);
    CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
    pg_scene_gpu_destroy(g_gpu, sg);
    pg_scene_free(scene);
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_gpu_incremental");
}
