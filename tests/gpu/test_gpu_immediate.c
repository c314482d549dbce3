/* test_gpu_immediate.c - the debugging mode --immediate (pg_session_desc.immediate) on lavapipe
 * with validation + synchronization validation (any message fails the test): every shipped
 * pipeline renders byte-identical LDR and HDR images with and without it, on the atrium with 64
 * lights and on the lit BLEND scene (so the transparent pass's blend runs too), over 2 frames
 * (the second frame has the frame-to-frame barriers of persistent resources). The immediate plan
 * says so (plan->immediate, aliasing off, every barrier ALL_COMMANDS -> ALL_COMMANDS) and runs
 * the same passes in the same order.
 * Also the record-time check of pg_pass_begin_rendering (core/runtime/graph_execute.h): a pass that
 * declares a full colour write but begins rendering with LOAD_OP_LOAD fails the frame with a
 * message naming the pass and slot; the same pass clearing renders. And a resource handle of the
 * plan before a resize is refused by pg_runtime_resource. */
#include <stdlib.h>
#include <unistd.h>
#include <string.h>
#include <vulkan/vulkan_core.h>

#include "graph_execute.h"
#include "pass_list.h"
#include "render_session.h"
#include "shader.h"
#include "test_util.h"

#define W 160
#define H 90

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;

static const char *const k_pipelines[] = {"naive", "forward_plus", "deferred", "deferred_oct16", "deferred_packed",
                                          "reference"};
#define N_PIPELINES 6

typedef struct shot {
    uint8_t *ldr, *hdr;
    size_t ldr_bytes, hdr_bytes;
    char order[256];
    bool immediate, aliasing_disabled, full_barriers;
    uint32_t n_barriers;
} shot;

static bool full_masks(const pg_barrier *b)
{
    return b->src_stages == VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT && b->src_access == VK_ACCESS_2_MEMORY_WRITE_BIT &&
           b->dst_stages == VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT &&
           b->dst_access == (VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
}

static bool render(const pg_scene_gpu *sg, const char *pipeline, bool immediate, const pg_frame_info *fi, shot *out)
{
    memset(out, 0, sizeof *out);
    char rel[96], path[PG_PATH_MAX];
    snprintf(rel, sizeof rel, "pipelines/%s.json", pipeline);
    pg_data_path(path, sizeof path, rel);
    pg_session_desc sd = {.pipeline_path = path, .registry = &g_reg, .immediate = immediate};
    pg_session *s = NULL;
    pg_error err = {0};
    if (pg_session_create(g_gpu, sg, &sd, &s, &err)) {
        CHECK_MSG(0, "%s: %s", pipeline, err.msg);
        return false;
    }
    bool ok = true;
    pg_frame_stats st;
    for (uint32_t f = 0; f < 2 && ok; f++)
        if (pg_session_render(s, fi, f == 1, &st, &err)) {
            CHECK_MSG(0, "%s: render: %s", pipeline, err.msg);
            ok = false;
        }
    if (ok) {
        const pg_graph_plan *p = s->plan;
        out->immediate = p->immediate;
        out->aliasing_disabled = p->aliasing_disabled;
        out->full_barriers = true;
        for (uint32_t k = 0; k < p->n_order; k++) {
            const pg_plan_pass *pp = &p->passes[p->order[k]];
            size_t len = strlen(out->order);
            snprintf(out->order + len, sizeof out->order - len, "%s%s", k ? "," : "", pp->name);
            for (uint32_t b = 0; b < pp->n_barriers; b++) out->full_barriers &= full_masks(&pp->barriers[b]);
            out->n_barriers += pp->n_barriers;
        }
        for (uint32_t b = 0; b < p->n_final_barriers; b++) out->full_barriers &= full_masks(&p->final_barriers[b]);
        for (int o = 0; o < 2 && ok; o++) {
            uint32_t w, h;
            pg_format fmt;
            const void *px = pg_runtime_output(s->runtime, o, &w, &h, &fmt);
            const pg_format_info *fi2 = px ? pg_format_get(fmt) : NULL;
            ok = px && fi2 && fi2->bytes_per_pixel > 0 && w == W && h == H;
            CHECK_MSG(ok, "%s: output %d not read back", pipeline, o);
            if (!ok) break;
            size_t n = (size_t)w * h * fi2->bytes_per_pixel;
            uint8_t *copy = malloc(n);
            if (!copy) {
                ok = false;
                break;
            }
            memcpy(copy, px, n);
            if (o == 0) out->ldr = copy, out->ldr_bytes = n;
            else out->hdr = copy, out->hdr_bytes = n;
        }
    }
    pg_session_destroy(s);
    return ok;
}

static void release(shot *s)
{
    free(s->ldr);
    free(s->hdr);
    memset(s, 0, sizeof *s);
}

static bool nonblank(const shot *s)
{
    for (size_t i = 0; i < s->ldr_bytes; i++)
        if (i % 4 != 3 && s->ldr[i]) return true;
    return false;
}

static void compare_all(const char *label, const pg_scene_gpu *sg, const pg_frame_info *fi, bool want_transparent)
{
    for (int p = 0; p < N_PIPELINES; p++) {
        shot a, b;
        if (!render(sg, k_pipelines[p], false, fi, &a)) continue;
        if (!render(sg, k_pipelines[p], true, fi, &b)) {
            release(&a);
            continue;
        }
        const bool ldr_same = a.ldr_bytes == b.ldr_bytes && !memcmp(a.ldr, b.ldr, a.ldr_bytes);
        const bool hdr_same = a.hdr_bytes == b.hdr_bytes && !memcmp(a.hdr, b.hdr, a.hdr_bytes);
        printf("%-8s %-16s immediate: ldr %s, hdr %s; %u vs %u barriers [%s]\n", label, k_pipelines[p],
               ldr_same ? "identical" : "DIFFERENT", hdr_same ? "identical" : "DIFFERENT", b.n_barriers, a.n_barriers,
               b.order);
        CHECK_MSG(nonblank(&a), "%s %s: blank image", label, k_pipelines[p]);
        CHECK_MSG(ldr_same && hdr_same, "%s %s: --immediate renders a different image", label, k_pipelines[p]);
        CHECK_MSG(!a.immediate && b.immediate && b.aliasing_disabled, "%s %s: immediate plan flags", label,
                  k_pipelines[p]);
        CHECK_MSG(b.full_barriers && !a.full_barriers, "%s %s: immediate barriers are not full", label,
                  k_pipelines[p]);
        CHECK_MSG(!strcmp(a.order, b.order), "%s %s: order %s vs %s", label, k_pipelines[p], a.order, b.order);
        CHECK_MSG(!want_transparent || strstr(b.order, "transparent"), "%s %s: no transparent pass: %s", label,
                  k_pipelines[p], b.order);
        release(&a);
        release(&b);
    }
}

/* A pass that only begins and ends rendering on its colour_write slot: with LOAD ("t_load_write",
 * a pass bug: it claims a full write) or CLEAR ("t_clear_write"). */
static pg_result t_declare(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)in, (void)e;
    pg_decl_write(d, "color", PG_RES_IMAGE, PG_ACCESS_COLOR_WRITE, PG_STAGE_FRAGMENT, PG_FMTCLASS_FLOAT);
    d->side_effects = true;
    return PG_OK;
}
static pg_result t_create(void *self, const pg_pass_create_ctx *ctx, pg_error *e)
{
    (void)self, (void)ctx, (void)e;
    return PG_OK;
}
static void t_record(void *self, const pg_pass_record_ctx *ctx, bool clear)
{
    (void)self;
    const uint32_t slot = 0;
    /* x 255 = 51, 153, 204 up to 1e-5: the same bytes under any rounding of the conversion to
     * UNORM (0.5 x 255 = 127.5 was 128 on lavapipe and not on an NVIDIA H100) */
    VkClearColorValue c = {{0.2f, 0.6f, 0.8f, 1}};
    pg_pass_begin_rendering(ctx, 1, &slot, clear ? &c : NULL, -1, false, 0);
    vkCmdEndRendering(ctx->cmd);
}
static void t_record_load(void *self, const pg_pass_record_ctx *ctx) { t_record(self, ctx, false); }
static void t_record_clear(void *self, const pg_pass_record_ctx *ctx) { t_record(self, ctx, true); }
static void t_destroy(void *self, pg_gpu *gpu) { (void)self, (void)gpu; }
static const pg_pass_type k_load_write = {.name = "t_load_write", .summary = "test",
                                          .instance_size = 8, .declare = t_declare, .create = t_create,
                                          .record = t_record_load, .destroy = t_destroy};
static const pg_pass_type k_clear_write = {.name = "t_clear_write", .summary = "test",
                                           .instance_size = 8, .declare = t_declare, .create = t_create,
                                           .record = t_record_clear, .destroy = t_destroy};

static void test_load_op_check(const pg_scene_gpu *sg, const pg_frame_info *fi)
{
    static const char *const types[2] = {"t_load_write", "t_clear_write"};
    for (int k = 0; k < 2; k++) {
        char path[PG_PATH_MAX];
        snprintf(path, sizeof path, "/tmp/test_gpu_immediate_%d_%d.json", (int)getpid(), k);
        FILE *f = fopen(path, "w");
        if (!f) {
            CHECK_MSG(0, "cannot write %s", path);
            return;
        }
        fprintf(f, "{\"name\": \"t\", \"resources\": [{\"name\": \"ldr\", \"type\": \"image\", \"format\": \"rgba8\"}],\n"
                   " \"passes\": [{\"name\": \"fill\", \"type\": \"%s\", \"writes\": [\"ldr\"]}], \"output\": \"ldr\"}\n",
                types[k]);
        fclose(f);
        pg_session_desc sd = {.pipeline_path = path, .registry = &g_reg};
        pg_session *s = NULL;
        pg_error err = {0};
        pg_result r = pg_session_create(g_gpu, sg, &sd, &s, &err);
        CHECK_MSG(r == PG_OK, "%s: %s", types[k], err.msg);
        if (!r) {
            r = pg_session_render(s, fi, true, NULL, &err);
            printf("load-op check %s: %s\n", types[k], r ? err.msg : "rendered");
            if (k == 0)
                CHECK_MSG(r == PG_ERR_INVALID_ARG &&
                              !strcmp(err.msg, "pass 'fill': slot 'color' is declared color_write (a full write) but "
                                               "rendering begins with LOAD_OP_LOAD: clear it, or declare a "
                                               "read-modify-write"),
                          "%s", err.msg);
            else
                CHECK_MSG(r == PG_OK, "%s", err.msg);
            if (k == 1 && !r) {
                uint32_t w, h;
                pg_format fmt;
                const uint8_t *px = pg_runtime_output(s->runtime, 0, &w, &h, &fmt);
                CHECK(px && px[0] == 51 && px[1] == 153 && px[2] == 204 && px[3] == 255);
                /* a handle of this plan, then a resize: the old handle is refused */
                pg_res_handle hd;
                const pg_phys_resource *res = NULL;
                CHECK(pg_plan_find_resource(s->plan, "ldr", &hd, &err) == PG_OK);
                CHECK(pg_runtime_resource(s->runtime, hd, &res, &err) == PG_OK && res && res->width == W);
                pg_frame_info f2 = *fi;
                f2.width = W / 2;
                f2.height = H / 2;
                CHECK_MSG(pg_session_render(s, &f2, false, NULL, &err) == PG_OK, "%s", err.msg);
                CHECK(pg_runtime_resource(s->runtime, hd, &res, &err) == PG_ERR_INVALID_ARG && !res);
                CHECK_MSG(strstr(err.msg, "stale resource handle #0: it is from another compiled plan"), "%s", err.msg);
            }
        }
        pg_session_destroy(s);
        remove(path);
    }
}

int main(void)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    if (getenv("PG_TEST_NO_GPU")) return pg_test_skip("test_gpu_immediate", "PG_TEST_NO_GPU");
    pg_error err = {0};
    pg_register_builtin_passes(&g_reg);
    pg_registry_add(&g_reg, &k_load_write, &err);
    pg_registry_add(&g_reg, &k_clear_write, &err);
    pg_gpu_desc gd = {.validation = true, .device_index = -1, .quiet = true};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_gpu_immediate: %s\n", err.msg);
        return 1;
    }
    static const char *const scenes[2] = {"default", PG_TEST_DIR "/corpus/gltf/blend/blend_lit.gltf"};
    for (int k = 0; k < 2; k++) {
        pg_scene *scene = NULL;
        pg_scene_gpu *sg = NULL;
        if (pg_scene_load(scenes[k], &scene, &err) || pg_scene_gpu_create(g_gpu, scene, &sg, &err)) {
            CHECK_MSG(0, "%s: %s", scenes[k], err.msg);
            pg_scene_free(scene);
            continue;
        }
        pg_frame_info fi = {.camera = pg_camera_default_for_scene(scene, (float)W / H),
                            .lights = pg_light_setup_default(scene, 64, 7), .time = 0.75f, .width = W, .height = H};
        compare_all(k ? "blend" : "atrium", sg, &fi, k == 1);
        if (k == 0) test_load_op_check(sg, &fi);
        pg_scene_gpu_destroy(g_gpu, sg);
        pg_scene_free(scene);
    }
    printf("validation messages: %u\n", g_gpu->validation_messages);
    CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_gpu_immediate");
}
