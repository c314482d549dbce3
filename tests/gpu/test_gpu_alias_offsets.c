/* test_gpu_alias_offsets.c - sub-allocated aliasing on the device (lavapipe in CI), with the Khronos
 * validation layer and synchronization validation on (any message fails). For each deferred
 * pipeline: the image with aliasing is byte-identical (LDR and HDR) to the one with
 * --no-aliasing; at run time (real memory requirements, core/runtime/graph_execute_memory.c) two resources bound
 * to overlapping bytes of one VkDeviceMemory are never alive at the same time, belong to one plan
 * block, start with a full overwrite and get an alias barrier; and aliasing saves device memory. */
#include <stdlib.h>
#include <string.h>

#include "graph_execute.h"
#include "image_util.h"
#include "pass_list.h"
#include "render_session.h"
#include "scenario.h"
#include "shader.h"
#include "test_util.h"

/* 256x128: every image size is a multiple of 64 KiB, so the images are stacked at offsets in one
 * VkDeviceMemory (at 320x180 lavapipe's alignment padding makes separate blocks the smaller) */
#define W 256
#define H 128

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;

typedef struct result {
    uint8_t *ldr;
    uint8_t *hdr;
    size_t hdr_bytes;
    uint64_t dev_unaliased, dev_aliased;
    uint32_t shared_pairs; /* pairs of resources that share bytes at run time */
    uint32_t at_offset;    /* resources bound at a non-zero offset of a shared VkDeviceMemory */
} result;

/* The run-time placement against the plan (see the file comment). */
static uint32_t check_placement(const pg_session *s, const char *label)
{
    const pg_graph_plan *p = s->plan;
    uint32_t pairs = 0;
    for (uint32_t i = 0; i < p->n_resources; i++) {
        const pg_plan_resource *ri = &p->resources[i];
        const pg_phys_resource *xi = pg_runtime_resource_at(s->runtime, (int)i);
        if (ri->culled || ri->first_pass < 0 || !xi || !xi->memory) continue;
        CHECK_MSG(xi->memory_size > 0, "%s: %s has no size", label, ri->name);
        for (uint32_t j = 0; j < i; j++) {
            const pg_plan_resource *rj = &p->resources[j];
            const pg_phys_resource *xj = pg_runtime_resource_at(s->runtime, (int)j);
            if (rj->culled || rj->first_pass < 0 || !xj || xj->memory != xi->memory) continue;
            const bool bytes = xi->memory_offset < xj->memory_offset + xj->memory_size &&
                               xj->memory_offset < xi->memory_offset + xi->memory_size;
            if (!bytes) continue;
            pairs++;
            const bool disjoint = ri->last_pass < rj->first_pass || rj->last_pass < ri->first_pass;
            CHECK_MSG(disjoint, "%s: %s and %s share bytes while both alive", label, ri->name, rj->name);
            CHECK_MSG(ri->block >= 0 && ri->block == rj->block, "%s: %s and %s share bytes across plan blocks", label,
                      ri->name, rj->name);
            const pg_plan_resource *later = ri->first_pass > rj->first_pass ? ri : rj;
            const int lr = later == ri ? (int)i : (int)j;
            CHECK_MSG(later->may_inherit, "%s: %s starts in used bytes without a full write", label, later->name);
            /* the later one's first pass carries its alias barrier */
            const pg_plan_pass *pp = &p->passes[p->order[later->first_pass]];
            bool barrier = false;
            for (uint32_t b = 0; b < pp->n_barriers; b++)
                barrier |= pp->barriers[b].resource == lr && pp->barriers[b].alias_prev >= 0 &&
                           pp->barriers[b].src_stages != 0;
            CHECK_MSG(barrier, "%s: %s shares bytes with %s without an alias barrier", label, later->name,
                      later == ri ? rj->name : ri->name);
        }
    }
    return pairs;
}

static bool render(const pg_scene_gpu *sg, const pg_scene *scene, const char *pipeline, bool no_alias, result *out)
{
    memset(out, 0, sizeof *out);
    char path[PG_PATH_MAX];
    pg_data_path(path, sizeof path, pipeline);
    pg_session_desc sd = {.pipeline_path = path, .registry = &g_reg, .disable_aliasing = no_alias};
    pg_session *s = NULL;
    pg_error err = {0};
    if (pg_session_create(g_gpu, sg, &sd, &s, &err)) {
        fprintf(stderr, "session: %s\n", err.msg);
        return false;
    }
    pg_frame_info fi = {
        .camera = pg_camera_default_for_scene(scene, (float)W / H),
        .lights = pg_light_setup_default(scene, 128, 7),
        .time = 1.0f,
        .width = W,
        .height = H,
    };
    pg_frame_stats st;
    bool ok = true;
    for (uint32_t f = 0; f < 2 && ok; f++) { /* two frames: the frame-to-frame wrap too */
        if (pg_session_render(s, &fi, f == 1, &st, &err)) {
            fprintf(stderr, "render: %s\n", err.msg);
            ok = false;
        }
    }
    if (ok) {
        uint32_t w, h, hw, hh;
        pg_format fmt, hf;
        const uint8_t *p = pg_runtime_output(s->runtime, 0, &w, &h, &fmt);
        const void *hp = pg_runtime_output(s->runtime, 1, &hw, &hh, &hf);
        ok = p && hp && w == W && h == H;
        if (ok) {
            out->ldr = malloc((size_t)w * h * 4);
            out->hdr_bytes = (size_t)hw * hh * pg_format_get(hf)->bytes_per_pixel;
            out->hdr = malloc(out->hdr_bytes);
            ok = out->ldr && out->hdr;
            if (ok) {
                memcpy(out->ldr, p, (size_t)w * h * 4);
                memcpy(out->hdr, hp, out->hdr_bytes);
            }
        }
        const pg_runtime_stats rs = pg_runtime_get_stats(s->runtime);
        out->dev_unaliased = rs.memory_bytes_unaliased;
        out->dev_aliased = rs.memory_bytes_transient;
        out->shared_pairs = check_placement(s, pipeline);
        for (uint32_t i = 0; i < s->plan->n_resources; i++) {
            const pg_phys_resource *x = pg_runtime_resource_at(s->runtime, (int)i);
            out->at_offset += x && x->memory && x->memory_offset > 0;
        }
    }
    pg_session_destroy(s);
    return ok;
}

int main(void)
{
    pg_register_builtin_passes(&g_reg);
    pg_gpu_desc gd = {.validation = true, .device_index = -1};
    pg_error err = {0};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_gpu_alias_offsets: %s\n", err.msg);
        return 1;
    }
    CHECK_MSG(g_gpu->validation, "the validation layer is not on");
    pg_scene *scene = NULL;
    pg_scene_gpu *sg = NULL;
    if (pg_scene_load("default", &scene, &err) || pg_scene_gpu_create(g_gpu, scene, &sg, &err)) {
        CHECK_MSG(0, "scene: %s", err.msg);
        pg_scene_free(scene);
        pg_gpu_destroy(g_gpu);
        return pg_test_finish("test_gpu_alias_offsets");
    }
    static const char *const pipelines[] = {"pipelines/deferred.json", "pipelines/deferred_oct16.json",
                                            "pipelines/deferred_packed.json"};
    for (size_t k = 0; k < sizeof pipelines / sizeof pipelines[0]; k++) {
        result a, n;
        const bool ok_a = render(sg, scene, pipelines[k], false, &a);
        const bool ok_n = render(sg, scene, pipelines[k], true, &n);
        CHECK_MSG(ok_a && ok_n, "%s: renders", pipelines[k]);
        if (ok_a && ok_n) {
            printf("%s %ux%u: device transient memory %llu B unaliased -> %llu B aliased; %u pairs share bytes; "
                   "%u resources at a non-zero offset\n",
                   pipelines[k], W, H, (unsigned long long)a.dev_unaliased, (unsigned long long)a.dev_aliased,
                   a.shared_pairs, a.at_offset);
            CHECK_MSG(memcmp(a.ldr, n.ldr, (size_t)W * H * 4) == 0, "%s: aliasing changes the LDR image", pipelines[k]);
            CHECK_MSG(a.hdr_bytes == n.hdr_bytes && memcmp(a.hdr, n.hdr, a.hdr_bytes) == 0,
                      "%s: aliasing changes the HDR image", pipelines[k]);
            pg_image_stats st = pg_rgba8_stats(a.ldr, W, H);
            CHECK_MSG(st.lit_fraction > 0.25, "%s: only %.1f%% lit (blank?)", pipelines[k], 100 * st.lit_fraction);
            CHECK_MSG(a.shared_pairs > 0 && a.dev_aliased < a.dev_unaliased, "%s: aliasing shared nothing",
                      pipelines[k]);
            CHECK_MSG(a.at_offset > 0, "%s: nothing bound at an offset", pipelines[k]);
            CHECK_MSG(n.shared_pairs == 0 && n.at_offset == 0 && n.dev_aliased == n.dev_unaliased,
                      "%s: --no-aliasing still shares", pipelines[k]);
        }
        free(a.ldr);
        free(a.hdr);
        free(n.ldr);
        free(n.hdr);
    }
    pg_scene_gpu_destroy(g_gpu, sg);
    pg_scene_free(scene);
    printf("validation messages: %u\n", g_gpu->validation_messages);
    CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_gpu_alias_offsets");
}
